// SPDX-License-Identifier: GPL-3.0-or-later
// Owns the precompiled header the benchmarks and the stress test reuse (tools/CMakeLists.txt).
int main() {
  return 0;
}

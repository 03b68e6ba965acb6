// SPDX-License-Identifier: GPL-3.0-or-later
// What every fuzz target shares: the input limits it runs under, and the rule that an input may
// only be rejected with the library's documented error type. Anything else (another exception, a
// sanitizer report, a hang, an allocation beyond libFuzzer's limit) is a finding.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <typeinfo>

#include "morphex/io.h"

namespace morphex::fuzz {

[[noreturn]] inline void finding(const char* what) {
  std::fprintf(stderr, "morphex fuzz finding: %s\n", what);
  std::abort();
}

// Small enough that a SE given as mesh:path=/dev/zero or a huge mesh file is refused quickly.
inline void limit_inputs() {
  static const bool once = [] {
    set_input_limits({/*max_file_bytes=*/1 << 20, /*max_faces=*/100'000});
    return true;
  }();
  (void)once;
}

template <class Expected, class Body>
void expect_only(Body&& body) {
  try {
    body();
  } catch (const Expected&) {
  } catch (const std::exception& e) {
    std::fprintf(stderr, "morphex fuzz finding: unexpected %s: %s\n", typeid(e).name(), e.what());
    std::abort();
  }
}

}  // namespace morphex::fuzz

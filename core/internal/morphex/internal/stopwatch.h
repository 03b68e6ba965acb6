// SPDX-License-Identifier: GPL-3.0-or-later
// Wall-clock timing for statistics, progress and benchmarks: one steady clock, seconds as double.
#pragma once

#include <chrono>

namespace morphex {

class Stopwatch {
 public:
  // Seconds since construction or the last restart() or lap().
  double seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }
  // seconds(), then restarts: successive laps time successive phases.
  double lap() {
    const auto now = std::chrono::steady_clock::now();
    const double s = std::chrono::duration<double>(now - start_).count();
    start_ = now;
    return s;
  }
  void restart() { start_ = std::chrono::steady_clock::now(); }

 private:
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

}  // namespace morphex

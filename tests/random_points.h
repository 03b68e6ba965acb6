// SPDX-License-Identifier: GPL-3.0-or-later
// Random rational points for the exact predicates' tests: mixed denominators (powers of two and
// others) and a few doubles, so that the filters meet every kind of coordinate.
#pragma once

#include <random>

#include "morphex/mesh.h"

namespace morphex::test_support {

class RandomPoints {
 public:
  explicit RandomPoints(unsigned seed) : random_(seed) {}
  FT coordinate() {
    // Mixed denominators (powers of two and others) and a few doubles.
    std::uniform_int_distribution<int> numerator(-50, 50), denominator(1, 12), kind(0, 3);
    if (kind(random_) == 0) return FT(std::uniform_real_distribution<double>(-3, 3)(random_));
    return FT(numerator(random_)) / FT(denominator(random_));
  }
  Point point() {
    const FT x = coordinate(), y = coordinate(), z = coordinate();
    return Point(x, y, z);
  }
  FT weight() { return FT(std::uniform_int_distribution<int>(-7, 7)(random_)) / 5; }

 private:
  std::mt19937 random_;
};

}  // namespace morphex::test_support

// SPDX-License-Identifier: GPL-3.0-or-later
// The parts of numbers that the exact sums and grids scaling coordinates to integers read
// (volume.cpp, input_grid.cpp): a double as an odd integer times a power of two, and integers
// (denominators) found by value in a hash map.
#pragma once

#include <gmpxx.h>

#include <cstddef>
#include <cstdint>
#include <cstring>

namespace morphex::detail {

// A finite nonzero double as odd * 2^exponent, |odd| < 2^53, read from its bits (frexp and
// ldexp took a fifth of a volume's time).
struct OddTimesPower {
  std::int64_t odd;
  int exponent;
};
inline OddTimesPower odd_times_power(double x) {
  std::uint64_t bits = 0;
  std::memcpy(&bits, &x, sizeof bits);
  const int field = int((bits >> 52) & 0x7ff);
  std::uint64_t mantissa = bits & ((std::uint64_t(1) << 52) - 1);
  int exponent = -1074;  // a subnormal's
  if (field != 0) {
    mantissa |= std::uint64_t(1) << 52;
    exponent = field - 1075;
  }
  const int zeros = __builtin_ctzll(mantissa);
  const auto odd = static_cast<std::int64_t>(mantissa >> zeros);
  return {bits >> 63 ? -odd : odd, exponent + zeros};
}

// Keys of an unordered_map of integers by value, a hash of their limbs: a rotated mesh's
// coordinates take turns among a hundred denominators or so, each found once by value.
struct MpzValueHash {
  std::size_t operator()(const mpz_class* z) const {
    std::size_t hash = mpz_size(z->get_mpz_t());
    for (std::size_t l = 0; l < mpz_size(z->get_mpz_t()); ++l)
      hash = (hash ^ mpz_getlimbn(z->get_mpz_t(), mp_size_t(l))) * 0x100000001b3ull;
    return hash;
  }
};
struct MpzValueEqual {
  bool operator()(const mpz_class* a, const mpz_class* b) const { return *a == *b; }
};

}  // namespace morphex::detail

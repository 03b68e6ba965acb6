// SPDX-License-Identifier: GPL-3.0-or-later
// Signed integers of a fixed number of 64-bit limbs (two's complement, least significant limb
// first), for exact sums of products of integers of about a hundred bits without GMP.
//
// The exact volume of a mesh with double coordinates is a sum of determinants of integers once
// the coordinates are scaled to a common power of two. mpq arithmetic spent most of its time in
// gcds and allocation; these fixed-size numbers need neither. Sizes are chosen by the caller so
// that nothing overflows (results are truncated to N limbs): see volume.cpp for the bounds.
#pragma once

#include <gmpxx.h>

#include <cstdint>

namespace morphex::detail {

template <int N>
struct WideInt {
  static constexpr int kLimbs = N;
  std::uint64_t limb[N] = {};

  static WideInt of(__int128 v) {
    WideInt w;
    const auto u = static_cast<unsigned __int128>(v);
    w.limb[0] = std::uint64_t(u);
    if constexpr (N > 1) w.limb[1] = std::uint64_t(u >> 64);
    const std::uint64_t fill = v < 0 ? ~std::uint64_t(0) : 0;
    for (int i = 2; i < N; ++i) w.limb[i] = fill;
    return w;
  }
  bool negative() const { return limb[N - 1] >> 63; }

  WideInt& operator+=(const WideInt& o) {
    unsigned __int128 carry = 0;
    for (int i = 0; i < N; ++i) {
      carry += static_cast<unsigned __int128>(limb[i]) + o.limb[i];
      limb[i] = std::uint64_t(carry);
      carry >>= 64;
    }
    return *this;
  }
  WideInt operator-() const { return negated_if(true); }
  WideInt& operator-=(const WideInt& o) { return *this += -o; }
  // -x when `negate`, else x, without a branch: signs of products in a determinant are coin
  // tosses, and a mispredicted branch costs more than the limbs' arithmetic.
  WideInt negated_if(bool negate) const {
    const std::uint64_t mask = 0 - std::uint64_t(negate);
    WideInt r;
    unsigned __int128 carry = negate;  // (x ^ mask) + 1 = ~x + 1 when negating
    for (int i = 0; i < N; ++i) {
      carry += static_cast<unsigned __int128>(limb[i] ^ mask);
      r.limb[i] = std::uint64_t(carry);
      carry >>= 64;
    }
    return r;
  }

  // this * 2^bits, 0 <= bits < 64 N (truncated to N limbs).
  WideInt shifted_left(int bits) const {
    WideInt r;
    const int limbs = bits / 64, rest = bits % 64;
    for (int i = N - 1; i >= limbs; --i) {
      const std::uint64_t low = limb[i - limbs];
      const std::uint64_t below =
          i - limbs - 1 >= 0 && rest > 0 ? limb[i - limbs - 1] >> (64 - rest) : 0;
      r.limb[i] = (rest > 0 ? low << rest : low) | below;
    }
    return r;
  }

  // Widened (sign-extended) to M >= N limbs.
  template <int M>
  WideInt<M> widen() const {
    WideInt<M> r;
    const std::uint64_t fill = negative() ? ~std::uint64_t(0) : 0;
    for (int i = 0; i < M; ++i) r.limb[i] = i < N ? limb[i] : fill;
    return r;
  }

  // z, which must be below 2^(64 N - 1) in magnitude. Limb by limb (mpz_export's generality cost
  // most of a rotated mesh's volume).
  static WideInt of_mpz(const mpz_class& z) {
    static_assert(sizeof(mp_limb_t) == sizeof(std::uint64_t) && GMP_NAIL_BITS == 0,
                  "GMP's limbs are 64-bit words");
    WideInt w;
    const std::size_t size = mpz_size(z.get_mpz_t());
    for (std::size_t i = 0; i < size && i < std::size_t(N); ++i)
      w.limb[i] = mpz_getlimbn(z.get_mpz_t(), mp_size_t(i));  // of |z|
    return sgn(z) < 0 ? -w : w;
  }

  mpz_class to_mpz() const {
    const WideInt magnitude = negative() ? -*this : *this;
    mpz_class z;
    mpz_import(z.get_mpz_t(), N, -1, sizeof(std::uint64_t), 0, 0, magnitude.limb);
    return negative() ? mpz_class(-z) : z;
  }
};

// a * b truncated to N limbs: exact when the product fits in N limbs with its sign.
template <int N, int A, int B>
WideInt<N> multiply(const WideInt<A>& a, const WideInt<B>& b) {
  const bool negative = a.negative() != b.negative();
  const WideInt<A> ma = a.negated_if(a.negative());
  const WideInt<B> mb = b.negated_if(b.negative());
  WideInt<N> r;
  for (int i = 0; i < A && i < N; ++i) {
    unsigned __int128 carry = 0;
    for (int j = 0; j < B && i + j < N; ++j) {
      carry += static_cast<unsigned __int128>(ma.limb[i]) * mb.limb[j] + r.limb[i + j];
      r.limb[i + j] = std::uint64_t(carry);
      carry >>= 64;
    }
    if (i + B < N) r.limb[i + B] = std::uint64_t(carry);
  }
  return r.negated_if(negative);
}

}  // namespace morphex::detail

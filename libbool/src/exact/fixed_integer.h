// SPDX-License-Identifier: GPL-3.0-or-later
// Signs of integer determinants without heap allocation, for the exact stage of the predicates.
//
// The exact stage works on homogeneous integer coordinates (point_table.h) of a few hundred bits.
// mpz arithmetic allocates for every temporary, which made the determinants cost several times
// their multiplications. Here numbers live in fixed stack buffers of limbs and GMP's low-level
// mpn routines do the arithmetic; a determinant too large for the buffers falls back to mpz.
#pragma once

#include <gmp.h>
#include <gmpxx.h>

#include <array>
#include <cstring>
#include <optional>

namespace morphex::detail {

// A signed integer of at most Limbs limbs (magnitude, size in limbs, sign).
template <int Limbs>
struct FixedInteger {
  mp_limb_t limb[Limbs];
  int size = 0;  // 0 for zero
  int sign = 0;  // -1, 0, +1

  // z into this; false when it has more than Limbs limbs. (Out-parameters here and below: the
  // buffers are large, and returning them in optionals copied them at every step.)
  bool assign(const mpz_class& z) {
    const std::size_t n = mpz_size(z.get_mpz_t());
    if (n > std::size_t(Limbs)) return false;
    size = int(n);
    sign = sgn(z);
    for (std::size_t i = 0; i < n; ++i) limb[i] = mpz_getlimbn(z.get_mpz_t(), i);
    return true;
  }
};

// The entries of `n` rows of 4 integers as fixed integers of E limbs into m; false when one is
// too large.
template <int E>
bool fixed_rows(const std::array<mpz_class, 4>* const* rows, int n, FixedInteger<E> (*m)[4]) {
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < 4; ++j)
      if (!m[i][j].assign((*rows[i])[j])) return false;
  return true;
}

// r = a * b; false when it may not fit in Out limbs.
template <int Out, int A, int B>
bool multiply(FixedInteger<Out>& r, const FixedInteger<A>& a, const FixedInteger<B>& b) {
  if (a.size == 0 || b.size == 0) {
    r.size = r.sign = 0;
    return true;
  }
  if (a.size + b.size > Out) return false;
  if (a.size >= b.size)
    mpn_mul(r.limb, a.limb, a.size, b.limb, b.size);
  else
    mpn_mul(r.limb, b.limb, b.size, a.limb, a.size);
  r.size = a.size + b.size;
  while (r.size > 0 && r.limb[r.size - 1] == 0) --r.size;
  r.sign = a.sign * b.sign;
  return true;
}

// acc += sign * x, or false when the sum may not fit.
template <int Acc, int X>
bool accumulate(FixedInteger<Acc>& acc, const FixedInteger<X>& x, int sign) {
  const int xs = x.sign * sign;
  if (xs == 0) return true;
  if (acc.sign == 0) {
    if (x.size > Acc) return false;
    std::memcpy(acc.limb, x.limb, sizeof(mp_limb_t) * std::size_t(x.size));
    acc.size = x.size;
    acc.sign = xs;
    return true;
  }
  if (acc.sign == xs) {  // magnitudes add
    const int n = std::max(acc.size, x.size);
    if (n + 1 > Acc) return false;
    mp_limb_t carry;
    if (acc.size >= x.size) {
      carry = mpn_add(acc.limb, acc.limb, acc.size, x.limb, x.size);
    } else {
      mp_limb_t sum[Acc];
      carry = mpn_add(sum, x.limb, x.size, acc.limb, acc.size);
      std::memcpy(acc.limb, sum, sizeof(mp_limb_t) * std::size_t(x.size));
    }
    acc.size = n;
    if (carry) acc.limb[acc.size++] = carry;
    return true;
  }
  // magnitudes subtract: the larger keeps its sign
  const int cmp =
      acc.size != x.size ? (acc.size > x.size ? 1 : -1) : mpn_cmp(acc.limb, x.limb, acc.size);
  if (cmp == 0) {
    acc.size = 0;
    acc.sign = 0;
    return true;
  }
  if (cmp > 0) {
    mpn_sub(acc.limb, acc.limb, acc.size, x.limb, x.size);
  } else {
    if (x.size > Acc) return false;
    mp_limb_t difference[Acc];
    mpn_sub(difference, x.limb, x.size, acc.limb, acc.size);
    std::memcpy(acc.limb, difference, sizeof(mp_limb_t) * std::size_t(x.size));
    acc.size = x.size;
    acc.sign = xs;
  }
  while (acc.size > 0 && acc.limb[acc.size - 1] == 0) --acc.size;
  if (acc.size == 0) acc.sign = 0;
  return true;
}

// The sign of the 3x3 determinant of integer rows (each of `Columns` >= 3 entries, the three
// given columns), or nullopt when an entry or a partial result is too large for the buffers.
template <std::size_t Columns>
std::optional<int> fixed_sign_of_det3(const std::array<mpz_class, Columns>* rows[3], int c0, int c1,
                                      int c2) {
  constexpr int E = 6;  // entries up to 384 bits
  FixedInteger<E> m[3][3];
  const int cols[3] = {c0, c1, c2};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (!m[i][j].assign((*rows[i])[cols[j]])) return std::nullopt;
  FixedInteger<3 * E + 1> det;
  // expansion along the first row: m00 (m11 m22 - m12 m21) - m01 (...) + m02 (...)
  const int signs[3] = {1, -1, 1};
  for (int k = 0; k < 3; ++k) {
    const int a = (k + 1) % 3, b = (k + 2) % 3;
    const int lo = std::min(a, b), hi = std::max(a, b);
    FixedInteger<2 * E + 1> minor;
    FixedInteger<2 * E> p, q;
    if (!multiply(p, m[1][lo], m[2][hi]) || !multiply(q, m[1][hi], m[2][lo]) ||
        !accumulate(minor, p, 1) || !accumulate(minor, q, -1))
      return std::nullopt;
    FixedInteger<3 * E + 1> term;
    if (!multiply(term, m[0][k], minor) || !accumulate(det, term, signs[k])) return std::nullopt;
  }
  return det.sign;
}

// The sign of the 4x4 determinant of integer rows, by the 2x2 minors of the first two and the
// last two rows, or nullopt when too large for the buffers.
inline std::optional<int> fixed_sign_of_det4(const std::array<mpz_class, 4>* rows[4]) {
  constexpr int E = 4;  // entries up to 256 bits
  FixedInteger<E> m[4][4];
  if (!fixed_rows<E>(rows, 4, m)) return std::nullopt;
  auto minor = [&](FixedInteger<2 * E + 1>& out, int r, int i, int j) {
    FixedInteger<2 * E> p, q;
    return multiply(p, m[r][i], m[r + 1][j]) && multiply(q, m[r][j], m[r + 1][i]) &&
           accumulate(out, p, 1) && accumulate(out, q, -1);
  };
  // det = sum over column pairs (i, j) of the first two rows of +- minor01(i,j) minor23(rest)
  static constexpr int pairs[6][4] = {{0, 1, 2, 3}, {0, 2, 1, 3}, {0, 3, 1, 2},
                                      {1, 2, 0, 3}, {1, 3, 0, 2}, {2, 3, 0, 1}};
  static constexpr int signs[6] = {1, -1, 1, 1, -1, 1};
  FixedInteger<4 * E + 3> det;
  for (int k = 0; k < 6; ++k) {
    FixedInteger<2 * E + 1> top, bottom;
    FixedInteger<4 * E + 2> term;
    if (!minor(top, 0, pairs[k][0], pairs[k][1]) || !minor(bottom, 2, pairs[k][2], pairs[k][3]) ||
        !multiply(term, top, bottom) || !accumulate(det, term, signs[k]))
      return std::nullopt;
  }
  return det.sign;
}

// The linear form of the plane through three points (homogeneous integer rows a, b, c):
// det [a; b; c; x] = sum_j C_j x_j, the cofactors C_j of the last row computed once. For many
// points against one plane each sign is then four products instead of a 4x4 determinant.
class FixedPlaneForm {
 public:
  // nullopt when an entry or a cofactor is too large for the buffers.
  static std::optional<FixedPlaneForm> through(const std::array<mpz_class, 4>* rows[3]) {
    FixedInteger<E> m[3][4];
    if (!fixed_rows<E>(rows, 3, m)) return std::nullopt;
    FixedPlaneForm form;
    for (int j = 0; j < 4; ++j) {
      // C_j = (-1)^(3 + j) det of the rows without column j, expanded along row a.
      int c[3], n = 0;
      for (int k = 0; k < 4; ++k)
        if (k != j) c[n++] = k;
      FixedInteger<kCofactor>& out = form.cofactor_[j];
      for (int e = 0; e < 3; ++e) {
        const int lo = c[e == 0 ? 1 : 0], hi = c[e == 2 ? 1 : 2];
        FixedInteger<2 * E + 1> minor;
        FixedInteger<2 * E> p, q;
        if (!multiply(p, m[1][lo], m[2][hi]) || !multiply(q, m[1][hi], m[2][lo]) ||
            !accumulate(minor, p, 1) || !accumulate(minor, q, -1))
          return std::nullopt;
        FixedInteger<kCofactor - 1> term;
        const int sign = (e == 1 ? -1 : 1) * ((3 + j) % 2 == 0 ? 1 : -1);
        if (!multiply(term, m[0][c[e]], minor) || !accumulate(out, term, sign)) return std::nullopt;
      }
    }
    return form;
  }

  // The sign of det [a; b; c; x], or nullopt when x's entries are too large.
  std::optional<int> sign_at(const std::array<mpz_class, 4>& x) const {
    FixedInteger<kCofactor + E + 2> sum;
    for (int j = 0; j < 4; ++j) {
      FixedInteger<E> xj;
      FixedInteger<kCofactor + E> term;
      if (!xj.assign(x[j]) || !multiply(term, cofactor_[j], xj) || !accumulate(sum, term, 1))
        return std::nullopt;
    }
    return sum.sign;
  }

 private:
  static constexpr int E = 4;                  // entries up to 256 bits, as fixed_sign_of_det4
  static constexpr int kCofactor = 3 * E + 3;  // a 3x3 determinant of such entries, with carries
  FixedInteger<kCofactor> cofactor_[4];
};

}  // namespace morphex::detail

// SPDX-License-Identifier: GPL-3.0-or-later
#include "exact/input_grid.h"

#include "exact/number_parts.h"

#include <cstring>
#include <unordered_map>

namespace morphex::detail {

namespace {

using Coordinate = InputGrid::Coordinate;
using GridPoint = InputGrid::GridPoint;
using Xyz = std::array<double, 3>;
// A numerator or a quotient while the grid is built (sign and magnitude, GMP's limbs).
using Limbs = FixedInteger<2>;

// Past this many distinct denominators the mesh is not a rotated one (each vertex of a Boolean's
// result has its own), and the grid's lcm would pass its bound anyway.
constexpr std::size_t kMaxDenominators = 4096;

// One coordinate before the common denominator is known: its numerator, and the key of its
// denominator (a rational's, by index into the distinct ones; a double's, by its exponent).
struct Pending {
  Limbs numerator;
  std::int32_t exponent = 0;      // a double's
  std::uint32_t denominator = 0;  // a rational's, + 1 (0: a double)
};

// The sign of a two's complement integer.
template <int N>
int sign(const WideInt<N>& x) {
  if (x.negative()) return -1;
  for (int i = 0; i < N; ++i)
    if (x.limb[i] != 0) return 1;
  return 0;
}

// a d - b c, below 2^253 in magnitude for differences below 2^126.
WideInt<4> cross_minor(const Coordinate& a, const Coordinate& b, const Coordinate& c,
                       const Coordinate& d) {
  WideInt<4> out = multiply<4>(a, d);
  out -= multiply<4>(b, c);
  return out;
}

Coordinate minus(const Coordinate& a, const Coordinate& b) {
  Coordinate d = a;
  d -= b;  // below 2^126: no wrap
  return d;
}

}  // namespace

std::unique_ptr<InputGrid> InputGrid::build(const std::vector<Input>& inputs,
                                            bool (*constructed)(const Point&)) {
  std::vector<Pending> pending(3 * inputs.size());
  std::unordered_map<const mpz_class*, std::uint32_t, MpzValueHash, MpzValueEqual> index;
  std::vector<const mpz_class*> denominators;
  int lowest = 0;  // the lowest exponent of a double's odd part, if negative
  auto add_double = [&](Pending& c, double x) {
    if (x == 0) return;
    const OddTimesPower parts = odd_times_power(x);
    c.numerator.limb[0] = std::uint64_t(parts.odd < 0 ? -parts.odd : parts.odd);
    c.numerator.size = 1;
    c.numerator.sign = parts.odd < 0 ? -1 : 1;
    c.exponent = parts.exponent;
    lowest = std::min(lowest, parts.exponent);
  };
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    Pending* c = &pending[3 * i];
    if (const Xyz* xyz = inputs[i].doubles) {
      for (int k = 0; k < 3; ++k) add_double(c[k], (*xyz)[k]);
      continue;
    }
    const Point& p = *inputs[i].point;
    if (has_double_coordinates(p)) {
      const auto& a = CGAL::approx(p);
      for (int k = 0; k < 3; ++k) add_double(c[k], a.cartesian(k).inf());
      continue;
    }
    if (constructed(p)) return nullptr;
    const auto& e = CGAL::exact(p);
    for (int k = 0; k < 3; ++k) {
      const mpq_class& x = e.cartesian(k);
      if (!c[k].numerator.assign(x.get_num())) return nullptr;
      const auto [at, added] = index.try_emplace(&x.get_den(), std::uint32_t(denominators.size()));
      if (added) {
        denominators.push_back(&x.get_den());
        if (denominators.size() > kMaxDenominators) return nullptr;
      }
      c[k].denominator = at->second + 1;
    }
  }
  // The common denominator: the distinct denominators' lcm, times the doubles' power of two.
  mpz_class common = 1;
  for (const mpz_class* d : denominators) {
    mpz_lcm(common.get_mpz_t(), common.get_mpz_t(), d->get_mpz_t());
    if (mpz_sizeinbase(common.get_mpz_t(), 2) > kMaxDenominatorBits) return nullptr;
  }
  if (lowest < 0) {
    const mp_bitcnt_t twos = mpz_scan1(common.get_mpz_t(), 0);
    if (mp_bitcnt_t(-lowest) > twos)
      mpz_mul_2exp(common.get_mpz_t(), common.get_mpz_t(), mp_bitcnt_t(-lowest) - twos);
    if (mpz_sizeinbase(common.get_mpz_t(), 2) > kMaxDenominatorBits) return nullptr;
  }
  // Each coordinate is its numerator times the common denominator over its own: one quotient
  // per distinct denominator, and one per exponent of a double, common 2^exponent (an integer:
  // 2^-lowest divides common). A double's odd part is at least 1, so exponents past lowest +
  // kBits give integers past the bound.
  std::vector<Limbs> by_denominator(denominators.size());
  for (std::size_t d = 0; d < denominators.size(); ++d) {
    mpz_class q;
    mpz_divexact(q.get_mpz_t(), common.get_mpz_t(), denominators[d]->get_mpz_t());
    by_denominator[d].assign(q);  // below 2^kMaxDenominatorBits: fits
  }
  std::vector<Limbs> by_exponent;  // by exponent - lowest
  mpz_class q = common;
  mpz_tdiv_q_2exp(q.get_mpz_t(), q.get_mpz_t(), mp_bitcnt_t(-lowest));
  for (int shift = 0; shift < kBits; ++shift, q *= 2) {
    Limbs quotient;
    if (!quotient.assign(q)) break;
    by_exponent.push_back(quotient);
  }
  auto grid = std::make_unique<InputGrid>();
  grid->points_.resize(inputs.size());
  for (std::size_t i = 0; i < pending.size(); ++i) {
    const Pending& c = pending[i];
    Coordinate& out = grid->points_[i / 3][i % 3];
    if (c.numerator.sign == 0) continue;  // zero
    const std::size_t shift = std::size_t(c.exponent - lowest);
    const Limbs* quotient = c.denominator != 0           ? &by_denominator[c.denominator - 1]
                            : shift < by_exponent.size() ? &by_exponent[shift]
                                                         : nullptr;
    FixedInteger<4> product;
    if (!quotient || !multiply(product, c.numerator, *quotient) || product.size > 2 ||
        (product.size == 2 && product.limb[1] >> (kBits - 64) != 0))
      return nullptr;
    Coordinate magnitude;
    for (int l = 0; l < product.size; ++l) magnitude.limb[l] = product.limb[l];
    out = magnitude.negated_if(product.sign < 0);
  }
  return grid;
}

int InputGrid::orientation(const GridPoint& p, const GridPoint& q, const GridPoint& r,
                           const GridPoint& s) {
  Coordinate d[3][3];
  const GridPoint* rows[3] = {&q, &r, &s};
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) d[i][k] = minus((*rows[i])[k], p[k]);
  // Along the first row, cofactors in cyclic order: sum over k of d0k (d1a d2b - d1b d2a).
  WideInt<6> det;
  for (int k = 0; k < 3; ++k) {
    const int a = (k + 1) % 3, b = (k + 2) % 3;
    det += multiply<6>(d[0][k], cross_minor(d[1][a], d[1][b], d[2][a], d[2][b]));
  }
  return sign(det);
}

int InputGrid::orientation_2(int u, int v, const GridPoint& p, const GridPoint& q,
                             const GridPoint& r) {
  return sign(
      cross_minor(minus(q[u], p[u]), minus(q[v], p[v]), minus(r[u], p[u]), minus(r[v], p[v])));
}

int InputGrid::compare(int axis, const GridPoint& p, const GridPoint& q) {
  return sign(minus(p[axis], q[axis]));
}

InputGrid::Plane::Plane(const GridPoint& a, const GridPoint& b, const GridPoint& c) : a_(&a) {
  Coordinate e[3], f[3];
  for (int k = 0; k < 3; ++k) {
    e[k] = minus(b[k], a[k]);
    f[k] = minus(c[k], a[k]);
  }
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    normal_[k] = cross_minor(e[i], e[j], f[i], f[j]);  // (e x f)_k = e_i f_j - e_j f_i
  }
}

int InputGrid::Plane::side(const GridPoint& s) const {
  WideInt<6> sum;
  for (int k = 0; k < 3; ++k) sum += multiply<6>(minus(s[k], (*a_)[k]), normal_[k]);
  return sign(sum);
}

}  // namespace morphex::detail

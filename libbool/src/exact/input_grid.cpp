// SPDX-License-Identifier: GPL-3.0-or-later
#include "exact/input_grid.h"

#include <cstring>
#include <unordered_map>

namespace morphex::detail {

namespace {

using Coordinate = InputGrid::Coordinate;
using GridPoint = InputGrid::GridPoint;
using Difference = FixedInteger<InputGrid::kLimbs + 1>;

// A finite nonzero double as odd * 2^exponent, read from its bits.
struct OddTimesPower {
  std::uint64_t odd;
  bool negative;
  int exponent;
};
OddTimesPower odd_times_power(double x) {
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
  return {mantissa >> zeros, (bits >> 63) != 0, exponent + zeros};
}

// Denominators by value (a hash of their limbs): a rotated mesh's coordinates take turns among
// a hundred or so.
struct LimbHash {
  std::size_t operator()(const mpz_class* z) const {
    std::size_t hash = mpz_size(z->get_mpz_t());
    for (std::size_t l = 0; l < mpz_size(z->get_mpz_t()); ++l)
      hash = (hash ^ mpz_getlimbn(z->get_mpz_t(), mp_size_t(l))) * 0x100000001b3ull;
    return hash;
  }
};
struct ValueEqual {
  bool operator()(const mpz_class* a, const mpz_class* b) const { return *a == *b; }
};

// Past this many distinct denominators the mesh is not a rotated one (each vertex of a Boolean's
// result has its own), and the grid's lcm would pass its bound anyway.
constexpr std::size_t kMaxDenominators = 4096;

// One coordinate before the common denominator is known: its numerator, and the key of its
// denominator (a rational's, by index into the distinct ones; a double's, by its exponent).
struct Pending {
  Coordinate numerator;
  std::int32_t exponent = 0;      // a double's
  std::uint32_t denominator = 0;  // a rational's, + 1 (0: a double)
};

// a - b.
Difference minus(const Coordinate& a, const Coordinate& b) {
  Difference d;
  accumulate(d, a, 1);
  accumulate(d, b, -1);  // capacities fit: two limbs each, a third for the carry
  return d;
}

// a * d - b * c.
FixedInteger<2 * InputGrid::kLimbs + 3> cross_minor(const Difference& a, const Difference& b,
                                                    const Difference& c, const Difference& d) {
  FixedInteger<2 * InputGrid::kLimbs + 2> ad, bc;
  FixedInteger<2 * InputGrid::kLimbs + 3> out;
  multiply(ad, a, d);
  multiply(bc, b, c);
  accumulate(out, ad, 1);
  accumulate(out, bc, -1);
  return out;
}

}  // namespace

std::unique_ptr<InputGrid> InputGrid::build(const std::vector<const Point*>& points,
                                            bool (*constructed)(const Point&)) {
  std::vector<Pending> pending(3 * points.size());
  std::unordered_map<const mpz_class*, std::uint32_t, LimbHash, ValueEqual> index;
  std::vector<const mpz_class*> denominators;
  int lowest = 0;  // the lowest exponent of a double's odd part, if negative
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Point& p = *points[i];
    if (has_double_coordinates(p)) {
      const auto& a = CGAL::approx(p);
      for (int k = 0; k < 3; ++k) {
        const double x = a.cartesian(k).inf();
        if (x == 0) continue;
        const OddTimesPower parts = odd_times_power(x);
        Coordinate& n = pending[3 * i + k].numerator;
        n.limb[0] = parts.odd;
        n.size = 1;
        n.sign = parts.negative ? -1 : 1;
        pending[3 * i + k].exponent = parts.exponent;
        lowest = std::min(lowest, parts.exponent);
      }
      continue;
    }
    if (constructed(p)) return nullptr;
    const auto& e = CGAL::exact(p);
    for (int k = 0; k < 3; ++k) {
      const mpq_class& c = e.cartesian(k);
      if (!pending[3 * i + k].numerator.assign(c.get_num())) return nullptr;
      const auto [at, added] = index.try_emplace(&c.get_den(), std::uint32_t(denominators.size()));
      if (added) {
        denominators.push_back(&c.get_den());
        if (denominators.size() > kMaxDenominators) return nullptr;
      }
      pending[3 * i + k].denominator = at->second + 1;
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
  // per distinct denominator, and per distinct exponent of a double (common * 2^exponent, an
  // integer since 2^-lowest divides common).
  std::vector<Coordinate> by_denominator(denominators.size());
  for (std::size_t d = 0; d < denominators.size(); ++d) {
    mpz_class q;
    mpz_divexact(q.get_mpz_t(), common.get_mpz_t(), denominators[d]->get_mpz_t());
    by_denominator[d].assign(q);  // below 2^kMaxDenominatorBits: fits
  }
  std::unordered_map<int, Coordinate> by_exponent;
  auto double_quotient = [&](int exponent) -> const Coordinate* {
    const auto found = by_exponent.find(exponent);
    if (found != by_exponent.end()) return &found->second;
    mpz_class q = common;
    if (exponent < 0)
      mpz_tdiv_q_2exp(q.get_mpz_t(), q.get_mpz_t(), mp_bitcnt_t(-exponent));
    else
      mpz_mul_2exp(q.get_mpz_t(), q.get_mpz_t(), mp_bitcnt_t(exponent));
    Coordinate c;
    if (!c.assign(q)) return nullptr;
    return &by_exponent.emplace(exponent, c).first->second;
  };
  auto grid = std::make_unique<InputGrid>();
  grid->points_.resize(points.size());
  for (std::size_t i = 0; i < pending.size(); ++i) {
    const Pending& c = pending[i];
    Coordinate& out = grid->points_[i / 3][i % 3];
    if (c.numerator.sign == 0) continue;  // zero: size 0, sign 0
    const Coordinate* quotient =
        c.denominator != 0 ? &by_denominator[c.denominator - 1] : double_quotient(c.exponent);
    FixedInteger<2 * kLimbs> product;
    if (!quotient || !multiply(product, c.numerator, *quotient) || product.size > kLimbs)
      return nullptr;
    std::memcpy(out.limb, product.limb, sizeof(mp_limb_t) * std::size_t(product.size));
    out.size = product.size;
    out.sign = product.sign;
  }
  return grid;
}

int InputGrid::orientation(const GridPoint& p, const GridPoint& q, const GridPoint& r,
                           const GridPoint& s) {
  Difference d[3][3];
  const GridPoint* rows[3] = {&q, &r, &s};
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) d[i][k] = minus((*rows[i])[k], p[k]);
  // Along the first row: d00 (d11 d22 - d12 d21) - d01 (d10 d22 - d12 d20) + d02 (...).
  FixedInteger<3 * kLimbs + 6> det;
  for (int k = 0; k < 3; ++k) {
    const int a = (k + 1) % 3, b = (k + 2) % 3;  // cyclic: the cofactor's sign is built in
    FixedInteger<3 * kLimbs + 5> term;
    multiply(term, d[0][k], cross_minor(d[1][a], d[1][b], d[2][a], d[2][b]));
    accumulate(det, term, 1);
  }
  return det.sign;
}

int InputGrid::orientation_2(int u, int v, const GridPoint& p, const GridPoint& q,
                             const GridPoint& r) {
  return cross_minor(minus(q[u], p[u]), minus(q[v], p[v]), minus(r[u], p[u]), minus(r[v], p[v]))
      .sign;
}

int InputGrid::compare(int axis, const GridPoint& p, const GridPoint& q) {
  return minus(p[axis], q[axis]).sign;
}

InputGrid::Plane::Plane(const GridPoint& a, const GridPoint& b, const GridPoint& c) : a_(&a) {
  Difference e[3], f[3];
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
  FixedInteger<3 * kLimbs + 6> sum;
  for (int k = 0; k < 3; ++k) {
    FixedInteger<3 * kLimbs + 5> term;
    multiply(term, normal_[k], minus(s[k], (*a_)[k]));
    accumulate(sum, term, 1);
  }
  return sum.sign;
}

}  // namespace morphex::detail

// SPDX-License-Identifier: GPL-3.0-or-later
// Exact signed volume of a mesh: one sixth of the sum over faces of det(a, b, c).
//
// Meshes read from files have double coordinates, and every double is an integer times a power
// of two. Scaled by the smallest such power present, the coordinates become integers of at most
// kMaxBits bits, and the sum of determinants is computed exactly in fixed-size integers
// (wide_integer.h): no allocation and no gcd per face, about a hundred times faster than the sum
// of rationals. Rational coordinates over a few denominators (a rotated mesh) are summed over
// their common denominator; over many (a Boolean's or a morphology's result) by
// volume_factored.cpp.
#include <gmpxx.h>
#include <tbb/combinable.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <array>
#include <climits>
#include <cmath>
#include <cstring>
#include <optional>
#include <type_traits>
#include <unordered_map>
#include <vector>

#include "exact/number_parts.h"
#include "exact/wide_integer.h"
#include "mesh/volume_internal.h"
#include "morphex/mesh.h"

namespace morphex {
namespace {

using detail::odd_times_power;
using detail::OddTimesPower;

using Exact = std::decay_t<decltype(CGAL::exact(std::declval<FT>()))>;

// Pairwise, so that operands stay of similar size; each level's additions run in parallel.
mpz_class sum_balanced(std::vector<mpz_class>& terms) {
  if (terms.empty()) return 0;
  while (terms.size() > 1) {
    const std::size_t half = (terms.size() + 1) / 2, pairs = terms.size() - half;
    tbb::parallel_for(std::size_t(0), pairs, [&](std::size_t i) { terms[i] += terms[i + half]; });
    terms.resize(half);
  }
  return terms[0];
}

// The widths of one exact sum: coordinates below 2^Bits in magnitude, 2x2 minors below
// 2^(2 Bits + 1), determinants below 3 * 2^(3 Bits + 1), and a sum of up to 2^32 of them below
// 2^(3 Bits + 35), each with a sign bit to spare in its limbs.
// The sum over a cycle (cycle_term) needs a bit more of each: sums and differences of coordinates
// below 2^(Bits + 2), minors below 2^(2 Bits + 3), terms below 2^(3 Bits + 5).
template <int Bits, int CoordinateLimbs, int MinorLimbs, int SumLimbs>
struct Widths {
  static_assert(Bits + 2 <= 64 * CoordinateLimbs && 2 * Bits + 4 <= 64 * MinorLimbs &&
                3 * Bits + 38 <= 64 * SumLimbs);
  static constexpr int kBits = Bits;
  using Coordinate = detail::WideInt<CoordinateLimbs>;
  using Minor = detail::WideInt<MinorLimbs>;
  using Sum = detail::WideInt<SumLimbs>;
};
// Two sizes: most meshes fit the first; coordinates computed in double (a cosine of 1e-16 beside
// a radius of 10) need the second.
using NarrowWidths = Widths<100, 2, 4, 6>;
using WideWidths = Widths<160, 3, 6, 9>;
// Rational coordinates over their common denominator (a rotated mesh: the rotation's denominator
// times the doubles' powers of two) need more.
using WiderWidths = Widths<250, 4, 8, 13>;

// The spread of the mesh's double coordinates: exponents of the lowest set bit and of the bound
// above the largest magnitude; nullopt when some coordinate is not a double.
struct Spread {
  int lowest = INT_MAX, highest = INT_MIN;
};
std::optional<Spread> double_spread(const Mesh& mesh) {
  Spread s;
  for (const Point& p : mesh.points) {
    if (!has_double_coordinates(p)) return std::nullopt;
    const auto& a = CGAL::approx(p);
    for (const double x : {a.x().inf(), a.y().inf(), a.z().inf()}) {
      if (x == 0) continue;
      const OddTimesPower parts = odd_times_power(x);
      const std::uint64_t magnitude = std::uint64_t(parts.odd < 0 ? -parts.odd : parts.odd);
      s.lowest = std::min(s.lowest, parts.exponent);
      s.highest = std::max(s.highest, parts.exponent + 64 - __builtin_clzll(magnitude));
    }
  }
  return s;
}

// A coordinate times 2^-lowest: an integer below 2^Bits, that is its odd mantissa shifted left.
template <class Coordinate>
Coordinate scaled_integer(double x, int lowest) {
  if (x == 0) return {};
  const OddTimesPower parts = odd_times_power(x);
  // lowest is the least exponent of any coordinate: the shift is >= 0.
  return Coordinate::of(parts.odd).shifted_left(parts.exponent - lowest);
}

// Flattened: its nine products inlined and unrolled (a call each was most of an exact volume's
// time); forcing that on multiply itself slowed the Boolean's determinants.
template <class W>
[[gnu::flatten]] typename W::Sum determinant(const std::array<typename W::Coordinate, 3>& a,
                                             const std::array<typename W::Coordinate, 3>& b,
                                             const std::array<typename W::Coordinate, 3>& c) {
  using detail::multiply;
  constexpr int kMinor = W::Minor::kLimbs, kSum = W::Sum::kLimbs;
  typename W::Sum d;
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    typename W::Minor minor = multiply<kMinor>(b[i], c[j]);
    minor -= multiply<kMinor>(b[j], c[i]);
    d += multiply<kSum>(a[k], minor);
  }
  return d;
}

// On a cycle (a closed surface whose every edge is used once each way) the sum of det(a, b, c)
// over the faces equals, by the divergence theorem, the sum of (a_x + b_x + c_x) times the x
// component of (b - a) x (c - a): both are six times the volume the cycle winds around. Three
// products per face instead of nine.
template <class W>
[[gnu::flatten]] typename W::Sum cycle_term(const std::array<typename W::Coordinate, 3>& a,
                                            const std::array<typename W::Coordinate, 3>& b,
                                            const std::array<typename W::Coordinate, 3>& c) {
  using detail::multiply;
  typename W::Coordinate x = a[0], by = b[1], bz = b[2], cy = c[1], cz = c[2];
  x += b[0];
  x += c[0];
  by -= a[1];
  bz -= a[2];
  cy -= a[1];
  cz -= a[2];
  typename W::Minor normal_x = multiply<W::Minor::kLimbs>(by, cz);
  normal_x -= multiply<W::Minor::kLimbs>(bz, cy);
  return multiply<W::Sum::kLimbs>(x, normal_x);
}

// The sum over the faces of det(a, b, c), each vertex's integer coordinates in `points`; by
// cycle_term when `cycle` says the faces form one.
template <class W>
mpz_class sum_of_determinants(const Mesh& mesh,
                              const std::vector<std::array<typename W::Coordinate, 3>>& points,
                              bool cycle) {
  tbb::combinable<typename W::Sum> partial;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, mesh.triangles.size(), 4096),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      typename W::Sum& sum = partial.local();
                      for (std::size_t f = range.begin(); f != range.end(); ++f) {
                        const Triangle& t = mesh.triangles[f];
                        sum += cycle ? cycle_term<W>(points[t[0]], points[t[1]], points[t[2]])
                                     : determinant<W>(points[t[0]], points[t[1]], points[t[2]]);
                      }
                    });
  typename W::Sum total;
  partial.combine_each([&](const typename W::Sum& s) { total += s; });
  return total.to_mpz();
}

template <class W>
Exact integer_volume_times_6(const Mesh& mesh, int lowest, bool cycle) {
  using Coordinate = typename W::Coordinate;
  std::vector<std::array<Coordinate, 3>> points(mesh.points.size());
  tbb::parallel_for(std::size_t(0), points.size(), [&](std::size_t v) {
    const auto& a = CGAL::approx(mesh.points[v]);
    points[v] = {scaled_integer<Coordinate>(a.x().inf(), lowest),
                 scaled_integer<Coordinate>(a.y().inf(), lowest),
                 scaled_integer<Coordinate>(a.z().inf(), lowest)};
  });
  // Each determinant is a product of three coordinates: scale by 2^(3 lowest).
  mpq_class volume(sum_of_determinants<W>(mesh, points, cycle));
  const long shift = 3L * lowest;
  if (shift >= 0)
    mpz_mul_2exp(volume.get_num_mpz_t(), volume.get_num_mpz_t(), shift);
  else
    mpz_mul_2exp(volume.get_den_mpz_t(), volume.get_den_mpz_t(), -shift);
  volume.canonicalize();
  return Exact(volume);
}

// Past this many bits of common denominator, the factored sum (volume_factored.cpp).
constexpr std::size_t kMaxDenominatorBits = 4096;

// Coordinate i over the common denominator: its numerator times quotient[quotient_of[i]], the
// common denominator over its own, one per distinct denominator.
struct OverCommon {
  std::vector<const mpq_class*> coordinate;
  mpz_class common = 1;
  std::vector<mpz_class> quotient;
  std::vector<std::uint32_t> quotient_of;
  std::size_t bits = 0;  // bounds the bits of every numerator times its quotient
};

std::optional<OverCommon> over_common_denominator(const Mesh& mesh) {
  OverCommon o;
  const std::size_t n = mesh.points.size();
  o.coordinate.resize(3 * n);
  for (std::size_t v = 0; v < n; ++v) {
    const auto& p = CGAL::exact(mesh.points[v]);
    for (int k = 0; k < 3; ++k) {
      const mpq_class& c = p.cartesian(k);
      o.coordinate[3 * v + k] = &c;
      if (mpz_divisible_p(o.common.get_mpz_t(), c.get_den_mpz_t())) continue;
      mpz_lcm(o.common.get_mpz_t(), o.common.get_mpz_t(), c.get_den_mpz_t());
      if (mpz_sizeinbase(o.common.get_mpz_t(), 2) > kMaxDenominatorBits) return std::nullopt;
    }
  }
  // A rotated mesh's coordinates take turns among a hundred denominators or so (the rotation's
  // times powers of two): each distinct one gets its quotient once, found by value.
  std::unordered_map<const mpz_class*, std::uint32_t, detail::MpzValueHash, detail::MpzValueEqual>
      quotient_index(64);
  o.quotient_of.resize(3 * n);
  std::vector<std::size_t> quotient_bits;
  for (std::size_t i = 0; i < 3 * n; ++i) {
    const mpz_class& den = o.coordinate[i]->get_den();
    const auto [at, added] = quotient_index.try_emplace(&den, std::uint32_t(o.quotient.size()));
    if (added) {
      o.quotient.emplace_back();
      mpz_divexact(o.quotient.back().get_mpz_t(), o.common.get_mpz_t(), den.get_mpz_t());
      quotient_bits.push_back(mpz_sizeinbase(o.quotient.back().get_mpz_t(), 2));
    }
    o.quotient_of[i] = at->second;
    o.bits = std::max(o.bits, mpz_sizeinbase(o.coordinate[i]->get_num_mpz_t(), 2) +
                                  quotient_bits[o.quotient_of[i]]);
  }
  return o;
}

// The sum of determinants over the common denominator in fixed-size integers: no allocation per
// coordinate or product. Every numerator times its quotient is below 2^W::kBits.
template <class W>
mpz_class sum_of_determinants(const Mesh& mesh, const OverCommon& o, bool cycle) {
  using Coordinate = typename W::Coordinate;
  std::vector<Coordinate> quotient(o.quotient.size());  // few: converted once each
  for (std::size_t q = 0; q < quotient.size(); ++q) quotient[q] = Coordinate::of_mpz(o.quotient[q]);
  std::vector<std::array<Coordinate, 3>> points(mesh.points.size());
  tbb::parallel_for(std::size_t(0), points.size(), [&](std::size_t v) {
    for (int k = 0; k < 3; ++k) {
      const std::size_t i = 3 * v + k;
      points[v][k] = detail::multiply<Coordinate::kLimbs>(
          Coordinate::of_mpz(o.coordinate[i]->get_num()), quotient[o.quotient_of[i]]);
    }
  });
  return sum_of_determinants<W>(mesh, points, cycle);
}

// Rational coordinates of a rotated mesh mostly share their denominators: over their least common
// multiple D they are integers, and the sum of determinants is a sum of integers (fixed-size when
// they fit, else GMP's; no gcd per face) divided by D^3 once. Nullopt when D grows past
// kMaxDenominatorBits (a denominator per constructed vertex), for the factored sum.
std::optional<Exact> common_denominator_volume_times_6(const Mesh& mesh, bool cycle) {
  static_assert(std::is_same_v<Exact, mpq_class>, "Epeck's exact number type is GMP's");
  const std::optional<OverCommon> o = over_common_denominator(mesh);
  if (!o) return std::nullopt;
  const mpz_class cube = o->common * o->common * o->common;
  if (o->bits <= std::size_t(WiderWidths::kBits) &&
      mesh.triangles.size() < (std::size_t(1) << 32)) {
    const mpz_class sum = o->bits <= std::size_t(NarrowWidths::kBits)
                              ? sum_of_determinants<NarrowWidths>(mesh, *o, cycle)
                          : o->bits <= std::size_t(WideWidths::kBits)
                              ? sum_of_determinants<WideWidths>(mesh, *o, cycle)
                              : sum_of_determinants<WiderWidths>(mesh, *o, cycle);
    Exact out(sum, cube);
    out.canonicalize();
    return out;
  }
  std::vector<mpz_class> integer(o->coordinate.size());
  tbb::parallel_for(std::size_t(0), integer.size(), [&](std::size_t i) {
    integer[i] = o->coordinate[i]->get_num() * o->quotient[o->quotient_of[i]];
  });
  std::vector<mpz_class> terms(mesh.triangles.size());
  tbb::parallel_for(std::size_t(0), terms.size(), [&](std::size_t i) {
    const Triangle& t = mesh.triangles[i];
    const mpz_class *a = &integer[3 * t[0]], *b = &integer[3 * t[1]], *c = &integer[3 * t[2]];
    // a . (b x c)
    terms[i] = a[0] * (b[1] * c[2] - b[2] * c[1]) + a[1] * (b[2] * c[0] - b[0] * c[2]) +
               a[2] * (b[0] * c[1] - b[1] * c[0]);
  });
  Exact out(sum_balanced(terms), cube);
  out.canonicalize();
  return out;
}

// The exact sum by integers when the coordinates allow it.
std::optional<Exact> integer_volume_times_6(const Mesh& mesh, bool cycle) {
  if (mesh.triangles.size() >= (std::size_t(1) << 32)) return std::nullopt;
  const std::optional<Spread> spread = double_spread(mesh);
  if (!spread) return std::nullopt;
  if (spread->lowest == INT_MAX) return Exact(0);  // every coordinate is zero
  const int bits = spread->highest - spread->lowest;
  if (bits <= NarrowWidths::kBits)
    return integer_volume_times_6<NarrowWidths>(mesh, spread->lowest, cycle);
  if (bits <= WideWidths::kBits)
    return integer_volume_times_6<WideWidths>(mesh, spread->lowest, cycle);
  return std::nullopt;
}

FT volume(const Mesh& mesh, bool cycle) {
  std::optional<Exact> six = integer_volume_times_6(mesh, cycle);
  if (!six) six = common_denominator_volume_times_6(mesh, cycle);
  if (!six) six = detail::factored_volume_times_6(mesh);
  return FT(*six / Exact(6));
}

}  // namespace

FT signed_volume(const Mesh& mesh) {
  return volume(mesh, false);
}

FT detail::signed_volume_of_cycle(const Mesh& mesh) {
  return volume(mesh, true);
}

namespace {
// The sign of the sum of det(a, b, c) in doubles, when the rounding errors cannot change it:
// each term is within 8 eps of its permanent (|ax| (|by cz| + |bz cy|) + ...), and a sum of n
// terms within (n - 1) eps of the sum of their magnitudes in any order, eps = 2^-52 so that it
// holds under any rounding mode; underflow adds at most 2^-1074 per operation. With `xyz` whose
// coordinates are within `error` of the exact ones, each exact determinant is moreover within
// 18 error (m + error)^2 of the doubles' one (six products of three coordinates, each moving by
// at most 3 error (m + error)^2), m the largest magnitude. Undecided when a coordinate is not a
// double (without `xyz`) or the magnitudes are out of range.
std::optional<CGAL::Sign> volume_sign_by_doubles(const Mesh& mesh,
                                                 const std::vector<std::array<double, 3>>* xyz,
                                                 double error) {
  struct Sum {
    double det = 0, permanent = 0, reach = 0;
    bool doubles = true;
  };
  const Sum sum = tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, mesh.num_triangles(), 4096), Sum{},
      [&](const tbb::blocked_range<std::size_t>& range, Sum s) {
        for (std::size_t f = range.begin(); f != range.end() && s.doubles; ++f) {
          double x[3][3];
          for (int k = 0; k < 3; ++k) {
            const VertexIndex v = mesh.triangles[f][k];
            if (xyz) {
              for (int i = 0; i < 3; ++i) x[k][i] = (*xyz)[v][i];
              continue;
            }
            const auto& p = CGAL::approx(mesh.points[v]);
            s.doubles = s.doubles && p.x().is_point() && p.y().is_point() && p.z().is_point();
            x[k][0] = p.x().inf(), x[k][1] = p.y().inf(), x[k][2] = p.z().inf();
          }
          const auto &a = x[0], &b = x[1], &c = x[2];
          s.det += a[0] * (b[1] * c[2] - b[2] * c[1]) + a[1] * (b[2] * c[0] - b[0] * c[2]) +
                   a[2] * (b[0] * c[1] - b[1] * c[0]);
          s.permanent += std::fabs(a[0]) * (std::fabs(b[1] * c[2]) + std::fabs(b[2] * c[1])) +
                         std::fabs(a[1]) * (std::fabs(b[2] * c[0]) + std::fabs(b[0] * c[2])) +
                         std::fabs(a[2]) * (std::fabs(b[0] * c[1]) + std::fabs(b[1] * c[0]));
          // (std::max, not a library call to std::fmax: a NaN fails the permanent's test.)
          for (int k = 0; k < 3; ++k)
            s.reach = std::max({s.reach, std::fabs(a[k]), std::fabs(b[k]), std::fabs(c[k])});
        }
        return s;
      },
      [](const Sum& a, const Sum& b) {
        return Sum{a.det + b.det, a.permanent + b.permanent, std::max(a.reach, b.reach),
                   a.doubles && b.doubles};
      });
  if (!sum.doubles || !(sum.permanent < 1e300) || !(sum.reach < 1e100)) return std::nullopt;
  const double n = double(mesh.num_triangles()), eps = 0x1p-52;
  // The permanents' own sum is rounded too: a factor 2 covers it, and the errors' term.
  const double m = (sum.reach + error) * (1 + 0x1p-50);
  const double bound = 2 * (n + 8) * eps * sum.permanent + 16 * n * 0x1p-1074 +
                       (error > 0 ? 2 * n * 18 * error * m * m : 0);
  if (sum.det > bound) return CGAL::POSITIVE;
  if (-sum.det > bound) return CGAL::NEGATIVE;
  return std::nullopt;
}
}  // namespace

namespace detail {
CGAL::Sign signed_volume_sign(const Mesh& mesh, const std::vector<std::array<double, 3>>& doubles,
                              double error) {
  if (doubles.size() == mesh.num_vertices() && !doubles.empty() && std::isfinite(error))
    if (const auto sign = volume_sign_by_doubles(mesh, &doubles, error)) return *sign;
  return morphex::signed_volume_sign(mesh);
}
}  // namespace detail

CGAL::Sign signed_volume_sign(const Mesh& mesh) {
  if (const auto sign = volume_sign_by_doubles(mesh, nullptr, 0)) return *sign;
  {
    CGAL::Protect_FPU_rounding<true> rounding;
    CGAL::Interval_nt<false> sum = 0;
    for (const Triangle& t : mesh.triangles) {
      const auto& a = CGAL::approx(mesh.points[t[0]]);
      const auto& b = CGAL::approx(mesh.points[t[1]]);
      const auto& c = CGAL::approx(mesh.points[t[2]]);
      sum += a.x() * (b.y() * c.z() - b.z() * c.y()) + a.y() * (b.z() * c.x() - b.x() * c.z()) +
             a.z() * (b.x() * c.y() - b.y() * c.x());
    }
    const CGAL::Uncertain<CGAL::Sign> sign = CGAL::sign(sum);
    if (CGAL::is_certain(sign)) return CGAL::get_certain(sign);
  }
  return CGAL::sign(signed_volume(mesh));
}

}  // namespace morphex

// SPDX-License-Identifier: GPL-3.0-or-later
// Orientation signs of points with double coordinates by plain double arithmetic and an error
// bound (a semi-static filter after Shewchuk's): a few multiplications instead of interval
// arithmetic. Undecided (nullopt) when the determinant is within the bound, or when the
// magnitudes leave the range where the bound holds (underflow, overflow); callers then take the
// interval and exact stages.
//
// The bounds hold under any rounding mode: Shewchuk's are for rounding to nearest, and the
// predicates of a traversal run with the FPU rounding upward (directed rounding errs by up to one
// unit in the last place instead of half), so his coefficients are doubled and rounded up.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <initializer_list>
#include <optional>

namespace morphex::detail {

using Xyz = std::array<double, 3>;

// Inside [kTiny, kHuge] no product of the filters underflows or overflows.
inline constexpr double kStaticTiny = 1e-140, kStaticHuge = 1e140;

// det [a, b, c] in doubles, and the sum of the magnitudes of its six products (its permanent),
// which the error bounds scale with.
struct DetAndPermanent {
  double det, permanent;
};
inline DetAndPermanent det_and_permanent(double ax, double ay, double az, double bx, double by,
                                         double bz, double cx, double cy, double cz) {
  const double bxcy = bx * cy, cxby = cx * by, cxay = cx * ay, axcy = ax * cy, axby = ax * by,
               bxay = bx * ay;
  return {az * (bxcy - cxby) + bz * (cxay - axcy) + cz * (axby - bxay),
          (std::fabs(bxcy) + std::fabs(cxby)) * std::fabs(az) +
              (std::fabs(cxay) + std::fabs(axcy)) * std::fabs(bz) +
              (std::fabs(axby) + std::fabs(bxay)) * std::fabs(cz)};
}

// sign det [a, b, c] for rows rounded once each from differences of doubles (or exact, which
// the bound covers too): the core of static_orientation.
inline std::optional<int> static_orientation_of_differences(double ax, double ay, double az,
                                                            double bx, double by, double bz,
                                                            double cx, double cy, double cz) {
  // All four points in one plane perpendicular to an axis (flat faces of CAD models): the
  // differences along it are exactly zero, and so is the determinant.
  if ((ax == 0 && bx == 0 && cx == 0) || (ay == 0 && by == 0 && cy == 0) ||
      (az == 0 && bz == 0 && cz == 0))
    return 0;
  const auto [det, permanent] = det_and_permanent(ax, ay, az, bx, by, bz, cx, cy, cz);
  // Shewchuk's orient3d bound A is (7 + 56 eps) eps with eps = 2^-53.
  const double bound = 1.6e-15 * permanent;
  if (!(permanent < kStaticHuge)) return std::nullopt;  // also NaN
  if (det > bound) return permanent > kStaticTiny ? std::optional<int>(1) : std::nullopt;
  if (-det > bound) return permanent > kStaticTiny ? std::optional<int>(-1) : std::nullopt;
  return std::nullopt;
}

// sign det [q - p, r - p, s - p]: CGAL's orientation(p, q, r, s).
inline std::optional<int> static_orientation(const Xyz& p, const Xyz& q, const Xyz& r,
                                             const Xyz& s) {
  return static_orientation_of_differences(q[0] - p[0], q[1] - p[1], q[2] - p[2], r[0] - p[0],
                                           r[1] - p[1], r[2] - p[2], s[0] - p[0], s[1] - p[1],
                                           s[2] - p[2]);
}

// sign det [(qu, qv), (ru, rv)] for differences q - p, r - p rounded from doubles (as computed
// below): orientation_2 of p, q, r when the differences share one origin p.
inline std::optional<int> static_orientation_2_of_differences(double qu, double qv, double ru,
                                                              double rv) {
  if ((qu == 0 && ru == 0) || (qv == 0 && rv == 0)) return 0;  // exactly on one axis-parallel line
  const double left = qu * rv, right = qv * ru;
  const double det = left - right, sum = std::fabs(left) + std::fabs(right);
  // Shewchuk's orient2d bound A is (3 + 16 eps) eps.
  const double bound = 7e-16 * sum;
  if (!(sum < kStaticHuge) || !(sum > kStaticTiny)) return std::nullopt;
  if (det > bound) return 1;
  if (-det > bound) return -1;
  return std::nullopt;
}

// m (the largest entry) with the errors, rounded up whatever the rounding mode.
inline double entry_bound(double m, double error) {
  return (m + 2 * error) * (1 + 0x1p-50);
}
// Below the normal range a product loses its relative accuracy: slack is never less than this.
inline constexpr double kNearSlackFloor = 1e-280;

// Points known only within `error` of the doubles given, in each coordinate (a rational input's
// interval's lower end): each difference is then off by up to 2 error besides its rounding, which
// moves each of the six products of the determinant by at most 3 (2 error) m^2, with m bounding the
// entries and their errors (entry_bound of the largest difference): 36 error m^2 in all, added to
// the bound (37: the rounding of the bound itself). No shortcut for coordinates that agree: the
// points they stand for may not. This slack serves every evaluation of that determinant (the
// check's precomputed planes too).
inline double orientation_near_slack(double m, double error) {
  const double e = entry_bound(m, error);
  return std::max(37 * error * e * e, kNearSlackFloor);
}

inline std::optional<int> static_orientation_near(const Xyz& p, const Xyz& q, const Xyz& r,
                                                  const Xyz& s, double error) {
  const double ax = q[0] - p[0], ay = q[1] - p[1], az = q[2] - p[2], bx = r[0] - p[0],
               by = r[1] - p[1], bz = r[2] - p[2], cx = s[0] - p[0], cy = s[1] - p[1],
               cz = s[2] - p[2];
  // std::max, not std::fmax (a library call): a NaN fails the permanent's test below anyway.
  const double m =
      std::max({std::fabs(ax), std::fabs(ay), std::fabs(az), std::fabs(bx), std::fabs(by),
                std::fabs(bz), std::fabs(cx), std::fabs(cy), std::fabs(cz)});
  const auto [det, permanent] = det_and_permanent(ax, ay, az, bx, by, bz, cx, cy, cz);
  if (!(permanent < kStaticHuge) || !(permanent > kStaticTiny)) return std::nullopt;
  const double bound = 1.6e-15 * permanent + orientation_near_slack(m, error);
  if (det > bound) return 1;
  if (-det > bound) return -1;
  return std::nullopt;
}

// sign det [a, b, d] (the turn from a to b seen along d) for rows a, b rounded once from
// differences of points known within `error` of their doubles (or exact vectors) and d exact.
// Each entry of a and b is off by up to 2 error besides its rounding, which moves the
// determinant by at most 6 (2 error) e |d| for each row and 6 (2 error)^2 |d| for both, e bounding
// the entries with their errors and |d| d's largest entry: 48 error e |d| (49 with the bound's
// rounding).
inline std::optional<int> static_turn_along(const Xyz& a, const Xyz& b, const Xyz& d,
                                            double error) {
  const auto [det, permanent] =
      det_and_permanent(a[0], a[1], a[2], b[0], b[1], b[2], d[0], d[1], d[2]);
  if (!(permanent < kStaticHuge) || !(permanent > kStaticTiny)) return std::nullopt;
  double bound = 1.6e-15 * permanent;
  if (error > 0) {
    const double m = std::max({std::fabs(a[0]), std::fabs(a[1]), std::fabs(a[2]), std::fabs(b[0]),
                               std::fabs(b[1]), std::fabs(b[2])}),
                 md = std::max({std::fabs(d[0]), std::fabs(d[1]), std::fabs(d[2])});
    bound += std::max(49 * error * entry_bound(m, error) * md, kNearSlackFloor);
  }
  if (det > bound) return 1;
  if (-det > bound) return -1;
  return std::nullopt;
}

// The same in two coordinates: each of the two products moves by at most 4 error m, 8 error m
// in all (9 with the bound's rounding).
inline std::optional<int> static_orientation_2_near(int u, int v, const Xyz& p, const Xyz& q,
                                                    const Xyz& r, double error) {
  const double qu = q[u] - p[u], qv = q[v] - p[v], ru = r[u] - p[u], rv = r[v] - p[v];
  const double m = std::max({std::fabs(qu), std::fabs(qv), std::fabs(ru), std::fabs(rv)});
  const double left = qu * rv, right = qv * ru;
  const double det = left - right, sum = std::fabs(left) + std::fabs(right);
  if (!(sum < kStaticHuge) || !(sum > kStaticTiny)) return std::nullopt;
  const double bound = 7e-16 * sum + std::max(9 * error * entry_bound(m, error), kNearSlackFloor);
  if (det > bound) return 1;
  if (-det > bound) return -1;
  return std::nullopt;
}

// sign det [q - p, r - p] in the coordinates u, v: CGAL's orientation of the projected points.
inline std::optional<int> static_orientation_2(int u, int v, const Xyz& p, const Xyz& q,
                                               const Xyz& r) {
  return static_orientation_2_of_differences(q[u] - p[u], q[v] - p[v], r[u] - p[u], r[v] - p[v]);
}

// The exact sign of the sum of terms[0 .. n) (finite, no overflow in the partial sums; n at most
// 32), by Shewchuk's growing expansion: each Two-Sum is exact when the FPU rounds to nearest,
// which the caller must ensure; the expansion's components do not overlap and grow in magnitude,
// so the last one carries the sign.
inline int sign_of_terms(const double* terms, int n) {
  double e[32];
  int m = 0;
  for (int t = 0; t < n; ++t) {
    double q = terms[t];
    int k = 0;
    for (int i = 0; i < m; ++i) {
      const double x = q + e[i], b_virtual = x - q, a_virtual = x - b_virtual;
      const double y = (q - a_virtual) + (e[i] - b_virtual);
      q = x;
      if (y != 0) e[k++] = y;
    }
    if (q != 0) e[k++] = q;
    m = k;
  }
  return m == 0 ? 0 : e[m - 1] > 0 ? 1 : -1;
}

// The same for at most 8 terms written out, by the rounded sum when it clears its error: n - 1
// additions, each off by at most half an ulp of a partial sum, no larger than the sum of the
// magnitudes; the bound takes four times that, which also covers the rounding of the magnitudes'
// sum. (A sum of subnormals is exact; an infinite bound falls through.) Most sums it is asked
// about are far from zero: the quadrants of a star's directions around a vertex.
inline int sign_of_sum(std::initializer_list<double> terms) {
  double sum = 0, magnitude = 0;
  for (const double t : terms) sum += t, magnitude += std::fabs(t);
  const double bound = double(terms.size()) * 0x1p-51 * magnitude;
  if (sum > bound) return 1;
  if (sum < -bound) return -1;
  return sign_of_terms(terms.begin(), int(terms.size()));
}

// The exact stage of orient3d and orient2d on doubles, without integers: the differences of
// nearby coordinates are exact doubles (Sterbenz), a product of doubles is exactly a sum of two
// (Veltkamp's split, Dekker's product), so a determinant of differences is exactly a sum of a few
// dozen doubles, whose sign a growing expansion gives. Round to nearest (the caller ensures it).
// nullopt when a difference is not exact or a magnitude leaves [2^-250, 2^250], the range where
// every product and its rounding error are normal doubles; the caller then decides in integers.

// a - b exactly, or false.
inline bool exact_difference(double a, double b, double& d) {
  d = a - b;
  const double b_virtual = a - d, a_virtual = d + b_virtual;
  if ((a - a_virtual) + (b_virtual - b) != 0) return false;
  // Products of three such differences, and their rounding errors, stay normal doubles.
  return d == 0 || (std::fabs(d) > 0x1p-250 && std::fabs(d) < 0x1p250);
}

// a * b = hi + lo exactly (|a|, |b| well inside the range checked above).
inline void exact_product(double a, double b, double& hi, double& lo) {
  constexpr double kSplitter = 134217729.0;  // 2^27 + 1
  const double ca = kSplitter * a, a_hi = ca - (ca - a), a_lo = a - a_hi;
  const double cb = kSplitter * b, b_hi = cb - (cb - b), b_lo = b - b_hi;
  hi = a * b;
  lo = ((a_hi * b_hi - hi) + a_hi * b_lo + a_lo * b_hi) + a_lo * b_lo;
}

// Four points lie in one plane when, seen along a coordinate axis, they stand at no more than two
// places: they lie on one or two lines parallel to that axis. Comparisons only, no arithmetic:
// extrusions, fillets and prisms along an axis (CAD models) put such quadruples, exactly coplanar,
// before the exact stage by the thousand, with coordinates of mixed magnitudes whose differences
// are often not doubles.
inline bool on_two_axis_lines(const Xyz& p, const Xyz& q, const Xyz& r, const Xyz& s) {
  for (int axis = 0; axis < 3; ++axis) {
    const int u = axis == 0 ? 1 : 0, v = axis == 2 ? 1 : 2;
    auto same = [&](const Xyz& x, const Xyz& y) { return x[u] == y[u] && x[v] == y[v]; };
    const Xyz* second = nullptr;  // the first place other than p's
    bool two = true;
    for (const Xyz* x : {&q, &r, &s}) {
      if (same(*x, p)) continue;
      if (second == nullptr)
        second = x;
      else if (!same(*x, *second))
        two = false;
    }
    if (two) return true;
  }
  return false;
}

// p, q, r, s form a parallelogram, perhaps a flat one (so they are coplanar): one of the exact
// differences u = q - p, v = r - p equals that of the opposite side. A mesh with
// repeated features (a lattice, an array of holes) placed by an affine map in doubles keeps such
// exact copies, by the ten thousand in one of the benchmark's CAD meshes.
inline bool parallelogram(const Xyz& p, const Xyz& q, const Xyz& r, const Xyz& s, const double* u,
                          const double* v) {
  auto equal = [](const Xyz& a, const Xyz& b, const double* d) {  // a - b == d exactly
    for (int k = 0; k < 3; ++k) {
      double e;
      if (!exact_difference(a[k], b[k], e) || e != d[k]) return false;
    }
    return true;
  };
  // The sides opposite each other: (p, q) and (r, s) either way, or (p, r) and (q, s).
  return equal(s, r, u) || equal(r, s, u) || equal(q, s, v);
}

// sign det [q - p, r - p, s - p] exactly (CGAL's orientation(p, q, r, s)), or nullopt.
inline std::optional<int> exact_orientation_of_doubles(const Xyz& p, const Xyz& q, const Xyz& r,
                                                       const Xyz& s) {
  double u[3], v[3], w[3];
  for (int k = 0; k < 3; ++k)
    if (!exact_difference(q[k], p[k], u[k]) || !exact_difference(r[k], p[k], v[k]) ||
        !exact_difference(s[k], p[k], w[k]))
      return std::nullopt;
  if (parallelogram(p, q, r, s, u, v)) return 0;
  // u . (v x w): six products u_i v_j w_k, each exactly four doubles.
  static constexpr int kTerms[6][4] = {{0, 1, 2, 1},  {0, 2, 1, -1}, {1, 2, 0, 1},
                                       {1, 0, 2, -1}, {2, 0, 1, 1},  {2, 1, 0, -1}};
  double terms[24];
  int n = 0;
  for (const auto& t : kTerms) {
    double h, l, hh, hl, lh, ll;
    exact_product(v[t[1]], w[t[2]], h, l);
    exact_product(u[t[0]], h, hh, hl);
    exact_product(u[t[0]], l, lh, ll);
    for (const double x : {hh, hl, lh, ll}) terms[n++] = t[3] * x;
  }
  return sign_of_terms(terms, n);
}

// sign det [q - p, r - p] in the coordinates u, v exactly (orientation_2 of the projections), or
// nullopt.
inline std::optional<int> exact_orientation_2_of_doubles(int u, int v, const Xyz& p, const Xyz& q,
                                                         const Xyz& r) {
  double qu, qv, ru, rv;
  if (!exact_difference(q[u], p[u], qu) || !exact_difference(q[v], p[v], qv) ||
      !exact_difference(r[u], p[u], ru) || !exact_difference(r[v], p[v], rv))
    return std::nullopt;
  double terms[4];
  exact_product(qu, rv, terms[0], terms[1]);
  exact_product(qv, ru, terms[2], terms[3]);
  terms[2] = -terms[2];
  terms[3] = -terms[3];
  return sign_of_terms(terms, 4);
}

}  // namespace morphex::detail

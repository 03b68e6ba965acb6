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

#include <array>
#include <cmath>
#include <optional>

namespace morphex::detail {

using Xyz = std::array<double, 3>;

// Inside [kTiny, kHuge] no product of the filters underflows or overflows.
inline constexpr double kStaticTiny = 1e-140, kStaticHuge = 1e140;

// sign det [q - p, r - p, s - p]: CGAL's orientation(p, q, r, s).
inline std::optional<int> static_orientation(const Xyz& p, const Xyz& q, const Xyz& r,
                                             const Xyz& s) {
  const double ax = q[0] - p[0], ay = q[1] - p[1], az = q[2] - p[2];
  const double bx = r[0] - p[0], by = r[1] - p[1], bz = r[2] - p[2];
  const double cx = s[0] - p[0], cy = s[1] - p[1], cz = s[2] - p[2];
  // All four points in one plane perpendicular to an axis (flat faces of CAD models): the
  // differences along it are exactly zero, and so is the determinant.
  if ((ax == 0 && bx == 0 && cx == 0) || (ay == 0 && by == 0 && cy == 0) ||
      (az == 0 && bz == 0 && cz == 0))
    return 0;
  const double bxcy = bx * cy, cxby = cx * by, cxay = cx * ay, axcy = ax * cy, axby = ax * by,
               bxay = bx * ay;
  const double det = az * (bxcy - cxby) + bz * (cxay - axcy) + cz * (axby - bxay);
  const double permanent = (std::fabs(bxcy) + std::fabs(cxby)) * std::fabs(az) +
                           (std::fabs(cxay) + std::fabs(axcy)) * std::fabs(bz) +
                           (std::fabs(axby) + std::fabs(bxay)) * std::fabs(cz);
  // Shewchuk's orient3d bound A is (7 + 56 eps) eps with eps = 2^-53.
  const double bound = 1.6e-15 * permanent;
  if (!(permanent < kStaticHuge)) return std::nullopt;  // also NaN
  if (det > bound) return permanent > kStaticTiny ? std::optional<int>(1) : std::nullopt;
  if (-det > bound) return permanent > kStaticTiny ? std::optional<int>(-1) : std::nullopt;
  return std::nullopt;
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

// sign det [q - p, r - p] in the coordinates u, v: CGAL's orientation of the projected points.
inline std::optional<int> static_orientation_2(int u, int v, const Xyz& p, const Xyz& q,
                                               const Xyz& r) {
  return static_orientation_2_of_differences(q[u] - p[u], q[v] - p[v], r[u] - p[u], r[v] - p[v]);
}

}  // namespace morphex::detail

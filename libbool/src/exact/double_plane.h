// SPDX-License-Identifier: GPL-3.0-or-later
// A triangle's plane in doubles, for deciding by a few products on which side of it many points
// lie: the check's face planes and the coplanar merge's edges.
#pragma once

#include <algorithm>
#include <cmath>
#include <optional>

#include "exact/static_filter.h"

namespace morphex::detail {

// The plane through p, q, r as N = (q - p) x (r - p), without p (its holder keeps it). The side
// of x is the sign of (x - p) . N, the orientation's determinant in another order: rounding the
// differences, the cross product and the dot product errs by less than 9 units of 2^-52 of
// sum_k |x - p|_k M_k, M_k the magnitudes of N_k's two products; 1e-14 of it leaves a wide
// margin under any rounding mode. When the points are only known within `error` of their doubles
// (a rational mesh: a rotated input, a Boolean's output), the exact determinant is moreover within
// orientation_near_slack of the doubles' one, as in static_orientation_near.
struct DoublePlane {
  double normal[3], magnitude[3];
  double reach;  // the largest coordinate of q - p and r - p

  static DoublePlane through(const Xyz& p, const Xyz& q, const Xyz& r) {
    const double a[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]};
    const double b[3] = {r[0] - p[0], r[1] - p[1], r[2] - p[2]};
    DoublePlane plane;
    plane.reach = 0;
    for (int k = 0; k < 3; ++k) {
      const int i = (k + 1) % 3, j = (k + 2) % 3;
      plane.normal[k] = a[i] * b[j] - a[j] * b[i];
      plane.magnitude[k] = std::fabs(a[i] * b[j]) + std::fabs(a[j] * b[i]);
      plane.reach = std::max({plane.reach, std::fabs(a[k]), std::fabs(b[k])});
    }
    return plane;
  }

  // CGAL's orientation(p, q, r, x) when the doubles decide it (p: the plane's first point).
  std::optional<int> side(const Xyz& p, const Xyz& x, double error) const {
    const double c[3] = {x[0] - p[0], x[1] - p[1], x[2] - p[2]};
    const double det = c[0] * normal[0] + c[1] * normal[1] + c[2] * normal[2];
    const double permanent = std::fabs(c[0]) * magnitude[0] + std::fabs(c[1]) * magnitude[1] +
                             std::fabs(c[2]) * magnitude[2];
    if (!(permanent > kStaticTiny && permanent < kStaticHuge)) return std::nullopt;
    double bound = 1e-14 * permanent;
    if (error > 0)
      bound += orientation_near_slack(
          std::max({reach, std::fabs(c[0]), std::fabs(c[1]), std::fabs(c[2])}), error);
    if (det > bound) return 1;
    if (-det > bound) return -1;
    return std::nullopt;
  }
};

}  // namespace morphex::detail

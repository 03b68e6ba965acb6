// SPDX-License-Identifier: GPL-3.0-or-later
// The angular order of faces around an edge, by exact predicates: the Boolean's separation of
// non-manifold edges pairs faces by it, and the check verifies that pairs sharing an edge by
// position do not interleave.
#pragma once

#include "exact/point_table.h"

namespace morphex::detail {

// Angle order of the faces around the directed axis u->v: true when face third vertex `p` comes
// before `q` counter-clockwise, starting from `ref`. Exact orientation predicates only.
struct AroundEdge {
  const PointTable& points;
  PointId u, v, ref;
  int half(PointId w) const {  // 0: angle in [0, pi), 1: [pi, 2 pi)
    const auto s = points.orientation(u, v, ref, w);
    if (s == CGAL::POSITIVE) return 0;
    if (s == CGAL::NEGATIVE) return 1;
    // In the plane of ref: angle 0 when on the same side of the axis as ref, else pi.
    return CGAL::coplanar_orientation(points.point(u), points.point(v), points.point(ref),
                                      points.point(w)) == CGAL::POSITIVE
               ? 0
               : 1;
  }
  bool operator()(PointId p, PointId q) const {
    const int hp = half(p), hq = half(q);
    if (hp != hq) return hp < hq;
    return points.orientation(u, v, p, q) == CGAL::POSITIVE;
  }
};

}  // namespace morphex::detail

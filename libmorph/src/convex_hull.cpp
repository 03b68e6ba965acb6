// SPDX-License-Identifier: GPL-3.0-or-later
// Convex hulls as solids, by CGAL's exact convex_hull_3 (morphex/convex_hull.h).
#include "morphex/convex_hull.h"

#include <CGAL/convex_hull_3.h>

#include <algorithm>
#include <array>

namespace morphex {

Mesh convex_hull(const std::vector<Point>& points) {
  Mesh hull;
  // CGAL writes lower-dimensional hulls as points, segments or polygons: only solids go on.
  std::size_t second = 1, third = 2;
  while (second < points.size() && points[second] == points[0]) ++second;
  while (third < points.size() &&
         (second >= points.size() || CGAL::collinear(points[0], points[second], points[third])))
    ++third;
  if (third >= points.size()) return hull;
  if (std::none_of(points.begin(), points.end(), [&](const Point& p) {
        return !CGAL::coplanar(points[0], points[second], points[third], p);
      }))
    return hull;
  std::vector<std::array<VertexIndex, 3>> faces;
  CGAL::convex_hull_3(points.begin(), points.end(), hull.points, faces);
  hull.triangles.assign(faces.begin(), faces.end());
  if (hull.triangles.size() < 4) return {};
  switch (signed_volume_sign(hull)) {
    case CGAL::ZERO:
      return {};  // flat
    case CGAL::NEGATIVE:
      // convex_hull_3 writes the hull of four points (a tetrahedron) inward.
      for (Triangle& t : hull.triangles) std::swap(t[1], t[2]);
      break;
    default:
      break;
  }
  return hull;
}

bool is_convex(const Mesh& solid) {
  return signed_volume(convex_hull(solid.points)) == signed_volume(solid);
}

}  // namespace morphex

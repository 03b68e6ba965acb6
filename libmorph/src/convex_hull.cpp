// SPDX-License-Identifier: GPL-3.0-or-later
// Convex hulls as solids, by CGAL's exact convex_hull_3 (morphex/convex_hull.h).
#include "morphex/convex_hull.h"

#include <CGAL/convex_hull_3.h>

#include <algorithm>
#include <array>

namespace morphex {

namespace {

// The hull's points sorted (x, then y, then z) and its triangles renumbered, each starting at its
// smallest index, in sorted order. convex_hull_3 numbers its output by walking a triangulation
// whose handles are pointers, so the numbering followed the allocator's layout: the same command
// wrote its result in different orders (a dilation of the unit cube by an octahedron, under
// glibc's malloc with and without a progress bar). A result must not depend on addresses.
void in_canonical_order(Mesh& hull) {
  std::vector<VertexIndex> order(hull.points.size());
  for (VertexIndex i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](VertexIndex a, VertexIndex b) {
    return CGAL::compare_xyz(hull.points[a], hull.points[b]) == CGAL::SMALLER;
  });
  std::vector<VertexIndex> new_index(order.size());
  std::vector<Point> points;
  points.reserve(order.size());
  for (VertexIndex i = 0; i < order.size(); ++i) {
    new_index[order[i]] = i;
    points.push_back(hull.points[order[i]]);
  }
  hull.points = std::move(points);
  for (Triangle& t : hull.triangles) {
    for (VertexIndex& v : t) v = new_index[v];
    std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
  }
  std::sort(hull.triangles.begin(), hull.triangles.end());
}

}  // namespace

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
  in_canonical_order(hull);
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

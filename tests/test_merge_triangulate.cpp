// SPDX-License-Identifier: GPL-3.0-or-later
// The coplanar merge's re-triangulation of a region from its boundary, on the short loops it
// fills without a triangulation (a triangle; quadrilaterals convex, dart-shaped, with a straight
// corner, cocircular) and on longer ones: every triangle turns as the seed, the triangles cover
// the loop's area exactly, and a convex quadrilateral is split along its Delaunay diagonal.
#include <CGAL/Polygon_2.h>
#include <CGAL/Polygon_2_algorithms.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "boolean/merge_triangulate.h"
#include "exact/point_table.h"

using namespace morphex;

namespace {

using Point2 = Kernel::Point_2;

// Points of the plane z = x / 3 + y / 5 over (x, y) (seen along z, the dominant axis).
Point lift(const Point2& p) {
  return Point(p.x(), p.y(), p.x() / 3 + p.y() / 5);
}

struct Filled {
  std::vector<Triangle> triangles;
  bool ok = false;
};

// The loop `polygon` (in order) as a boundary given in a shuffled edge order, reversed when
// `reversed`, filled by triangulate_in_plane; checked against the polygon's exact area.
Filled fill(const std::vector<Point2>& polygon, bool reversed, unsigned shuffle) {
  std::vector<Point2> loop = polygon;
  if (reversed) std::reverse(loop.begin(), loop.end());
  Mesh a;
  // The plane's facet and a seed turning as the loop: a small triangle inside the loop's box.
  const FT loop_area = CGAL::polygon_area_2(loop.begin(), loop.end(), Kernel());
  const bool positive = loop_area > 0;
  a.points = {lift({0, 0}), lift({1, 0}), lift({0, 1})};
  if (!positive) std::swap(a.points[1], a.points[2]);
  for (const Point2& p : loop) a.points.push_back(lift(p));
  const Mesh b;
  const detail::PointTable table(a, b);
  detail::IdMesh surface;
  for (std::uint32_t v = 0; v < a.points.size(); ++v) surface.vertex_point.push_back(v);
  detail::Boundary boundary;
  const auto n = VertexIndex(loop.size());
  for (VertexIndex i = 0; i < n; ++i) boundary.emplace_back(3 + i, 3 + (i + 1) % n);
  std::shuffle(boundary.begin(), boundary.end(), std::mt19937(shuffle));
  const std::array<detail::PointId, 3> plane = {0, 1, 2};
  const auto triangles = detail::triangulate_in_plane(table, surface, plane, boundary, {0, 1, 2});
  Filled out;
  if (!triangles) return out;
  out.triangles = *triangles;
  FT area = 0;
  for (const Triangle& t : out.triangles) {
    const Point2 p(a.points[t[0]].x(), a.points[t[0]].y()),
        q(a.points[t[1]].x(), a.points[t[1]].y()), r(a.points[t[2]].x(), a.points[t[2]].y());
    const FT twice = (q.x() - p.x()) * (r.y() - p.y()) - (q.y() - p.y()) * (r.x() - p.x());
    if (twice == 0 || (twice > 0) != positive) return out;  // degenerate or turned over
    area += twice / 2;
  }
  out.ok = area == loop_area;
  return out;
}

Point2 corner(const std::vector<Point2>& polygon, VertexIndex v, bool reversed) {
  const std::size_t i = v - 3, n = polygon.size();
  return polygon[reversed ? n - 1 - i : i];
}

}  // namespace

TEST(MergeTriangulate, ShortLoopsAreFilledAsTheirTriangulation) {
  const std::vector<std::vector<Point2>> quads = {
      {{0, 0}, {4, 0}, {5, 3}, {1, 2}},  // convex
      {{0, 0}, {4, 2}, {0, 4}, {1, 2}},  // a dart: only the diagonal from (1, 2) is inside
      {{0, 0}, {2, 0}, {4, 0}, {2, 3}},  // straight at (2, 0): only the diagonal from it
      {{0, 0}, {4, 0}, {4, 2}, {0, 2}},  // cocircular: either diagonal
      {{1, 2}, {0, 0}, {4, 2}, {0, 4}},  // the dart from its reflex corner
  };
  for (const bool reversed : {false, true})
    for (unsigned shuffle = 0; shuffle < 4; ++shuffle) {
      const Filled triangle = fill({{0, 0}, {3, 1}, {1, 2}}, reversed, shuffle);
      ASSERT_TRUE(triangle.ok);
      EXPECT_EQ(triangle.triangles.size(), 1u);
      for (std::size_t k = 0; k < quads.size(); ++k) {
        const Filled quad = fill(quads[k], reversed, shuffle);
        ASSERT_TRUE(quad.ok) << k << " " << reversed << " " << shuffle;
        ASSERT_EQ(quad.triangles.size(), 2u) << k;
      }
    }
}

TEST(MergeTriangulate, ConvexQuadrilateralsTakeTheDelaunayDiagonal) {
  std::mt19937 random(7);
  std::uniform_int_distribution<int> coordinate(-20, 20);
  int convex = 0, other = 0;
  for (int i = 0; i < 400; ++i) {
    std::vector<Point2> quad;
    for (int k = 0; k < 4; ++k) quad.emplace_back(coordinate(random), coordinate(random));
    const CGAL::Polygon_2<Kernel> polygon(quad.begin(), quad.end());
    if (!polygon.is_simple() || polygon.area() == 0) continue;
    const bool reversed = i % 2;
    const Filled filled = fill(quad, reversed, unsigned(i));
    ASSERT_TRUE(filled.ok) << i;
    ASSERT_EQ(filled.triangles.size(), 2u) << i;
    if (!polygon.is_convex()) {
      ++other;
      continue;
    }
    ++convex;
    // Neither triangle's circle holds the fourth corner strictly inside.
    for (const Triangle& t : filled.triangles) {
      VertexIndex fourth = 3;
      while (std::find(t.begin(), t.end(), fourth) != t.end()) ++fourth;
      const Point2 p = corner(quad, t[0], reversed), q = corner(quad, t[1], reversed),
                   r = corner(quad, t[2], reversed), s = corner(quad, fourth, reversed);
      if (CGAL::collinear(p, q, r)) continue;
      EXPECT_NE(CGAL::side_of_bounded_circle(p, q, r, s), CGAL::ON_BOUNDED_SIDE) << i;
    }
  }
  EXPECT_GT(convex, 50);
  EXPECT_GT(other, 50);
}

TEST(MergeTriangulate, LongerLoopsAreTriangulated) {
  const std::vector<Point2> pentagon = {{0, 0}, {4, 0}, {5, 3}, {2, 5}, {-1, 3}};
  const std::vector<Point2> comb = {{0, 0}, {6, 0}, {6, 4}, {5, 1}, {4, 4},
                                    {3, 1}, {2, 4}, {1, 1}, {0, 4}};
  for (const bool reversed : {false, true}) {
    const Filled five = fill(pentagon, reversed, 3);
    ASSERT_TRUE(five.ok);
    EXPECT_EQ(five.triangles.size(), 3u);
    const Filled teeth = fill(comb, reversed, 5);
    ASSERT_TRUE(teeth.ok);
    EXPECT_EQ(teeth.triangles.size(), 7u);
  }
}

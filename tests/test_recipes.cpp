// SPDX-License-Identifier: GPL-3.0-or-later
// Predicates decided from how points were made or placed, without their exact coordinates:
// collinear rows of cut points (facet_lines.h), coordinates an input gives a crossing, points on
// lines parallel to an axis and a parallelogram's corners (coplanar by comparisons and exact
// differences, static_filter.h). Each is checked against CGAL on the exact points, degenerate
// cases included.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "boolean/facet_lines.h"
#include "exact/point_table.h"
#include "exact/static_filter.h"
#include "random_points.h"

using namespace morphex;
using test_support::RandomPoints;

// Cut points of one facet of a whose collinearity their recipes decide: crossings of b's edges
// on a plane with the facet, and of edges of a in the facet's plane with that plane of b. Only
// exactly collinear triples are called collinear: not crossings of b's edges that lie in the
// facet's plane itself (their common plane is the facet's), nor of b's edges off the plane.
TEST(FacetLines, CollinearByRecipesOnlyWhenExactlyCollinear) {
  RandomPoints random(21);
  Mesh a, b;
  for (int i = 0; i < 3; ++i) a.points.push_back(random.point());
  const Point f0 = a.points[0], f1 = a.points[1], f2 = a.points[2];
  const Kernel::Plane_3 facet_plane(f0, f1, f2);
  ASSERT_FALSE(facet_plane.is_degenerate());
  const Point b0 = random.point(), b1 = random.point(), b2 = random.point();  // b's plane
  b.points = {b0, b1, b2};
  const Kernel::Plane_3 plane_b(b0, b1, b2);
  ASSERT_FALSE(plane_b.is_degenerate());
  auto on = [&](const Point& p, const Point& q, const Point& r) {
    return p + random.weight() * (q - p) + random.weight() * (r - p);
  };
  // b: points on its plane, points off it, points in the facet's plane; a: points in the facet's
  // plane, and planes of random points.
  for (int i = 0; i < 40; ++i) b.points.push_back(on(b0, b1, b2));
  for (int i = 0; i < 20; ++i) b.points.push_back(random.point());
  for (int i = 0; i < 30; ++i) b.points.push_back(on(f0, f1, f2));
  for (int i = 0; i < 30; ++i) a.points.push_back(on(f0, f1, f2));
  for (int i = 0; i < 30; ++i) a.points.push_back(random.point());
  detail::PointTable table(a, b);
  auto id = [&](int side, std::size_t v) { return table.vertex(side, std::uint32_t(v)); };
  const std::array<detail::PointId, 3> facet = {id(0, 0), id(0, 1), id(0, 2)};
  // Crossings of the edges (p, q) of `side` with the plane (u, v, w), where it is a crossing.
  auto crossings = [&](int side, std::size_t from, std::size_t to, int other, std::size_t u,
                       std::size_t v, std::size_t w) {
    const Mesh& mesh = side == 0 ? a : b;
    const Mesh& plane_mesh = other == 0 ? a : b;
    const Kernel::Plane_3 plane(plane_mesh.points[u], plane_mesh.points[v], plane_mesh.points[w]);
    std::vector<detail::PointId> out;
    for (std::size_t p = from; p < to; ++p)
      for (std::size_t q = p + 1; q < to; q += 3) {
        const auto sp = plane.oriented_side(mesh.points[p]),
                   sq = plane.oriented_side(mesh.points[q]);
        if (sp == CGAL::ON_ORIENTED_BOUNDARY || sq == CGAL::ON_ORIENTED_BOUNDARY || sp == sq)
          continue;
        out.push_back(table.add({detail::Recipe::Kind::EdgePlane, -1, id(side, p), id(side, q),
                                 id(other, u), id(other, v), id(other, w)}));
      }
    return out;
  };
  // On the line of the facet's plane and b's: b's edges on its plane through the facet, the
  // facet's own edges and a's edges in its plane through b's plane.
  std::vector<detail::PointId> on_line = crossings(1, 3, 43, 0, 0, 1, 2);
  for (const auto& more : {crossings(0, 0, 3, 1, 0, 1, 2), crossings(0, 3, 33, 1, 0, 1, 2)})
    on_line.insert(on_line.end(), more.begin(), more.end());
  // Elsewhere on the facet's plane: b's edges off b's plane through it, b's edges in it through
  // planes of a.
  std::vector<detail::PointId> elsewhere = crossings(1, 43, 63, 0, 0, 1, 2);
  for (std::size_t k = 33; k + 2 < 63; k += 3) {
    const auto more = crossings(1, 63, 93, 0, k, k + 1, k + 2);
    elsewhere.insert(elsewhere.end(), more.begin(), more.end());
  }
  ASSERT_GE(on_line.size(), 60u);
  ASSERT_GE(elsewhere.size(), 60u);
  for (const detail::PointId x : on_line) {
    ASSERT_EQ(table.orientation(facet[0], facet[1], facet[2], x), CGAL::COPLANAR);
    ASSERT_EQ(plane_b.oriented_side(table.point(x)), CGAL::ON_ORIENTED_BOUNDARY);
  }
  std::mt19937 pick(22);
  auto any = [&](const std::vector<detail::PointId>& from) {
    return from[std::uniform_int_distribution<std::size_t>(0, from.size() - 1)(pick)];
  };
  const int dropped = table.dominant_axis(facet[0], facet[1], facet[2]);
  // One object for all triples, as a triangulation asks (it keeps the plane it found), and a
  // fresh one for each.
  detail::FacetLines lines(table, facet);
  int decided = 0;
  for (int i = 0; i < 3000; ++i) {
    const detail::PointId p = any(on_line), q = any(on_line), r = any(on_line);
    if (p == q || q == r || p == r) continue;
    ASSERT_TRUE(detail::FacetLines(table, facet).collinear(p, q, r)) << i;
    ASSERT_TRUE(lines.collinear(p, q, r)) << i;
    ASSERT_EQ(table.orientation_2(dropped, p, q, r, &lines), CGAL::COLLINEAR) << i;
    ++decided;
  }
  EXPECT_GE(decided, 2500);
  int collinear = 0;
  for (int i = 0; i < 3000; ++i) {
    const std::vector<detail::PointId>& first = i % 3 ? elsewhere : on_line;
    const detail::PointId p = any(first), q = any(elsewhere), r = any(i % 2 ? elsewhere : on_line);
    if (p == q || q == r || p == r) continue;
    const bool exactly = CGAL::collinear(table.point(p), table.point(q), table.point(r));
    collinear += exactly;
    if (!exactly) {
      ASSERT_FALSE(detail::FacetLines(table, facet).collinear(p, q, r)) << i;
      ASSERT_FALSE(lines.collinear(p, q, r)) << i;
    }
    ASSERT_EQ(table.orientation_2(dropped, p, q, r, &lines), table.orientation_2(dropped, p, q, r))
        << i;
  }
  EXPECT_LT(collinear, 100);
}

// Crossings of a plane perpendicular to an axis (its three points share that coordinate) have
// that coordinate exactly, as an interval of one point when it is a double; crossings of edges
// perpendicular to an axis compare along it as their ends do: every comparison agrees with CGAL,
// equal coordinates included.
TEST(PointTable, CrossingsOfAxisPerpendicularPlanesAndEdgesCompareExactly) {
  RandomPoints random(31);
  Mesh a, b;
  const FT half(0.5), third = FT(1) / 3;
  // a: a plane x = 1/2, edges whose ends share x = 1/3 (not a double), and edges whose ends' x
  // differ from 1/3 by less than the intervals can tell; b: points around them.
  for (int i = 0; i < 3; ++i)
    a.points.push_back(Point(half, random.coordinate(), random.coordinate()));
  for (int i = 0; i < 20; ++i)
    a.points.push_back(Point(third, random.coordinate(), random.coordinate()));
  const FT tiny = FT(1) / FT(std::pow(2.0, 80));
  for (int i = 0; i < 20; ++i)
    a.points.push_back(Point(third + (1 + i % 2) * tiny, random.coordinate(), random.coordinate()));
  for (int i = 0; i < 40; ++i) b.points.push_back(random.point());
  detail::PointTable table(a, b);
  auto id = [&](int side, std::size_t v) { return table.vertex(side, std::uint32_t(v)); };
  const Kernel::Plane_3 plane(a.points[0], a.points[1], a.points[2]);
  ASSERT_FALSE(plane.is_degenerate());
  std::vector<detail::PointId> on_plane, on_edges, ids;
  for (std::size_t p = 0; p < 40; ++p)
    for (std::size_t q = p + 1; q < 40; q += 7) {
      const auto sp = plane.oriented_side(b.points[p]), sq = plane.oriented_side(b.points[q]);
      if (sp != CGAL::ON_ORIENTED_BOUNDARY && sq != CGAL::ON_ORIENTED_BOUNDARY && sp != sq)
        on_plane.push_back(table.add({detail::Recipe::Kind::EdgePlane, -1, id(1, p), id(1, q),
                                      id(0, 0), id(0, 1), id(0, 2)}));
    }
  for (std::size_t e = 3; e + 1 < 43; e += 2)
    for (std::size_t k = 0; k + 2 < 40; k += 3) {
      const Kernel::Plane_3 other(b.points[k], b.points[k + 1], b.points[k + 2]);
      const auto sp = other.oriented_side(a.points[e]), sq = other.oriented_side(a.points[e + 1]);
      if (!other.is_degenerate() && sp != CGAL::ON_ORIENTED_BOUNDARY &&
          sq != CGAL::ON_ORIENTED_BOUNDARY && sp != sq)
        on_edges.push_back(table.add({detail::Recipe::Kind::EdgePlane, -1, id(0, e), id(0, e + 1),
                                      id(1, k), id(1, k + 1), id(1, k + 2)}));
    }
  ASSERT_GE(on_plane.size(), 20u);
  ASSERT_GE(on_edges.size(), 20u);
  for (const detail::PointId x : on_plane) {
    EXPECT_TRUE(table.approx(x).cartesian(0).is_point());
    EXPECT_EQ(table.point(x).x(), half);
  }
  int near = 0;
  for (const detail::PointId x : on_edges) {
    const FT x0 = table.point(x).x();
    if (table.recipe(x).p < 23)
      EXPECT_EQ(x0, third);
    else
      near += third < x0 && x0 < third + 2 * tiny;
  }
  EXPECT_GE(near, 10);
  for (std::size_t v = 0; v < 43; ++v) ids.push_back(id(0, v));
  ids.insert(ids.end(), on_plane.begin(), on_plane.end());
  ids.insert(ids.end(), on_edges.begin(), on_edges.end());
  int equal = 0;
  for (const detail::PointId p : ids)
    for (const detail::PointId q : ids)
      for (int axis = 0; axis < 3; ++axis) {
        const CGAL::Comparison_result expected =
            CGAL::compare(table.point(p).cartesian(axis), table.point(q).cartesian(axis));
        ASSERT_EQ(table.compare(axis, p, q), expected) << p << " " << q << " " << axis;
        equal += p != q && expected == CGAL::EQUAL;
      }
  EXPECT_GT(equal, 1000);
}

// Quadruples of doubles on one or two lines parallel to a coordinate axis are coplanar by
// comparisons alone (static_filter.h); the point table answers them so before its exact stage.
// Coordinates of mixed magnitudes, so that most differences are not doubles, and points nudged
// one unit in the last place off their line, which must not be taken for coplanar.
TEST(PointTable, PointsOnTwoAxisParallelLinesAreCoplanarByComparisons) {
  std::mt19937 random(41);
  const std::vector<double> places = {0.0313356780, -0.0186299998, 3.75, 1e-7, -2.5e5};
  std::uniform_int_distribution<std::size_t> place(0, places.size() - 1);
  std::uniform_int_distribution<int> axis_of(0, 2), nudged(0, 4);
  std::uniform_real_distribution<double> along(-1, 1);
  Mesh a, b;
  std::vector<int> axis_of_point;
  for (int i = 0; i < 400; ++i) {
    const int axis = i % 3, u = axis == 0 ? 1 : 0, v = axis == 2 ? 1 : 2;
    detail::Xyz x;
    x[axis] = std::ldexp(along(random), int(place(random)) * 9 - 20);
    x[u] = places[place(random)];
    x[v] = places[place(random)];
    if (nudged(random) == 0) {
      const int k = i % 2 ? u : v;
      x[k] = std::nextafter(x[k], 1e9);
    }
    a.points.push_back(Point(x[0], x[1], x[2]));
    axis_of_point.push_back(axis);
  }
  detail::PointTable table(a, b);
  const auto& xyz = table.input_doubles();
  ASSERT_EQ(xyz.size(), a.points.size());
  std::uniform_int_distribution<std::uint32_t> pick(0, 399);
  int claimed = 0, nonzero = 0;
  for (int i = 0; i < 200000; ++i) {
    // Points made along one axis, so that two lines (or one) often hold all four.
    std::uint32_t ids[4] = {pick(random), 0, 0, 0};
    for (int k = 1; k < 4; ++k) do
        ids[k] = pick(random);
      while (axis_of_point[ids[k]] != axis_of_point[ids[0]]);
    const auto expected =
        CGAL::orientation(a.points[ids[0]], a.points[ids[1]], a.points[ids[2]], a.points[ids[3]]);
    if (detail::on_two_axis_lines(xyz[ids[0]], xyz[ids[1]], xyz[ids[2]], xyz[ids[3]])) {
      ++claimed;
      ASSERT_EQ(expected, CGAL::ZERO) << i;
    }
    nonzero += expected != CGAL::ZERO;
    const auto p = [&](int k) { return table.vertex(0, ids[k]); };
    ASSERT_EQ(table.orientation(p(0), p(1), p(2), p(3)), expected) << i;
  }
  EXPECT_GT(claimed, 1000);
  EXPECT_GT(nonzero, 1000);
}

// Parallelograms of doubles (a feature and its copy moved by one vector) are coplanar by their
// exact differences alone (static_filter.h), in every order of their corners; a corner nudged by
// the grid's finest unit in any coordinate breaks it, and the orientation is then CGAL's.
TEST(StaticFilter, ParallelogramsOfDoublesAreCoplanarByTheirDifferences) {
  std::mt19937 random(43);
  std::uniform_int_distribution<std::int64_t> grid(-(std::int64_t(1) << 30), std::int64_t(1) << 30);
  std::uniform_int_distribution<int> coordinate(0, 2), scale(0, 3);
  auto point = [&] {  // binary fractions of mixed magnitudes whose sums and differences are exact
    detail::Xyz x;
    for (double& c : x) c = std::ldexp(double(grid(random)), -42 - 4 * scale(random));
    return x;
  };
  auto cgal = [](const detail::Xyz& x) { return Point(x[0], x[1], x[2]); };
  int claimed = 0, nudged_nonzero = 0;
  for (int i = 0; i < 4000; ++i) {
    const detail::Xyz p = point(), q = point(), r = point();
    detail::Xyz s;
    for (int k = 0; k < 3; ++k) s[k] = r[k] + (q[k] - p[k]);
    if (i % 2) {
      const int k = coordinate(random);
      s[k] += 0x1p-54;  // the grid's finest unit: the differences stay exact
    }
    // The four corners in each order around the parallelogram and across it.
    const std::array<detail::Xyz, 4> corners = {p, q, r, s};
    std::array<int, 4> order = {0, 1, 2, 3};
    do {
      const detail::Xyz &a = corners[order[0]], &b = corners[order[1]], &c = corners[order[2]],
                        &d = corners[order[3]];
      const int expected = int(CGAL::orientation(cgal(a), cgal(b), cgal(c), cgal(d)));
      const auto o = detail::exact_orientation_of_doubles(a, b, c, d);
      ASSERT_TRUE(o.has_value()) << i;
      ASSERT_EQ(*o, expected) << i;
      double u[3], v[3];
      for (int k = 0; k < 3; ++k) u[k] = b[k] - a[k], v[k] = c[k] - a[k];
      if (detail::parallelogram(a, b, c, d, u, v)) {
        ++claimed;
        ASSERT_EQ(expected, 0) << i;
      }
      nudged_nonzero += i % 2 && expected != 0;
    } while (std::next_permutation(order.begin(), order.end()));
  }
  EXPECT_EQ(claimed, 2000 * 24);  // every order of every parallelogram
  EXPECT_GT(nudged_nonzero, 2000 * 20);
}

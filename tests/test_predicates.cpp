// SPDX-License-Identifier: GPL-3.0-or-later
// The Boolean's own exact predicates and point identity against CGAL's, on random rational points
// and on exactly degenerate ones (coplanar, collinear, equal), where the filters must fall through
// to the exact stage.
#include <gtest/gtest.h>

#include <random>

#include "filtered.h"
#include "point_index.h"
#include "projection_traits.h"

using namespace morphex;

namespace {

class RandomPoints {
 public:
  explicit RandomPoints(unsigned seed) : random_(seed) {}
  FT coordinate() {
    // Mixed denominators (powers of two and others) and a few doubles.
    std::uniform_int_distribution<int> numerator(-50, 50), denominator(1, 12), kind(0, 3);
    if (kind(random_) == 0) return FT(std::uniform_real_distribution<double>(-3, 3)(random_));
    return FT(numerator(random_)) / FT(denominator(random_));
  }
  Point point() {
    const FT x = coordinate(), y = coordinate(), z = coordinate();
    return Point(x, y, z);
  }
  FT weight() { return FT(std::uniform_int_distribution<int>(-7, 7)(random_)) / 5; }

 private:
  std::mt19937 random_;
};

}  // namespace

TEST(ExactPredicates, Orient3dAgreesWithCgalOnGeneralAndCoplanarPoints) {
  RandomPoints random(11);
  int zeros = 0;
  for (int i = 0; i < 3000; ++i) {
    const Point p = random.point(), q = random.point(), r = random.point();
    // Every third s lies exactly on the plane pqr (an exact affine combination).
    const Point s =
        i % 3 == 0 ? p + random.weight() * (q - p) + random.weight() * (r - p) : random.point();
    const auto expected = CGAL::orientation(p, q, r, s);
    ASSERT_EQ(detail::orient3d(p, q, r, s), expected) << i;
    ASSERT_EQ(
        detail::exact_orientation(CGAL::exact(p), CGAL::exact(q), CGAL::exact(r), CGAL::exact(s)),
        expected)
        << i;
    zeros += expected == CGAL::COPLANAR;
  }
  EXPECT_GE(zeros, 1000);  // the degenerate third really exercised the exact stage
}

TEST(ExactPredicates, ProjectedOrientationAgreesWithCgalOnCollinearPoints) {
  RandomPoints random(12);
  const auto xy = detail::FilteredProjectionTraits<2>().orientation_2_object();
  const auto yz = detail::FilteredProjectionTraits<0>().orientation_2_object();
  const auto xz = detail::FilteredProjectionTraits<1>().orientation_2_object();
  const auto cgal_xy = CGAL::Projection_traits_xy_3<Kernel>().orientation_2_object();
  const auto cgal_yz = CGAL::Projection_traits_yz_3<Kernel>().orientation_2_object();
  const auto cgal_xz = CGAL::Projection_traits_xz_3<Kernel>().orientation_2_object();
  int zeros = 0;
  for (int i = 0; i < 3000; ++i) {
    const Point p = random.point(), q = random.point();
    const Point r = i % 2 == 0 ? p + random.weight() * (q - p) : random.point();  // collinear
    ASSERT_EQ(xy(p, q, r), cgal_xy(p, q, r)) << i;
    ASSERT_EQ(yz(p, q, r), cgal_yz(p, q, r)) << i;
    ASSERT_EQ(xz(p, q, r), cgal_xz(p, q, r)) << i;
    ASSERT_EQ(detail::collinear3d(p, q, r), CGAL::collinear(p, q, r)) << i;
    zeros += cgal_xy(p, q, r) == CGAL::COLLINEAR;
  }
  EXPECT_GE(zeros, 1500);
  // Collinear in two projections but not in space.
  EXPECT_FALSE(detail::collinear3d(Point(0, 0, 0), Point(1, 0, 0), Point(2, 0, FT(1) / 3)));
}

TEST(ExactPredicates, FilteredSideOfOrientedCircleAgreesWithCgal) {
  RandomPoints random(13);
  const auto ours = detail::FilteredProjectionTraits<2>().side_of_oriented_circle_2_object();
  const auto cgal = CGAL::Projection_traits_xy_3<Kernel>().side_of_oriented_circle_2_object();
  for (int i = 0; i < 2000; ++i) {
    const Point p = random.point(), q = random.point(), r = random.point();
    // Every other t is a reflection of p, q or r through the centre's axes (cocircular): here
    // simply another vertex of the rectangle p, q, p', q' when the points allow it.
    const Point t = i % 2 == 0 ? Point(q.x(), p.y(), r.z()) : random.point();
    ASSERT_EQ(ours(p, q, r, t), cgal(p, q, r, t)) << i;
  }
  // An exactly cocircular quadruple: the corners of an axis-aligned rectangle.
  const Point a(0, 0, 1), b(FT(3) / 7, 0, 2), c(FT(3) / 7, FT(5) / 3, 3), d(0, FT(5) / 3, 4);
  EXPECT_EQ(ours(a, b, c, d), CGAL::ON_ORIENTED_BOUNDARY);
}

TEST(PointIndex, EqualPositionsShareOneIdWhateverTheirConstruction) {
  std::vector<Point> points;
  detail::PointIndex index(points);
  const Point half(FT(1) / 2, FT(1) / 4, 0);        // doubles
  const Point third(FT(1) / 3, FT(2) / 3, FT(-1));  // not doubles
  const std::uint32_t a = index.id(half), b = index.id(third);
  EXPECT_NE(a, b);
  // The same positions reached through constructions (lazy, wide intervals) find the same ids.
  const Point half_again = CGAL::midpoint(Point(0, 0, 0), Point(1, FT(1) / 2, 0));
  const Point third_again = Point(0, 1, -2) + (Point(1, 0, 1) - Point(0, 1, -2)) / 3;
  EXPECT_EQ(index.id(half_again), a);
  EXPECT_EQ(index.id(third_again), b);
  EXPECT_EQ(index.id(Point(-0.0, 0.0, 0.0)), index.id(Point(0, 0, 0)));  // -0 == +0
  EXPECT_EQ(points.size(), 3u);
  // Many distinct points: ids are consecutive in order of first insertion.
  RandomPoints random(14);
  std::map<std::uint32_t, Point> seen;
  for (int i = 0; i < 5000; ++i) {
    const Point p = random.point();
    const std::uint32_t id = index.id(p);
    ASSERT_LT(id, points.size());
    ASSERT_EQ(points[id], p);
    const auto [it, inserted] = seen.emplace(id, p);
    if (!inserted) ASSERT_EQ(it->second, p);
  }
}

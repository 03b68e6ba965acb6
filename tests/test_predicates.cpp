// SPDX-License-Identifier: GPL-3.0-or-later
// The Boolean's own exact predicates and point identity against CGAL's, on random rational points
// and on exactly degenerate ones (coplanar, collinear, equal), where the filters must fall through
// to the exact stage.
#include <gtest/gtest.h>

#include <memory>
#include <numeric>
#include <random>
#include <string>

#include "exact/filtered.h"
#include "exact/fixed_integer.h"
#include "exact/point_index.h"
#include "exact/point_table.h"
#include "exact/projection_traits.h"
#include "exact/stable_vector.h"
#include "exact/static_filter.h"
#include "exact/triangle_overlap.h"
#include "random_points.h"

using namespace morphex;
using test_support::RandomPoints;

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

// Positions are hashed by coordinates truncated to 40 bits, from the intervals when both ends
// agree and from the exact value otherwise. Coordinates at and within 2^-60 of a truncation cut,
// as doubles and as rationals reached by two constructions with different intervals, and at
// tiny and huge magnitudes: equal values always share an id, different ones never do (against a
// map ordered by exact value).
TEST(PointIndex, CoordinatesAtTruncationCutsAreIdentifiedExactly) {
  std::vector<Point> points;
  detail::PointIndex index(points);
  std::map<std::array<FT, 3>, std::uint32_t> by_value;  // exact lexicographic order
  std::mt19937 random(40);
  std::uniform_int_distribution<int> offset(-3, 3), pick(0, 5);
  const double scales[] = {1.0, 0x1p-1005, 0x1p-998, 0x1p999, 0x1p1003, 3.0};
  for (int i = 0; i < 3000; ++i) {
    FT c[3];
    for (FT& x : c) {
      const double cut = scales[pick(random)] * (1 + std::ldexp(double(pick(random)), -39));
      // On the cut, a double away from it, or a rational (thirds) within 2^-60 of it.
      x = FT(cut) +
          FT(cut) * FT(offset(random)) * (pick(random) % 2 ? FT(0x1p-60) : FT(1) / 3 * FT(0x1p-58));
    }
    // Two constructions of the same point: directly, and through a midpoint (wider intervals).
    const Point p(c[0], c[1], c[2]);
    const Point shifted(c[0] + FT(1) / 7, c[1] - FT(2) / 9, c[2] + FT(5) / 11);
    const Point q = CGAL::midpoint(
        shifted, Point(c[0] * 2 - shifted.x(), c[1] * 2 - shifted.y(), c[2] * 2 - shifted.z()));
    const std::uint32_t id = index.id(i % 2 ? p : q);
    ASSERT_EQ(index.id(i % 2 ? q : p), id) << i;
    const auto [it, inserted] = by_value.emplace(std::array<FT, 3>{c[0], c[1], c[2]}, id);
    ASSERT_EQ(it->second, id) << i << (inserted ? ": a new value found an old id" : "");
  }
  EXPECT_EQ(points.size(), by_value.size());
  EXPECT_GT(by_value.size(), 1000u);
}

// The check indexes a mesh of doubles from its table's copy of the coordinates (find_or_insert of
// three doubles) instead of its Points: both ways give one id per exact position, and either finds
// what the other stored, rationals included; -0 is +0.
TEST(PointIndex, DoublesFindTheIdsOfTheirPoints) {
  detail::PositionIndex index;
  std::map<std::array<FT, 3>, std::uint32_t> by_value;
  std::mt19937 random(43);
  std::uniform_int_distribution<int> offset(-2, 2), pick(0, 5);
  const double scales[] = {1.0, 0x1p-1005, 0x1p999, 0x1p1003, 3.0, -0.0};
  std::uint32_t next = 0;
  std::vector<std::array<double, 3>> earlier;
  for (int i = 0; i < 4000; ++i) {
    std::array<double, 3> xyz;
    for (double& x : xyz)  // on a truncation cut or a few units in the last place from it
      x = scales[pick(random)] *
          (1 + std::ldexp(double(pick(random)), -39) + std::ldexp(double(offset(random)), -52));
    if (i % 3 == 2) xyz = earlier[std::size_t(random()) % earlier.size()];  // a position met again
    earlier.push_back(xyz);
    const bool rational = i % 5 == 4;  // a third of a double: never a double itself
    const Point p =
        rational ? Point(FT(xyz[0]) / 3, FT(xyz[1]), FT(xyz[2])) : Point(xyz[0], xyz[1], xyz[2]);
    const std::uint32_t id =
        i % 2 || rational ? index.find_or_insert(p, next) : index.find_or_insert(xyz, next);
    if (id == next) ++next;
    if (!rational)
      ASSERT_EQ(i % 2 ? index.find_or_insert(xyz, next) : index.find_or_insert(p, next), id) << i;
    const auto [it, inserted] = by_value.emplace(std::array<FT, 3>{p.x(), p.y(), p.z()}, id);
    ASSERT_EQ(it->second, id) << i << (inserted ? ": a new value found an old id" : "");
  }
  EXPECT_EQ(next, by_value.size());
  EXPECT_GT(by_value.size(), 1000u);
  EXPECT_LT(by_value.size(), 3000u);  // positions met again
}

// The exact sign of a short sum of doubles (the diagonal proofs of vertex stars) against the
// rational sum: terms of every magnitude that cancel exactly, up to one unit in the last place, or
// to a few units of the partial sum's.
TEST(StaticFilter, SignOfSumIsExact) {
  std::mt19937_64 random(52);
  std::uniform_real_distribution<double> unit(-1, 1);
  std::uniform_int_distribution<int> exponent(-60, 60), count(1, 6);
  int zeros = 0;
  for (int i = 0; i < 20000; ++i) {
    std::vector<double> t;
    for (int k = count(random); k > 0; --k) t.push_back(std::ldexp(unit(random), exponent(random)));
    if (i % 3 == 0) {  // cancel: append the negated partial sum, rounded, and its rounding error
      const double s = std::accumulate(t.begin(), t.end(), 0.0);
      t.push_back(-s);
      if (i % 2) t.push_back(std::nextafter(0.0, 1.0) * double(i % 5 - 2));
    } else if (i % 3 == 1 && t.size() > 1) {
      // Within a few units in the last place of the partial sum: where a rounded sum's sign can
      // be wrong, at the edge of the filter's error bound.
      const double s = std::accumulate(t.begin(), t.end(), 0.0);
      t.push_back(-s);
      if (s != 0) t.push_back(std::ldexp(double(i % 7 - 3), std::ilogb(s) - 52));
    }
    FT exact = 0;
    for (const double x : t) exact += FT(x);
    int ours = 0;
    switch (t.size()) {
      case 1:
        ours = detail::sign_of_sum({t[0]});
        break;
      case 2:
        ours = detail::sign_of_sum({t[0], t[1]});
        break;
      case 3:
        ours = detail::sign_of_sum({t[0], t[1], t[2]});
        break;
      case 4:
        ours = detail::sign_of_sum({t[0], t[1], t[2], t[3]});
        break;
      case 5:
        ours = detail::sign_of_sum({t[0], t[1], t[2], t[3], t[4]});
        break;
      case 6:
        ours = detail::sign_of_sum({t[0], t[1], t[2], t[3], t[4], t[5]});
        break;
      case 7:
        ours = detail::sign_of_sum({t[0], t[1], t[2], t[3], t[4], t[5], t[6]});
        break;
      default:
        ours = detail::sign_of_sum({t[0], t[1], t[2], t[3], t[4], t[5], t[6], t[7]});
    }
    ASSERT_EQ(ours, int(CGAL::sign(exact))) << i;
    zeros += CGAL::sign(exact) == CGAL::ZERO;
  }
  EXPECT_GT(zeros, 100);
}

// The exact stage on doubles (static_filter.h) against CGAL's exact orientations, on the cases it
// exists for: nearby points (coordinates of one magnitude, as a facet's neighbours have) exactly
// on a plane or a line (binary fractions, as CAD models and grids have), a rounding away from a
// plane, and in general position. It must decide them all at ordinary magnitudes (else the
// integers would still do the work), and leave alone magnitudes where products would underflow
// or overflow, and differences that are not exact doubles.
TEST(StaticFilter, ExactOrientationsOfDoublesAgreeWithCgal) {
  std::mt19937 random(61);
  std::uniform_int_distribution<int> small(-64, 64), kind(0, 3), axis(0, 2);
  std::uniform_real_distribution<double> unit(1, 2), middle(1.25, 1.75);
  int decided = 0, zeros = 0, ordinary = 0;
  for (const double scale : {1.0, 0x1p-40, 0x1p40, 0x1p-300, 0x1p300}) {
    for (int i = 0; i < 4000; ++i) {
      const int k = kind(random);
      auto point = [&]() -> detail::Xyz {  // every coordinate in [1, 2) before scaling
        const double x = 1.5 + small(random) / 256.0, y = 1.5 + small(random) / 256.0;
        switch (k) {
          case 0:  // on the plane x - y + 2z = 3
            return {x * scale, y * scale, (3 - x + y) / 2 * scale};
          case 1: {  // a rounding away from the plane x + y - z = 1.5
            const double a = middle(random), b = middle(random);
            return {a * scale, b * scale, std::nextafter(a + b - 1.5, 4.0) * scale};
          }
          case 2:  // on the line x = y = z
            return {x * scale, x * scale, x * scale};
          default:
            return {unit(random) * scale, unit(random) * scale, unit(random) * scale};
        }
      };
      const detail::Xyz p = point(), q = point(), r = point(), t = point();
      auto cgal = [](const detail::Xyz& x) { return Point(x[0], x[1], x[2]); };
      const int expected = int(CGAL::orientation(cgal(p), cgal(q), cgal(r), cgal(t)));
      const bool in_range = scale > 0x1p-100 && scale < 0x1p100;
      ordinary += in_range;
      const auto o = detail::exact_orientation_of_doubles(p, q, r, t);
      EXPECT_EQ(o.has_value(), in_range) << "scale " << scale << " case " << i;
      if (o) {
        ASSERT_EQ(*o, expected) << "scale " << scale << " case " << i;
        ++decided;
        zeros += *o == 0;
      }
      const int u = axis(random), v = (u + 1 + axis(random) % 2) % 3;
      const auto project = [&](const detail::Xyz& x) { return Kernel::Point_2(x[u], x[v]); };
      const auto o2 = detail::exact_orientation_2_of_doubles(u, v, p, q, r);
      EXPECT_EQ(o2.has_value(), in_range);
      if (o2)
        ASSERT_EQ(*o2, int(CGAL::orientation(project(p), project(q), project(r))))
            << "scale " << scale << " case " << i;
    }
  }
  EXPECT_EQ(decided, ordinary);
  EXPECT_GT(zeros, ordinary / 8);
  // A difference that is not one double (1 + 2^-60 - 2^-60 needs more bits) is left alone.
  EXPECT_FALSE(
      detail::exact_orientation_of_doubles({1, 1, 1}, {0x1p-60, 1, 1}, {1, 2, 1}, {1, 1, 2}));
}

// The point table's predicates on ids (intervals, then homogeneous integers) against CGAL's on
// the same points, among them constructions (edge/plane crossings kept as recipes, lazy).
// When every input is a double the table decides most signs by plain double arithmetic and an
// error bound (static_filter.h). Its answers must be CGAL's exact ones on general points, on
// points a rounding away from a plane or line, exactly on axis-parallel and tilted planes, and at
// magnitudes where the bound stops holding (the filter must then leave the decision to later
// stages).
TEST(PointTable, StaticFiltersAgreeWithCgalOnDoubles) {
  std::mt19937 random(16);
  std::uniform_real_distribution<double> unit(-1, 1);
  std::uniform_int_distribution<int> small(-4, 4), kind(0, 4);
  for (const double scale : {1.0, 1e-150, 1e150, 3e-5, 7e4}) {
    Mesh m;
    auto add = [&](double x, double y, double z) {
      m.points.emplace_back(x * scale, y * scale, z * scale);
    };
    for (int i = 0; i < 400; ++i) {
      switch (kind(random)) {
        case 0:  // on the plane z = 1/4
          add(unit(random), unit(random), 0.25);
          break;
        case 1:  // on the tilted plane x + 2y - z = 0, small integers: exactly representable
          add(small(random), small(random), 0),
              m.points.back() = Point(m.points.back().x(), m.points.back().y(),
                                      m.points.back().x() + 2 * m.points.back().y());
          break;
        case 2: {  // one rounding away from the plane x + y + z = 1
          const double x = unit(random), y = unit(random);
          add(x, y, std::nextafter(1 - x - y, 2.0));
          break;
        }
        default:
          add(unit(random), unit(random), unit(random));
      }
    }
    detail::PointTable table(m, m, true);
    for (int i = 0; i < 6000; ++i) {
      const auto id = [&] {
        return detail::PointId(std::uniform_int_distribution<int>(0, 399)(random));
      };
      const detail::PointId p = id(), q = id(), r = id(), t = id();
      ASSERT_EQ(table.orientation(p, q, r, t),
                CGAL::orientation(m.points[p], m.points[q], m.points[r], m.points[t]))
          << "scale " << scale << " case " << i;
      const int dropped = i % 3;
      const auto project = [&](detail::PointId v) {
        const Point& x = m.points[v];
        return dropped == 0   ? Kernel::Point_2(x.y(), x.z())
               : dropped == 1 ? Kernel::Point_2(x.x(), x.z())
                              : Kernel::Point_2(x.x(), x.y());
      };
      ASSERT_EQ(table.orientation_2(dropped, p, q, r),
                CGAL::orientation(project(p), project(q), project(r)))
          << "scale " << scale << " case " << i;
    }
  }
}

TEST(PointTable, PredicatesAndConstructionsAgreeWithCgal) {
  RandomPoints random(15);
  Mesh a, b;
  for (int i = 0; i < 600; ++i) a.points.push_back(random.point());
  // b: half of its points lie on planes or lines through points of a (degenerate predicates)
  for (int i = 0; i < 600; ++i) {
    const Point &p = a.points[(7 * i) % 600], &q = a.points[(7 * i + 1) % 600],
                &r = a.points[(7 * i + 2) % 600];
    b.points.push_back(i % 2 ? random.point()
                             : p + random.weight() * (q - p) + random.weight() * (r - p));
  }
  detail::PointTable table(a, b);
  auto id = [&](int side, int v) { return table.vertex(side, std::uint32_t(v)); };
  // Crossings of a's edges with planes of three a points, where the ends are on both sides.
  std::vector<detail::PointId> crossings;
  std::vector<Point> expected_crossings;
  for (int i = 0; crossings.size() < 200 && i < 3000; ++i) {
    const int p = i % 600, q = (i * 13 + 5) % 600, u = (i * 7 + 1) % 600, v = (i * 11 + 2) % 600,
              w = (i * 17 + 3) % 600;
    const Point &pp = a.points[p], &pq = a.points[q];
    const Kernel::Plane_3 plane(a.points[u], a.points[v], a.points[w]);
    if (plane.is_degenerate()) continue;
    const auto sp = plane.oriented_side(pp), sq = plane.oriented_side(pq);
    if (sp == CGAL::ON_ORIENTED_BOUNDARY || sq == CGAL::ON_ORIENTED_BOUNDARY || sp == sq) continue;
    detail::Recipe recipe{
        detail::Recipe::Kind::EdgePlane, -1, id(0, p), id(0, q), id(0, u), id(0, v), id(0, w)};
    crossings.push_back(table.add(recipe));
    const auto x = CGAL::intersection(plane, Kernel::Segment_3(pp, pq));
    expected_crossings.push_back(*boost::get<Point>(&*x));
  }
  ASSERT_GE(crossings.size(), 100u);
  // A later operation's table reads a constructed point's homogeneous coordinates without making
  // its rational ones: in lowest terms, they are those the rational coordinates give (W their
  // least common denominator). Here from the parents; at the end from the table's exact values.
  auto expect_homogeneous_as_from_rationals = [&] {
    for (std::size_t i = 0; i < crossings.size(); ++i)
      EXPECT_EQ(detail::homogeneous_of(table.point(crossings[i])),
                detail::homogeneous_of(CGAL::exact(expected_crossings[i])))
          << i;
  };
  expect_homogeneous_as_from_rationals();
  for (std::size_t i = 0; i < crossings.size(); ++i) {
    EXPECT_EQ(table.point(crossings[i]), expected_crossings[i]) << i;
    const auto approx = table.approx(crossings[i]);
    for (int k = 0; k < 3; ++k)  // the interval holds the exact value
      EXPECT_TRUE(approx.cartesian(k).inf() <=
                      CGAL::to_double(expected_crossings[i].cartesian(k)) &&
                  CGAL::to_double(expected_crossings[i].cartesian(k)) <= approx.cartesian(k).sup());
  }
  // Every predicate on ids of inputs and crossings against CGAL on the points.
  std::vector<detail::PointId> ids;
  for (int v = 0; v < 600; ++v) ids.push_back(id(v % 2, v));
  ids.insert(ids.end(), crossings.begin(), crossings.end());
  std::mt19937 pick(16);
  std::uniform_int_distribution<std::size_t> any(0, ids.size() - 1);
  for (int i = 0; i < 3000; ++i) {
    const detail::PointId p = ids[any(pick)], q = ids[any(pick)], r = ids[any(pick)],
                          s = ids[any(pick)];
    const Point P = table.point(p), Q = table.point(q), R = table.point(r), S = table.point(s);
    ASSERT_EQ(table.orientation(p, q, r, s), CGAL::orientation(P, Q, R, S)) << i;
    ASSERT_EQ(table.orientation_2(2, p, q, r),
              CGAL::Projection_traits_xy_3<Kernel>().orientation_2_object()(P, Q, R))
        << i;
    ASSERT_EQ(table.orientation_2(0, p, q, r),
              CGAL::Projection_traits_yz_3<Kernel>().orientation_2_object()(P, Q, R))
        << i;
    ASSERT_EQ(table.side_of_oriented_circle(1, p, q, r, s),
              CGAL::Projection_traits_xz_3<Kernel>().side_of_oriented_circle_2_object()(P, Q, R, S))
        << i;
    ASSERT_EQ(table.compare(1, p, q), CGAL::compare(P.y(), Q.y())) << i;
  }
  // Degenerate on purpose: points of b on planes of a, and a crossing on its own plane.
  for (int i = 0; i < 600; i += 2) {
    const int j = (7 * i) % 600;
    ASSERT_EQ(table.orientation(id(0, j), id(0, (j + 1) % 600), id(0, (j + 2) % 600), id(1, i)),
              CGAL::COPLANAR)
        << i;
  }
  for (std::size_t i = 0; i < crossings.size(); ++i) {
    const detail::Recipe& r = table.recipe(crossings[i]);
    ASSERT_EQ(table.orientation(r.a, r.b, r.c, crossings[i]), CGAL::COPLANAR) << i;
  }
  expect_homogeneous_as_from_rationals();
}

// The point table's constructed points: references taken before the array grows past several
// blocks still read the same elements, each index finds its own element, a move takes the
// elements along, and every element is destroyed once.
TEST(StableVector, ElementsStayInPlaceAsItGrows) {
  auto alive = std::make_shared<int>(0);
  struct Counted {
    std::shared_ptr<int> alive;
    std::string name;
    Counted(std::shared_ptr<int> a, std::string n) : alive(std::move(a)), name(std::move(n)) {
      ++*alive;
    }
    ~Counted() { --*alive; }
  };
  {
    detail::StableVector<Counted, 3> v;  // blocks of 8
    const Counted& first = v.emplace_back(alive, "0");
    std::vector<const Counted*> where;
    for (int i = 1; i < 100; ++i) where.push_back(&v.emplace_back(alive, std::to_string(i)));
    EXPECT_EQ(v.size(), 100u);
    EXPECT_EQ(*alive, 100);
    EXPECT_EQ(&v[0], &first);
    EXPECT_EQ(first.name, "0");
    for (int i = 1; i < 100; ++i) {
      EXPECT_EQ(&v[std::size_t(i)], where[std::size_t(i - 1)]);
      EXPECT_EQ(v[std::size_t(i)].name, std::to_string(i));
    }
    detail::StableVector<Counted, 3> moved(std::move(v));
    EXPECT_EQ(moved.size(), 100u);
    EXPECT_EQ(&moved[42], where[41]);
    EXPECT_EQ(*alive, 100);
  }
  EXPECT_EQ(*alive, 0);
}

// Guigue and Devillers' overlap test against CGAL's do_intersect on triangles with vertices on
// tiny grids, where zero signs (touching, shared vertices, edges in the other's plane) abound.
TEST(TriangleOverlap, AgreesWithCgalOnDegenerateTriangles) {
  std::mt19937 random(17);
  int tested = 0, meeting = 0;
  for (int grid : {1, 2, 3, 8}) {
    std::uniform_int_distribution<int> coordinate(0, grid);
    for (int i = 0; i < 4000; ++i) {
      Mesh a, b;
      for (int k = 0; k < 3; ++k) {
        a.points.emplace_back(coordinate(random), coordinate(random), coordinate(random));
        b.points.emplace_back(coordinate(random), coordinate(random), coordinate(random));
      }
      if (CGAL::collinear(a.points[0], a.points[1], a.points[2]) ||
          CGAL::collinear(b.points[0], b.points[1], b.points[2]))
        continue;
      detail::PointTable table(a, b);
      const std::array<detail::PointId, 3> t1{0, 1, 2}, t2{3, 4, 5};
      std::int8_t s1[3], s2[3];
      for (int k = 0; k < 3; ++k) {
        s1[k] = std::int8_t(table.orientation(t2[0], t2[1], t2[2], t1[k]));
        s2[k] = std::int8_t(table.orientation(t1[0], t1[1], t1[2], t2[k]));
      }
      const bool one_side_1 = s1[0] != 0 && s1[0] == s1[1] && s1[1] == s1[2];
      const bool one_side_2 = s2[0] != 0 && s2[0] == s2[1] && s2[1] == s2[2];
      const bool coplanar = s1[0] == 0 && s1[1] == 0 && s1[2] == 0;
      if (one_side_1 || one_side_2 || coplanar) continue;
      const bool truth =
          CGAL::do_intersect(Kernel::Triangle_3(a.points[0], a.points[1], a.points[2]),
                             Kernel::Triangle_3(b.points[0], b.points[1], b.points[2]));
      ASSERT_EQ(detail::TriangleOverlap(table)(t1, t2, s1, s2), truth)
          << "grid " << grid << " " << i;
      ++tested;
      meeting += truth;
    }
  }
  EXPECT_GT(tested, 5000);
  EXPECT_GT(meeting, 1000);
  EXPECT_LT(meeting, tested);
}

// The static filters for points known within an error of their doubles (rational inputs: a
// rotated mesh) against CGAL's exact orientation of the exact points: nearly coplanar and nearly
// collinear points, each moved off its double by up to the error, at scales 2^-80 to 2^80. A
// sign given must be the exact one; most generic configurations must get one.
TEST(StaticFilter, SignsOfPointsNearTheirDoublesAreExact) {
  std::mt19937_64 random(61);
  std::uniform_real_distribution<double> unit(-1, 1);
  std::uniform_int_distribution<int> scale_exponent(-80, 80), shift(-3, 3);
  int decided_generic = 0, generic = 0, decided_near = 0, wrong = 0;
  for (int i = 0; i < 20000; ++i) {
    const int e = scale_exponent(random);
    const double scale = std::ldexp(1.0, e), error = std::ldexp(scale, -45 + shift(random));
    const bool near = i % 2 == 0;
    std::array<detail::Xyz, 4> d;
    for (int k = 0; k < 3; ++k)
      d[k] = {unit(random) * scale, unit(random) * scale, unit(random) * scale};
    if (near) {  // the fourth in the plane of the first three, up to rounding (z over x, y)
      const double a = unit(random), b = unit(random);
      for (int c = 0; c < 3; ++c)
        d[3][c] = d[0][c] + a * (d[1][c] - d[0][c]) + b * (d[2][c] - d[0][c]);
    } else {
      d[3] = {unit(random) * scale, unit(random) * scale, unit(random) * scale};
    }
    // The exact points: each coordinate off its double by a rational within the error.
    std::array<Point, 4> p;
    for (int k = 0; k < 4; ++k) {
      FT c[3];
      for (int j = 0; j < 3; ++j)
        c[j] = FT(d[k][j]) + FT(error) * FT(int(random() % 2001) - 1000) / 1000;
      p[k] = Point(c[0], c[1], c[2]);
    }
    const int exact = int(CGAL::orientation(p[0], p[1], p[2], p[3]));
    if (const auto o = detail::static_orientation_near(d[0], d[1], d[2], d[3], error)) {
      wrong += *o != exact;
      (near ? decided_near : decided_generic)++;
    }
    generic += !near;
    // Two dimensions, on (x, y): the fourth point again, or (near) one on the line of the
    // first two up to rounding, moved off its double as above.
    using Point_2 = Kernel::Point_2;
    detail::Xyz c = d[3];
    Point_2 x2(p[3].x(), p[3].y());
    if (near) {
      const double t = unit(random);
      for (int j = 0; j < 2; ++j) c[j] = d[0][j] + t * (d[1][j] - d[0][j]);
      x2 = Point_2(FT(c[0]) + FT(error) * FT(int(random() % 2001) - 1000) / 1000,
                   FT(c[1]) + FT(error) * FT(int(random() % 2001) - 1000) / 1000);
    }
    const int exact_2 =
        int(CGAL::orientation(Point_2(p[0].x(), p[0].y()), Point_2(p[1].x(), p[1].y()), x2));
    if (const auto o = detail::static_orientation_2_near(0, 1, d[0], d[1], c, error))
      wrong += *o != exact_2;
  }
  EXPECT_EQ(wrong, 0);
  EXPECT_GT(decided_generic, generic * 9 / 10);
  EXPECT_LT(decided_near, 10000 / 2);  // nearly coplanar: mostly left to the exact stages
}

// The turn from a to b seen along an exact direction d, for a, b differences of points near
// their doubles (the star proof along a mean normal): a sign given is that of the exact
// determinant, in doubles (error 0) and within errors, on nearly degenerate configurations too.
TEST(StaticFilter, TurnsAlongADirectionAreExact) {
  std::mt19937_64 random(67);
  std::uniform_real_distribution<double> unit(-1, 1);
  std::uniform_int_distribution<int> scale_exponent(-60, 60), shift(-3, 3);
  int decided_generic = 0, generic = 0, wrong = 0;
  for (int i = 0; i < 20000; ++i) {
    const double scale = std::ldexp(1.0, scale_exponent(random));
    const double error = i % 3 == 0 ? 0 : std::ldexp(scale, -45 + shift(random));
    const bool near = i % 2 == 0;
    std::array<detail::Xyz, 3> q;  // v, p, q
    for (auto& x : q) x = {unit(random) * scale, unit(random) * scale, unit(random) * scale};
    const detail::Xyz d = {unit(random), unit(random), unit(random)};
    if (near)  // q - v nearly along p - v and d: a turn of almost nothing
      for (int c = 0; c < 3; ++c)
        q[2][c] = q[0][c] + 0.7 * (q[1][c] - q[0][c]) + 1e-3 * scale * unit(random) * 1e-12 +
                  0.3 * scale * d[c];
    std::array<Point, 3> p;  // exact points off the doubles by up to the error
    for (int k = 0; k < 3; ++k) {
      FT c[3];
      for (int j = 0; j < 3; ++j)
        c[j] = FT(q[k][j]) + FT(error) * FT(int(random() % 2001) - 1000) / 1000;
      p[k] = Point(c[0], c[1], c[2]);
    }
    const Kernel::Vector_3 a = p[1] - p[0], b = p[2] - p[0], dv(d[0], d[1], d[2]);
    const int exact = int(CGAL::sign(CGAL::determinant(a, b, dv)));
    const detail::Xyz ad = {q[1][0] - q[0][0], q[1][1] - q[0][1], q[1][2] - q[0][2]},
                      bd = {q[2][0] - q[0][0], q[2][1] - q[0][1], q[2][2] - q[0][2]};
    if (const auto o = detail::static_turn_along(ad, bd, d, error)) {
      wrong += *o != exact;
      decided_generic += !near;
    }
    generic += !near;
  }
  EXPECT_EQ(wrong, 0);
  EXPECT_GT(decided_generic, generic * 9 / 10);
}

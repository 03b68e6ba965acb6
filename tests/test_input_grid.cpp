// SPDX-License-Identifier: GPL-3.0-or-later
// The inputs' integer grid (exact/input_grid.h) against CGAL's exact predicates: rotated points
// (rational, over divisors of one denominator times powers of two) with doubles beside them,
// exactly coplanar, collinear and equal configurations where only the exact stage can answer,
// inputs the grid must refuse, and a PointTable that switches to the grid while it is asked.
#include <gtest/gtest.h>

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "exact/input_grid.h"
#include "exact/point_table.h"
#include "morphex/shapes.h"

using namespace morphex;
using detail::InputGrid;

namespace {

bool never_constructed(const Point&) {
  return false;
}
bool always_constructed(const Point&) {
  return true;
}

// Points on a few planes and lines (integer combinations of a few doubles), half of them turned
// by an exact rotation whose half tangents are 3/10 and 7/20 (denominators 109 and 449 times
// powers of two), with doubles of several magnitudes and zeros among the rest.
std::vector<Point> rotated_cloud(unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_int_distribution<int> small(-9, 9);
  const double scales[] = {1.0, 0.125, 3.0 / 1024, 1e-3, 17.5};
  std::vector<Point> base;
  for (int i = 0; i < 120; ++i) {
    const double s = scales[i % 5];
    const double x = small(random) * s, y = small(random) * s;
    switch (i % 4) {
      case 0:  // the plane z = 2 x - y, shared by a quarter of the points
        base.emplace_back(x, y, 2 * x - y);
        break;
      case 1:  // the line x = y = z / 4
        base.emplace_back(x, x, 4 * x);
        break;
      case 2:  // the plane x = 0.375
        base.emplace_back(0.375, x, y);
        break;
      default:
        base.emplace_back(x, y, small(random) * scales[(i + 2) % 5]);
    }
  }
  const Transformation turn =
      half_tangent_rotation(0, FT(3) / 10) * half_tangent_rotation(2, FT(7) / 20);
  std::vector<Point> out;
  for (std::size_t i = 0; i < base.size(); ++i) {
    Point p = i % 2 == 0 ? turn.transform(base[i]) : base[i];
    CGAL::exact(p);
    out.push_back(p);
  }
  return out;
}

// The grid's inputs: the points, each taken through its own representation.
std::vector<InputGrid::Input> addresses(const std::vector<Point>& points) {
  std::vector<InputGrid::Input> out;
  for (const Point& p : points) out.push_back({&p, nullptr});
  return out;
}

}  // namespace

TEST(InputGrid, PredicatesAgreeWithCgalOnRotatedPointsAndDoubles) {
  const std::vector<Point> points = rotated_cloud(5);
  const auto grid = InputGrid::build(addresses(points), &never_constructed);
  ASSERT_NE(grid, nullptr);
  const std::size_t n = points.size();
  // The same grid when the caller hands over the doubles it knows.
  std::vector<std::array<double, 3>> xyz(n);
  std::vector<InputGrid::Input> given = addresses(points);
  for (std::size_t i = 0; i < n; ++i)
    if (has_double_coordinates(points[i])) {
      xyz[i] = {CGAL::to_double(points[i].x()), CGAL::to_double(points[i].y()),
                CGAL::to_double(points[i].z())};
      given[i].doubles = &xyz[i];
    }
  const auto same = InputGrid::build(given, &never_constructed);
  ASSERT_NE(same, nullptr);
  for (std::size_t i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k)
      for (int l = 0; l < 2; ++l) ASSERT_EQ((*same)[i][k].limb[l], (*grid)[i][k].limb[l]) << i;
  std::mt19937 random(6);
  // Quadruples within one class (i mod 4, and the same parity: turned or not) are often
  // degenerate; any others rarely.
  auto pick = [&](std::size_t like) {
    std::size_t i = random() % n;
    if (random() % 4 != 0) i = (i - i % 8 + like % 8) % n;
    return i;
  };
  int zeros3 = 0, zeros2 = 0, equal = 0, cases = 0;
  for (int k = 0; k < 20000; ++k) {
    const std::size_t p = random() % n, q = pick(p), r = pick(p), s = pick(p);
    const auto expected = CGAL::orientation(points[p], points[q], points[r], points[s]);
    ASSERT_EQ(InputGrid::orientation((*grid)[p], (*grid)[q], (*grid)[r], (*grid)[s]), int(expected))
        << p << " " << q << " " << r << " " << s;
    const InputGrid::Plane plane((*grid)[p], (*grid)[q], (*grid)[r]);
    ASSERT_EQ(plane.side((*grid)[s]), int(expected));
    zeros3 += expected == CGAL::COPLANAR;
    for (int dropped = 0; dropped < 3; ++dropped) {
      const int u = dropped == 0 ? 1 : 0, v = dropped == 2 ? 1 : 2;
      auto project = [&](const Point& a) {
        return Kernel::Point_2(a.cartesian(u), a.cartesian(v));
      };
      const auto expected_2 =
          CGAL::orientation(project(points[p]), project(points[q]), project(points[r]));
      ASSERT_EQ(InputGrid::orientation_2(u, v, (*grid)[p], (*grid)[q], (*grid)[r]),
                int(expected_2));
      zeros2 += expected_2 == CGAL::COLLINEAR;
      const auto order = CGAL::compare(points[p].cartesian(dropped), points[q].cartesian(dropped));
      ASSERT_EQ(InputGrid::compare(dropped, (*grid)[p], (*grid)[q]), int(order));
      equal += order == CGAL::EQUAL;
    }
    ++cases;
  }
  // The configurations the exact stage is for must have been met, many times each.
  EXPECT_GT(zeros3, 2000);
  EXPECT_GT(zeros2, 2000);
  EXPECT_GT(equal, 1000);
  EXPECT_EQ(cases, 20000);
}

// Integer coordinates up to the grid's bound, so that differences, minors and determinants come
// near the widths their types hold (an overflow would wrap and change a sign): random points of
// either sign, and points q + r - p exactly coplanar with p, q, r.
TEST(InputGrid, CoordinatesNearTheBoundAgreeWithCgal) {
  gmp_randclass random(gmp_randinit_default);
  random.seed(12);
  const mpz_class bound = mpz_class(1) << InputGrid::kBits;
  auto coordinate = [&](int bits) {
    mpz_class x = random.get_z_bits(bits);
    if (random.get_z_bits(1) == 1) x = -x;
    return x;
  };
  std::vector<Point> points;
  for (int i = 0; i < 200; ++i) {
    if (i % 8 == 3) {  // q + r - p of the previous three, each below 2^123
      const auto& p = points[i - 3];
      const auto& q = points[i - 2];
      const auto& r = points[i - 1];
      points.push_back(q + (r - p));
      continue;
    }
    const int bits = i % 8 < 4 ? 123 : InputGrid::kBits;
    points.emplace_back(FT(coordinate(bits)), FT(coordinate(bits)), FT(coordinate(bits)));
  }
  for (const Point& p : points)
    for (int k = 0; k < 3; ++k) ASSERT_LT(abs(CGAL::exact(p.cartesian(k))), mpq_class(bound));
  const auto grid = InputGrid::build(addresses(points), &never_constructed);
  ASSERT_NE(grid, nullptr);
  int zeros = 0;
  auto agree = [&](std::size_t a, std::size_t b, std::size_t c, std::size_t d) {
    const auto expected = CGAL::orientation(points[a], points[b], points[c], points[d]);
    ASSERT_EQ(InputGrid::orientation((*grid)[a], (*grid)[b], (*grid)[c], (*grid)[d]), int(expected))
        << a << " " << b << " " << c << " " << d;
    ASSERT_EQ(InputGrid::Plane((*grid)[a], (*grid)[b], (*grid)[c]).side((*grid)[d]), int(expected));
    ASSERT_EQ(InputGrid::compare(0, (*grid)[a], (*grid)[d]),
              int(CGAL::compare(points[a].x(), points[d].x())));
    zeros += expected == CGAL::COPLANAR;
  };
  std::mt19937 pick(13);
  for (std::size_t group = 0; group + 3 < points.size(); group += 8) {
    std::array<std::size_t, 4> order = {group, group + 1, group + 2, group + 3};
    do agree(order[0], order[1], order[2], order[3]);  // all 24 orders of a coplanar four
    while (std::next_permutation(order.begin(), order.end()));
  }
  for (int k = 0; k < 3000; ++k)
    agree(pick() % points.size(), pick() % points.size(), pick() % points.size(),
          pick() % points.size());
  EXPECT_GE(zeros, 25 * 24);
}

TEST(InputGrid, RefusesWhatItCannotHold) {
  // Denominators whose lcm passes the bound: distinct primes near 2^40.
  std::vector<Point> primes;
  mpz_class prime(mpz_class(1) << 40);
  for (int i = 0; i < 4; ++i) {
    mpz_nextprime(prime.get_mpz_t(), prime.get_mpz_t());
    primes.emplace_back(FT(mpq_class(1, prime)), FT(0), FT(1));
  }
  EXPECT_EQ(InputGrid::build(addresses(primes), &never_constructed), nullptr);
  // Two such denominators fit (80 bits).
  primes.resize(2);
  EXPECT_NE(InputGrid::build(addresses(primes), &never_constructed), nullptr);
  // Doubles 2^-90 beside 2^35: the integer 2^125 over the common denominator 2^90 passes the
  // grid's bound; beside 2^34 it fits.
  const std::vector<Point> spread = {Point(std::ldexp(1.0, -90), 0, 0),
                                     Point(std::ldexp(1.0, 35), 1, 2)};
  EXPECT_EQ(InputGrid::build(addresses(spread), &never_constructed), nullptr);
  const std::vector<Point> close = {Point(std::ldexp(1.0, -90), 0, 0),
                                    Point(-std::ldexp(1.0, 34), 1, 2)};
  EXPECT_NE(InputGrid::build(addresses(close), &never_constructed), nullptr);
  // A point that an earlier operation constructed keeps its own exact stage.
  const std::vector<Point> rational = {Point(FT(1) / 3, FT(2), FT(0))};
  EXPECT_EQ(InputGrid::build(addresses(rational), &always_constructed), nullptr);
  EXPECT_NE(InputGrid::build(addresses(rational), &never_constructed), nullptr);
}

// The table's exact stage before the grid exists, while it is being built, and after: every
// answer the same as CGAL's. The cloud is asked far more often than the count that builds the
// grid, from parallel tasks: as one mesh, and as two (its doubles against its rational points,
// with questions across the two, where the table keeps its homogeneous stage).
TEST(PointTable, RationalInputsAgreeWithCgalBeforeAndAfterTheirGrid) {
  const std::vector<Point> pts = rotated_cloud(8);
  const std::size_t n = pts.size();
  Mesh cloud, doubles, rationals;  // rotated_cloud turns the even points only
  cloud.points = pts;
  for (std::size_t i = 0; i < n; ++i) (i % 2 == 0 ? rationals : doubles).points.push_back(pts[i]);
  for (Mesh* m : {&cloud, &doubles, &rationals}) m->triangles.push_back({0, 1, 2});
  std::vector<std::array<std::size_t, 4>> questions;
  std::mt19937 random(9);
  for (int k = 0; k < 6000; ++k) {
    const std::size_t p = random() % n;
    // Mostly another point of p's class (its index mod 8): often a degenerate configuration.
    auto like = [&] { return k % 4 == 0 ? random() % n : (random() % (n / 8)) * 8 + p % 8; };
    questions.push_back({p, like(), like(), like()});
  }
  for (const bool two_meshes : {false, true}) {
    const detail::PointTable table = two_meshes ? detail::PointTable(doubles, rationals)
                                                : detail::PointTable(cloud, cloud, true);
    auto id = [&](std::size_t i) {
      return two_meshes ? table.vertex(i % 2 == 0 ? 1 : 0, std::uint32_t(i / 2))
                        : detail::PointId(i);
    };
    std::vector<int> wrong(questions.size(), 0);
    tbb::parallel_for(std::size_t(0), questions.size(), [&](std::size_t k) {
      const auto [p, q, r, s] = questions[k];
      const detail::PointId ip = id(p), iq = id(q), ir = id(r), is = id(s);
      if (table.orientation(ip, iq, ir, is) != CGAL::orientation(pts[p], pts[q], pts[r], pts[s]))
        wrong[k] |= 1;
      if (ip != iq && iq != ir && ip != ir) {
        const detail::PointTable::PlaneSides sides(table, {ip, iq, ir});
        if (sides(is) != CGAL::orientation(pts[p], pts[q], pts[r], pts[s])) wrong[k] |= 2;
      }
      const int axis = int(k % 3);
      if (table.compare(axis, ip, iq) !=
          CGAL::compare(pts[p].cartesian(axis), pts[q].cartesian(axis)))
        wrong[k] |= 4;
      const int u = axis == 0 ? 1 : 0, v = axis == 2 ? 1 : 2;
      const auto projected =
          CGAL::orientation(Kernel::Point_2(pts[p].cartesian(u), pts[p].cartesian(v)),
                            Kernel::Point_2(pts[q].cartesian(u), pts[q].cartesian(v)),
                            Kernel::Point_2(pts[r].cartesian(u), pts[r].cartesian(v)));
      if (table.orientation_2(axis, ip, iq, ir) != projected) wrong[k] |= 8;
    });
    for (std::size_t k = 0; k < questions.size(); ++k)
      ASSERT_EQ(wrong[k], 0) << (two_meshes ? "two meshes" : "one mesh") << ", question " << k
                             << " (1 orientation, 2 plane sides, 4 compare, 8 projected "
                             << "orientation)";
  }
}

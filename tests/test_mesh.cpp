// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include "morphex/mesh.h"

using namespace morphex;

TEST(Rational, PrintsLowestTerms) {
  EXPECT_EQ(to_rational_string(FT(6) / FT(16)), "3/8");
  EXPECT_EQ(to_rational_string(FT(27)), "27");
  EXPECT_EQ(to_rational_string(FT(-1) / FT(3)), "-1/3");
  EXPECT_EQ(to_rational_string(FT(0.1)), "3602879701896397/36028797018963968");
}

TEST(Rational, ParsesRationalsAndDecimals) {
  EXPECT_EQ(parse_exact_number("6/16"), FT(3) / FT(8));
  EXPECT_EQ(parse_exact_number("-7"), FT(-7));
  EXPECT_EQ(parse_exact_number("0.1"), FT(0.1));
  EXPECT_EQ(parse_exact_number("1e2"), FT(100));
  EXPECT_EQ(parse_exact_number("123456789012345678901234567890/3"),
            FT(CGAL::exact(parse_exact_number("41152263004115226300411522630"))));
  EXPECT_THROW(parse_exact_number("1/0"), std::invalid_argument);
  EXPECT_THROW(parse_exact_number("abc"), std::invalid_argument);
  EXPECT_THROW(parse_exact_number("nan"), std::invalid_argument);
  EXPECT_THROW(parse_exact_number("inf"), std::invalid_argument);
  EXPECT_THROW(parse_exact_number(""), std::invalid_argument);
}

namespace {
Mesh unit_cube() {
  Mesh m;
  for (int i = 0; i < 8; ++i) m.points.emplace_back(i & 1, (i >> 1) & 1, (i >> 2) & 1);
  m.triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                 {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  return m;
}
}  // namespace

TEST(Volume, UnitCubeIsExactlyOne) {
  EXPECT_EQ(signed_volume(unit_cube()), FT(1));
}

TEST(Volume, ScaledByAThirdIsExact) {
  Mesh m = unit_cube();
  for (Point& p : m.points) p = Point(p.x() / 3, p.y() / 3, p.z() / 3);
  EXPECT_EQ(to_rational_string(signed_volume(m)), "1/27");
  make_exact(m);
  EXPECT_EQ(to_rational_string(signed_volume(m)), "1/27");
}

TEST(Volume, ReversedOrientationIsNegative) {
  Mesh m = unit_cube();
  for (Triangle& t : m.triangles) std::swap(t[1], t[2]);
  EXPECT_EQ(signed_volume(m), FT(-1));
}

TEST(DoubleMesh, RoundTripIsLosslessForDoubles) {
  Mesh m = unit_cube();
  m.points[0] = Point(0.1, -2.5e-7, 3.0);
  Mesh back = from_double(to_double(m));
  ASSERT_EQ(back.points.size(), m.points.size());
  for (std::size_t i = 0; i < m.points.size(); ++i) EXPECT_EQ(back.points[i], m.points[i]);
  EXPECT_EQ(back.triangles, m.triangles);
}

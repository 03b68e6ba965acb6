// SPDX-License-Identifier: GPL-3.0-or-later
// The exact stage's integers (fixed_integer.h) and plane forms (PointTable::PlaneSides) against
// GMP's determinants: signs of 3x3 and 4x4 determinants, and of many points against one plane.
#include <gtest/gtest.h>

#include <array>
#include <random>
#include <string>

#include "exact/filtered.h"
#include "exact/fixed_integer.h"
#include "exact/point_table.h"

using namespace morphex;

// Determinant signs on stack buffers against mpz, from 20-bit to 600-bit entries (beyond the
// buffers the fixed versions must decline, never answer wrongly), with exactly singular
// matrices: a row that is a combination of the others.
TEST(FixedInteger, DeterminantSignsAgreeWithMpz) {
  gmp_randclass random(gmp_randinit_default);
  random.seed(18);
  int fixed4 = 0, declined4 = 0, zeros = 0;
  for (int bits : {20, 62, 64, 100, 200, 250, 300, 600})
    for (int i = 0; i < 300; ++i) {
      std::array<mpz_class, 4> r[4];
      for (auto& row : r)
        for (auto& x : row) {
          x = random.get_z_bits(bits);
          if (random.get_z_bits(1) == 1) x = -x;
        }
      if (i % 3 == 0)  // singular: row 3 = a row 0 + b row 1 - c row 2
        for (int j = 0; j < 4; ++j) r[3][j] = 3 * r[0][j] - 2 * r[1][j] + 5 * r[2][j];
      const std::array<mpz_class, 4>* rows[4] = {&r[0], &r[1], &r[2], &r[3]};
      const int expected = detail::sign_of_det4(r[0], r[1], r[2], r[3]);
      zeros += expected == 0;
      if (const auto sign = detail::fixed_sign_of_det4(rows)) {
        ASSERT_EQ(*sign, expected) << bits << " bits, case " << i;
        ++fixed4;
      } else {
        ++declined4;
      }
      const std::array<mpz_class, 4>* rows3[3] = {&r[0], &r[1], &r[3]};
      const mpz_class d3 = r[0][0] * (r[1][1] * r[3][3] - r[1][3] * r[3][1]) -
                           r[0][1] * (r[1][0] * r[3][3] - r[1][3] * r[3][0]) +
                           r[0][3] * (r[1][0] * r[3][1] - r[1][1] * r[3][0]);
      if (const auto sign = detail::fixed_sign_of_det3<4>(rows3, 0, 1, 3))
        ASSERT_EQ(*sign, sgn(d3)) << bits << " bits, case " << i;
    }
  EXPECT_GT(fixed4, 1500);    // the buffers hold up to 256-bit entries
  EXPECT_GT(declined4, 400);  // 300- and 600-bit entries fall back
  EXPECT_GT(zeros, 600);
}

// The plane form's signs (cofactors of three rows computed once, then four products per point)
// against mpz determinants: many points per plane, a third of them on it, entries of 20 to 600
// bits (beyond the buffers the form, or its evaluation, must decline).
TEST(FixedInteger, PlaneFormSignsAgreeWithMpz) {
  gmp_randclass random(gmp_randinit_default);
  random.seed(19);
  int answered = 0, declined = 0, zeros = 0;
  auto draw = [&](int bits) {
    mpz_class x = random.get_z_bits(bits);
    return random.get_z_bits(1) == 1 ? mpz_class(-x) : x;
  };
  for (int bits : {20, 64, 100, 250, 256, 300, 600})
    for (int plane = 0; plane < 40; ++plane) {
      std::array<mpz_class, 4> r[3];
      for (auto& row : r)
        for (auto& x : row) x = draw(bits);
      const std::array<mpz_class, 4>* rows[3] = {&r[0], &r[1], &r[2]};
      const auto form = detail::FixedPlaneForm::through(rows);
      for (int i = 0; i < 20; ++i) {
        std::array<mpz_class, 4> x;
        for (int j = 0; j < 4; ++j)
          x[j] = i % 3 == 0 ? mpz_class(2 * r[0][j] - 7 * r[1][j] + r[2][j]) : draw(bits);
        const int expected = detail::sign_of_det4(r[0], r[1], r[2], x);
        zeros += expected == 0;
        const std::optional<int> sign = form ? form->sign_at(x) : std::nullopt;
        if (!sign) {
          ++declined;
          continue;
        }
        ASSERT_EQ(*sign, expected) << bits << " bits, plane " << plane << ", point " << i;
        ++answered;
      }
    }
  EXPECT_GT(answered, 3000);  // up to 256-bit entries
  EXPECT_GT(declined, 1500);  // 300- and 600-bit ones (and the on-plane points past the buffers)
  EXPECT_GT(zeros, 1500);
}

// A plane's sides by its linear form (PointTable::PlaneSides) against the 4x4 determinant of each
// point (orientation_exact): doubles, small rationals (the fixed-size form) and rationals whose
// homogeneous coordinates are too large for it (the GMP equation), points on the plane included.
TEST(PlaneSides, AgreeWithTheDeterminantOfEachPoint) {
  std::mt19937_64 random(71);
  std::uniform_int_distribution<int> coordinate(-20, 20);
  for (const int digits : {0, 3, 100}) {  // a common denominator of 10^digits + 7
    const FT denominator =
        FT(mpq_class(mpz_class("1" + std::string(digits, '0')) + (digits == 0 ? 0 : 7)));
    Mesh m;
    for (int i = 0; i < 40; ++i) {
      const FT x = FT(coordinate(random)) / denominator, y = FT(coordinate(random)) / denominator;
      // Every fourth point on the plane z = x + 2 y of the first three (which lie on it too).
      const FT z = i < 3 || i % 4 == 0 ? x + 2 * y : FT(coordinate(random)) / denominator;
      m.points.emplace_back(x, y, z);
    }
    m.triangles.push_back({0, 1, 2});
    const detail::PointTable table(m, m, true);
    for (int plane = 0; plane + 2 < 40; plane += 7) {
      const std::array<detail::PointId, 3> corners = {table.vertex(0, VertexIndex(plane)),
                                                      table.vertex(0, VertexIndex(plane + 1)),
                                                      table.vertex(0, VertexIndex(plane + 2))};
      const detail::PointTable::PlaneSides sides(table, corners);
      for (VertexIndex v = 0; v < 40; ++v) {
        const detail::PointId s = table.vertex(0, v);
        const CGAL::Sign expected = table.orientation_exact(corners[0], corners[1], corners[2], s);
        ASSERT_EQ(sides.exact(s), expected)
            << digits << " digits, plane " << plane << ", point " << v;
        ASSERT_EQ(sides(s), expected);
      }
    }
  }
}

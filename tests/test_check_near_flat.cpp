// SPDX-License-Identifier: GPL-3.0-or-later
// Nearly flat patches in the self-intersection check (check_planar.h): flat faces of long thin
// facets that a rounded rotation left flat only up to rounding are proved embedded along an axis,
// and only what reaches into their slab is tested against them, piece by piece. Against CGAL's
// triangle predicates over every pair, and (the boxes) against exact points of the triangles.
#include <gtest/gtest.h>

#include <random>

#include "check/check_planar.h"
#include "check_test_support.h"
#include "exact/point_table.h"
#include "morphex/check.h"
#include "morphex/internal/fixtures.h"

using namespace morphex;
using test_support::improper_pairs_by_brute_force;
using test_support::improper_pairs_by_check;
using test_support::proved_patches_of;
using test_support::turned_and_rounded;

namespace {
std::size_t slabs(const detail::PlanarPatches& p) {
  std::size_t n = 0;
  for (const auto& patch : p.patches) n += patch.kind == detail::PlanarPatch::Kind::NearlyFlat;
  return n;
}
}  // namespace

// A fan prism's caps (long thin facets from one rim vertex) turned in doubles are no longer
// exactly flat; both are proved as nearly flat patches, and the solid is valid with no improper
// pair, as testing every pair finds too.
TEST(NearFlat, TurnedCapsAreProvedAsNearlyFlatPatches) {
  for (const auto& [a, b] : {std::pair{0.3, 0.7}, std::pair{1.1, -0.4}, std::pair{2.5, 2.9}}) {
    const Mesh m = turned_and_rounded(make_fan_prism(40, 2.0, 1.0), a, b);
    EXPECT_EQ(proved_patches_of(m, false).patches.size(), 0u);  // no longer exactly flat
    const detail::PlanarPatches patches = proved_patches_of(m, true);
    EXPECT_EQ(patches.patches.size(), 2u);
    EXPECT_EQ(slabs(patches), 2u);
    for (const auto& patch : patches.patches) EXPECT_EQ(patch.triangles.size(), 38u);
    const MeshReport r = check_mesh(m);
    EXPECT_TRUE(r.valid_solid()) << describe_problems(r);
    EXPECT_TRUE(improper_pairs_by_brute_force(m).empty());
  }
}

// Broken caps (a rim vertex moved inward or two swapped: folds inside the patch), a cap bent
// out of its plane by a little or a lot, and other solids piercing, touching or beside a cap,
// all turned in doubles: the improper pairs the check lists are exactly those of all pairs.
TEST(NearFlat, ImproperPairsAgreeWithBruteForce) {
  std::mt19937 random(31);
  auto pick = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(random); };
  int intersecting = 0, with_slabs = 0;
  for (int i = 0; i < 70; ++i) {
    const int n = pick(17, 30);
    const int kind = pick(0, 6);
    Mesh m = test_support::fan_prism_case(n, kind, pick);
    m = turned_and_rounded(m, pick(1, 600) / 100.0, pick(1, 600) / 100.0);
    with_slabs += slabs(proved_patches_of(m, true)) > 0;
    const auto expected = improper_pairs_by_brute_force(m);
    ASSERT_EQ(improper_pairs_by_check(m), expected) << "case " << i << " kind " << kind;
    intersecting += !expected.empty();
  }
  EXPECT_GT(intersecting, 20);
  EXPECT_LT(intersecting, 62);
  EXPECT_GT(with_slabs, 45);  // the cases go through the nearly flat patches
}

// The boxes the slab test relies on hold what they claim, checked on exact points: every point
// of a triangle lies in one of its pieces' boxes, and every point of it within a slab lies in
// the box of its part in the slab (none when the triangle is said to be outside). Thin
// triangles in all directions, some with rational corners (intervals wider than a point), with
// the boxes along the coordinate axes and along a turned frame (box_frame.h: the boxes hold the
// images of the points).
TEST(NearFlat, PiecesAndSlabPartsHoldTheirTriangles) {
  std::mt19937 random(37);
  std::uniform_real_distribution<double> coordinate(-1, 1);
  constexpr int kSteps = 12;  // points i/kSteps, j/kSteps of the triangle, corners and edges too
  int outside = 0, pieces_used = 0;
  // The coordinate axes, and a turned frame (any linear map: the boxes hold the images).
  detail::BoxFrame frames[2];
  frames[1].world = false;
  frames[1].axis = {detail::Xyz{0.2, -0.4, 0.8944271909999159},
                    detail::Xyz{0.9128709291752769, 0.4082482904638631, 0.0},
                    detail::Xyz{-0.3651483716701107, 0.816496580927726, 0.4472135954999579}};
  for (int trial = 0; trial < 300; ++trial) {
    Mesh m;
    const Point a(coordinate(random), coordinate(random), coordinate(random));
    const Vector long_side(coordinate(random), coordinate(random), coordinate(random));
    const FT width = FT(1) / std::uniform_int_distribution<int>(1, 1000)(random);
    const Vector across(coordinate(random) * width, coordinate(random) * width,
                        coordinate(random) * width);
    const FT third = trial % 3 == 0 ? FT(1) / 3 : FT(1) / 4;  // thirds: not dyadic
    m.points = {a, a + long_side, a + long_side * third + across};
    m.triangles = {{0, 1, 2}};
    const detail::PointTable table(m, m, true);
    const std::array<detail::PointId, 3> t = {0, 1, 2};
    detail::PlanarPatch slab;
    slab.kind = detail::PlanarPatch::Kind::NearlyFlat;
    slab.normal = {coordinate(random), coordinate(random), coordinate(random)};
    slab.low = coordinate(random);
    slab.high = slab.low + std::abs(coordinate(random)) / 4;
    const detail::BoxFrame& frame = frames[trial % 2];
    std::vector<CGAL::Bbox_3> pieces;
    std::optional<CGAL::Bbox_3> part;
    {
      const detail::UpwardRounding rounding;
      const detail::ApproxCorners corners = detail::corners_in(table, frame, t);
      detail::add_pieces(corners, detail::pieces_for(corners), pieces);
      part = detail::part_in_slab(table, slab, t, frame);
    }
    pieces_used += pieces.size() > 1;
    outside += !part;
    // The exact image of p along the frame's axes lies in the box.
    auto in = [&](const Point& p, const CGAL::Bbox_3& b) {
      for (int k = 0; k < 3; ++k) {
        const FT x = frame.world ? p[k]
                                 : p.x() * frame.axis[k][0] + p.y() * frame.axis[k][1] +
                                       p.z() * frame.axis[k][2];
        if (x < b.min(k) || x > b.max(k)) return false;
      }
      return true;
    };
    for (int i = 0; i <= kSteps; ++i)
      for (int j = 0; i + j <= kSteps; ++j) {
        const FT u = FT(i) / kSteps, v = FT(j) / kSteps;
        const Point p =
            m.points[0] + (m.points[1] - m.points[0]) * u + (m.points[2] - m.points[0]) * v;
        bool covered = false;
        for (const auto& b : pieces) covered = covered || in(p, b);
        ASSERT_TRUE(covered) << "trial " << trial;
        const FT h = slab.normal[0] * p.x() + slab.normal[1] * p.y() + slab.normal[2] * p.z();
        if (h >= slab.low && h <= slab.high) {
          ASSERT_TRUE(part) << "trial " << trial;
          ASSERT_TRUE(in(p, *part)) << "trial " << trial;
        }
      }
  }
  EXPECT_GT(pieces_used, 100);
  EXPECT_GT(outside, 30);
  EXPECT_LT(outside, 270);
}

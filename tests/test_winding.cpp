// SPDX-License-Identifier: GPL-3.0-or-later
// winding_solid: the region {w >= k} of self-intersecting chains, exactly, against closed forms
// and against the exact Booleans of the same solids.
#include <gtest/gtest.h>

#include <random>

#include "morphex/boolean.h"
#include "morphex/check.h"
#include "morphex/internal/fixtures.h"
#include "morphex/winding.h"

using namespace morphex;

namespace {

FT valid_volume(const Mesh& m) {
  const MeshReport report = check_mesh(m);
  EXPECT_TRUE(report.valid_solid()) << describe_problems(report);
  return report.volume;
}

Mesh boolean(const Mesh& a, const Mesh& b, BooleanOp op) {
  const BooleanResult r = compute_boolean(check_solid(a), check_solid(b), op);
  return r.solid;
}

Mesh box(FT x0, FT y0, FT z0, FT x1, FT y1, FT z1) {
  return make_box(Point(x0, y0, z0), Point(x1, y1, z1));
}

// The three selections of a pair of solids written as one chain: union, intersection, A - B.
void expect_like_booleans(const Mesh& a, const Mesh& b) {
  const Mesh both = concatenate(a, b);
  WindingOptions twice;
  twice.threshold = 2;
  EXPECT_EQ(valid_volume(winding_solid(both)), valid_volume(boolean(a, b, BooleanOp::Union)));
  EXPECT_EQ(valid_volume(winding_solid(both, {}, twice)),
            valid_volume(boolean(a, b, BooleanOp::Intersection)));
  EXPECT_EQ(valid_volume(winding_solid(concatenate(a, reversed(b)))),
            valid_volume(boolean(a, b, BooleanOp::Difference)));
}

}  // namespace

TEST(Winding, ValidSolidIsItself) {
  const Mesh cube = make_cube(1);
  WindingStats stats;
  const Mesh out = winding_solid(cube, {}, {}, &stats);
  EXPECT_EQ(valid_volume(out), 8);
  EXPECT_EQ(stats.intersecting_pairs, 0u);
  EXPECT_EQ(stats.patches, 1u);
  const Mesh sphere = make_icosphere(3, 1);
  EXPECT_EQ(valid_volume(winding_solid(sphere)), signed_volume(sphere));
}

TEST(Winding, TwoOverlappingCubesInOneMesh) {
  const Mesh a = box(0, 0, 0, 2, 2, 2), b = box(1, 1, 1, 3, 3, 3);
  EXPECT_EQ(valid_volume(winding_solid(concatenate(a, b))), 8 + 8 - 1);
  WindingOptions twice;
  twice.threshold = 2;
  EXPECT_EQ(valid_volume(winding_solid(concatenate(a, b), {}, twice)), 1);
}

// Within a work budget the arrangement either gives up after pairing (more candidate pairs per
// triangle than allowed) or gives exactly winding_solid's solid.
TEST(Winding, WithinABudgetGivesUpOrAgrees) {
  // Ten cubes, each overlapping the next: every triangle's box meets several others.
  Mesh stack;
  for (int i = 0; i < 10; ++i)
    stack = concatenate(stack, box(FT(i) / 3, FT(i) / 5, 0, FT(i) / 3 + 1, FT(i) / 5 + 1, 1));
  WindingStats stats;
  const Mesh whole = winding_solid(stack, {}, {}, &stats);
  const double per_triangle = double(stats.candidate_pairs) / double(stack.triangles.size());
  ASSERT_GT(per_triangle, 1);
  WindingStats gave_up;
  EXPECT_FALSE(winding_solid_within(per_triangle / 2, stack, {}, {}, &gave_up).has_value());
  EXPECT_EQ(gave_up.candidate_pairs, stats.candidate_pairs);  // it paired, then stopped
  EXPECT_EQ(gave_up.intersecting_pairs, 0u);
  const std::optional<Mesh> within = winding_solid_within(per_triangle * 2, stack);
  ASSERT_TRUE(within.has_value());
  EXPECT_EQ(valid_volume(*within), valid_volume(whole));
  EXPECT_EQ(within->triangles.size(), whole.triangles.size());
}

TEST(Winding, CoplanarFacesAndContacts) {
  // Shared faces, edges and vertices, coplanar overlaps, identical and nested solids.
  const Mesh unit = box(0, 0, 0, 1, 1, 1);
  for (const auto& [a, b] :
       {make_cubes_sharing_face(), make_cubes_sharing_edge(), make_cubes_sharing_vertex()})
    expect_like_booleans(a, b);
  expect_like_booleans(unit, box(FT(1) / 2, 0, 0, FT(3) / 2, 1, 1));  // coplanar overlap
  expect_like_booleans(unit, box(FT(1) / 2, FT(1) / 2, 0, 2, 2, 1));  // coplanar corner
  expect_like_booleans(unit, unit);                                   // identical
  expect_like_booleans(unit, box(FT(1) / 4, FT(1) / 4, FT(1) / 4, FT(3) / 4, FT(3) / 4,
                                 FT(3) / 4));         // nested
  expect_like_booleans(unit, box(2, 2, 2, 3, 3, 3));  // disjoint
}

TEST(Winding, DuplicateShellsHaveWindingTwo) {
  const Mesh cube = make_cube(1);
  const Mesh twice = concatenate(cube, cube);
  EXPECT_EQ(valid_volume(winding_solid(twice)), 8);
  WindingOptions three;
  three.threshold = 3;
  EXPECT_TRUE(winding_solid(twice, {}, three).empty());
  // A shell and its reverse cancel: nothing is left.
  WindingStats stats;
  EXPECT_TRUE(winding_solid(concatenate(cube, reversed(cube)), {}, {}, &stats).empty());
  EXPECT_EQ(stats.cancelled_faces, 24u);
}

TEST(Winding, WeightsCountSolids) {
  // Weight 2 on one cube: the overlap is covered three times.
  const Mesh a = box(0, 0, 0, 2, 2, 2), b = box(1, 1, 1, 3, 3, 3);
  const Mesh both = concatenate(a, b);
  std::vector<int> weights(both.triangles.size(), 1);
  for (std::size_t f = 0; f < a.triangles.size(); ++f) weights[f] = 2;
  WindingOptions k;
  k.threshold = 2;
  EXPECT_EQ(valid_volume(winding_solid(both, weights, k)), 8);
  k.threshold = 3;
  EXPECT_EQ(valid_volume(winding_solid(both, weights, k)), 1);
}

TEST(Winding, ThreeSheetsMeetAtPoints) {
  // Three boxes whose faces cross pairwise inside facets: triple points.
  const Mesh a = box(0, 0, 0, 4, 4, 2), b = box(1, -1, 1, 3, 5, 3), c = box(-1, 1, 1, 5, 3, 3);
  WindingStats stats;
  const Mesh u = winding_solid(concatenate(concatenate(a, b), c), {}, {}, &stats);
  EXPECT_GT(stats.triple_points, 0u);
  EXPECT_EQ(valid_volume(u),
            valid_volume(boolean(boolean(a, b, BooleanOp::Union), c, BooleanOp::Union)));
}

TEST(Winding, RandomSolidsAgreeWithBooleans) {
  std::mt19937 random(7);
  std::uniform_int_distribution<int> coordinate(-4, 4), turn(-3, 3);
  for (int round = 0; round < 12; ++round) {
    const Mesh sphere = make_icosphere(1 + round % 2, 2);
    const Transformation rotation =
        quaternion_rotation(turn(random), turn(random), turn(random), 5);
    const Mesh a = translated(transformed(sphere, rotation),
                              Vector(FT(coordinate(random)) / 4, FT(coordinate(random)) / 4, 0));
    const FT x0 = FT(coordinate(random)) / 2, y0 = FT(coordinate(random)) / 2;
    const Mesh b = box(x0, y0, -1, x0 + 1 + FT(coordinate(random) + 4) / 4,
                       y0 + 1 + FT(coordinate(random) + 4) / 4, 1);
    SCOPED_TRACE(round);
    expect_like_booleans(a, b);
  }
}

// Groups (a translated piece of a valid surface each) spare the pairs within a group and nothing
// else: the same solids exactly, from fewer candidate pairs.
TEST(Winding, GroupsSpareOnlyThePairsWithinThem) {
  std::mt19937 random(11);
  std::uniform_int_distribution<int> coordinate(-4, 4), turn(-3, 3);
  for (int round = 0; round < 6; ++round) {
    SCOPED_TRACE(round);
    const Mesh a = transformed(make_icosphere(1 + round % 2, 2),
                               quaternion_rotation(turn(random), turn(random), turn(random), 5));
    const Mesh b = translated(a, Vector(FT(coordinate(random)) / 4, FT(coordinate(random)) / 4,
                                        FT(coordinate(random) + 5) / 8));
    const Mesh both = concatenate(a, b);
    std::vector<std::uint32_t> groups(both.triangles.size(), 0);
    std::fill(groups.begin() + std::ptrdiff_t(a.triangles.size()), groups.end(), 1);
    for (const int threshold : {1, 2}) {
      WindingOptions plain, grouped;
      plain.threshold = grouped.threshold = threshold;
      grouped.groups = &groups;
      WindingStats plain_stats, grouped_stats;
      const Mesh expected = winding_solid(both, {}, plain, &plain_stats);
      const Mesh result = winding_solid(both, {}, grouped, &grouped_stats);
      EXPECT_LT(grouped_stats.candidate_pairs, plain_stats.candidate_pairs / 2);
      EXPECT_EQ(valid_volume(result), valid_volume(expected));
      EXPECT_EQ(valid_volume(boolean(result, expected, BooleanOp::Difference)), 0);
      EXPECT_EQ(valid_volume(boolean(expected, result, BooleanOp::Difference)), 0);
    }
  }
}

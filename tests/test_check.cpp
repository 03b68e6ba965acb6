// SPDX-License-Identifier: GPL-3.0-or-later
// Validity checks: every generator gives a valid solid with its hand-computed exact volume, and
// each kind of defect is detected and described; CGAL's self-intersection test is the oracle.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <mutex>
#include <optional>
#include <random>

#include "check/check_internal.h"
#include "check/check_planar.h"
#include "check_test_support.h"
#include "exact/point_index.h"
#include "exact/point_table.h"
#include "mesh/volume_internal.h"
#include "morphex/check.h"
#include "morphex/internal/fixtures.h"
#include "peers.h"
#include "tree/box_tree.h"

using namespace morphex;

namespace {

void expect_valid(const Mesh& m, const char* what) {
  const MeshReport r = check_mesh(m);
  EXPECT_TRUE(r.valid_solid()) << what << ": " << describe_problems(r);
}

bool cgal_self_intersects(const Mesh& m) {
  return peers::cgal_does_self_intersect(m);
}

}  // namespace

TEST(Check, GeneratorsGiveValidSolidsWithExactVolumes) {
  EXPECT_EQ(check_mesh(make_cube(FT(1) / 2)).volume, FT(1));
  EXPECT_EQ(check_mesh(make_box(Point(0, 0, 0), Point(2, 3, FT(1) / 5))).volume, FT(6) / 5);
  EXPECT_EQ(check_mesh(make_tetrahedron()).volume, FT(1) / 6);
  EXPECT_EQ(check_mesh(make_octahedron(FT(3))).volume, FT(36));  // 4 r^3 / 3
  // Icosahedron with vertices (0, +-1, +-g) and cyclic permutations, summed as 20 tetrahedra
  // from the origin: 8 "corner" faces like (0,1,g), (g,0,1), (1,g,0) have det 1 + g^3, and 12
  // "edge" faces like (0,1,g), (0,-1,g), (g,0,1) have det 2 g^2, so
  // V = (8 (1 + g^3) + 24 g^2) / 6 = (4 + 4 g^3 + 12 g^2) / 3  (17.45... for g = 1.618).
  const FT g = FT(1618) / 1000;
  EXPECT_EQ(check_mesh(make_icosahedron()).volume, (4 + 4 * g * g * g + 12 * g * g) / 3);
  expect_valid(make_icosahedron(), "icosahedron");
  expect_valid(make_icosphere(2, FT(1)), "icosphere");
  expect_valid(make_torus(24, 12, 1.0, 0.25), "torus");
  expect_valid(make_cylinder(16, 1.0, 0.5), "cylinder");
  expect_valid(make_octahedron(FT(1)), "octahedron");
}

TEST(Check, CountsAndGenus) {
  const MeshReport cube = check_mesh(make_cube(FT(1)));
  EXPECT_EQ(cube.triangles, 12u);
  EXPECT_EQ(cube.vertices, 8u);
  EXPECT_EQ(cube.components, 1u);
  EXPECT_EQ(cube.genus, 0);
  EXPECT_EQ(check_mesh(make_torus(24, 12, 1.0, 0.25)).genus, 1);
  const MeshReport two = check_mesh(concatenate(make_cube(FT(1)), make_torus(12, 6, 5.0, 0.5)));
  EXPECT_EQ(two.components, 2u);
  EXPECT_EQ(two.genus, 1);
  EXPECT_DOUBLE_EQ(cube.bbox.xmin(), -1.0);
  EXPECT_DOUBLE_EQ(cube.bbox.zmax(), 1.0);
}

TEST(Check, OpenMeshIsNotClosed) {
  Mesh m = make_cube(FT(1));
  m.triangles.pop_back();
  const MeshReport r = check_mesh(m);
  EXPECT_EQ(r.border_edges, 3u);
  EXPECT_FALSE(r.closed());
  EXPECT_FALSE(r.valid_solid());
  const std::string message = describe_problems(r);
  EXPECT_NE(message.find("not closed: 3 border edges, first at vertex"), std::string::npos)
      << message;
}

TEST(Check, InvertedMeshIsNotOutward) {
  const MeshReport r = check_mesh(reversed(make_cube(FT(1))));
  EXPECT_TRUE(r.consistently_oriented);
  EXPECT_FALSE(r.outward);
  EXPECT_LT(r.volume, 0);
  EXPECT_NE(describe_problems(r).find("inward"), std::string::npos);
}

TEST(Check, InconsistentOrientation) {
  Mesh m = make_cube(FT(1));
  std::swap(m.triangles[0][1], m.triangles[0][2]);
  const MeshReport r = check_mesh(m);
  EXPECT_FALSE(r.consistently_oriented);
  EXPECT_FALSE(r.valid_solid());
}

TEST(Check, HollowSolidIsOutward) {
  // a cavity: the inner shell is oriented inward, and that is what a valid hollow solid needs
  const Mesh hollow = concatenate(make_cube(FT(2)), reversed(make_cube(FT(1))));
  const MeshReport r = check_mesh(hollow);
  EXPECT_TRUE(r.valid_solid()) << describe_problems(r);
  EXPECT_EQ(r.volume, FT(64 - 8));
  // the same cavity oriented outward is wrong
  EXPECT_FALSE(check_mesh(concatenate(make_cube(FT(2)), make_cube(FT(1)))).outward);
}

// Nesting is decided for every shell at once (one ray each against all faces): shells that share
// a segment and its ends by position, shells nested many deep, and cavities that touch.
TEST(Check, ManyShellsNestedAndTouching) {
  const Mesh fan = make_tetrahedra_on_segment(200);
  const MeshReport r = check_mesh(fan);
  EXPECT_TRUE(r.valid_solid()) << describe_problems(r);
  EXPECT_EQ(r.components, 200u);
  // One shell turned inside out among 199 that share its segment: its folds no longer alternate.
  Mesh one_flipped = fan;
  for (int k = 0; k < 4; ++k)
    std::swap(one_flipped.triangles[4 * 137 + k][1], one_flipped.triangles[4 * 137 + k][2]);
  const MeshReport flipped = check_mesh(one_flipped);
  EXPECT_GT(flipped.self_intersections, 0u) << describe_problems(flipped);
  // The fan in the cavity of a hollow cube is material again (depth 2); turned inward inside a
  // solid cube it is 200 cavities that touch along the segment (depth 1).
  const Mesh fan_below = translated(fan, Vector(0, 0, -FT(1) / 2));
  const Mesh hollow = concatenate(make_cube(FT(4)), reversed(make_cube(FT(3))));
  expect_valid(concatenate(hollow, fan_below), "fan in a cavity");
  EXPECT_FALSE(check_mesh(concatenate(hollow, reversed(fan_below))).outward);
  const MeshReport cavities = check_mesh(concatenate(make_cube(FT(2)), reversed(fan_below)));
  EXPECT_TRUE(cavities.valid_solid()) << describe_problems(cavities);
  EXPECT_EQ(cavities.components, 201u);
  EXPECT_FALSE(check_mesh(concatenate(make_cube(FT(2)), fan_below)).outward);
  // Twelve cubes nested, orientations alternating from outward at the outside; one turned wrong.
  Mesh nested;
  for (int k = 12; k >= 1; --k)
    nested = concatenate(nested, k % 2 == 0 ? make_cube(FT(k)) : reversed(make_cube(FT(k))));
  expect_valid(nested, "nested cubes");
  EXPECT_EQ(check_mesh(nested).volume,
            FT(8 * (1728 - 1331 + 1000 - 729 + 512 - 343 + 216 - 125 + 64 - 27 + 8 - 1)));
  Mesh wrong = nested;
  for (int k = 0; k < 12; ++k)
    std::swap(wrong.triangles[12 * 5 + k][1], wrong.triangles[12 * 5 + k][2]);
  EXPECT_FALSE(check_mesh(wrong).outward);
}

TEST(Check, SelfIntersectionsAgreeWithCgal) {
  const Mesh crossing = concatenate(make_cube(FT(1)), make_cube(FT(1), Point(1, 1, 1)));
  const MeshReport r = check_mesh(crossing);
  EXPECT_GT(r.self_intersections, 0u);
  ASSERT_TRUE(r.first_self_intersection.has_value());
  EXPECT_TRUE(triangles_intersect_improperly(crossing, r.first_self_intersection->first,
                                             r.first_self_intersection->second));
  EXPECT_TRUE(cgal_self_intersects(crossing));
  for (const Mesh& m : {make_icosphere(2, FT(1)), make_torus(24, 12, 1.0, 0.25)}) {
    EXPECT_EQ(check_mesh(m).self_intersections > 0, cgal_self_intersects(m));
  }
  // a vertex of one cube touching the middle of another's face (a T contact) intersects
  const Mesh touching = concatenate(make_cube(FT(1)), make_octahedron(FT(1)) /* inside */);
  EXPECT_EQ(check_mesh(touching).self_intersections > 0, cgal_self_intersects(touching));
}

TEST(Check, SeparatedNonManifoldContactsAreValid) {
  // Coincident but distinct vertices: the way a Boolean result represents touching solids.
  for (auto [a, b] : {make_cubes_sharing_edge(), make_cubes_sharing_vertex()}) {
    const MeshReport r = check_mesh(concatenate(a, b));
    EXPECT_TRUE(r.valid_solid()) << describe_problems(r);
    EXPECT_EQ(r.components, 2u);
  }
  // sharing a whole face is not a valid solid boundary: the two faces overlap
  auto [a, b] = make_cubes_sharing_face();
  EXPECT_GT(check_mesh(concatenate(a, b)).self_intersections, 0u);
}

TEST(Check, NonManifoldFeaturesByIndex) {
  // the same two cubes with the shared edge's vertices merged: a non-manifold edge
  auto [a, b] = make_cubes_sharing_edge();
  Mesh m = concatenate(a, b);
  for (Triangle& t : m.triangles)
    for (VertexIndex& v : t)
      for (VertexIndex u = 0; u < 8; ++u)
        if (v >= 8 && m.points[v] == m.points[u]) v = u;
  const MeshReport r = check_mesh(m);
  EXPECT_GT(r.non_manifold_edges, 0u);
  EXPECT_FALSE(r.valid_solid());
}

namespace {
// A cube with one more face, its corners on the z axis at heights z0 < z1 < z2 (collinear).
Mesh cube_with_flat_face(int z0, int z1, int z2) {
  Mesh m = make_cube(FT(1));
  for (const int z : {z0, z1, z2}) m.points.push_back(Point(0, 0, z));
  m.triangles.push_back({8, 9, 10});
  return m;
}
}  // namespace

TEST(Check, DegenerateFace) {
  const MeshReport r = check_mesh(cube_with_flat_face(5, 6, 7));
  EXPECT_EQ(r.degenerate_faces, 1u);
  EXPECT_EQ(r.first_degenerate_face, 12u);
  // A degenerate face through the cube is reported as degenerate, not as crossing the faces
  // it passes (its pairs are not tested: the triangle tests need proper triangles).
  const MeshReport t = check_mesh(cube_with_flat_face(-3, 0, 3));
  EXPECT_EQ(t.degenerate_faces, 1u);
  EXPECT_EQ(t.self_intersections, 0u);
  // a closed mesh whose first problem is a face with collinear corners
  Mesh flat = make_tetrahedron();
  flat.points[2] = Point(2, 0, 0);  // (0,0,0), (1,0,0), (2,0,0) collinear
  const MeshReport f = check_mesh(flat);
  EXPECT_GT(f.degenerate_faces, 0u);
  EXPECT_NE(describe_problems(f).find("degenerate faces, first is face"), std::string::npos)
      << describe_problems(f);
  // Collinear along a diagonal, in doubles and turned (rational): no projection certainly turns,
  // so the exact tests decide; a proper face just off the line is not degenerate.
  Mesh diagonal = make_cube(FT(1));
  for (const int k : {2, 3, 5}) diagonal.points.push_back(Point(k, k, k));
  diagonal.triangles.push_back({8, 9, 10});
  Mesh off = diagonal;
  off.points[10] = Point(5, 5, FT(5) + FT(1) / (1 << 30));
  for (const Mesh& m : {diagonal, transformed(diagonal, quaternion_rotation(1, 2, 3, 5))})
    EXPECT_EQ(check_mesh(m).degenerate_faces, 1u);
  for (const Mesh& m : {off, transformed(off, quaternion_rotation(1, 2, 3, 5))})
    EXPECT_EQ(check_mesh(m).degenerate_faces, 0u);
}

TEST(Check, EmptyMeshIsAValidEmptySolid) {
  const MeshReport r = check_mesh(Mesh{});
  EXPECT_TRUE(r.valid_solid());
  EXPECT_EQ(r.volume, FT(0));
}

TEST(Spatial, WindingNumberIncludingGrazingRays) {
  const Mesh cube = make_cube(FT(1));
  const TriangleTree tree(cube);
  EXPECT_EQ(winding_number(cube, tree, Point(0, 0, 0)), 1);
  EXPECT_EQ(winding_number(cube, tree, Point(FT(1) / 2, FT(1) / 2, FT(1) / 2)), 1);
  EXPECT_EQ(winding_number(cube, tree, Point(3, 0, 0)), 0);
  EXPECT_EQ(winding_number(cube, tree, Point(-3, -1, -1)), 0);  // aligned with an edge's line
  EXPECT_EQ(winding_number(cube, tree, Point(2, 1, 0)), 0);     // in a face plane
  EXPECT_THROW(winding_number(cube, tree, Point(1, 0, 0)), std::domain_error);
  const Mesh torus = make_torus(24, 12, 1.0, 0.25);
  const TriangleTree torus_tree(torus);
  EXPECT_EQ(winding_number(torus, torus_tree, Point(0, 0, 0)), 0);  // the hole
  EXPECT_EQ(winding_number(torus, torus_tree, Point(1, 0, 0)), 1);  // inside the tube
  const Mesh reversed_cube = reversed(cube);
  EXPECT_EQ(winding_number(reversed_cube, TriangleTree(reversed_cube), Point(0, 0, 0)), -1);
}

TEST(Spatial, TreeFindsExactlyTheOverlappingBoxes) {
  const Mesh m = make_icosphere(3, FT(1));
  const TriangleTree tree(m);
  const CGAL::Bbox_3 query(0.1, 0.1, 0.1, 0.9, 0.9, 0.9);
  std::vector<std::uint32_t> found, expected;
  tree.for_each_overlap(query, [&](std::uint32_t t) { found.push_back(t); });
  for (std::uint32_t t = 0; t < m.num_triangles(); ++t) {
    if (tree.float_box(t).overlaps(FloatBox::of(query))) expected.push_back(t);
    // conservative: the stored box holds the triangle's exact points
    const Triangle& f = m.triangles[t];
    const CGAL::Bbox_3 exact =
        m.points[f[0]].bbox() + m.points[f[1]].bbox() + m.points[f[2]].bbox();
    EXPECT_TRUE(CGAL::do_overlap(tree.box(t), exact) && tree.box(t).xmin() <= exact.xmin() &&
                tree.box(t).xmax() >= exact.xmax() && tree.box(t).zmin() <= exact.zmin() &&
                tree.box(t).zmax() >= exact.zmax())
        << t;
  }
  std::sort(found.begin(), found.end());
  EXPECT_EQ(found, expected);
  EXPECT_FALSE(found.empty());
}

TEST(Spatial, FloatBoxesRoundOutwardAtEveryMagnitude) {
  const double tiny = std::numeric_limits<float>::denorm_min();
  const double huge = 1e300, big = double(std::numeric_limits<float>::max());
  const std::vector<double> values = {0.0,     0.1,    -0.1,     1.0 / 3,    -1.0 / 3,
                                      1e-40,   -1e-40, tiny / 3, -tiny / 3,  3.0e38 + 1e30,
                                      big * 2, huge,   -huge,    16777217.0, -16777217.0};
  for (const double lo : values)
    for (const double hi : values) {
      if (lo > hi) continue;
      const CGAL::Bbox_3 exact(lo, lo, lo, hi, hi, hi);
      const FloatBox box = FloatBox::of(exact);
      for (int k = 0; k < 3; ++k) {
        EXPECT_LE(double(box.lo[k]), lo) << lo;
        EXPECT_GE(double(box.hi[k]), hi) << hi;
        // the float next to the bound is not conservative (the rounding is tight)
        if (std::isfinite(box.lo[k]) && double(box.lo[k]) != lo)
          EXPECT_GT(double(std::nextafter(box.lo[k], std::numeric_limits<float>::infinity())), lo);
        if (std::isfinite(box.hi[k]) && double(box.hi[k]) != hi)
          EXPECT_LT(double(std::nextafter(box.hi[k], -std::numeric_limits<float>::infinity())), hi);
      }
    }
}

TEST(Spatial, OverlappingPairsOfTwoTreesAreThoseOfAllPairs) {
  const Mesh a = make_icosphere(2, FT(1));
  const Mesh b = translated(make_icosphere(3, FT(1)), Vector(FT(1) / 3, FT(1) / 5, FT(1) / 7));
  const TriangleTree ta(a), tb(b);
  std::vector<std::pair<std::uint32_t, std::uint32_t>> expected;
  for (std::uint32_t i = 0; i < a.num_triangles(); ++i)
    for (std::uint32_t j = 0; j < b.num_triangles(); ++j)
      if (ta.float_box(i).overlaps(tb.float_box(j))) expected.emplace_back(i, j);
  auto pairs = TriangleTree::overlapping_pairs(ta, tb);
  std::sort(pairs.begin(), pairs.end());
  EXPECT_EQ(pairs, expected);
  EXPECT_FALSE(expected.empty());
  // The self traversal: each unordered pair of distinct triangles once.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> self, self_expected;
  std::mutex lock;
  tb.for_each_self_pair([&](std::size_t, std::uint32_t i, std::uint32_t j) {
    std::lock_guard<std::mutex> guard(lock);
    self.emplace_back(std::min(i, j), std::max(i, j));
  });
  for (std::uint32_t i = 0; i < b.num_triangles(); ++i)
    for (std::uint32_t j = i + 1; j < b.num_triangles(); ++j)
      if (tb.float_box(i).overlaps(tb.float_box(j))) self_expected.emplace_back(i, j);
  std::sort(self.begin(), self.end());
  EXPECT_EQ(self, self_expected);
}

namespace {

// Every pair (i, j) of a triangle of `a` and one of `b` whose boxes overlap, in order.
std::vector<std::pair<std::uint32_t, std::uint32_t>> sorted_pairs(const TriangleTree& a,
                                                                  const TriangleTree& b) {
  auto pairs = TriangleTree::overlapping_pairs(a, b);
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

// `kept` holds every triangle of `mesh` once, each with the box a fresh tree gives it, and meets
// `other`'s tree in the pairs a fresh tree meets, and a box in the triangles a fresh tree finds.
void expect_tree_as_fresh(const TriangleTree& kept, const Mesh& mesh, const Mesh& other) {
  ASSERT_EQ(kept.size(), mesh.num_triangles());
  const TriangleTree fresh(mesh), tb(other);
  for (std::uint32_t t = 0; t < mesh.num_triangles(); ++t) {
    const FloatBox &x = kept.float_box(t), &y = fresh.float_box(t);
    EXPECT_TRUE(std::equal(x.lo, x.lo + 3, y.lo) && std::equal(x.hi, x.hi + 3, y.hi))
        << "triangle " << t;
  }
  const auto pairs = sorted_pairs(kept, tb);
  EXPECT_FALSE(pairs.empty());
  EXPECT_EQ(pairs, sorted_pairs(fresh, tb));
  std::vector<std::uint32_t> found, expected;
  for (std::uint32_t t = 0; t < other.num_triangles(); t += 7) {
    found.clear();
    expected.clear();
    kept.for_each_overlap(tb.float_box(t), [&](std::uint32_t f) { found.push_back(f); });
    fresh.for_each_overlap(tb.float_box(t), [&](std::uint32_t f) { expected.push_back(f); });
    std::sort(found.begin(), found.end());
    std::sort(expected.begin(), expected.end());
    ASSERT_EQ(found, expected) << "query " << t;
  }
}

}  // namespace

// The tree the check hands to the Boolean (check_internal.h) is the one the Boolean would build:
// the same boxes of every triangle, so the same candidate pairs. A smooth mesh's is the check's
// own tree, in the order of a fresh one; a mesh whose flat faces are proved as patches gets the
// check's two trees (the patches, the rest) joined. A mesh with a degenerate face gets none.
TEST(Check, HandsTheBooleanATreeOverEveryTriangle) {
  const Mesh smooth = make_icosphere(3, FT(1));
  const Mesh other = translated(make_icosphere(2, FT(1)), Vector(FT(1) / 3, FT(1) / 5, FT(1) / 7));
  std::optional<TriangleTree> kept;
  const MeshReport r = detail::check_mesh_keeping_tree(smooth, kValidityOnly, kept);
  EXPECT_TRUE(r.valid_solid());
  ASSERT_TRUE(kept.has_value());
  expect_tree_as_fresh(*kept, smooth, other);
  EXPECT_EQ(TriangleTree::overlapping_pairs(*kept, TriangleTree(other)),
            TriangleTree::overlapping_pairs(TriangleTree(smooth), TriangleTree(other)));

  // Two flat caps of 64 triangles each, proved as patches, and the side strips.
  const Mesh fans = make_fan_prism(64, 1.0, 1.0);
  const Mesh crossing =
      translated(make_icosphere(2, FT(1) / 2), Vector(FT(1) / 3, FT(1) / 5, FT(1)));
  const MeshReport f = detail::check_mesh_keeping_tree(fans, kValidityOnly, kept);
  EXPECT_TRUE(f.valid_solid());
  ASSERT_TRUE(kept.has_value());
  expect_tree_as_fresh(*kept, fans, crossing);

  Mesh degenerate = fans;
  degenerate.triangles.push_back({0, 0, 1});
  degenerate.triangles.push_back({1, 0, 0});
  const MeshReport d = detail::check_mesh_keeping_tree(degenerate, kValidityOnly, kept);
  EXPECT_FALSE(d.valid_solid());
  EXPECT_FALSE(kept.has_value());
}

// Self-intersection detection against CGAL's on pairs of shapes that cross, touch on the 1/4 grid
// (faces, edges, vertices meeting other features) or miss each other, under axis-preserving and
// rational rotations. Meshes where two distinct vertices coincide are left out: there CGAL's test
// (by vertex index) and ours (contacts at common positions are allowed) differ by design.
// The check's outward test reads the table's doubles, each coordinate within an error of the
// exact one (a rational mesh: a rotated input, a Boolean's output). Doubles moved by up to that
// error from flat or nearly flat solids, whose exact volume is 0 or tiny: the sign is still the
// exact one, though the doubles' own sum is far from it.
TEST(Check, VolumeSignFromDoublesWithinAnErrorIsTheExactOne) {
  // A flat pillow (a square, triangulated on one side along one diagonal and on the other along
  // the other) of volume 0, and a tetrahedron of height h.
  Mesh pillow;
  pillow.points = {Point(0, 0, 0), Point(4, 0, 0), Point(4, 3, 0), Point(0, 3, 0)};
  pillow.triangles = {{0, 1, 2}, {0, 2, 3}, {1, 0, 3}, {1, 3, 2}};
  const double h = 0x1p-30, error = 0x1p-20;
  Mesh tetrahedron;
  tetrahedron.points = {Point(0, 0, 0), Point(4, 0, 0), Point(0, 3, 0), Point(1, 1, h)};
  tetrahedron.triangles = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {2, 0, 3}};
  std::mt19937 random(7);
  std::uniform_real_distribution<double> move(-error, error);
  int misled = 0;
  for (int i = 0; i < 40; ++i) {
    for (const Mesh* m : {&pillow, &tetrahedron}) {
      std::vector<std::array<double, 3>> xyz;
      for (const Point& p : m->points)
        xyz.push_back({CGAL::to_double(p.x()) + move(random), CGAL::to_double(p.y()) + move(random),
                       CGAL::to_double(p.z()) + move(random)});
      const CGAL::Sign exact = CGAL::sign(signed_volume(*m));
      ASSERT_EQ(exact, m == &pillow ? CGAL::ZERO : CGAL::POSITIVE);
      EXPECT_EQ(detail::signed_volume_sign(*m, xyz, error), exact) << "case " << i;
      // The same doubles taken as exact (error 0) decide another sign: the error's term is what
      // keeps their sum from being taken.
      misled += detail::signed_volume_sign(*m, xyz, 0) != exact;
    }
  }
  EXPECT_GT(misled, 40);
  // A solid of ordinary size keeps its sign with its doubles moved.
  const Mesh cube = make_cube(FT(1));
  std::vector<std::array<double, 3>> xyz;
  for (const Point& p : cube.points)
    xyz.push_back({CGAL::to_double(p.x()) + move(random), CGAL::to_double(p.y()) + move(random),
                   CGAL::to_double(p.z()) + move(random)});
  EXPECT_EQ(detail::signed_volume_sign(cube, xyz, error), CGAL::POSITIVE);
  EXPECT_EQ(detail::signed_volume_sign(reversed(cube), xyz, error), CGAL::NEGATIVE);
}

// The check's volume of a closed, consistently oriented mesh (a cycle) takes three products per
// face (the divergence theorem along x) instead of a determinant's nine: exactly the determinants'
// sum on cycles of every path (doubles at both integer widths, a rotation's common denominator,
// large coordinates that cancel), and the determinants themselves where the faces are no cycle.
TEST(Check, ACyclesVolumeIsTheSumOfDeterminants) {
  Mesh spread = make_icosphere(2, FT(1));  // doubles 130 bits apart: the wider integers
  spread.points[0] = Point(std::ldexp(1.0, -130), spread.points[0].y(), spread.points[0].z());
  const std::vector<std::pair<const char*, Mesh>> cycles = {
      {"cube", make_cube(FT(1))},
      {"icosphere", make_icosphere(3, FT(1))},
      {"torus", make_torus(24, 12, 1.0, 0.25)},
      {"spread", spread},
      {"far away", translated(make_torus(16, 8, 1.0, 0.25), Vector(1e12, -3e9, 7))},
      {"turned", transformed(make_torus(16, 8, 1.0, 0.25), quaternion_rotation(1, 2, 3, 5))},
      {"turned far", transformed(translated(make_icosphere(2, FT(1)), Vector(1e6, 0.5, -3)),
                                 quaternion_rotation(7, 1, 4, 2))},
      {"reversed", reversed(make_icosphere(2, FT(1)))}};
  for (const auto& [name, mesh] : cycles) {
    const MeshReport r = check_mesh(mesh);
    ASSERT_TRUE(r.closed() && r.consistently_oriented) << name;
    EXPECT_EQ(detail::signed_volume_of_cycle(mesh), signed_volume(mesh)) << name;
    EXPECT_EQ(r.volume, signed_volume(mesh)) << name;
  }
  // An open box (a cube without its top) is no cycle: there the two sums differ, and the check
  // reports the determinants'.
  Mesh open = make_cube(FT(1), Point(3, 5, 7));
  open.triangles.pop_back();
  open.triangles.pop_back();
  const MeshReport r = check_mesh(open);
  ASSERT_FALSE(r.closed());
  EXPECT_NE(detail::signed_volume_of_cycle(open), signed_volume(open));
  EXPECT_EQ(r.volume, signed_volume(open));
}

// Under a rational rotation the coordinates are no longer doubles, and the check's filters run
// on doubles known within an error (the planes' side test, the stars' proofs, the coplanar
// search, the outward test): every verdict is the one on the unrotated mesh, and CGAL's.
TEST(Check, RationalMeshesGetTheVerdictsOfTheirDoubles) {
  const Transformation rotation = quaternion_rotation(1, 2, 3, 5);
  const std::vector<std::pair<const char*, Mesh>> cases = {
      {"icosphere", make_icosphere(3, FT(1))},
      {"torus", make_torus(24, 12, 1.0, 0.25)},
      {"fan prism", make_fan_prism(40, 2.0, 1.0)},
      {"crossing cubes", concatenate(make_cube(FT(1)), make_cube(FT(1), Point(1, 1, 1)))},
      {"touching cube and octahedron", concatenate(make_cube(FT(1)), make_octahedron(FT(1)))},
      {"hollow cube", concatenate(make_cube(FT(2)), reversed(make_cube(FT(1))))},
      {"cavity oriented outward", concatenate(make_cube(FT(2)), make_cube(FT(1)))},
      {"inverted icosphere", reversed(make_icosphere(2, FT(1)))}};
  for (const auto& [what, m] : cases) {
    const Mesh turned = transformed(m, rotation);
    ASSERT_FALSE(CGAL::approx(turned.points[1].x()).is_point()) << what;
    const MeshReport before = check_mesh(m, kValidityOnly),
                     after = check_mesh(turned, kValidityOnly);
    EXPECT_EQ(after.valid_solid(), before.valid_solid()) << what;
    EXPECT_EQ(after.outward, before.outward) << what;
    EXPECT_EQ(after.self_intersections, before.self_intersections) << what;
    EXPECT_EQ(after.self_intersections > 0, cgal_self_intersects(turned)) << what;
  }
}

TEST(Check, SelfIntersectionsAgreeWithCgalOnRandomContacts) {
  std::mt19937 random(19);
  auto pick = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(random); };
  auto grid = [&](int lo, int hi) { return FT(pick(lo, hi)) / 4; };
  auto shape = [&]() -> Mesh {
    switch (pick(0, 3)) {
      case 0: {
        const FT x = grid(-4, 0), y = grid(-4, 0), z = grid(-4, 0);
        return make_box(Point(x, y, z), Point(x + grid(1, 8), y + grid(1, 8), z + grid(1, 8)));
      }
      case 1:
        return transformed(make_tetrahedron(), Transformation(CGAL::SCALING, grid(2, 8)));
      case 2:
        return make_octahedron(grid(1, 6));
      default:
        return make_icosphere(1, grid(2, 6));
    }
  };
  int tested = 0, intersecting = 0;
  for (int i = 0; i < 300; ++i) {
    Mesh b = shape();
    if (pick(0, 1))
      b = transformed(b, quaternion_rotation(pick(-3, 3), pick(-3, 3), pick(-3, 3), pick(1, 3)));
    b = translated(b, Vector(grid(-6, 6), grid(-6, 6), grid(-6, 6)));
    const Mesh m = concatenate(shape(), b);
    bool coincident = false;
    for (std::size_t u = 0; u < m.points.size() && !coincident; ++u)
      for (std::size_t v = u + 1; v < m.points.size() && !coincident; ++v)
        coincident = m.points[u] == m.points[v];
    if (coincident) continue;
    const bool ours = check_mesh(m, kValidityOnly).self_intersections > 0;
    ASSERT_EQ(ours, cgal_self_intersects(m)) << "case " << i;
    ++tested;
    intersecting += ours;
  }
  EXPECT_GT(tested, 150);
  EXPECT_GT(intersecting, 40);
  EXPECT_LT(intersecting, tested - 40);
}

// Pairs of triangles with one common vertex, half of them in one plane (axis-parallel or tilted,
// on a small grid, so that side rays are often collinear): whether they meet beyond the vertex
// agrees with CGAL's self-intersection test, which treats vertex-sharing triangles by index.
TEST(Check, TrianglesSharingAVertexAgreeWithCgal) {
  std::mt19937 random(23);
  auto pick = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(random); };
  int coplanar = 0, intersecting = 0, tested = 0;
  for (int i = 0; i < 600; ++i) {
    const int plane = pick(0, 2);  // 0: z = 0, 1: z = x + 2y, 2: anywhere
    auto point = [&]() {
      const int x = pick(-3, 3), y = pick(-3, 3);
      return plane == 0   ? Point(x, y, 0)
             : plane == 1 ? Point(x, y, x + 2 * y)
                          : Point(x, y, pick(-3, 3));
    };
    Mesh m;
    for (int k = 0; k < 5; ++k) m.points.push_back(point());
    m.triangles = {{0, 1, 2}, {0, 3, 4}};
    bool usable = true;  // distinct positions, proper triangles
    for (int u = 0; u < 5; ++u)
      for (int v = u + 1; v < 5; ++v) usable = usable && m.points[u] != m.points[v];
    usable = usable && !CGAL::collinear(m.points[0], m.points[1], m.points[2]) &&
             !CGAL::collinear(m.points[0], m.points[3], m.points[4]);
    if (!usable) continue;
    const bool ours = check_mesh(m, kValidityOnly).self_intersections > 0;
    ASSERT_EQ(ours, cgal_self_intersects(m)) << "case " << i;
    ++tested;
    intersecting += ours;
    coplanar += plane < 2;
  }
  EXPECT_GT(tested, 300);
  EXPECT_GT(coplanar, 150);
  EXPECT_GT(intersecting, 50);
  EXPECT_LT(intersecting, tested - 50);
}

namespace {
using test_support::improper_pairs_by_brute_force;

// The verified flat patches of a mesh, as the check computes them.
detail::PlanarPatches planar_patches_of(const Mesh& m) {
  return test_support::proved_patches_of(m, false);
}
}  // namespace

// Fans of long thin facets are proved embedded as whole patches; once a cap is broken (a rim
// vertex moved or two swapped in its plane) or other solids pierce, touch or overlap it, the
// improper pairs the check lists are exactly those of all pairs tested one by one.
TEST(Check, FlatFansAgreeWithBruteForce) {
  const Mesh fan = make_fan_prism(40, 2.0, 1.0);
  EXPECT_EQ(planar_patches_of(fan).patches.size(), 2u);  // both caps, proved
  EXPECT_TRUE(check_mesh(fan).valid_solid());
  std::mt19937 random(29);
  auto pick = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(random); };
  int broken = 0, intersecting = 0;
  for (int i = 0; i < 80; ++i) {
    const int n = pick(17, 36);
    // Moved, swapped, a tetrahedron through or onto the cap, another fan prism.
    const int kind = pick(0, 4);
    const Mesh m = test_support::fan_prism_case(n, std::array{0, 1, 3, 4, 6}[kind], pick);
    CheckOptions options;
    options.list_self_intersections = true;
    const MeshReport r = check_mesh(m, options);
    const auto expected = improper_pairs_by_brute_force(m);
    ASSERT_EQ(r.self_intersecting_pairs, expected) << "case " << i << " kind " << kind;
    ASSERT_EQ(r.self_intersections, expected.size());
    if (!expected.empty()) ASSERT_EQ(r.first_self_intersection, expected.front());
    // Turned by a rational rotation, the caps' planes and the walls' are off the axes and off
    // doubles: what lies in a plane is decided exactly (a cap's vertices known to lie in it, each
    // wall's plane built once for the cap triangles near it), and the pairs are the same.
    const MeshReport turned = check_mesh(transformed(m, quaternion_rotation(2, 1, 3, 4)), options);
    ASSERT_EQ(turned.self_intersecting_pairs, expected) << "turned case " << i << " kind " << kind;
    intersecting += !expected.empty();
    broken += kind < 2;
  }
  EXPECT_GT(intersecting, 30);
  EXPECT_LT(intersecting, 75);
  EXPECT_GT(broken, 15);
}

namespace {
// A flat fan around a centre whose rim goes around `turns` times: every triangle turns one way.
Mesh wound_fan(int n, int turns) {
  DoubleMesh d;
  d.points.push_back({0, 0, 0});
  for (int i = 0; i < n; ++i) {
    const double a = 6.283185307179586 * turns * i / n;
    d.points.push_back({std::cos(a), std::sin(a), 0});
  }
  for (VertexIndex i = 0; i < VertexIndex(n); ++i)
    d.triangles.push_back({0, 1 + i, 1 + (i + 1) % VertexIndex(n)});
  return from_double(d);
}

// A flat strip along a spiral of `turns` turns, narrowing less per turn than its width: every
// vertex star is proper, but the strip's border crosses itself.
Mesh spiral_strip(int n, double turns) {
  DoubleMesh d;
  for (int i = 0; i <= n; ++i) {
    const double a = 6.283185307179586 * turns * i / n, r = 2 - 0.05 * a;
    d.points.push_back({r * std::cos(a), r * std::sin(a), 0});
    d.points.push_back({(r + 0.5) * std::cos(a), (r + 0.5) * std::sin(a), 0});
  }
  for (VertexIndex i = 0; i < VertexIndex(n); ++i) {
    const VertexIndex in = 2 * i, out = in + 1;
    d.triangles.push_back({in, in + 2, out});
    d.triangles.push_back({out, in + 2, out + 2});
  }
  return from_double(d);
}
}  // namespace

// Flat patches whose triangles all turn one way and still overlap: a fan wound twice (its centre
// star wraps twice) and a spiral strip (its border crosses itself). Neither may be taken as
// embedded; their improper pairs are those of all pairs tested one by one.
TEST(Check, WoundFansAndSpiralStripsAreNotTakenAsEmbedded) {
  EXPECT_EQ(planar_patches_of(wound_fan(41, 1)).patches.size(), 1u);
  EXPECT_EQ(planar_patches_of(spiral_strip(60, 0.9)).patches.size(), 1u);
  EXPECT_EQ(test_support::proved_patches_of(
                test_support::turned_and_rounded(wound_fan(41, 1), 0.4, 0.9), true)
                .patches.size(),
            1u);
  // Turned in doubles, they are nearly flat: not taken as embedded that way either.
  for (const Mesh& flat :
       {wound_fan(41, 2), wound_fan(61, 3), spiral_strip(60, 1.5), spiral_strip(90, 2.2)})
    for (const Mesh& m : {flat, test_support::turned_and_rounded(flat, 0.4, 0.9)}) {
      EXPECT_TRUE(test_support::proved_patches_of(m, true).patches.empty());
      CheckOptions options;
      options.list_self_intersections = true;
      const auto expected = improper_pairs_by_brute_force(m);
      EXPECT_FALSE(expected.empty());
      EXPECT_EQ(check_mesh(m, options).self_intersecting_pairs, expected);
    }
}

// A flat patch's border comes from its corners (an edge a -> s is inside when a corner at a ends
// at s). A fan with one triangle repeated uses two edges twice one way: its triangles are not
// proved embedded as one patch, and the pairs the check lists are those of all pairs tested one by
// one (the two copies, which meet in more than an edge).
TEST(Check, FlatFanWithARepeatedTriangle) {
  Mesh m = wound_fan(41, 1);
  m.triangles.push_back(m.triangles[7]);
  for (const detail::PlanarPatch& patch : planar_patches_of(m).patches) {
    const auto& t = patch.triangles;
    EXPECT_FALSE(std::find(t.begin(), t.end(), 7u) != t.end() &&
                 std::find(t.begin(), t.end(), 41u) != t.end());
  }
  CheckOptions options;
  options.list_self_intersections = true;
  const MeshReport r = check_mesh(m, options);
  const auto expected = improper_pairs_by_brute_force(m);
  EXPECT_FALSE(expected.empty());
  EXPECT_EQ(r.self_intersecting_pairs, expected);
}

namespace {
// A cone over a regular n-gon of radius 2 in z = 0 winding `turns` times, apex at `apex`, with a
// flat fan cap from the polygon's first vertex: long thin facets meeting at the apex.
Mesh cone(int n, int turns, const Point& apex) {
  DoubleMesh d;
  for (int i = 0; i < n; ++i) {
    const double a = 6.283185307179586 * turns * i / n;
    d.points.push_back({2 * std::cos(a), 2 * std::sin(a), 0});
  }
  Mesh m = from_double(d);
  m.points.push_back(apex);
  const VertexIndex top = VertexIndex(n);
  for (VertexIndex i = 0; i < top; ++i) m.triangles.push_back({i, (i + 1) % top, top});
  for (VertexIndex k = 1; k + 1 < top; ++k) m.triangles.push_back({0, k + 1, k});
  return m;
}
}  // namespace

// The cone's exact volume: a third of its base (n triangles from the centre, by the definition
// on the generator's double coordinates) times its height.
FT volume_of_fan_cone(int n, double radius, double height) {
  const Mesh m = make_fan_cone(n, radius, height);
  FT base = 0;
  for (int i = 0; i < n; ++i) {
    const Point &p = m.points[std::size_t(i)], &q = m.points[std::size_t((i + 1) % n)];
    base += (p.x() * q.y() - p.y() * q.x()) / 2;
  }
  return base * FT(height) / 3;
}

// Cones whose apex star is proved as a whole (projected along z it is one fan wrapping once),
// and cones where it must not be: the apex below the cap (the sides cross it), on a rim vertex's
// vertical, or the rim wound twice. Improper pairs are those of all pairs tested one by one.
TEST(Check, ConeStarsAgreeWithBruteForce) {
  const Mesh upright = cone(48, 1, Point(0, 0, 3));
  EXPECT_TRUE(check_mesh(upright).valid_solid());
  const Mesh generated = make_fan_cone(500, 2.0, 1.0);
  EXPECT_TRUE(check_mesh(generated).valid_solid());
  EXPECT_EQ(check_mesh(generated).volume, volume_of_fan_cone(500, 2.0, 1.0));
  std::mt19937 random(31);
  auto pick = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(random); };
  int intersecting = 0;
  for (int i = 0; i < 40; ++i) {
    const int turns = pick(0, 5) == 0 ? 2 : 1;
    const Point apex(FT(pick(-4, 4)) / 2, FT(pick(-4, 4)) / 2, FT(pick(-2, 6)) / 2);
    const Mesh m = cone(2 * pick(17, 30) + 1, turns, apex);
    CheckOptions options;
    options.list_self_intersections = true;
    const auto expected = improper_pairs_by_brute_force(m);
    ASSERT_EQ(check_mesh(m, options).self_intersecting_pairs, expected)
        << "case " << i << " turns " << turns << " apex " << apex;
    intersecting += !expected.empty();
  }
  EXPECT_GT(intersecting, 8);
  EXPECT_LT(intersecting, 36);
}

namespace {
// A flat ring between a regular n-gon of radius 2 and one of radius `inner` centred at
// (shift, 0), triangulated between them: a patch with a hole.
Mesh flat_ring(int n, double inner, double shift) {
  DoubleMesh d;
  for (int i = 0; i < n; ++i) {
    const double a = 6.283185307179586 * i / n;
    d.points.push_back({2 * std::cos(a), 2 * std::sin(a), 0});
    d.points.push_back({shift + inner * std::cos(a), inner * std::sin(a), 0});
  }
  for (VertexIndex i = 0; i < VertexIndex(n); ++i) {
    const VertexIndex o = 2 * i, in = o + 1, o2 = 2 * ((i + 1) % VertexIndex(n)), in2 = o2 + 1;
    d.triangles.push_back({o, o2, in});
    d.triangles.push_back({in, o2, in2});
  }
  return from_double(d);
}
}  // namespace

// A flat ring (two border polygons, the hole turning against the triangles) is proved embedded
// as one patch, an off-centre hole still inside too; once the hole pokes out of the outer polygon
// the ring is not one proved patch (its unfolded pieces may be), and the improper pairs are those
// of all pairs tested one by one.
TEST(Check, FlatPatchesWithHoles) {
  for (const double shift : {0.0, 0.9}) {
    const Mesh ring = flat_ring(20, 1.0, shift);
    const auto patches = planar_patches_of(ring).patches;
    ASSERT_EQ(patches.size(), 1u);
    EXPECT_EQ(patches[0].triangles.size(), 40u);
    EXPECT_EQ(check_mesh(ring).self_intersections, 0u);
    EXPECT_TRUE(improper_pairs_by_brute_force(ring).empty());
  }
  for (const double shift : {1.5, 2.2}) {
    const Mesh m = flat_ring(20, 1.0, shift);
    for (const auto& patch : planar_patches_of(m).patches) EXPECT_LT(patch.triangles.size(), 40u);
    CheckOptions options;
    options.list_self_intersections = true;
    const auto expected = improper_pairs_by_brute_force(m);
    EXPECT_FALSE(expected.empty());
    EXPECT_EQ(check_mesh(m, options).self_intersecting_pairs, expected);
  }
}

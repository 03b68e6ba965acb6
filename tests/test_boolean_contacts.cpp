// SPDX-License-Identifier: GPL-3.0-or-later
// Booleans of solids that already touch themselves: inputs with separated non-manifold features
// (coincident vertices, doubled edges) met again by the other operand. Each case here was once
// answered with an invalid solid; every result must be valid, satisfy the exact identities and
// agree with the exact winding arrangement of the two boundaries (morphex/winding.h: another
// route through intersection and labelling; CGAL's Nef polyhedra are no oracle here, since they
// cannot be built from a surface whose coincident vertices are distinct).
//
// The three file pairs in tests/data/contacts come from dilating CGAL's `man` by a ball (union
// tree operands, cropped to a box around the failing spot with `morphex bool intersection`).
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <utility>

#include "morphex/boolean.h"
#include "morphex/check.h"
#include "morphex/io.h"
#include "morphex/repair.h"
#include "morphex/shapes.h"
#include "morphex/winding.h"

using namespace morphex;

namespace {

Mesh valid_result(const Mesh& a, const Mesh& b, BooleanOp op, const std::string& name) {
  const BooleanResult r = compute_boolean(check_solid(a), check_solid(b), op);
  const MeshReport report = check_mesh(r.solid);
  EXPECT_TRUE(report.valid_solid())
      << name << " " << to_string(op) << ": " << describe_problems(report);
  return r.solid;
}

// The volume of {x : w(x) >= threshold} for the chain A + B (union: 1, intersection: 2).
FT winding_volume(const Mesh& a, const Mesh& b, int threshold) {
  WindingOptions options;
  options.threshold = threshold;
  const Mesh solid = winding_solid(concatenate(a, b), {}, options);
  EXPECT_TRUE(check_mesh(solid, kValidityOnly).valid_solid()) << "winding " << threshold;
  return signed_volume(solid);
}

// Valid results, vol(A u B) + vol(A n B) = vol(A) + vol(B), vol(A - B) = vol(A) - vol(A n B)
// and vol(B - A) = vol(B) - vol(A n B); union and intersection equal to the winding
// arrangement's. Returns the volumes of the union and the intersection.
std::pair<FT, FT> expect_exact(const Mesh& a, const Mesh& b, const std::string& name) {
  const FT va = signed_volume(a), vb = signed_volume(b);
  const FT unite = signed_volume(valid_result(a, b, BooleanOp::Union, name));
  const FT common = signed_volume(valid_result(a, b, BooleanOp::Intersection, name));
  EXPECT_EQ(unite + common, va + vb) << name;
  EXPECT_EQ(signed_volume(valid_result(a, b, BooleanOp::Difference, name)), va - common) << name;
  EXPECT_EQ(signed_volume(valid_result(b, a, BooleanOp::Difference, name)), vb - common) << name;
  EXPECT_EQ(unite, winding_volume(a, b, 1)) << name << " union vs winding";
  EXPECT_EQ(common, winding_volume(a, b, 2)) << name << " intersection vs winding";
  return {unite, common};
}

void expect_exact_pair(const std::string& stem) {
  const std::string dir = MORPHEX_TEST_DATA_DIR "/contacts/";
  expect_exact(read_mesh(dir + stem + "_left.off"), read_mesh(dir + stem + "_right.off"), stem);
}

// Two unit cubes touching along the edge x = y = 1, 0 <= z <= 1, united with the slab
// [0, 2]^2 x [1, 2] on top: the edge is doubled, with one vertex at its top end (the slab joins
// the cubes there) and two copies at its bottom end.
Mesh cubes_joined_by_a_slab() {
  const Mesh cubes =
      valid_result(make_box(Point(0, 0, 0), Point(1, 1, 1)),
                   make_box(Point(1, 1, 0), Point(2, 2, 1)), BooleanOp::Union, "cubes");
  return valid_result(cubes, make_box(Point(0, 0, 1), Point(2, 2, 2)), BooleanOp::Union, "slab");
}

}  // namespace

// Two cubes touching along an edge under a slab that joins them at the top: the union has one
// vertex at the edge's top end and two copies at its bottom end. A box around the bottom end
// cuts the edge across, so the part that stays has both ends shared by the two pairs of faces
// along it, and only the top end, an input vertex nobody else touches, sees the four faces.
// The pairs must still be split apart.
TEST(Contacts, DoubledEdgeWithOneVertexCopyIsCutAcross) {
  const Mesh joined = cubes_joined_by_a_slab();
  EXPECT_EQ(signed_volume(joined), FT(6));
  const FT h = FT(1) / 2;
  const auto [unite, common] =
      expect_exact(make_box(Point(h, h, -1), Point(3 * h, 3 * h, h)), joined, "cut across");
  // closed forms: the box meets each cube in (1/2)^2 x 1/2 and misses the slab
  EXPECT_EQ(common, FT(1) / 4);
  EXPECT_EQ(unite, 6 + FT(3) / 2 - FT(1) / 4);
}

// The same solid subtracted from a box around the edge's top end: the result is two wedges that
// touch along the edge, so the top end, an input vertex strictly inside the box that nothing
// else touches, splits into two vertices. (The difference pairs each face of the edge with one
// of the other wedge, not as the input paired them.)
TEST(Contacts, InputVertexOnADoubledEdgeSplitsWhenTheEdgeIsPairedAnew) {
  const Mesh joined = cubes_joined_by_a_slab();
  const FT h = FT(1) / 2;
  const Mesh box = make_box(Point(h, h, h), Point(3 * h, 3 * h, 3 * h));
  const Mesh wedges = valid_result(box, joined, BooleanOp::Difference, "box - joined");
  EXPECT_EQ(signed_volume(wedges), FT(1) / 4);  // two (1/2)^3 boxes
  EXPECT_EQ(check_mesh(wedges).components, 2u);
  expect_exact(box, joined, "around the top end");
}

// A face of the result belongs to pairs on two of its edges that both need splitting: the second
// split must find its edge in the half the first one split off.
TEST(Contacts, FaceSplitOnTwoOfItsEdges) {
  expect_exact_pair("crease_pair");
}

// Two sheets touching along a segment inside a flat region that coplanar merging simplifies: the
// region must keep the segment's edge, or a merged triangle covers the other sheet's edge.
TEST(Contacts, FlatRegionKeepsTheSegmentAnotherSheetTouches) {
  expect_exact_pair("touching_sheets");
}

// Three pairs of faces on one edge, two of which share both vertex copies: every pair of the
// edge is split, or the unsplit pair's edge would hold the others' midpoints.
TEST(Contacts, ThreeWedgesAlongOneEdge) {
  expect_exact_pair("three_wedges");
}

// Two closed surfaces that meet only along three common edges, yet cross there: the unit cube,
// its faces at the origin split by the diagonals that miss the origin, and the octahedron of
// radius 1 around the origin, whose face x + y + z = 1 runs along those diagonals into the cube.
// No two triangles meet improperly, but around each diagonal the cube's faces and the
// octahedron's alternate: the check must refuse the pair as one mesh, and repair must unite it.
TEST(Contacts, FoldsCrossingAlongASharedSegmentAreRefused) {
  Mesh cube;
  for (int v = 0; v < 8; ++v) cube.points.push_back(Point(v >> 2, (v >> 1) & 1, v & 1));
  cube.triangles = {{0, 2, 4}, {4, 2, 6}, {0, 4, 1}, {4, 5, 1}, {0, 1, 2}, {2, 1, 3},
                    {1, 5, 7}, {1, 7, 3}, {2, 3, 7}, {2, 7, 6}, {4, 6, 7}, {4, 7, 5}};
  const Mesh octahedron = make_octahedron(FT(1));
  ASSERT_TRUE(check_mesh(cube).valid_solid());
  ASSERT_TRUE(check_mesh(octahedron).valid_solid());
  const Mesh both = concatenate(cube, octahedron);
  CheckOptions list;
  list.list_self_intersections = true;
  const MeshReport report = check_mesh(both, list);
  EXPECT_FALSE(report.valid_solid());
  // each of the three diagonals: the cube's two faces on it against the octahedron's two
  EXPECT_GE(report.self_intersections, 3u);
  for (const auto& [i, j] : report.self_intersecting_pairs) {  // a cube face and an octahedron face
    EXPECT_LT(i, 12u);
    EXPECT_GE(j, 12u);
  }
  // the octant x, y, z >= 0 of the octahedron (volume 1/6) lies in the cube
  const FT unite = 1 + FT(4) / 3 - FT(1) / 6;
  EXPECT_EQ(signed_volume(repair_mesh(both).solid), unite);
  EXPECT_EQ(expect_exact(cube, octahedron, "cube and octahedron").first, unite);
}

// The octahedron of radius 1 inscribed in the cube [-1, 1]^3 (its faces fanned from their centres,
// where the octahedron's vertices are): every vertex of the inner shell lies on the outer one, so
// the nesting test must look at a face's centre. Turned outward the two are not one solid; turned
// inward the octahedron is a cavity touching the walls at six points.
TEST(Contacts, ShellInscribedInAnotherIsNestedByItsFaces) {
  Mesh cube;
  for (int axis = 0; axis < 3; ++axis)
    for (const int side : {-1, 1}) {
      const int b = (axis + 1) % 3, d = (axis + 2) % 3;
      auto at = [&](int u, int v) {
        FT c[3];
        c[axis] = side;
        c[b] = u;
        c[d] = v;
        const Point p(c[0], c[1], c[2]);
        const auto found = std::find(cube.points.begin(), cube.points.end(), p);
        if (found != cube.points.end()) return VertexIndex(found - cube.points.begin());
        cube.points.push_back(p);
        return VertexIndex(cube.points.size() - 1);
      };
      const VertexIndex centre = at(0, 0);
      const VertexIndex ring[4] = {at(-1, -1), at(1, -1), at(1, 1), at(-1, 1)};
      for (int i = 0; i < 4; ++i) {
        Triangle t = {centre, ring[i], ring[(i + 1) % 4]};
        // (b, d, axis) is a right-handed frame: the ring turns about +axis, outward for side 1
        if (side < 0) std::swap(t[1], t[2]);
        cube.triangles.push_back(t);
      }
    }
  const Mesh octahedron = make_octahedron(FT(1));
  ASSERT_TRUE(check_mesh(concatenate(cube, make_octahedron(FT(1) / 2))).self_intersections == 0);
  const MeshReport cube_report = check_mesh(cube);
  ASSERT_TRUE(cube_report.valid_solid()) << describe_problems(cube_report);
  const MeshReport both = check_mesh(concatenate(cube, octahedron));
  EXPECT_EQ(both.self_intersections, 0u);
  EXPECT_FALSE(both.outward);
  EXPECT_EQ(signed_volume(repair_mesh(concatenate(cube, octahedron)).solid), FT(8));
  const MeshReport hollow = check_mesh(concatenate(cube, reversed(octahedron)));
  EXPECT_TRUE(hollow.valid_solid()) << describe_problems(hollow);
  EXPECT_EQ(hollow.volume, 8 - FT(4) / 3);
}

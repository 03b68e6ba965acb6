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

#include <string>
#include <utility>

#include "morphex/boolean.h"
#include "morphex/check.h"
#include "morphex/io.h"
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
  Mesh chain = a;
  const auto offset = VertexIndex(chain.points.size());
  chain.points.insert(chain.points.end(), b.points.begin(), b.points.end());
  for (const Triangle& t : b.triangles)
    chain.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
  WindingOptions options;
  options.threshold = threshold;
  const Mesh solid = winding_solid(chain, {}, options);
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

}  // namespace

// Two cubes touching along an edge under a slab that joins them at the top: the union has one
// vertex at the edge's top end and two copies at its bottom end. A box around the bottom end
// cuts the edge across, so the part that stays has both ends shared by the two pairs of faces
// along it, and only the top end, an input vertex nobody else touches, sees the four faces.
// The pairs must still be split apart.
TEST(Contacts, DoubledEdgeWithOneVertexCopyIsCutAcross) {
  const Mesh cubes =
      valid_result(make_box(Point(0, 0, 0), Point(1, 1, 1)),
                   make_box(Point(1, 1, 0), Point(2, 2, 1)), BooleanOp::Union, "cubes");
  const Mesh joined =
      valid_result(cubes, make_box(Point(0, 0, 1), Point(2, 2, 2)), BooleanOp::Union, "slab");
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
  const Mesh cubes = valid_result(make_box(Point(0, 0, 0), Point(1, 1, 1)),
                                  make_box(Point(1, 1, 0), Point(2, 2, 1)), BooleanOp::Union,
                                  "cubes");
  const Mesh joined =
      valid_result(cubes, make_box(Point(0, 0, 1), Point(2, 2, 2)), BooleanOp::Union, "slab");
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

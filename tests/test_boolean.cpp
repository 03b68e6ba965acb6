// SPDX-License-Identifier: GPL-3.0-or-later
// Exact Booleans: a generated degenerate suite with exact identities and independent closed forms.
#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include <random>
#include <sstream>

#include "morphex/boolean.h"
#include "morphex/check.h"
#include "morphex/internal/fixtures.h"
#include "morphex/internal/solid_access.h"
#include "morphex/winding.h"

using namespace morphex;

namespace {

struct Box {
  FT min[3], max[3];
};

Mesh box_mesh(const Box& b) {
  return make_box(Point(b.min[0], b.min[1], b.min[2]), Point(b.max[0], b.max[1], b.max[2]));
}

// Volume of the intersection of two axis-aligned boxes: an independent exact closed form.
FT overlap_volume(const Box& a, const Box& b) {
  FT v = 1;
  for (int i = 0; i < 3; ++i) {
    const FT lo = CGAL::max(a.min[i], b.min[i]), hi = CGAL::min(a.max[i], b.max[i]);
    if (hi <= lo) return 0;
    v *= hi - lo;
  }
  return v;
}

FT box_volume(const Box& b) {
  return (b.max[0] - b.min[0]) * (b.max[1] - b.min[1]) * (b.max[2] - b.min[2]);
}

Box shifted(const Box& b, FT dx, FT dy, FT dz) {
  return {{b.min[0] + dx, b.min[1] + dy, b.min[2] + dz},
          {b.max[0] + dx, b.max[1] + dy, b.max[2] + dz}};
}

// Runs op, requires a valid solid, returns its exact volume.
FT checked_volume(const Mesh& a, const Mesh& b, BooleanOp op, Mesh* out = nullptr) {
  const BooleanResult r = compute_boolean(check_solid(a), check_solid(b), op);
  EXPECT_EQ(r.stats.orientation_conflicts, 0u);
  const MeshReport report = check_mesh(r.solid);
  EXPECT_TRUE(report.valid_solid()) << to_string(op) << ": " << describe_problems(report);
  if (out) *out = r.solid;
  return report.volume;
}

struct Identities {
  FT unite, intersect, difference;
};

Identities check_identities(const Mesh& a, const Mesh& b) {
  const FT va = signed_volume(a), vb = signed_volume(b);
  Identities v{checked_volume(a, b, BooleanOp::Union),
               checked_volume(a, b, BooleanOp::Intersection),
               checked_volume(a, b, BooleanOp::Difference)};
  EXPECT_EQ(v.unite + v.intersect, va + vb) << "union " << to_rational_string(v.unite)
                                            << " intersection " << to_rational_string(v.intersect);
  EXPECT_EQ(v.difference, va - v.intersect) << "difference " << to_rational_string(v.difference);
  return v;
}

const Box kUnit{{0, 0, 0}, {1, 1, 1}};

}  // namespace

// The unit cube against a second box at every offset in {-1, -1/2, 0, 1/2, 1}^3 (125 cases):
// identical cubes, coplanar overlaps, and contacts along faces, edges and vertices, plus disjoint.
class CubeOffsets : public ::testing::TestWithParam<std::tuple<int, int, int>> {};

TEST_P(CubeOffsets, ExactIdentitiesAndClosedForm) {
  const auto [i, j, k] = GetParam();
  const Box b = shifted(kUnit, FT(i) / 2, FT(j) / 2, FT(k) / 2);
  const Identities v = check_identities(box_mesh(kUnit), box_mesh(b));
  EXPECT_EQ(v.intersect, overlap_volume(kUnit, b));
}

INSTANTIATE_TEST_SUITE_P(Degenerate, CubeOffsets,
                         ::testing::Combine(::testing::Range(-2, 3), ::testing::Range(-2, 3),
                                            ::testing::Range(-2, 3)));

// A half-size box at offsets that put its faces on the cube's faces (nested with coplanar faces).
class NestedBoxes : public ::testing::TestWithParam<std::tuple<int, int, int>> {};

TEST_P(NestedBoxes, ExactIdentitiesAndClosedForm) {
  const auto [i, j, k] = GetParam();
  const Box small{{0, 0, 0}, {FT(1) / 2, FT(1) / 2, FT(1) / 2}};
  const Box b = shifted(small, FT(i) / 4, FT(j) / 4, FT(k) / 4);
  const Identities v = check_identities(box_mesh(kUnit), box_mesh(b));
  EXPECT_EQ(v.intersect, overlap_volume(kUnit, b));
  // and the other way round: B minus A
  const FT diff_ba = checked_volume(box_mesh(b), box_mesh(kUnit), BooleanOp::Difference);
  EXPECT_EQ(diff_ba, box_volume(b) - overlap_volume(kUnit, b));
}

INSTANTIATE_TEST_SUITE_P(Degenerate, NestedBoxes,
                         ::testing::Combine(::testing::Range(0, 3), ::testing::Range(0, 3),
                                            ::testing::Range(0, 3)));

TEST(Boolean, CubesSharingAFaceUniteIntoOneBox) {
  const Box b = shifted(kUnit, 1, 0, 0);
  Mesh unite;
  EXPECT_EQ(checked_volume(box_mesh(kUnit), box_mesh(b), BooleanOp::Union, &unite), FT(2));
  // the shared face is gone: a 2x1x1 box needs no vertex inside the shared square
  EXPECT_EQ(check_mesh(unite).components, 1u);
  EXPECT_EQ(checked_volume(box_mesh(kUnit), box_mesh(b), BooleanOp::Intersection), FT(0));
}

TEST(Boolean, MergeCoplanarFacesOfAnUnmergedResult) {
  // Without merging, the union of two cubes sharing a face keeps the triangles that the shared
  // square cut into the side walls; merge_coplanar_faces then gives the 2x1x1 box the Boolean's
  // own merging gives: 12 triangles on its 8 corners, same exact volume.
  BooleanOptions unmerged;
  unmerged.merge_coplanar = false;
  const Mesh a = box_mesh(kUnit), b = box_mesh(shifted(kUnit, 1, 0, 0));
  const BooleanResult raw =
      compute_boolean(check_solid(a), check_solid(b), BooleanOp::Union, unmerged);
  EXPECT_GT(raw.solid.num_triangles(), 12u);
  const Mesh merged = merge_coplanar_faces(check_solid(raw.solid));
  const MeshReport report = check_mesh(merged);
  EXPECT_TRUE(report.valid_solid()) << describe_problems(report);
  EXPECT_EQ(report.volume, FT(2));
  EXPECT_EQ(merged.num_triangles(), 12u);
  EXPECT_EQ(
      merged.num_triangles(),
      compute_boolean(check_solid(a), check_solid(b), BooleanOp::Union).solid.num_triangles());
  EXPECT_EQ(merge_coplanar_faces(check_solid(Mesh{})).num_triangles(), 0u);
}

TEST(Boolean, CubesSharingAnEdgeGiveASeparatedValidResult) {
  const Box b = shifted(kUnit, 1, 1, 0);
  Mesh unite;
  EXPECT_EQ(checked_volume(box_mesh(kUnit), box_mesh(b), BooleanOp::Union, &unite), FT(2));
  const MeshReport report = check_mesh(unite);
  EXPECT_EQ(report.non_manifold_edges, 0u);
  // the result is a valid input of the next operation
  const Box c{{FT(1) / 2, FT(1) / 2, FT(1) / 4}, {FT(3) / 2, FT(3) / 2, FT(3) / 4}};
  const Identities v = check_identities(unite, box_mesh(c));
  EXPECT_EQ(v.intersect, overlap_volume(kUnit, c) + overlap_volume(b, c));
}

TEST(Boolean, CubesSharingAVertexGiveASeparatedValidResult) {
  const Box b = shifted(kUnit, 1, 1, 1);
  Mesh unite;
  EXPECT_EQ(checked_volume(box_mesh(kUnit), box_mesh(b), BooleanOp::Union, &unite), FT(2));
  EXPECT_EQ(check_mesh(unite).non_manifold_vertices, 0u);
  const Identities v =
      check_identities(unite, box_mesh(shifted(kUnit, FT(1) / 2, FT(1) / 2, FT(1) / 2)));
  EXPECT_EQ(v.intersect, FT(2) / 8);
}

TEST(Boolean, IdenticalMeshes) {
  const Mesh a = make_icosphere(1, FT(1));
  const FT va = signed_volume(a);
  EXPECT_EQ(checked_volume(a, a, BooleanOp::Union), va);
  EXPECT_EQ(checked_volume(a, a, BooleanOp::Intersection), va);
  Mesh diff;
  EXPECT_EQ(checked_volume(a, a, BooleanOp::Difference, &diff), FT(0));
  EXPECT_TRUE(diff.empty());
}

TEST(Boolean, NestedAndDisjointSolids) {
  const Mesh outer = make_cube(FT(2));
  const Mesh inner = make_icosphere(1, FT(1));
  const FT vo = signed_volume(outer), vi = signed_volume(inner);
  EXPECT_EQ(checked_volume(outer, inner, BooleanOp::Union), vo);
  EXPECT_EQ(checked_volume(outer, inner, BooleanOp::Intersection), vi);
  Mesh hollow;
  EXPECT_EQ(checked_volume(outer, inner, BooleanOp::Difference, &hollow), vo - vi);
  EXPECT_EQ(check_mesh(hollow).components, 2u);
  EXPECT_EQ(checked_volume(inner, outer, BooleanOp::Difference), FT(0));
  const Mesh far = translated(inner, Kernel::Vector_3(10, 0, 0));
  EXPECT_EQ(checked_volume(outer, far, BooleanOp::Union), vo + vi);
  EXPECT_EQ(checked_volume(outer, far, BooleanOp::Intersection), FT(0));
  EXPECT_EQ(checked_volume(outer, far, BooleanOp::Difference), vo);
}

TEST(Boolean, RotatedCubesWithRationalRotation) {
  // rotation about z by the Pythagorean angle (cos, sin) = (3/5, 4/5): exact
  const CGAL::Aff_transformation_3<Kernel> rotation(FT(3) / 5, FT(-4) / 5, 0, FT(4) / 5, FT(3) / 5,
                                                    0, 0, 0, 1);
  const Mesh a = make_cube(FT(1));
  const Mesh b = transformed(make_cube(FT(1)), rotation);  // shares the top and bottom planes
  check_identities(a, b);
  check_identities(a, translated(b, Kernel::Vector_3(FT(1) / 3, FT(1) / 7, FT(1) / 2)));
}

TEST(Boolean, TransversalCrossingsAreLabelledByTheSeedsOrientationRule) {
  const Mesh a = make_icosphere(2, FT(1));
  const Mesh b = translated(a, Kernel::Vector_3(FT(1) / 2, FT(1) / 3, FT(1) / 5));
  const BooleanResult r = compute_boolean(check_solid(a), check_solid(b), BooleanOp::Union);
  EXPECT_GT(r.stats.patches_by_orientation_rule, 0u);
  EXPECT_EQ(r.stats.orientation_conflicts, 0u);
  EXPECT_EQ(r.stats.patches, r.stats.patches_by_orientation_rule + r.stats.patches_by_ray_cast);
}

TEST(Boolean, CrossingSpheresAndTorus) {
  const Mesh a = make_icosphere(2, FT(1));
  check_identities(
      a, translated(make_icosphere(2, FT(1)), Kernel::Vector_3(FT(1) / 2, FT(1) / 3, FT(1) / 5)));
  check_identities(make_torus(16, 8, 1.0, 0.3),
                   make_box(Point(-2, -2, -FT(1) / 10), Point(0, 2, 2)));
}

TEST(Boolean, ChainOfTenOperationsStaysValidAndExact) {
  Mesh current = box_mesh(kUnit);
  FT expected = 1;
  // Alternately add and carve unit-wide slabs: each step's volume is known in closed form.
  for (int step = 0; step < 10; ++step) {
    const FT x = FT(step) / 10;
    const Box slab{{x, FT(-1) / 2, FT(1) / 4}, {x + FT(1) / 20, FT(3) / 2, FT(3) / 4}};
    const BooleanOp op = step % 2 == 0 ? BooleanOp::Union : BooleanOp::Difference;
    const BooleanResult r = compute_boolean(check_solid(current), check_solid(box_mesh(slab)), op);
    const MeshReport report = check_mesh(r.solid);
    ASSERT_TRUE(report.valid_solid()) << "step " << step << ": " << describe_problems(report);
    const FT inside = overlap_volume(kUnit, slab);
    // union adds the part of the slab outside the cube; difference removes the part inside
    expected += op == BooleanOp::Union ? box_volume(slab) - inside : -inside;
    EXPECT_EQ(report.volume, expected) << "step " << step;
    current = r.solid;
  }
}

TEST(Boolean, InvalidInputIsRefusedWithAReason) {
  Mesh open = make_cube(FT(1));
  open.triangles.pop_back();
  // A Boolean takes Solids: the check that makes them refuses the operand, naming it.
  try {
    check_solids(open, "first operand", make_cube(FT(1)), "second operand");
    ADD_FAILURE() << "an open operand was accepted";
  } catch (const InvalidSolid& e) {
    EXPECT_EQ(e.where(), "first operand");
    EXPECT_NE(e.problem().find("not closed"), std::string::npos) << e.what();
  }
  Mesh inverted = make_cube(FT(1));
  for (Triangle& t : inverted.triangles) std::swap(t[1], t[2]);
  try {
    check_solids(make_cube(FT(1)), "first operand", inverted, "second operand");
    ADD_FAILURE() << "an inward operand was accepted";
  } catch (const InvalidSolid& e) {
    EXPECT_EQ(e.where(), "second operand");
  }
}

TEST(Boolean, EmptyOperands) {
  const Mesh cube = make_cube(FT(1)), empty;
  EXPECT_EQ(checked_volume(cube, empty, BooleanOp::Union), FT(8));
  EXPECT_EQ(checked_volume(cube, empty, BooleanOp::Intersection), FT(0));
  EXPECT_EQ(checked_volume(empty, cube, BooleanOp::Difference), FT(0));
}

TEST(Boolean, ProvenanceNamesTheInputFaces) {
  BooleanOptions options;
  options.provenance = true;
  const Mesh a = box_mesh(kUnit), b = box_mesh(shifted(kUnit, FT(1) / 2, FT(1) / 3, FT(1) / 5));
  const BooleanResult r =
      compute_boolean(check_solid(a), check_solid(b), BooleanOp::Union, options);
  ASSERT_EQ(r.provenance.size(), r.solid.num_triangles());
  bool from_a = false, from_b = false;
  for (const FaceOrigin& o : r.provenance) {
    (o.mesh == 0 ? from_a : from_b) = true;
    EXPECT_LT(o.face, o.mesh == 0 ? a.num_triangles() : b.num_triangles());
  }
  EXPECT_TRUE(from_a && from_b);
}

namespace {

// An exact rotation: about z, then x, by angles whose half-tangents are the rationals tz and tx.
CGAL::Aff_transformation_3<Kernel> rational_rotation(const FT& tz, const FT& tx) {
  return half_tangent_rotation(0, tx) * half_tangent_rotation(2, tz);
}

}  // namespace

// Random rational rigid motions with a fixed seed. Half of the cases only translate by quarters
// (no rotation), which puts faces, edges and vertices of the two meshes on each other.
TEST(Boolean, RandomRationalRigidMotions) {
  std::mt19937 random(20261122);
  std::uniform_int_distribution<int> small(-4, 4), numerator(-9, 9);
  const std::vector<Mesh> shapes = {make_cube(FT(1)), make_icosphere(1, FT(1)),
                                    make_octahedron(FT(1)),
                                    make_box(Point(-1, 0, 0), Point(1, FT(1) / 2, 2))};
  for (int i = 0; i < 40; ++i) {
    const Mesh& a = shapes[i % shapes.size()];
    Mesh b = shapes[(i / shapes.size() + i) % shapes.size()];
    if (i % 2 == 1)
      b = transformed(b, rational_rotation(FT(numerator(random)) / 10, FT(numerator(random)) / 10));
    b = translated(
        b, Kernel::Vector_3(FT(small(random)) / 4, FT(small(random)) / 4, FT(small(random)) / 4));
    SCOPED_TRACE("case " + std::to_string(i));
    check_identities(a, b);
  }
}

TEST(Boolean, VertexOnAFacetAndEdgeInAFacet) {
  // the octahedron's lowest vertex touches the middle of the cube's top face
  const Mesh cube = make_cube(FT(1));
  const Mesh octahedron = make_octahedron(FT(1));
  Mesh unite;
  EXPECT_EQ(checked_volume(cube, translated(octahedron, Kernel::Vector_3(0, 0, 2)),
                           BooleanOp::Union, &unite),
            FT(8) + FT(4) / 3);
  EXPECT_EQ(check_mesh(unite).components, 2u);
  // the octahedron sunk by a half: its equator is above the face, a small pyramid is inside
  const Identities v =
      check_identities(cube, translated(octahedron, Kernel::Vector_3(0, 0, FT(3) / 2)));
  EXPECT_EQ(v.intersect,
            FT(1) / 3 * FT(1) / 2 * FT(1) / 2 * 2 / 2);  // square pyramid: (2 h^2) h / 3, h = 1/2
  // a tetrahedron lying on the top face with one edge along the face's diagonal
  check_identities(cube, translated(make_tetrahedron(), Kernel::Vector_3(-1, -1, 1)));
}

TEST(Boolean, VertexTouchingAFacetAtItsCentroid) {
  // A point contact builds no segment, so the touched facet stays whole and is labelled by one
  // point inside it. Its centroid lies on the other solid here: another point must be taken.
  const Mesh cube = make_cube(FT(1));
  int touched = 0;
  for (const Triangle& t : cube.triangles) {
    const Point &p = cube.points[t[0]], &q = cube.points[t[1]], &r = cube.points[t[2]];
    if (p.z() != 1 || q.z() != 1 || r.z() != 1) continue;
    const Point apex = CGAL::centroid(p, q, r);
    const Mesh above = translated(make_octahedron(FT(1)), apex - Point(0, 0, -1));
    Mesh unite;
    EXPECT_EQ(checked_volume(cube, above, BooleanOp::Union, &unite), FT(8) + FT(4) / 3);
    EXPECT_EQ(check_mesh(unite).components, 2u);
    EXPECT_EQ(checked_volume(cube, above, BooleanOp::Intersection), 0);
    EXPECT_EQ(checked_volume(cube, above, BooleanOp::Difference), FT(8));
    ++touched;
  }
  EXPECT_EQ(touched, 2);  // both triangles of the top face
}

// Inputs whose own non-manifold features are separated (coincident vertices and edges that are
// distinct in the mesh): the other operand crosses the doubled edge's interior, touches it with
// vertices, or is the same solid. Point identity must merge the coincident features where the
// other mesh meets them, so that every result is a valid solid with exact volumes.
TEST(Boolean, SeparatedFeaturesOfAnInputAreCrossedAndTouched) {
  Mesh along_edge, at_vertex;
  ASSERT_EQ(checked_volume(box_mesh(kUnit), box_mesh(shifted(kUnit, 1, 1, 0)), BooleanOp::Union,
                           &along_edge),
            FT(2));
  ASSERT_EQ(checked_volume(box_mesh(kUnit), box_mesh(shifted(kUnit, 1, 1, 1)), BooleanOp::Union,
                           &at_vertex),
            FT(2));
  const Point on_edge(1, 1, FT(1) / 2);
  // Octahedron on the doubled edge: two vertices on the edge, four on the faces around it.
  const Mesh octahedron = translated(make_octahedron(FT(1) / 4), on_edge - CGAL::ORIGIN);
  // A box turned about the edge by a rational angle: the edge crosses its top and bottom faces.
  const Mesh turned = translated(transformed(make_box(Point(FT(-1) / 4, FT(-1) / 4, FT(1) / 4),
                                                      Point(FT(1) / 4, FT(1) / 4, FT(3) / 4)),
                                             quaternion_rotation(5, 0, 0, 2)),
                                 Vector(1, 1, 0));
  // A tetrahedron whose edge PQ crosses the doubled edge at its midpoint (an edge/edge contact):
  // the unit tetrahedron mapped by x -> P + [Q - P, R - P, S - P] x.
  const FT h = FT(1) / 2, q = FT(1) / 4;
  const Mesh crossing_edge =
      transformed(make_tetrahedron(), Transformation(1, 1, 1, h, -1, 0, 0, 3 * h, 0, q, -q, h));
  for (const Mesh* solid : {&along_edge, &at_vertex}) {
    for (const Mesh* other : {&octahedron, &turned, &crossing_edge})
      check_identities(*solid, *other);
    check_identities(*solid, *solid);
    check_identities(*solid, translated(*solid, Vector(FT(1) / 3, FT(1) / 5, FT(1) / 7)));
    check_identities(*solid, translated(*solid, Vector(1, 0, 0)));
  }
  // the octahedron meets each cube in a quarter of its volume: (4/3) r^3 / 4 each
  const FT quarter = FT(4) / 3 * FT(1) / 64 / 4;
  EXPECT_EQ(checked_volume(along_edge, octahedron, BooleanOp::Intersection), 2 * quarter);
}

// A box minus two cubes sharing an edge, the edge inside the box: along the edge the result is
// two opposite wedges, but around each end it is one piece, so no vertex copy tells the two
// pairs of faces on the edge apart. Each pair is split at its own copy of the edge's midpoint.
TEST(Boolean, WedgesMeetingAlongAnEdgeInsideTheResult) {
  Mesh cubes;
  ASSERT_EQ(
      checked_volume(box_mesh(kUnit), box_mesh(shifted(kUnit, 1, 1, 0)), BooleanOp::Union, &cubes),
      FT(2));
  const Mesh outer = make_box(Point(-1, -1, -1), Point(3, 3, 2));
  Mesh carved;
  EXPECT_EQ(checked_volume(outer, cubes, BooleanOp::Difference, &carved), FT(48 - 2));
  EXPECT_EQ(check_mesh(carved).non_manifold_edges, 0u);
  // the carved solid is a valid input: cut it through the doubled edge and fill one cube back
  check_identities(carved, make_box(Point(0, 0, FT(1) / 2), Point(2, 2, 3)));
  check_identities(carved, cubes);
  EXPECT_EQ(checked_volume(carved, box_mesh(kUnit), BooleanOp::Union), FT(48 - 1));
}

TEST(Boolean, LazyAndEvaluatedOutputsAreTheSameSolid) {
  const Mesh a = make_icosphere(2, FT(1));
  const Mesh b = transformed(a, quaternion_rotation(9, 1, 2, 3));
  BooleanOptions evaluated;
  evaluated.exact_output = true;
  for (BooleanOp op : {BooleanOp::Union, BooleanOp::Intersection, BooleanOp::Difference}) {
    const BooleanResult lazy = compute_boolean(check_solid(a), check_solid(b), op),
                        exact = compute_boolean(check_solid(a), check_solid(b), op, evaluated);
    EXPECT_EQ(lazy.solid.mesh().triangles, exact.solid.mesh().triangles);
    ASSERT_EQ(lazy.solid.mesh().points.size(), exact.solid.mesh().points.size());
    for (std::size_t i = 0; i < lazy.solid.mesh().points.size(); ++i)
      EXPECT_EQ(CGAL::exact(lazy.solid.mesh().points[i]), CGAL::exact(exact.solid.mesh().points[i]))
          << i;
  }
}

TEST(ManySolids, TreeUnionAndOneWindingArrangementAgreeExactly) {
  // Three boxes crossing pairwise (their faces meet at triple points), touching and coplanar
  // cubes, nested and disjoint ones, and crossing icospheres: both unions, same exact volume.
  std::vector<Mesh> solids = {
      make_box(Point(0, 0, 0), Point(4, 1, 1)),
      make_box(Point(1, -1, 0), Point(2, 3, 2)),
      make_box(Point(0, 0, -1), Point(3, 2, 1)),
      make_cube(FT(1) / 2, Point(6, 0, 0)),
      make_cube(FT(1) / 2, Point(7, 0, 0)),
      make_cube(FT(1) / 4, Point(6, 0, 0)),
      make_cube(FT(1), Point(-5, -5, -5)),
      make_icosphere(1, FT(1)),
      translated(make_icosphere(1, FT(1)), Vector(FT(1) / 3, FT(1) / 5, FT(1) / 7))};
  UnionStats tree_stats;
  const Mesh by_tree = compute_union(solids_of(solids), &tree_stats);
  // The same union as one winding arrangement of all the boundaries (w >= 1).
  Mesh chain;
  for (const Mesh& s : solids) chain = concatenate(chain, s);
  const Mesh by_arrangement = winding_solid(chain);
  const MeshReport tree_report = check_mesh(by_tree),
                   arrangement_report = check_mesh(by_arrangement);
  EXPECT_TRUE(tree_report.valid_solid()) << describe_problems(tree_report);
  EXPECT_TRUE(arrangement_report.valid_solid()) << describe_problems(arrangement_report);
  EXPECT_EQ(tree_report.volume, arrangement_report.volume);
  EXPECT_EQ(tree_report.components, arrangement_report.components);
  EXPECT_GT(tree_stats.binary_unions, 0u);
  // an independent closed form for the disjoint parts: the two touching cubes and the far cube
  const Mesh far_part = compute_union(solids_of({solids[3], solids[4], solids[5], solids[6]}));
  EXPECT_EQ(signed_volume(far_part), FT(2) + FT(8));
}

TEST(Parallel, ResultsAreIdenticalForAnyNumberOfThreads) {
  const Mesh a = make_icosphere(3, FT(1));
  const Mesh b = transformed(translated(make_icosphere(3, FT(1)), Vector(FT(1) / 3, FT(1) / 5, 0)),
                             quaternion_rotation(7, 1, 2, 3));
  std::vector<Mesh> pieces;
  for (int i = 0; i < 12; ++i)
    pieces.push_back(make_cube(FT(1) / 2, Point(FT(i) / 3, FT(i % 3) / 4, FT(i % 2) / 5)));
  auto run = [&](int threads) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    std::vector<Mesh> out;
    for (BooleanOp op : {BooleanOp::Union, BooleanOp::Intersection, BooleanOp::Difference})
      out.push_back(compute_boolean(check_solid(a), check_solid(b), op).solid);
    out.push_back(compute_union(solids_of(pieces)));
    return out;
  };
  const std::vector<Mesh> one = run(1), two = run(2), four = run(4);
  for (std::size_t i = 0; i < one.size(); ++i) {
    EXPECT_FALSE(one[i].empty());
    for (const std::vector<Mesh>* other : {&two, &four}) {
      EXPECT_EQ(one[i].triangles, (*other)[i].triangles) << "result " << i;
      ASSERT_EQ(one[i].points.size(), (*other)[i].points.size()) << "result " << i;
      for (std::size_t p = 0; p < one[i].points.size(); ++p)
        EXPECT_EQ(one[i].points[p], (*other)[i].points[p]) << "result " << i << " point " << p;
    }
  }
}

namespace {

// The Boolean of a and b with the input check (which hands the operation its trees) and on inputs
// taken as valid: the same candidate pairs and the same result, triangle for triangle.
void expect_checked_as_trusted(const Mesh& a, const Mesh& b, BooleanOp op) {
  const BooleanResult checked = compute_boolean(check_solid(a), check_solid(b), op),
                      plain =
                          compute_boolean(detail::trusted_solid(a), detail::trusted_solid(b), op);
  EXPECT_GT(checked.stats.intersecting_pairs, 0u);
  EXPECT_EQ(checked.stats.candidate_pairs, plain.stats.candidate_pairs);
  EXPECT_EQ(checked.solid.mesh().triangles, plain.solid.mesh().triangles);
  EXPECT_EQ(checked.solid.mesh().points, plain.solid.mesh().points);
}

}  // namespace

// With the input check, step 2 and step 6 use the trees the check built (check_internal.h): the
// result is the one the operation gives on inputs taken as valid, triangle for triangle.
TEST(Boolean, CheckedInputsGiveTheResultOfTrustedOnes) {
  const Mesh a = make_icosphere(3, FT(1));
  const Mesh b = translated(transformed(a, quaternion_rotation(7, 1, 2, 3)),
                            Vector(FT(1) / 2, FT(1) / 3, FT(0)));
  for (const BooleanOp op : {BooleanOp::Union, BooleanOp::Intersection, BooleanOp::Difference})
    expect_checked_as_trusted(a, b, op);
}

// A coarse operand against a fine one: step 2 queries the coarse tree with the fine facets' boxes
// on inputs taken as valid, and the fine tree (the input check's) with the coarse facets' boxes
// when the inputs are checked. Both keep the pairs whose coarse facet's plane may cross the fine
// facet's box: the same pairs, and the same result.
TEST(Boolean, CoarseAgainstFinePairsAreFoundFromEitherSide) {
  // Facets in general directions: the plane test drops many pairs whose boxes overlap.
  const Mesh fine = make_icosphere(4, FT(1));
  const Mesh coarse =
      translated(make_icosphere(1, FT(4) / 5), Vector(FT(1) / 2, FT(1) / 3, FT(1) / 7));
  expect_checked_as_trusted(coarse, fine, BooleanOp::Union);
  expect_checked_as_trusted(fine, coarse, BooleanOp::Union);
}

// An operand whose flat faces the check proves as patches: step 2 and step 6 use its two trees
// joined (the patches, the rest), which give the pairs a fresh tree gives, and the same result.
TEST(Boolean, CheckedInputsWithFlatPatchesGiveTheResultOfTrustedOnes) {
  const Mesh fans = make_fan_prism(96, 1.0, 1.0);  // caps of 96 triangles around a centre
  const Mesh sphere =
      translated(make_icosphere(3, FT(1) / 2), Vector(FT(1) / 3, FT(1) / 5, FT(9) / 10));
  expect_checked_as_trusted(fans, sphere, BooleanOp::Union);
  expect_checked_as_trusted(sphere, fans, BooleanOp::Difference);
  // Coarse against fine: the coarse sphere's facets query the fine prism's joined tree (taken as
  // valid, the prism's facets query the sphere's tree).
  const Mesh fine_fans = make_fan_prism(3000, 1.0, 1.0);
  const Mesh coarse =
      translated(make_icosphere(1, FT(1) / 2), Vector(FT(1) / 3, FT(0), FT(9) / 10));
  expect_checked_as_trusted(coarse, fine_fans, BooleanOp::Intersection);
}

// Large enough that the parallel passes split into several blocks: the candidate pairs compacted
// by blocks of 16,384, the output vertices numbered by blocks of 16,384 keys, the points made by
// blocks of 4,096.
TEST(Parallel, LargeResultsAreIdenticalForAnyNumberOfThreads) {
  // A sphere against a copy turned by a small angle: every facet is cut (the dense case).
  const Mesh a = make_icosphere(4, FT(1));
  const Mesh b = transformed(a, quaternion_rotation(200, 1, 2, 3));
  const Solid sa = detail::trusted_solid(a), sb = detail::trusted_solid(b);
  auto run = [&](int threads) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    return compute_boolean(sa, sb, BooleanOp::Union);
  };
  const BooleanResult one = run(1), two = run(2);
  EXPECT_GT(one.stats.candidate_pairs, 16384u);
  EXPECT_GT(one.solid.mesh().num_vertices(), 16384u);
  EXPECT_EQ(one.solid.mesh().triangles, two.solid.mesh().triangles);
  ASSERT_EQ(one.solid.mesh().points.size(), two.solid.mesh().points.size());
  // The points by their interval approximations (the same recipes give the same bounds): an exact
  // comparison of 25,000 constructed points would evaluate each one, for seconds.
  for (std::size_t p = 0; p < one.solid.mesh().points.size(); ++p)
    for (int k = 0; k < 3; ++k) {
      const auto &x = CGAL::approx(one.solid.mesh().points[p]).cartesian(k),
                 &y = CGAL::approx(two.solid.mesh().points[p]).cartesian(k);
      ASSERT_TRUE(x.inf() == y.inf() && x.sup() == y.sup()) << "point " << p;
    }
}

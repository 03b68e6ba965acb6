// SPDX-License-Identifier: GPL-3.0-or-later
// The coplanar merge of a Boolean's result: no vertex is left inside a flat region, on double and
// on rational (turned) inputs, curved surfaces against flat faces included.
#include <gtest/gtest.h>

#include <algorithm>
#include <utility>
#include <vector>

#include "morphex/boolean.h"
#include "morphex/check.h"
#include "morphex/internal/fixtures.h"

using namespace morphex;

namespace {

// The vertices all of whose faces lie in one plane, decided exactly on the mesh's points: the
// merge removes every such vertex of a clean result (one region around it, no crease).
std::size_t flat_vertices(const Mesh& mesh) {
  std::vector<std::vector<std::uint32_t>> faces_of(mesh.num_vertices());
  for (std::uint32_t f = 0; f < mesh.num_triangles(); ++f)
    for (const VertexIndex v : mesh.triangles[f]) faces_of[v].push_back(f);
  std::size_t flat = 0;
  for (VertexIndex v = 0; v < mesh.num_vertices(); ++v) {
    if (faces_of[v].empty()) continue;
    const Triangle& first = mesh.triangles[faces_of[v].front()];
    const Point &p = mesh.points[first[0]], &q = mesh.points[first[1]], &r = mesh.points[first[2]];
    bool in_plane = true;
    for (const std::uint32_t f : faces_of[v])
      for (const VertexIndex w : mesh.triangles[f])
        in_plane = in_plane && CGAL::orientation(p, q, r, mesh.points[w]) == CGAL::COPLANAR;
    flat += in_plane;
  }
  return flat;
}

// The Boolean with its coplanar merge, and without it.
std::pair<BooleanResult, BooleanResult> merged_and_unmerged(const Mesh& a, const Mesh& b,
                                                            BooleanOp op) {
  BooleanOptions unmerged_options;
  unmerged_options.merge_coplanar = false;
  return {compute_boolean(check_solid(a), check_solid(b), op),
          compute_boolean(check_solid(a), check_solid(b), op, unmerged_options)};
}

// The Boolean merged and unmerged: both valid with one exact volume, the merged one with no flat
// vertex and no more faces (`flat`: the unmerged one has flat vertices). Returns the merged one.
Mesh merged_checked(const Mesh& a, const Mesh& b, BooleanOp op, bool flat) {
  const auto [merged, unmerged] = merged_and_unmerged(a, b, op);
  const MeshReport report = check_mesh(merged.solid), raw = check_mesh(unmerged.solid);
  EXPECT_TRUE(report.valid_solid()) << describe_problems(report);
  EXPECT_EQ(report.volume, raw.volume);
  EXPECT_LE(merged.solid.num_triangles(), unmerged.solid.num_triangles());
  if (flat) EXPECT_GT(flat_vertices(unmerged.solid), 0u);
  EXPECT_EQ(flat_vertices(merged.solid), 0u);
  return merged.solid;
}

// A turn by a rational quaternion: coordinates no longer doubles.
const Transformation kTurn = quaternion_rotation(FT(7), FT(1), FT(2), FT(3));

}  // namespace

// Two boxes overlapping along x, with common top, bottom, front and back planes: the unmerged
// union has vertices inside those faces (where one box's edges cross the other's facets), which
// only the exact stage finds coplanar; merged, it is the 3x2x1 box's 12 triangles.
TEST(BooleanMerge, OverlappingBoxesMergeIntoOneBox) {
  const Mesh a = make_box(Point(-1, -1, -1), Point(1, 1, 0));
  const Mesh b = make_box(Point(0, -1, -1), Point(2, 1, 0));
  for (const bool turned : {false, true}) {
    SCOPED_TRACE(turned ? "turned" : "as made");
    const Mesh merged = turned ? merged_checked(transformed(a, kTurn), transformed(b, kTurn),
                                                BooleanOp::Union, true)
                               : merged_checked(a, b, BooleanOp::Union, true);
    EXPECT_EQ(merged.num_triangles(), 12u);
    EXPECT_EQ(merged.num_vertices(), 8u);
  }
}

// A prism whose top is a fan of 16 facets and a box overlapping it, with common top and bottom
// planes: the top's flat region spans many planes, tested against its first plane's linear form.
TEST(BooleanMerge, FannedTopAndBoxMergeIntoOneFace) {
  const Mesh prism = make_fan_prism(16, 1.0, 1.0);
  const Mesh box = make_box(Point(0, FT(-1) / 2, 0), Point(2, FT(1) / 2, 1));
  for (const bool turned : {false, true}) {
    SCOPED_TRACE(turned ? "turned" : "as made");
    if (turned)
      merged_checked(transformed(prism, kTurn), transformed(box, kTurn), BooleanOp::Union, true);
    else
      merged_checked(prism, box, BooleanOp::Union, true);
  }
}

// A sphere pushed through a box's top face: the face is cut along the sphere, whose own facets
// (curved, each its own plane) are told apart from their neighbours in doubles.
TEST(BooleanMerge, SphereThroughABoxFaceLeavesNoFlatVertex) {
  const Mesh box = make_box(Point(-1, -1, -1), Point(1, 1, FT(1) / 8));
  const Mesh sphere = make_icosphere(3, FT(1) / 2);
  for (const BooleanOp op : {BooleanOp::Union, BooleanOp::Difference, BooleanOp::Intersection}) {
    SCOPED_TRACE(to_string(op));
    merged_checked(box, sphere, op, false);
    SCOPED_TRACE("turned");
    merged_checked(transformed(box, kTurn), transformed(sphere, kTurn), op, false);
  }
}

// Two cubes sharing a face, turned: the side walls of both lie in common planes that only the
// exact stage recognizes (different facets), and the union is the 2x1x1 box's 12 triangles.
TEST(BooleanMerge, TurnedCubesSharingAFaceMergeIntoOneBox) {
  const auto [a, b] = make_cubes_sharing_face();
  const Mesh merged =
      merged_checked(transformed(a, kTurn), transformed(b, kTurn), BooleanOp::Union, false);
  EXPECT_EQ(merged.num_triangles(), 12u);
  EXPECT_EQ(merged.num_vertices(), 8u);
}

namespace {

// The box [-1, 1]^2 x [-1, 0] with its bottom a fan of four triangles around its centre (a flat
// vertex of the input itself), outward.
Mesh box_with_fanned_bottom() {
  Mesh m;
  for (const int z : {-1, 0})
    for (const auto& [x, y] : {std::pair{-1, -1}, {1, -1}, {1, 1}, {-1, 1}})
      m.points.emplace_back(x, y, z);
  m.points.emplace_back(0, 0, -1);                            // 8: the bottom's centre
  m.triangles = {{4, 5, 6}, {4, 6, 7},                        // top
                 {8, 1, 0}, {8, 2, 1}, {8, 3, 2}, {8, 0, 3},  // bottom, seen from below
                 {0, 1, 5}, {0, 5, 4}, {1, 2, 6}, {1, 6, 5},  // sides
                 {2, 3, 7}, {2, 7, 6}, {3, 0, 4}, {3, 4, 7}};
  return m;
}

bool has_vertex(const Mesh& mesh, const Point& p) {
  return std::find(mesh.points.begin(), mesh.points.end(), p) != mesh.points.end();
}

}  // namespace

// A box standing on half of another's top: the union's contact leaves the point where the lower
// top's diagonal crosses the upper box's wall on a straight crease, which the merge removes; the
// lower box's bottom, which the upper one does not touch, keeps its own centre vertex (the merge
// changes only what the Boolean cut).
TEST(BooleanMerge, UntouchedFacesKeepTheirVertices) {
  const Mesh a = box_with_fanned_bottom();
  ASSERT_TRUE(check_mesh(a).valid_solid()) << describe_problems(check_mesh(a));
  const Mesh b = make_box(Point(0, -1, 0), Point(2, 1, 1));
  for (const bool turned : {false, true}) {
    SCOPED_TRACE(turned ? "turned" : "as made");
    auto place = [&](const Point& p) { return turned ? kTurn(p) : p; };
    const Mesh pa = turned ? transformed(a, kTurn) : a, pb = turned ? transformed(b, kTurn) : b;
    const auto [merged, unmerged] = merged_and_unmerged(pa, pb, BooleanOp::Union);
    const MeshReport report = check_mesh(merged.solid);
    EXPECT_TRUE(report.valid_solid()) << describe_problems(report);
    EXPECT_EQ(report.volume, check_mesh(unmerged.solid).volume);
    EXPECT_TRUE(has_vertex(unmerged.solid, place(Point(0, 0, 0))));
    EXPECT_FALSE(has_vertex(merged.solid, place(Point(0, 0, 0))));
    EXPECT_TRUE(has_vertex(merged.solid, place(Point(0, 0, -1))));
    EXPECT_EQ(flat_vertices(merged.solid), 1u);
  }
}

// Where the inputs have no removable vertex of their own, merging only around what the Boolean
// cut removes exactly what merging the whole unmerged result removes: boxes placed on a half-unit
// grid against a unit cube (coplanar faces, shared edges and corners, nested and touching boxes),
// every operation, as made and turned.
TEST(BooleanMerge, AroundTheCutAsOverTheWholeSurface) {
  const Mesh cube = make_box(Point(0, 0, 0), Point(1, 1, 1));
  std::size_t merged_somewhere = 0;
  for (int dx = -2; dx <= 2; ++dx)
    for (int dy = 0; dy <= 2; ++dy)
      for (int dz = 0; dz <= 1; ++dz) {
        const FT x = FT(dx) / 2, y = FT(dy) / 2, z = FT(dz) / 2;
        const Mesh box = make_box(Point(x, y, z), Point(x + 1, y + FT(1) / 2, z + 1));
        for (const bool turned : {false, true}) {
          const Mesh a = turned ? transformed(cube, kTurn) : cube,
                     b = turned ? transformed(box, kTurn) : box;
          for (const BooleanOp op :
               {BooleanOp::Union, BooleanOp::Intersection, BooleanOp::Difference}) {
            SCOPED_TRACE(::testing::Message() << to_string(op) << " box at " << dx << "/2 " << dy
                                              << "/2 " << dz << "/2" << (turned ? " turned" : ""));
            const auto [merged, unmerged] = merged_and_unmerged(a, b, op);
            const Mesh whole = merge_coplanar_faces(check_solid(unmerged.solid));
            EXPECT_EQ(merged.solid.num_triangles(), whole.num_triangles());
            EXPECT_EQ(merged.solid.mesh().num_vertices(), whole.num_vertices());
            EXPECT_EQ(check_mesh(merged.solid).volume, check_mesh(whole).volume);
            merged_somewhere += merged.solid.num_triangles() < unmerged.solid.num_triangles();
          }
        }
      }
  EXPECT_GT(merged_somewhere, 30u);  // the merge had work to do in many of the 180 cases
}

// SPDX-License-Identifier: GPL-3.0-or-later
// repair_mesh against independent exact methods: CGAL Nef polyhedra for unions, and exact
// ray-cast winding numbers of the input (morphex::winding_number, not the arrangement's own
// classification) on both sides of every output face and at random points.
#include <gtest/gtest.h>

#include <array>
#include <random>

#include "morphex/check.h"
#include "morphex/internal/fixtures.h"
#include "morphex/repair.h"
#include "peers.h"
#include "tree/box_tree.h"

using namespace morphex;

namespace {

Mesh box(FT x0, FT y0, FT z0, FT x1, FT y1, FT z1) {
  return make_box(Point(x0, y0, z0), Point(x1, y1, z1));
}

// The mesh with vertices at one position merged (as a file would list them once).
Mesh welded(const Mesh& m) {
  Mesh out;
  std::vector<VertexIndex> id(m.points.size());
  for (std::size_t v = 0; v < m.points.size(); ++v) {
    std::size_t k = 0;
    while (k < out.points.size() && out.points[k] != m.points[v]) ++k;
    if (k == out.points.size()) out.points.push_back(m.points[v]);
    id[v] = VertexIndex(k);
  }
  for (const Triangle& t : m.triangles) out.triangles.push_back({id[t[0]], id[t[1]], id[t[2]]});
  return out;
}

int winding(const Mesh& closed, const TriangleTree& tree, const Point& p) {
  return winding_number(closed, tree, p);
}

// The output bounds exactly {w_input >= 1}: just behind every output face the input winds at
// least once, just in front of it less; and random points agree.
void expect_positive_winding_region(const Mesh& input, const Mesh& output, int random_points) {
  const TriangleTree in_tree(input), out_tree(output);
  CGAL::Bbox_3 box;
  for (const Point& p : input.points) box += p.bbox();
  const FT eps = FT(1) / (1 << 20) * FT(box.xmax() - box.xmin() + box.ymax() - box.ymin() + 1);
  int checked = 0;
  for (const Triangle& t : output.triangles) {
    const Point& a = output.points[t[0]];
    const Point& b = output.points[t[1]];
    const Point& c = output.points[t[2]];
    const Point centre = CGAL::centroid(a, b, c);
    Vector n = CGAL::cross_product(b - a, c - a);
    n = n / FT(CGAL::abs(n.x()) + CGAL::abs(n.y()) + CGAL::abs(n.z()));
    try {
      EXPECT_GE(winding(input, in_tree, centre - eps * n), 1);
      EXPECT_LT(winding(input, in_tree, centre + eps * n), 1);
      ++checked;
    } catch (const std::domain_error&) {
      // the offset point lies on another sheet: nothing to compare there
    }
  }
  EXPECT_GT(checked, int(output.triangles.size()) / 2);
  std::mt19937 random(11);
  std::uniform_real_distribution<double> u(0, 1);
  for (int i = 0; i < random_points; ++i) {
    const Point p(box.xmin() + u(random) * (box.xmax() - box.xmin()),
                  box.ymin() + u(random) * (box.ymax() - box.ymin()),
                  box.zmin() + u(random) * (box.zmax() - box.zmin()));
    try {
      EXPECT_EQ(winding(input, in_tree, p) >= 1, winding(output, out_tree, p) == 1);
    } catch (const std::domain_error&) {
    }
  }
}

RepairResult repaired(const Mesh& m) {
  RepairResult r = repair_mesh(m);
  const MeshReport report = check_mesh(r.solid);
  EXPECT_TRUE(report.valid_solid()) << describe_problems(report);
  return r;
}

}  // namespace

TEST(Repair, ValidSolidComesBackUnchanged) {
  const Mesh sphere = make_icosphere(2, 1);
  const RepairResult r = repaired(sphere);
  EXPECT_FALSE(r.report.changed);
  EXPECT_EQ(r.solid.mesh().triangles, sphere.triangles);
}

TEST(Repair, TwoOverlappingCubesWrittenAsOneMesh) {
  const Mesh a = box(0, 0, 0, 2, 2, 2), b = box(1, 1, 1, 3, 3, 3);
  const RepairResult r = repaired(concatenate(a, b));
  EXPECT_TRUE(r.report.changed);
  EXPECT_GT(r.report.intersecting_pairs, 0u);
  EXPECT_EQ(signed_volume(r.solid), 15);
  EXPECT_EQ(signed_volume(r.solid), peers::nef_boolean(a, b, BooleanOp::Union).volume);
  EXPECT_EQ(r.report.components_in, 2u);
  EXPECT_EQ(r.report.components_out, 1u);
  expect_positive_winding_region(concatenate(a, b), r.solid, 200);
}

TEST(Repair, TouchingAlongAnEdgeAndAtAVertex) {
  for (const auto& [a, b] : {make_cubes_sharing_edge(), make_cubes_sharing_vertex()}) {
    // One mesh, the common vertices listed once: non-manifold where the cubes touch.
    const Mesh touching = welded(concatenate(a, b));
    EXPECT_FALSE(check_mesh(touching).valid_solid());
    const RepairResult r = repaired(touching);
    EXPECT_EQ(signed_volume(r.solid), 2);
    EXPECT_EQ(signed_volume(r.solid), peers::nef_boolean(a, b, BooleanOp::Union).volume);
    EXPECT_GT(r.report.merged_vertices + r.report.components_in, 0u);
  }
}

TEST(Repair, FoldOver) {
  // A cube whose top corner is pulled through the bottom face: its three faces cross the bottom.
  Mesh folded = make_cube(1);
  for (Point& p : folded.points)
    if (p == Point(1, 1, 1)) p = Point(FT(1) / 3, FT(1) / 4, -2);
  ASSERT_GT(check_mesh(folded).self_intersections, 0u);
  const RepairResult r = repaired(folded);
  expect_positive_winding_region(folded, r.solid, 400);
}

TEST(Repair, CoincidentDuplicateShells) {
  const Mesh cube = make_cube(1);
  const RepairResult r = repaired(concatenate(cube, cube));
  EXPECT_EQ(signed_volume(r.solid), 8);
  EXPECT_EQ(r.report.duplicate_faces, 12u);
  // The same shell twice with its own vertices: winding 2 inside, the same solid.
  const Mesh shifted = translated(cube, Vector(FT(1) / 2, 0, 0));
  const RepairResult s = repaired(concatenate(concatenate(cube, cube), shifted));
  EXPECT_EQ(signed_volume(s.solid), 8 + 2);  // [-1, 1]^3 and its copy shifted by 1/2 along x
}

// The same cube twice, the copy's bottom and front faces split by the other diagonals: eight of
// its triangles repeat the first cube's and four do not. Dropping the repeated ones would leave an
// open chain; both shells are kept instead, and the winding counts 2 inside.
TEST(Repair, CoincidentShellsTriangulatedPartlyAlike) {
  Mesh first, copy;
  for (int v = 0; v < 8; ++v) first.points.push_back(Point(v >> 2, (v >> 1) & 1, v & 1));
  copy.points = first.points;
  first.triangles = {{0, 2, 4}, {4, 2, 6}, {0, 4, 1}, {4, 5, 1}, {0, 1, 2}, {2, 1, 3},
                     {1, 5, 7}, {1, 7, 3}, {2, 3, 7}, {2, 7, 6}, {4, 6, 7}, {4, 7, 5}};
  copy.triangles = {{0, 2, 6}, {0, 6, 4}, {0, 4, 5}, {0, 5, 1}, {0, 1, 2}, {2, 1, 3},
                    {1, 5, 7}, {1, 7, 3}, {2, 3, 7}, {2, 7, 6}, {4, 6, 7}, {4, 7, 5}};
  ASSERT_TRUE(check_mesh(first).valid_solid());
  ASSERT_TRUE(check_mesh(copy).valid_solid());
  const RepairResult r = repaired(concatenate(first, copy));
  EXPECT_EQ(signed_volume(r.solid), 1);
  EXPECT_EQ(r.report.duplicate_faces, 0u);  // every face kept
}

TEST(Repair, DegenerateAndDuplicateFaces) {
  // The unit cube with an edge split by its midpoint m on one side only, closed by a face
  // (a, b, m) without area: a degenerate face and a T-junction; plus a repeated face.
  Mesh cube = make_box(Point(0, 0, 0), Point(1, 1, 1));
  const Triangle f = cube.triangles[0];
  const VertexIndex a = f[0], b = f[1], c = f[2];
  const auto m = VertexIndex(cube.points.size());
  cube.points.push_back(CGAL::midpoint(cube.points[a], cube.points[b]));
  cube.triangles[0] = {a, m, c};
  cube.triangles.push_back({m, b, c});
  cube.triangles.push_back({a, b, m});
  cube.triangles.push_back(cube.triangles[5]);
  const MeshReport before = check_mesh(cube);
  EXPECT_GT(before.degenerate_faces, 0u);
  const RepairResult r = repaired(cube);
  EXPECT_EQ(signed_volume(r.solid), 1);
  EXPECT_EQ(r.report.degenerate_faces, 1u);
  EXPECT_EQ(r.report.duplicate_faces, 1u);
}

TEST(Repair, InsideOutIsTurned) {
  const RepairResult r = repaired(reversed(make_cube(1)));
  EXPECT_TRUE(r.report.reversed);
  EXPECT_EQ(signed_volume(r.solid), 8);
}

TEST(Repair, RefusesOpenAndInconsistentMeshes) {
  Mesh open = make_cube(1);
  open.triangles.pop_back();
  try {
    repair_mesh(open);
    FAIL() << "an open mesh was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("not closed"), std::string::npos) << e.what();
  }
  Mesh flipped = make_cube(1);
  std::swap(flipped.triangles[3][1], flipped.triangles[3][2]);
  try {
    repair_mesh(flipped);
    FAIL() << "a mesh with a turned face was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("not consistently oriented"), std::string::npos)
        << e.what();
  }
}

TEST(Repair, RandomOverlapsAgreeWithNef) {
  std::mt19937 random(5);
  std::uniform_int_distribution<int> offset(-3, 3), turn(-2, 2);
  for (int round = 0; round < 8; ++round) {
    const Mesh a = transformed(make_icosphere(1, 2),
                               quaternion_rotation(turn(random), turn(random), turn(random), 4));
    const Mesh b = translated(make_cube(FT(3) / 2),
                              Vector(FT(offset(random)) / 2, FT(offset(random)) / 2, FT(1) / 3));
    SCOPED_TRACE(round);
    const RepairResult r = repaired(concatenate(a, b));
    EXPECT_EQ(signed_volume(r.solid), peers::nef_boolean(a, b, BooleanOp::Union).volume);
  }
}

namespace {

// A soup of `count` random tetrahedra with double corners in one box, each positively oriented:
// a closed chain whose every face crosses many others (an untrusted file of issue 44, item 5).
Mesh tetrahedron_soup(std::size_t count, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> coordinate(0, 1), size(1, 4);
  Mesh soup;
  for (std::size_t t = 0; t < count; ++t) {
    const double x = coordinate(random), y = coordinate(random), z = coordinate(random);
    const double s = size(random);
    std::array<Point, 4> p;
    for (Point& q : p)
      q = Point(x + s * coordinate(random), y + s * coordinate(random), z + s * coordinate(random));
    if (CGAL::orientation(p[0], p[1], p[2], p[3]) == CGAL::ZERO) continue;
    if (CGAL::orientation(p[0], p[1], p[2], p[3]) == CGAL::NEGATIVE) std::swap(p[0], p[1]);
    const VertexIndex v = VertexIndex(soup.points.size());
    soup.points.insert(soup.points.end(), p.begin(), p.end());
    // outward for a positively oriented (p0, p1, p2, p3)
    soup.triangles.push_back({v, v + 2, v + 1});
    soup.triangles.push_back({v, v + 1, v + 3});
    soup.triangles.push_back({v + 1, v + 2, v + 3});
    soup.triangles.push_back({v, v + 3, v + 2});
  }
  return soup;
}

}  // namespace

// 500 random tetrahedra crossing each other (issue 44, item 5): W = 1.6e8 against the default
// budget of 2e6; before the budget the repair used 1.5 GB and 25 s at 300 tetrahedra and 10 GB at
// 500. It is refused at once, before the arrangement is built.
TEST(Repair, SoupOfCrossingTetrahedraExceedsTheBudget) {
  const Mesh soup = tetrahedron_soup(500, 7);
  try {
    repair_mesh(soup);
    FAIL() << "a soup of 500 crossing tetrahedra was repaired within the budget";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("repair would exceed its budget"), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("1000 per input face"), std::string::npos) << e.what();
  }
  RepairOptions tight;
  tight.budget = 1;  // the minimum work still lets small meshes through
  EXPECT_TRUE(
      check_mesh(repair_mesh(tetrahedron_soup(40, 7), tight).solid, kValidityOnly).valid_solid());
}

TEST(Repair, BudgetCanBeRaisedOrRemoved) {
  // 100 tetrahedra: W = 8.2e5 (under the minimum); 150: W = 3.2e6, above 1000 x 600 faces.
  const Mesh soup = tetrahedron_soup(150, 7);
  EXPECT_THROW(repair_mesh(soup), InputError);
  RepairOptions raised;
  raised.budget = 10000;
  EXPECT_TRUE(check_mesh(repair_mesh(soup, raised).solid, kValidityOnly).valid_solid());
  RepairOptions none;
  none.budget = 0;
  EXPECT_TRUE(check_mesh(repair_mesh(soup, none).solid, kValidityOnly).valid_solid());
}

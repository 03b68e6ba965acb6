// SPDX-License-Identifier: GPL-3.0-or-later
// Rounding exact results to floating-point formats as valid solids (morphex/rounding.h, issue 42):
// generated worst cases (slivers thinner than a float's spacing, near-coincident vertices, faces
// that rounding makes touch or cross), each written in every plain format and read back both by
// morphex and by an independent reader (CGAL's polygon soup I/O and Polygon Mesh Processing).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <random>

#include "morphex/boolean.h"
#include "morphex/check.h"
#include "morphex/internal/fixtures.h"
#include "morphex/io.h"
#include "morphex/rounding.h"
#include "peers.h"

namespace fs = std::filesystem;
using namespace morphex;

namespace {

class TempDir {
 public:
  TempDir()
      : path_(fs::temp_directory_path() / ("morphex_rounding_" + std::to_string(::getpid()))) {
    fs::create_directories(path_);
  }
  ~TempDir() { fs::remove_all(path_); }
  std::string file(const std::string& name) const { return (path_ / name).string(); }

 private:
  fs::path path_;
};

Mesh boolean(const Mesh& a, const Mesh& b, BooleanOp op) {
  return compute_boolean(check_solid(a), check_solid(b), op).solid.mesh();
}

MeshReport checked(const Mesh& m) {
  return check_mesh(m, CheckOptions{true, true});
}

// Read back by CGAL's own readers (not morphex's): welded, oriented as a soup, made a mesh; closed,
// without self-intersections (faces touching at coincident copies of a vertex count as meeting
// there, so results that touch themselves are only checked as closed), positive volume.
void expect_independently_valid(const std::string& path, bool touching_allowed) {
  const peers::ForeignRead read = peers::cgal_read_back(path);
  ASSERT_TRUE(read.read) << path;
  EXPECT_TRUE(read.closed) << path;
  if (!touching_allowed) EXPECT_FALSE(read.self_intersecting) << path;
  EXPECT_GT(read.volume, 0) << path;
}

// Writes `exact` in every plain format; each file must read back (by morphex) as a valid solid
// with the rounded mesh's coordinates, and within `tolerance` of the exact volume (relative).
void expect_written_valid(const Mesh& exact, const std::string& what, double tolerance,
                          bool touching_allowed = false) {
  TempDir dir;
  const double exact_volume = CGAL::to_double(signed_volume(exact));
  for (const char* ext : {"off", "obj", "ply", "stl", "glb", "3mf"}) {
    const std::string path = dir.file(what + "." + ext);
    const MeshFormat format = format_from_path(path);
    if (!format_available(format)) continue;
    WriteOptions options;
    options.measure_rounding = true;
    const RoundingReport r = write_mesh(exact, path, options);
    if (!format_readable(format)) continue;  // glb: written for viewers
    const Mesh back = read_mesh(path);
    const MeshReport report = checked(back);
    EXPECT_TRUE(report.valid_solid()) << what << "." << ext << ": " << describe_problems(report);
    const double volume = CGAL::to_double(report.volume);
    // 3MF keeps six decimals (with gaps, see rounding.cpp): on a unit-sized solid a few 1e-6
    // per coordinate.
    const double within = std::string(ext) == "3mf" ? std::max(tolerance, 5e-5) : tolerance;
    EXPECT_NEAR(volume, exact_volume, within * std::fabs(exact_volume) + 1e-300)
        << what << "." << ext;
    EXPECT_NEAR(CGAL::to_double(report.volume) - exact_volume, r.volume_change,
                1e-9 * std::fabs(exact_volume))
        << what << "." << ext;
    if (std::string(ext) != "3mf") expect_independently_valid(path, touching_allowed);
  }
}

}  // namespace

// Coordinates already on the grid are left alone: nothing moves, nothing is checked again.
TEST(Rounding, MeshesOnTheGridAreUnchanged) {
  const Mesh cube = make_cube(FT(1));
  const RoundedMesh r = round_mesh(cube, {RoundingGrid::Float});
  EXPECT_EQ(r.report.moved_vertices, 0u);
  EXPECT_EQ(r.report.rounds, 0u);
  EXPECT_EQ(r.report.max_displacement, 0.0);
  EXPECT_EQ(r.mesh.points, to_double(cube).points);
  EXPECT_EQ(r.mesh.triangles, cube.triangles);
}

TEST(Rounding, CoordinatesRoundToNearest) {
  EXPECT_EQ(round_coordinate(FT(1) / 3, RoundingGrid::Double), 1.0 / 3);
  EXPECT_EQ(round_coordinate(FT(1) / 3, RoundingGrid::Float), double(1.0f / 3));
  // 3MF: a float that lib3mf writes and reads back unchanged, near the value (lib3mf itself
  // checks the model on every write: expect_written_valid below writes through it).
  for (const double x : {1.0 / 3, 0.063531, -0.12749199569225311, -180.61083984375, 17.3}) {
    const double v = round_coordinate(FT(x), RoundingGrid::ThreeMf);
    EXPECT_NEAR(v, x, 1e-5 + 1e-6 * std::fabs(x)) << x;
    EXPECT_EQ(double(float(v)), v) << x;
  }
  EXPECT_TRUE(std::isinf(round_coordinate(FT(1e300), RoundingGrid::Float)));
  // The nearest double of a rational, not a neighbour (CGAL's to_double may give one).
  const FT x = FT(1) + FT(1) / FT(std::ldexp(1.0, 53)) * FT(3) / FT(2);  // 1 + 1.5 ulp/2
  EXPECT_EQ(round_coordinate(x, RoundingGrid::Double), 1 + std::ldexp(1.0, -52));
}

// A solid whose every vertex moves but nothing breaks: one round, no resolution.
TEST(Rounding, ThirdsMoveWithoutBreaking) {
  const Mesh cube = make_cube(FT(1) / 3);
  const RoundedMesh r = round_mesh(cube, {RoundingGrid::Float, true});
  EXPECT_EQ(r.report.moved_vertices, 8u);
  EXPECT_EQ(r.report.rounds, 0u);
  EXPECT_LE(r.report.max_displacement, std::ldexp(1.0, -25));
  EXPECT_LT(std::fabs(r.report.relative_volume_change), 1e-6);
  expect_written_valid(cube, "thirds", 1e-6);
}

// Two boxes 1e-10 apart: in floats their facing walls coincide, opposite: the rounded mesh is
// resolved into one box.
TEST(Rounding, NearlyTouchingBoxesMergeInFloats) {
  const FT gap = FT(1) / FT(1e10);
  const Mesh a = make_box(Point(0, 0, 0), Point(1, 1, 1));
  const Mesh b = make_box(Point(1 + gap, 0, 0), Point(2, 1, 1));
  const Mesh both = concatenate(a, b);
  ASSERT_TRUE(checked(both).valid_solid());
  const RoundedMesh r = round_mesh(both, {RoundingGrid::Float});
  EXPECT_GE(r.report.rounds, 1u);
  const MeshReport after = checked(from_double(r.mesh));
  EXPECT_TRUE(after.valid_solid()) << describe_problems(after);
  EXPECT_EQ(after.volume, FT(2));
  EXPECT_EQ(after.components, 1u);
  // In doubles the gap stays: nothing to resolve.
  EXPECT_EQ(round_mesh(both, {RoundingGrid::Double}).report.rounds, 0u);
  expect_written_valid(both, "gap", 1e-9);
}

// A slot thinner than a float's spacing, cut into a box: its walls collapse onto each other.
TEST(Rounding, ThinSlotCollapses) {
  const FT t = FT(1) / FT(3e9);
  const Mesh box = make_box(Point(0, 0, 0), Point(1, 1, 1));
  const Mesh slot = make_box(Point(FT(1) / 2, FT(-1), FT(1) / 4), Point(FT(1) / 2 + t, 2, 2));
  const Mesh cut = boolean(box, slot, BooleanOp::Difference);
  ASSERT_TRUE(checked(cut).valid_solid());
  const RoundedMesh r = round_mesh(cut, {RoundingGrid::Float});
  EXPECT_GE(r.report.rounds, 1u);
  EXPECT_TRUE(checked(from_double(r.mesh)).valid_solid());
  expect_written_valid(cut, "slot", 1e-8, true);
}

// A sliver tetrahedron whose apex lies a fraction of a float's spacing above its base: in floats
// it is flat, and thinner than the grid everywhere: it collapses to the empty solid.
TEST(Rounding, SliverThinnerThanTheGridCollapses) {
  const FT third = FT(1) / 3, h = FT(1) / FT(1e12);
  Mesh m;
  m.points = {Point(1, 0, 0), Point(0, 1, 0), Point(0, 0, 1),
              Point(third - h, third - h, third - h)};
  m.triangles = {{0, 1, 2}, {0, 3, 1}, {1, 3, 2}, {2, 3, 0}};
  const MeshReport before = checked(m);
  ASSERT_TRUE(before.valid_solid()) << describe_problems(before);
  const RoundedMesh r = round_mesh(m, {RoundingGrid::Float, true});
  EXPECT_TRUE(r.report.collapsed);
  EXPECT_TRUE(r.mesh.triangles.empty());
  EXPECT_TRUE(r.report.volume_measured);
  // In doubles the apex stays above the base: the sliver survives unchanged in shape.
  const RoundedMesh d = round_mesh(m, {RoundingGrid::Double});
  EXPECT_FALSE(d.report.collapsed);
  EXPECT_TRUE(checked(from_double(d.mesh)).valid_solid());
}

// Tiny shapes where 3MF's six decimals leave only a few grid steps per feature: random unions of
// rotated boxes, rounded with many vertices merged and faces crossing; always valid, and the
// volume within the grid's reach.
TEST(Rounding, CoarseGridStress) {
  std::mt19937 random(42);
  std::uniform_int_distribution<int> coordinate(0, 40), turn(1, 12);
  const FT unit = FT(1) / FT(1e6);  // 3MF's grid spacing
  int resolved = 0;
  for (int trial = 0; trial < 40; ++trial) {
    Mesh result;
    for (int k = 0; k < 3; ++k) {
      const FT x = FT(coordinate(random)) * unit / 3, y = FT(coordinate(random)) * unit / 3,
               z = FT(coordinate(random)) * unit / 3, s = FT(turn(random) + 8) * unit / 7;
      const Mesh box = transformed(make_box(Point(x, y, z), Point(x + s, y + s / 2, z + s)),
                                   half_tangent_rotation(k, FT(1) / FT(turn(random) + 1)));
      result = result.empty() ? box : boolean(result, box, BooleanOp::Union);
    }
    const RoundedMesh r = round_mesh(result, {RoundingGrid::ThreeMf, true});
    resolved += r.report.rounds > 0;
    const MeshReport after = checked(from_double(r.mesh));
    ASSERT_TRUE(after.valid_solid()) << "trial " << trial << ": " << describe_problems(after);
    // Each vertex moves at most half a grid step per round in each coordinate.
    const double area_bound = 1e-9;  // the boxes' surfaces are below (40/3 + 3)^2 1e-12 * 6
    EXPECT_LE(std::fabs(r.report.volume_change), area_bound * 0.5e-6 * double(r.report.rounds + 1))
        << "trial " << trial;
  }
  EXPECT_GT(resolved, 5);  // the test exercises the resolution, not only the rounding
}

// STL stores a soup: where a solid touches itself, welding would join what the solid keeps
// apart. The reader separates it again, so a written result reads back valid.
TEST(Rounding, TouchingResultsReadBackFromStl) {
  TempDir dir;
  const auto [a, b] = make_cubes_sharing_edge();
  const Mesh both = boolean(a, b, BooleanOp::Union);
  ASSERT_TRUE(checked(both).valid_solid());
  write_mesh(both, dir.file("edge.stl"));
  const MeshReport back = checked(read_mesh(dir.file("edge.stl")));
  EXPECT_TRUE(back.valid_solid()) << describe_problems(back);
  EXPECT_EQ(back.volume, checked(both).volume);
  const auto [c, d] = make_cubes_sharing_vertex();
  write_mesh(boolean(c, d, BooleanOp::Union), dir.file("vertex.stl"));
  EXPECT_TRUE(checked(read_mesh(dir.file("vertex.stl"))).valid_solid());
  // An open soup is left as it is, for the check to report.
  Mesh open = make_cube(FT(1));
  open.triangles.pop_back();
  write_mesh(open, dir.file("open.stl"));
  EXPECT_EQ(checked(read_mesh(dir.file("open.stl"))).border_edges, 3u);
}

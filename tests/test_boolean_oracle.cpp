// SPDX-License-Identifier: GPL-3.0-or-later
// Agreement with independent exact methods on the same input: CGAL Nef polyhedra and CGAL
// corefinement (both Epeck) must give exactly the volume morphex gives.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

#include "morphex/boolean.h"
#include "morphex/check.h"
#include "morphex/io.h"
#include "morphex/shapes.h"
#include "peers.h"

using namespace morphex;

namespace {

FT nef_volume(const Mesh& a, const Mesh& b, BooleanOp op) {
  return peers::nef_boolean(a, b, op).volume;
}

// CGAL corefinement refuses some degenerate outputs; it is an oracle only where it succeeds.
std::optional<FT> corefinement_volume(const Mesh& a, const Mesh& b, BooleanOp op) {
  if (const auto r = peers::corefinement_boolean(a, b, op)) return r->volume;
  return std::nullopt;
}

void expect_agreement(const Mesh& a, const Mesh& b, const std::string& name) {
  for (BooleanOp op : {BooleanOp::Union, BooleanOp::Intersection, BooleanOp::Difference}) {
    const BooleanResult r = compute_boolean(check_solid(a), check_solid(b), op);
    const MeshReport report = check_mesh(r.solid);
    EXPECT_TRUE(report.valid_solid())
        << name << " " << to_string(op) << ": " << describe_problems(report);
    EXPECT_EQ(report.volume, nef_volume(a, b, op)) << name << " " << to_string(op) << " vs Nef";
    if (const auto v = corefinement_volume(a, b, op))
      EXPECT_EQ(report.volume, *v) << name << " " << to_string(op) << " vs corefinement";
  }
}

std::string demo_dir() {
  if (const char* d = std::getenv("MORPHEX_DATA_DIR")) return d;
  const char* home = std::getenv("HOME");
  return std::string(home ? home : ".") + "/.cache/morphex/cgal-demo";
}

}  // namespace

TEST(Oracle, OverlappingCubesWithCoplanarFaces) {
  // the seed's figure: cubes overlapping with coplanar top and bottom faces
  expect_agreement(make_box(Point(0, 0, 0), Point(2, 2, 2)),
                   make_box(Point(1, 1, 0), Point(3, 3, 2)), "coplanar cubes");
}

TEST(Oracle, CubesTouchingOnAFace) {
  expect_agreement(make_cube(FT(1)), translated(make_cube(FT(1)), Kernel::Vector_3(2, 0, 0)),
                   "face contact");
}

TEST(Oracle, CrossingIcospheres) {
  expect_agreement(make_icosphere(2, FT(1)),
                   translated(make_icosphere(2, FT(1)), Kernel::Vector_3(FT(1) / 2, FT(1) / 3, 0)),
                   "icospheres");
}

TEST(Oracle, StarAndCross) {
  const std::string dir = demo_dir();
  if (!std::filesystem::exists(dir + "/star.off"))
    GTEST_SKIP() << "run scripts/fetch-cgal-demo-meshes";
  const Mesh star = read_mesh(dir + "/star.off"), cross = read_mesh(dir + "/cross.off");
  expect_agreement(star, cross, "star/cross");
}

TEST(Oracle, ElephantAgainstARotatedElephant) {
  const std::string dir = demo_dir();
  if (!std::filesystem::exists(dir + "/elephant.off"))
    GTEST_SKIP() << "run scripts/fetch-cgal-demo-meshes";
  const Mesh elephant = read_mesh(dir + "/elephant.off");
  // rotation about z by the half-tangent 1/12 (about 9.5 degrees), then a small shift
  const FT t = FT(1) / 12, c = (1 - t * t) / (1 + t * t), s = 2 * t / (1 + t * t);
  Mesh other = transformed(elephant, Transformation(c, -s, 0, s, c, 0, 0, 0, 1));
  other = translated(other, Vector(FT(1) / 100, FT(1) / 50, 0));
  for (BooleanOp op : {BooleanOp::Union, BooleanOp::Intersection, BooleanOp::Difference}) {
    const BooleanResult r = compute_boolean(check_solid(elephant), check_solid(other), op);
    const MeshReport report = check_mesh(r.solid);
    EXPECT_TRUE(report.valid_solid()) << describe_problems(report);
    const auto expected = corefinement_volume(elephant, other, op);
    ASSERT_TRUE(expected.has_value());
    EXPECT_EQ(report.volume, *expected) << to_string(op);
  }
}

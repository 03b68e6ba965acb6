// SPDX-License-Identifier: GPL-3.0-or-later
// Minkowski sums and dilations against CGAL's minkowski_sum_3 (Nef polyhedra, exact): identical
// exact volumes on small convex and non-convex inputs with cube, octahedron, ball and zonoball SEs.

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

#include "morphex/boolean.h"
#include "morphex/check.h"
#include "morphex/io.h"
#include "morphex/minkowski.h"
#include "morphex/morphology.h"
#include "morphex/shapes.h"
#include "peers.h"

using namespace morphex;

namespace {

FT cgal_minkowski_volume(const Mesh& a, const Mesh& b) {
  return peers::nef_minkowski_sum(a, b).volume;
}

void expect_same_dilation(const Mesh& a, const std::string& name,
                          std::vector<const char*> specs = {"cube:r=1/10", "octahedron:r=1/7",
                                                            "ball:r=1/8,level=0"}) {
  for (const char* spec : specs) {
    const StructuringElement se = parse_structuring_element(spec);
    const Mesh ours = dilation(check_solid(a), se);
    const MeshReport report = check_mesh(ours);
    EXPECT_TRUE(report.valid_solid()) << name << " + " << spec << ": " << describe_problems(report);
    EXPECT_EQ(report.volume, cgal_minkowski_volume(a, se.mesh)) << name << " + " << spec;
  }
}

std::string demo_dir() {
  if (const char* d = std::getenv("MORPHEX_DATA_DIR")) return d;
  const char* home = std::getenv("HOME");
  return std::string(home ? home : ".") + "/.cache/morphex/cgal-demo";
}

Mesh l_shape() {
  return compute_boolean(check_solid(make_box(Point(0, 0, 0), Point(2, 1, 1))),
                         check_solid(make_box(Point(0, 0, 0), Point(1, 2, 1))), BooleanOp::Union)
      .solid;
}

}  // namespace

TEST(MinkowskiOracle, LShape) {
  expect_same_dilation(l_shape(), "L-shape");
}

// Zonoballs take one sweep per generator (the convolution and its union are not involved): on the
// L-shape, whose facets are parallel to some generators, and on it turned by a rational rotation.
TEST(MinkowskiOracle, Zonoball) {
  expect_same_dilation(l_shape(), "L-shape", {"zonoball:r=1/8,level=0", "zonoball:r=1/3,level=1"});
  expect_same_dilation(transformed(l_shape(), quaternion_rotation(5, 1, 2, 3)), "turned L-shape",
                       {"zonoball:r=1/8,level=0"});
}

// Even cylinders take the sweeps, odd ones the convolution pieces: both against minkowski_sum_3.
TEST(MinkowskiOracle, Cylinder) {
  expect_same_dilation(l_shape(), "L-shape",
                       {"cylinder:r=1/8,h=1/3,segments=6", "cylinder:r=1/8,h=1/3,segments=7"});
  expect_same_dilation(transformed(l_shape(), quaternion_rotation(5, 1, 2, 3)), "turned L-shape",
                       {"cylinder:r=1/9,h=1/4,segments=8"});
}

TEST(MinkowskiOracle, Torus) {
  expect_same_dilation(make_torus(8, 4, 1.0, 0.4), "torus");
}

TEST(MinkowskiOracle, StarAndCross) {
  const std::string dir = demo_dir();
  if (!std::filesystem::exists(dir + "/star.off"))
    GTEST_SKIP() << "run scripts/fetch-cgal-demo-meshes";
  expect_same_dilation(read_mesh(dir + "/star.off"), "star");
  expect_same_dilation(read_mesh(dir + "/cross.off"), "cross");
}

TEST(MinkowskiOracle, NonConvexPlusNonConvex) {
  // both operands non-convex: the triangle-pair route against Nef's convex decomposition
  const Mesh l = l_shape();
  const Mesh small_l =
      transformed(l, Transformation(FT(1) / 5, 0, 0, 0, FT(1) / 7, 0, 0, 0, FT(1) / 3));
  const Mesh ours = minkowski_sum(check_solid(l), check_solid(small_l));
  const MeshReport report = check_mesh(ours);
  EXPECT_TRUE(report.valid_solid()) << describe_problems(report);
  EXPECT_EQ(report.volume, cgal_minkowski_volume(l, small_l));
}

// SPDX-License-Identifier: GPL-3.0-or-later
// Solids (morphex/solid.h): made only by the check and the exact operations, valid by type.
#include <gtest/gtest.h>

#include "morphex/boolean.h"
#include "morphex/check.h"
#include "morphex/shapes.h"
#include "morphex/solid.h"

using namespace morphex;

TEST(Solid, TheCheckRefusesWhatIsNotAValidSolidNamingIt) {
  Mesh open = make_cube(FT(1));
  open.triangles.pop_back();
  try {
    check_solid(open, "lid.off");
    ADD_FAILURE() << "an open mesh became a Solid";
  } catch (const InvalidSolid& e) {
    EXPECT_EQ(e.where(), "lid.off");
    EXPECT_EQ(e.problem().rfind("mesh is not closed: 3 border edges", 0), 0u) << e.what();
    const InputError& input = e;  // exit code 2 on the command line, ValueError in Python
    EXPECT_STREQ(input.what(), e.what());
  }
  const Solid cube = check_solid(make_cube(FT(1)), "cube");
  EXPECT_EQ(cube.num_triangles(), 12u);
  EXPECT_EQ(signed_volume(cube), FT(8));  // a Solid is a const Mesh& to every reader
}

TEST(Solid, TheEmptySolidIsValidAndNeutralForUnion) {
  const Solid empty;
  EXPECT_TRUE(empty.empty());
  EXPECT_TRUE(check_mesh(empty).valid_solid());
  const Solid cube = check_solid(make_cube(FT(1)));
  EXPECT_EQ(signed_volume(compute_boolean(cube, empty, BooleanOp::Union).solid), FT(8));
  EXPECT_TRUE(compute_boolean(cube, empty, BooleanOp::Intersection).solid.empty());
}

TEST(Solid, CopiesShareTheirMeshAndResultsAreSolidsAgain) {
  const Solid a = check_solid(make_cube(FT(1)));
  const Solid copy = a;  // NOLINT: the copy is the point
  EXPECT_EQ(&copy.mesh(), &a.mesh());
  // A chain: each result feeds the next operation without a check, and stays valid.
  Solid current = a;
  for (int i = 1; i <= 3; ++i) {
    const Solid moved = transformed(
        a, Kernel::Aff_transformation_3(CGAL::TRANSLATION, Kernel::Vector_3(FT(i) / 2, 0, 0)));
    current = compute_boolean(current, moved, BooleanOp::Union).solid;
    const MeshReport report = check_mesh(current);
    ASSERT_TRUE(report.valid_solid()) << describe_problems(report);
    EXPECT_EQ(report.volume, FT(8) + FT(2 * i));  // each step adds a 1/2 x 2 x 2 slab
  }
}

TEST(Solid, MotionsKeepItValidAndReflectionsOutward) {
  const Solid box = check_solid(make_box(Point(0, 0, 0), Point(1, 2, 3)));
  const Kernel::Aff_transformation_3 mirror(-1, 0, 0, 0, 1, 0, 0, 0, 1);
  const Solid mirrored = transformed(box, mirror);
  const MeshReport report = check_mesh(mirrored);
  EXPECT_TRUE(report.valid_solid()) << describe_problems(report);
  EXPECT_EQ(report.volume, FT(6));  // outward: positive volume
  const Kernel::Aff_transformation_3 flat(1, 0, 0, 0, 1, 0, 0, 0, 0);
  EXPECT_THROW(transformed(box, flat), InputError);
}

TEST(Solid, BothOperandsAreCheckedAtOnceAndTheFirstInvalidNamed) {
  Mesh inward = make_cube(FT(1));
  for (Triangle& t : inward.triangles) std::swap(t[1], t[2]);
  try {
    check_solids(make_cube(FT(1)), "A", inward, "B");
    ADD_FAILURE() << "an inward mesh became a Solid";
  } catch (const InvalidSolid& e) {
    EXPECT_EQ(e.where(), "B");
  }
  const auto [a, b] = check_solids(make_cube(FT(1)), "A", make_cube(FT(1), Point(1, 1, 1)), "B");
  EXPECT_EQ(signed_volume(compute_boolean(a, b, BooleanOp::Intersection).solid), FT(1));
}

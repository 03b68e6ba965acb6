// SPDX-License-Identifier: GPL-3.0-or-later
// Descriptors and retrieval: metrics on a hand-checked example, .cla parsing, scale invariance and
// the documented rotation behaviour of the granulometry, the procedural collection.
#include <gtest/gtest.h>

#include <cmath>

#include "morphex/boolean.h"
#include "morphex/check.h"
#include "morphex/collection.h"
#include "morphex/descriptors.h"
#include "morphex/generators.h"
#include "morphex/retrieval.h"

using namespace morphex;

namespace {

Mesh l_shape() {
  return compute_boolean(make_box(Point(0, 0, 0), Point(2, FT(1) / 2, FT(1) / 2)),
                         make_box(Point(0, 0, 0), Point(FT(1) / 2, 3, FT(1) / 2)), BooleanOp::Union)
      .mesh;
}

DescriptorSettings quick() {
  DescriptorSettings s;
  s.radii = {0.1, 0.3};
  s.closings = false;
  s.d2_samples = 512;
  return s;
}

}  // namespace

TEST(Retrieval, ScoresOfAHandCheckedExample) {
  // a1, a2 in class A; b1, b2 in class B. Rankings (nearest first):
  //   a1: b1 a2 b2   a2: b1 a1 b2   b1: a2 a1 b2   b2: b1 a1 a2
  const std::vector<std::string> names = {"a1", "a2", "b1", "b2"}, classes = {"A", "A", "B", "B"};
  const std::vector<std::vector<double>> d = {
      {0, 1, 0.7, 3}, {1, 0, 0.5, 4}, {0.7, 0.5, 0, 1}, {3, 4, 1, 0}};
  const RetrievalScores s = evaluate_retrieval(names, classes, d);
  EXPECT_EQ(s.queries, 4u);
  EXPECT_DOUBLE_EQ(s.nearest_neighbor, 0.25);  // only b2 finds its class first
  EXPECT_DOUBLE_EQ(s.first_tier, 0.25);
  EXPECT_DOUBLE_EQ(s.second_tier, 0.75);                  // b1's class mate is third
  EXPECT_DOUBLE_EQ(s.e_measure, 0.5);                     // 3 results, 1 relevant: P = 1/3, R = 1
  EXPECT_DOUBLE_EQ(s.dcg, (3 + 1 / std::log2(3.0)) / 4);  // ranks 2 count fully, rank 3 by 1/log2 3
}

TEST(Retrieval, ClaFilesAreParsedAndCheckedWithLineNumbers) {
  const auto labels = parse_cla("PSB 1\n2 3\n\nA 0 2\nx\ny\n\nB 0 1\nz\n", "l.cla");
  EXPECT_EQ(labels.size(), 3u);
  EXPECT_EQ(labels.at("y"), "A");
  EXPECT_EQ(labels.at("z"), "B");
  try {
    parse_cla("PSB 1\n1 3\nA 0 2\nx\ny\n", "l.cla");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "l.cla: line 5: the header announces 3 models, the classes list 2");
  }
  EXPECT_THROW(parse_cla("OFF\n", "l.cla"), InputError);
}

TEST(Descriptors, ScaledCopyHasTheSameGranulometry) {
  const Mesh a = l_shape();
  const Mesh b = transformed(a, Transformation(CGAL::SCALING, FT(5) / 2));
  const Descriptors da = describe(a, quick()), db = describe(b, quick());
  ASSERT_EQ(da.granulometry.size(), 2u);
  EXPECT_NEAR(db.scale_length / da.scale_length, 2.5, 1e-12);
  for (std::size_t i = 0; i < 2; ++i) EXPECT_NEAR(da.granulometry[i], db.granulometry[i], 1e-9);
  EXPECT_LT(da.granulometry[1], da.granulometry[0]);  // growing cubes remove more
  EXPECT_LT(da.granulometry[1], 0.9);
  EXPECT_LT(l1_distance(da.d2, db.d2), 1e-9);  // same samples, distances divided by their mean
}

TEST(Descriptors, PoseNormalisationMakesRotatedCopiesAgree) {
  const Mesh a = l_shape();
  const Mesh turned = transformed(a, quaternion_rotation(3, 1, -2, 5));
  const Descriptors da = describe(a, quick()), dt = describe(turned, quick());
  for (std::size_t i = 0; i < 2; ++i) EXPECT_NEAR(da.granulometry[i], dt.granulometry[i], 1e-3);
  // Documented: without pose normalisation the cube SE sees the rotation.
  DescriptorSettings raw = quick();
  raw.normalise_pose = false;
  const Descriptors ra = describe(a, raw), rt = describe(turned, raw);
  EXPECT_GT(l1_distance(ra.granulometry, rt.granulometry), 1e-3);
}

TEST(Descriptors, InvalidInputIsRefused) {
  Mesh open = make_cube(FT(1));
  open.triangles.pop_back();
  EXPECT_THROW(describe(open), std::invalid_argument);
}

TEST(Collection, EveryShapeIsAValidSolidWithItsLabel) {
  const auto meshes = make_collection(2, 7);
  ASSERT_EQ(meshes.size(), 2 * collection_families().size());
  for (const LabelledMesh& m : meshes) {
    const MeshReport r = check_mesh(m.mesh);
    EXPECT_TRUE(r.valid_solid()) << m.name << ": " << describe_problems(r);
    EXPECT_EQ(m.name.rfind(m.label + "-", 0), 0u);
    EXPECT_EQ(r.genus, m.label == "frame" ? 1 : 0) << m.name;
  }
  EXPECT_EQ(to_cla(meshes).rfind("PSB 1\n6 12\n", 0), 0u);
  // deterministic for a seed
  EXPECT_EQ(signed_volume(make_collection(1, 7)[0].mesh), signed_volume(meshes[0].mesh));
}

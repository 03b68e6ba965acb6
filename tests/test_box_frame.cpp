// SPDX-License-Identifier: GPL-3.0-or-later
// The axes the check and the Boolean box a turned part along (box_frame.h): taken for turned CAD
// parts only, sound (every point of a triangle lies in its box in the frame), and never a change
// of verdict: the pairs found on a turned part are the pairs found on the part itself.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "exact/point_table.h"
#include "morphex/boolean.h"
#include "morphex/check.h"
#include "morphex/internal/fixtures.h"
#include "tree/box_frame.h"

using namespace morphex;

namespace {

detail::BoxFrame frame_of(const Mesh& m) {
  const detail::PointTable table(m, m, true);
  return detail::choose_box_frame(m, table.input_near_doubles());
}

// Two long thin cylinders crossing each other, side by side: their side strips meet along lines.
Mesh crossing_tubes() {
  const Mesh tube = make_cylinder(96, 0.05, 1.0);
  return concatenate(tube, translated(tube, Vector(FT(3) / 100, 0, 0)));
}

const Transformation kTurn = quaternion_rotation(1, 2, 3, 5);

}  // namespace

TEST(BoxFrame, TurnedCadPartsAreBoxedAlongTheirOwnAxes) {
  for (const Mesh& part : {make_cylinder(96, 0.05, 1.0), make_fan_prism(64, 1.0, 3.0)}) {
    EXPECT_TRUE(frame_of(part).world);  // already along the axes
    const detail::BoxFrame turned = frame_of(transformed(part, kTurn));
    ASSERT_FALSE(turned.world);
    // The part's axis (z, turned) is one of the frame's axes.
    const Vector axis = kTurn(Vector(0, 0, 1));
    const double z[3] = {CGAL::to_double(axis.x()), CGAL::to_double(axis.y()),
                         CGAL::to_double(axis.z())};
    double best = 0;
    for (const auto& a : turned.axis)
      best = std::max(best, std::fabs(a[0] * z[0] + a[1] * z[1] + a[2] * z[2]));
    EXPECT_GT(best, 0.999);
  }
  // A round surface has no axes to find: any frame boxes it alike.
  EXPECT_TRUE(frame_of(transformed(make_icosphere(4, FT(1)), kTurn)).world);
}

TEST(BoxFrame, BoxesHoldEveryPointOfTheirTriangles) {
  const Mesh m = transformed(crossing_tubes(), kTurn);
  const detail::PointTable table(m, m, true);
  const detail::BoxFrame frame = detail::choose_box_frame(m, table.input_near_doubles());
  ASSERT_FALSE(frame.world);
  std::mt19937 random(5);
  std::uniform_int_distribution<int> weight(0, 16);
  for (std::uint32_t t = 0; t < m.num_triangles(); t += 7) {
    FloatBox box;
    {
      const detail::UpwardRounding rounding;
      for (const VertexIndex v : m.triangles[t])
        box += detail::box_in_frame(frame, table.approx(v));
    }
    // An exact point of the triangle, and its exact image along the frame's axes.
    const int w[3] = {weight(random), weight(random), weight(random) + 1};
    const FT total = w[0] + w[1] + w[2];
    FT x[3] = {0, 0, 0};
    for (int k = 0; k < 3; ++k) {
      const Point& p = m.points[m.triangles[t][k]];
      for (int c = 0; c < 3; ++c) x[c] += p.cartesian(c) * w[k] / total;
    }
    for (int k = 0; k < 3; ++k) {
      const FT image = x[0] * frame.axis[k][0] + x[1] * frame.axis[k][1] + x[2] * frame.axis[k][2];
      EXPECT_LE(FT(box.lo[k]), image) << "triangle " << t;
      EXPECT_GE(FT(box.hi[k]), image) << "triangle " << t;
    }
  }
  // A box's image holds the images of its corners.
  const CGAL::Bbox_3 b(-0.3, 0.1, 0.2, 0.7, 0.15, 0.9);
  FloatBox image;
  {
    const detail::UpwardRounding rounding;
    image = detail::box_in_frame(frame, b);
  }
  for (int corner = 0; corner < 8; ++corner) {
    const double c[3] = {corner & 1 ? b.xmax() : b.xmin(), corner & 2 ? b.ymax() : b.ymin(),
                         corner & 4 ? b.zmax() : b.zmin()};
    for (int k = 0; k < 3; ++k) {
      const FT at =
          FT(c[0]) * frame.axis[k][0] + FT(c[1]) * frame.axis[k][1] + FT(c[2]) * frame.axis[k][2];
      EXPECT_LE(FT(image.lo[k]), at);
      EXPECT_GE(FT(image.hi[k]), at);
    }
  }
}

// The check boxes the turned tubes along their own axes, and finds the pairs it finds on them
// unturned (where it boxes along the coordinate axes): the frame changes the speed only.
TEST(BoxFrame, TheCheckFindsThePairsOfTheUnturnedPart) {
  const Mesh part = crossing_tubes(), turned = transformed(part, kTurn);
  ASSERT_TRUE(frame_of(part).world);
  ASSERT_FALSE(frame_of(turned).world);
  CheckOptions list = kValidityOnly;
  list.list_self_intersections = true;
  const MeshReport before = check_mesh(part, list), after = check_mesh(turned, list);
  EXPECT_GT(before.self_intersections, 100u);
  EXPECT_EQ(after.self_intersections, before.self_intersections);
  EXPECT_EQ(after.self_intersecting_pairs, before.self_intersecting_pairs);
}

// Parallel thin tubes 0.2 apart along x, in a row centred on the z axis.
Mesh tubes(int count) {
  const Mesh tube = make_cylinder(12, 0.05, 1.0);
  Mesh row = translated(tube, Vector(-FT(count - 1) / 10, 0, 0));
  for (int i = 1; i < count; ++i)
    row = concatenate(row, translated(tube, Vector(FT(2 * i - (count - 1)) / 10, 0, 0)));
  return row;
}

// A row of parallel thin tubes and one crossing them all at an angle, turned: each operand's
// check boxes it along its own axes (and keeps no tree: caps of 12 triangles are no patches),
// and the Boolean pairs them along the axes of one of them, by two trees (3 tubes against one)
// or by queries of the larger operand's boxes in the smaller's tree (9 against one). The results
// are exact (the volume identity) and valid solids.
TEST(BoxFrame, BooleansOfTurnedPartsAreExact) {
  const Mesh b = transformed(
      transformed(make_cylinder(12, 0.05, 1.0), half_tangent_rotation(1, FT(1) / 2)), kTurn);
  ASSERT_FALSE(frame_of(b).world);
  for (const int count : {3, 9}) {
    const Mesh a = transformed(tubes(count), kTurn);
    ASSERT_GT(a.num_triangles() * b.num_triangles(), 4096u);  // step 2 by trees
    ASSERT_FALSE(frame_of(a).world);
    const detail::PointTable both(a, b);
    const auto& xyz = both.input_near_doubles();
    ASSERT_FALSE(detail::choose_box_frame(a, xyz.data(), b, xyz.data() + both.vertex(1, 0)).world);
    FT volume[2];
    for (const BooleanOp op : {BooleanOp::Union, BooleanOp::Intersection}) {
      const BooleanResult r = compute_boolean(check_solid(a), check_solid(b), op);
      EXPECT_TRUE(check_mesh(r.solid, kValidityOnly).valid_solid()) << count;
      volume[op == BooleanOp::Union ? 0 : 1] = signed_volume(r.solid);
    }
    EXPECT_GT(volume[1], 0);
    EXPECT_EQ(volume[0] + volume[1], signed_volume(a) + signed_volume(b)) << count;
  }
}

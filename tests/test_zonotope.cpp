// SPDX-License-Identifier: GPL-3.0-or-later
// Zonotope structuring elements: recognised exactly from their meshes (and nothing else is), the
// round zonoball's shape, and morphology by one sweep per generator giving the convolution's
// solid exactly.
#include <gtest/gtest.h>

#include <algorithm>

#include "minkowski_internal.h"
#include "morph_test_support.h"
#include "morphex/boolean.h"
#include "morphex/check.h"
#include "morphex/convex_hull.h"
#include "morphex/morphology.h"
#include "morphex/shapes.h"
#include "morphex/structuring_element.h"

using namespace morphex;

using morphex::test_support::valid_volume;
using morphex::test_support::volume_outside;

namespace {

// Generators equal up to order and sign.
bool same_generators(std::vector<Vector> a, std::vector<Vector> b) {
  if (a.size() != b.size()) return false;
  for (const Vector& g : a) {
    const auto match =
        std::find_if(b.begin(), b.end(), [&](const Vector& h) { return h == g || h == -g; });
    if (match == b.end()) return false;
    b.erase(match);
  }
  return true;
}

const Vector kBodyDiagonals[] = {Vector(1, 1, 1), Vector(1, 1, -1), Vector(1, -1, 1),
                                 Vector(-1, 1, 1)};

}  // namespace

// Boxes, a rhombic dodecahedron (four body diagonals), a sheared off-centre parallelepiped and a
// zonohedron of seven generators with rational lengths, three of them coplanar: each mesh gives
// back its centre and generators.
TEST(Zonotope, RecognisedExactlyFromItsMesh) {
  const std::vector<std::pair<Point, std::vector<Vector>>> cases = {
      {Point(0, 0, 0), {Vector(1, 0, 0), Vector(0, 2, 0), Vector(0, 0, FT(1) / 3)}},
      {Point(0, 0, 0),
       {kBodyDiagonals[0], kBodyDiagonals[1], kBodyDiagonals[2], kBodyDiagonals[3]}},
      {Point(5, -FT(1) / 7, 2), {Vector(1, FT(1) / 3, 0), Vector(0, 1, 2), Vector(-1, 1, 1)}},
      {Point(FT(1) / 2, 0, 0),
       {Vector(1, 0, 0), Vector(0, 1, 0), Vector(1, 1, 0), Vector(0, 0, FT(3) / 5), Vector(1, 2, 3),
        Vector(-2, 1, FT(1) / 2), Vector(FT(1) / 9, -1, 1)}}};
  for (const auto& [centre, halves] : cases) {
    SCOPED_TRACE(std::to_string(halves.size()) + " generators");
    const Mesh z = detail::zonotope_mesh(centre, halves);
    valid_volume(z, "zonotope");
    const auto found = detail::zonotope_of(z);
    ASSERT_TRUE(found.has_value());
    EXPECT_EQ(found->centre, centre);
    EXPECT_TRUE(same_generators(found->halves, halves));
  }
  // A box's generators come along x, y, z in that order (the sweeps' order for boxes).
  const auto box = detail::zonotope_of(make_box(Point(0, 0, 0), Point(4, 3, 2)));
  ASSERT_TRUE(box.has_value());
  EXPECT_EQ(box->centre, Point(2, FT(3) / 2, 1));
  EXPECT_EQ(box->halves,
            (std::vector<Vector>{Vector(2, 0, 0), Vector(0, FT(3) / 2, 0), Vector(0, 0, 1)}));
}

// A cylinder with an even number of segments is a prism over a centrally symmetric polygon: a
// zonotope of one generator per pair of opposite polygon edges and one along its axis, centred at
// its reference point. The generators are the polygon's own edges halved and the half height.
TEST(Zonotope, EvenCylindersAreZonotopes) {
  for (const int segments : {4, 12, 16, 64}) {
    SCOPED_TRACE(std::to_string(segments) + " segments");
    const StructuringElement se = parse_structuring_element(
        "cylinder:r=1/3,h=1/5,segments=" + std::to_string(segments) + ",ox=1/2");
    const auto z = detail::zonotope_of(se.mesh);
    ASSERT_TRUE(z.has_value());
    EXPECT_EQ(z->halves.size(), std::size_t(segments / 2 + 1));
    EXPECT_EQ(z->centre, Point(FT(1) / 2, 0, 0));
    EXPECT_EQ(std::count(z->halves.begin(), z->halves.end(), Vector(0, 0, FT(1) / 10)) +
                  std::count(z->halves.begin(), z->halves.end(), Vector(0, 0, -FT(1) / 10)),
              1);
    EXPECT_EQ(valid_volume(detail::zonotope_mesh(z->centre, z->halves), "rebuilt"),
              valid_volume(se.mesh, "cylinder"));
  }
}

// Polytopes that are not zonotopes, some close to one, take the convolution.
TEST(Zonotope, OtherPolytopesAreNotRecognised) {
  std::vector<Point> cut_corner;  // a cube with one corner cut off
  for (const Point& p : make_cube(FT(1)).points)
    if (p != Point(1, 1, 1)) cut_corner.push_back(p);
  for (const Point& p : {Point(FT(1) / 2, 1, 1), Point(1, FT(1) / 2, 1), Point(1, 1, FT(1) / 2)})
    cut_corner.push_back(p);
  std::vector<Point> prism;  // a triangular prism
  for (const FT z : {FT(0), FT(1)})
    for (const Point& p : {Point(0, 0, z), Point(1, 0, z), Point(0, 1, z)}) prism.emplace_back(p);
  // A rhombic dodecahedron with one vertex pushed out along its own direction.
  Mesh pushed = detail::zonotope_mesh(Point(CGAL::ORIGIN), {kBodyDiagonals[0], kBodyDiagonals[1],
                                                            kBodyDiagonals[2], kBodyDiagonals[3]});
  for (Point& p : pushed.points)
    if (p == Point(4, 0, 0)) p = Point(FT(41) / 10, 0, 0);
  const std::vector<std::pair<std::string, Mesh>> others = {
      {"octahedron", parse_structuring_element("octahedron:r=1").mesh},
      {"ball level 0", parse_structuring_element("ball:r=1,level=0").mesh},
      {"ball level 1", parse_structuring_element("ball:r=1,level=1").mesh},
      {"cylinder, 15 segments", parse_structuring_element("cylinder:r=1,h=1,segments=15").mesh},
      {"cylinder, 3 segments", parse_structuring_element("cylinder:r=1,h=1,segments=3").mesh},
      {"cut corner", convex_hull(cut_corner)},
      {"triangular prism", convex_hull(prism)},
      {"pushed vertex", convex_hull(pushed.points)}};
  for (const auto& [name, mesh] : others) {
    SCOPED_TRACE(name);
    valid_volume(mesh, name);
    EXPECT_FALSE(detail::zonotope_of(mesh).has_value());
  }
}

// The zonoball: a zonotope of 7 or 13 generators, convex and valid, its farthest vertices on or
// just outside the sphere of radius r, and round: every face plane at least 0.81 r (level 0) or
// 0.91 r (level 1) from the centre.
TEST(Zonotope, ZonoballIsRoundAndOnOrOutsideItsSphere) {
  const FT r = FT(1) / 20;
  for (const int level : {0, 1}) {
    SCOPED_TRACE("level " + std::to_string(level));
    const StructuringElement se =
        parse_structuring_element("zonoball:r=1/20,level=" + std::to_string(level));
    EXPECT_TRUE(se.convex);
    valid_volume(se.mesh, "zonoball");
    const auto z = detail::zonotope_of(se.mesh);
    ASSERT_TRUE(z.has_value());
    EXPECT_EQ(z->halves.size(), level == 0 ? 7u : 13u);
    EXPECT_EQ(z->centre, Point(CGAL::ORIGIN));
    FT far2 = 0;
    for (const Point& p : se.mesh.points)
      far2 = CGAL::max(far2, (p - CGAL::ORIGIN).squared_length());
    EXPECT_GE(far2, r * r);
    EXPECT_LT(CGAL::to_double(far2), CGAL::to_double(r * r) * (1 + 1e-12));
    const FT in = level == 0 ? FT(81) / 100 : FT(91) / 100;
    for (const Triangle& t : se.mesh.triangles) {
      const Kernel::Plane_3 plane(se.mesh.points[t[0]], se.mesh.points[t[1]], se.mesh.points[t[2]]);
      const FT d2 = CGAL::squared_distance(Point(CGAL::ORIGIN), plane);
      EXPECT_GE(d2, in * in * r * r);
    }
  }
  EXPECT_THROW(parse_structuring_element("zonoball:r=1,level=2"), StructuringElementError);
}

// Dilations and erosions by zonotopes as sweeps equal the convolution's solid (its pieces closed
// by the automatic route), exactly: on a torus under a rational rotation (no facet parallel to a
// generator), a sphere dented by a cube (facets parallel to the axes' generators) and an L-shape
// (edges parallel to generators, facets parallel to the sweeps), by the round zonoball and an
// off-centre sheared parallelepiped.
TEST(Zonotope, SweepsGiveTheConvolutionsSolid) {
  const Mesh dented = compute_boolean(check_solid(make_icosphere(1, FT(1))),
                                      check_solid(make_cube(FT(1) / 2)), BooleanOp::Difference)
                          .solid;
  const Mesh l_shape =
      compute_boolean(check_solid(make_box(Point(0, 0, 0), Point(2, 1, 1))),
                      check_solid(make_box(Point(0, 0, 0), Point(1, 2, 1))), BooleanOp::Union)
          .solid;
  const std::vector<std::pair<std::string, Mesh>> inputs = {
      {"tilted torus", transformed(make_torus(8, 6, 1.0, 0.4), quaternion_rotation(3, 1, 2, 1))},
      {"dented", dented},
      {"L-shape", l_shape}};
  const std::vector<std::pair<std::string, Mesh>> elements = {
      {"zonoball", parse_structuring_element("zonoball:r=1/6,level=0").mesh},
      {"cylinder", parse_structuring_element("cylinder:r=1/6,h=1/4,segments=8,oz=1/16").mesh},
      {"parallelepiped",
       detail::zonotope_mesh(Point(FT(1) / 10, 0, -FT(1) / 20),
                             {Vector(FT(1) / 8, 0, 0), Vector(FT(1) / 16, FT(1) / 7, 0),
                              Vector(0, FT(1) / 20, FT(1) / 9)})}};
  for (const auto& [se_name, b] : elements) {
    const auto z = detail::zonotope_of(b);
    ASSERT_TRUE(z.has_value());
    for (const auto& [name, a] : inputs) {
      for (const bool erode : {false, true}) {
        SCOPED_TRACE(name + (erode ? " eroded by " : " dilated by ") + se_name);
        const Mesh swept = detail::zonotope_morphology(a, *z, erode);
        const Mesh surface = erode ? reversed(a) : a;
        const Mesh element = erode ? reflected(b) : b;
        const Point c = detail::interior_point(element);
        const auto convolved =
            detail::convolution_union(surface, element, c, translated(a, c - CGAL::ORIGIN), erode,
                                      detail::PieceRoute::Automatic, nullptr);
        ASSERT_TRUE(convolved.has_value());
        const FT volume = valid_volume(swept, "swept");
        EXPECT_GT(volume, 0);
        EXPECT_EQ(volume, valid_volume(*convolved, "convolved"));
        EXPECT_EQ(volume_outside(swept, *convolved), 0);
        EXPECT_EQ(volume_outside(*convolved, swept), 0);
      }
    }
  }
}

// The public operations take the sweeps for a zonoball: an opening lies inside the input, a
// closing contains it, and both are idempotent, exactly.
TEST(Zonotope, OpeningAndClosingByAZonoballAreIdempotent) {
  const Mesh a =
      compute_boolean(check_solid(make_box(Point(0, 0, 0), Point(2, 1, 1))),
                      check_solid(make_box(Point(0, 0, 0), Point(1, 2, 1))), BooleanOp::Union)
          .solid;
  const StructuringElement se = parse_structuring_element("zonoball:r=1/3,level=1");
  const Mesh opened = opening(check_solid(a), se), closed = closing(check_solid(a), se);
  const FT v_open = valid_volume(opened, "opening"), v_close = valid_volume(closed, "closing");
  EXPECT_EQ(volume_outside(opened, a), 0);
  EXPECT_EQ(volume_outside(a, closed), 0);
  EXPECT_LT(v_open, signed_volume(a));
  EXPECT_GT(v_close, signed_volume(a));
  EXPECT_EQ(valid_volume(opening(check_solid(opened), se), "open twice"), v_open);
  EXPECT_EQ(valid_volume(closing(check_solid(closed), se), "close twice"), v_close);
}

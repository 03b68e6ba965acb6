// SPDX-License-Identifier: GPL-3.0-or-later
// libmorph: structuring elements, exact closed forms of Minkowski sums, and the morphological laws
// as exact volume identities. Every result is checked to be a valid solid.
#include <gtest/gtest.h>

#include <algorithm>

#include "minkowski_internal.h"
#include "morph_test_support.h"
#include "morphex/boolean.h"
#include "morphex/check.h"
#include "morphex/minkowski.h"
#include "morphex/morphology.h"
#include "morphex/shapes.h"
#include "morphex/structuring_element.h"

using namespace morphex;

using morphex::test_support::valid_volume;
using morphex::test_support::volume_outside;

namespace {

Mesh l_shape() {
  const BooleanResult r =
      compute_boolean(check_solid(make_box(Point(0, 0, 0), Point(2, 1, 1))),
                      check_solid(make_box(Point(0, 0, 0), Point(1, 2, 1))), BooleanOp::Union);
  return r.solid;
}

std::string error_of(const std::string& spec) {
  try {
    parse_structuring_element(spec);
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(StructuringElement, ShapesHaveTheirExactVolumes) {
  EXPECT_EQ(valid_volume(parse_structuring_element("cube:r=1/2").mesh, "cube"), FT(1));
  EXPECT_EQ(valid_volume(parse_structuring_element("box:x=1,y=2,z=3").mesh, "box"), FT(48));
  EXPECT_EQ(valid_volume(parse_structuring_element("octahedron:r=3").mesh, "octahedron"), FT(36));
  const StructuringElement moved = parse_structuring_element("cube:r=1,ox=5,oy=-1/2");
  EXPECT_EQ(check_mesh(moved.mesh).bbox.xmin(), 4.0);
  EXPECT_EQ(check_mesh(moved.mesh).bbox.ymax(), 0.5);
  EXPECT_EQ(moved.spec, "cube:r=1,ox=5,oy=-1/2");
}

TEST(StructuringElement, BallVerticesAreOnOrOutsideTheSphere) {
  for (int level = 0; level <= 2; ++level) {
    const StructuringElement ball =
        parse_structuring_element("ball:r=1/20,level=" + std::to_string(level));
    EXPECT_TRUE(ball.convex);
    EXPECT_EQ(ball.mesh.points.size(), 10u * (1u << (2 * level)) + 2u);
    EXPECT_EQ(ball.mesh.triangles.size(), 20u * (1u << (2 * level)));
    valid_volume(ball.mesh, "ball");
    for (const Point& p : ball.mesh.points) {
      const FT d2 = (p - CGAL::ORIGIN).squared_length();
      EXPECT_GE(d2, FT(1) / 400);
      EXPECT_LT(CGAL::to_double(d2), 1.0 / 400 * (1 + 1e-12));
    }
  }
  const StructuringElement cylinder = parse_structuring_element("cylinder:r=1,h=2,segments=12");
  EXPECT_EQ(cylinder.mesh.points.size(), 24u);
  EXPECT_TRUE(cylinder.convex);
  EXPECT_NEAR(CGAL::to_double(valid_volume(cylinder.mesh, "cylinder")), 6.0, 1e-9);  // 12 sin 30
}

TEST(StructuringElement, MeshFromFileKeepsItsCoordinatesAndConvexity) {
  const StructuringElement cube =
      parse_structuring_element(std::string("mesh:path=") + MORPHEX_TEST_DATA_DIR "/unit_cube.off");
  EXPECT_TRUE(cube.convex);
  EXPECT_EQ(valid_volume(cube.mesh, "mesh SE"), FT(1));
  EXPECT_FALSE(is_convex(l_shape()));
}

TEST(StructuringElement, BadSpecificationsAreClearErrors) {
  EXPECT_EQ(error_of("sphere:r=1"),
            "unknown structuring element shape 'sphere' (did you mean 'ball'? expected cube, "
            "box, octahedron, ball, zonoball, cylinder or mesh)");
  EXPECT_EQ(error_of("cub:r=1"),
            "unknown structuring element shape 'cub' (did you mean 'cube'? expected cube, "
            "box, octahedron, ball, zonoball, cylinder or mesh)");
  EXPECT_EQ(error_of("xyzzy:r=1"),
            "unknown structuring element shape 'xyzzy' (expected cube, box, octahedron, ball, "
            "zonoball, cylinder or mesh)");
  EXPECT_EQ(error_of("ball:radius=1"),
            "ball: radius: unknown parameter (ball takes r, level, ox, oy, oz)");
  EXPECT_EQ(error_of("cube"), "cube: r: missing (required)");
  EXPECT_EQ(error_of("cube:r=-1"), "cube: r: expected a positive number, got -1");
  EXPECT_EQ(error_of("cube:r=abc"), "cube: r: expected a number, got abc");
  EXPECT_EQ(error_of("ball:r=1,level=9"), "ball: level: expected an integer from 0 to 5, got 9");
  EXPECT_EQ(error_of("cube:r=1,r=2"), "cube: r: given twice");
  EXPECT_EQ(error_of("cube:r"), "structuring element 'cube:r': expected key=value, got 'r'");
  EXPECT_NE(error_of("mesh:path=" MORPHEX_TEST_DATA_DIR "/open_cube.off").find("not a valid solid"),
            std::string::npos);
}

TEST(Minkowski, BoxPlusBoxIsTheBoxWithSummedHalfSizes) {
  const Mesh a = make_box(Point(-1, -2, -3), Point(1, 2, 3));
  const StructuringElement b = parse_structuring_element("box:x=1/2,y=1/4,z=1/8");
  const Mesh sum = minkowski_sum(check_solid(a), check_solid(b.mesh));
  const Mesh expected =
      make_box(Point(FT(-3) / 2, FT(-9) / 4, FT(-25) / 8), Point(FT(3) / 2, FT(9) / 4, FT(25) / 8));
  EXPECT_EQ(valid_volume(sum, "box + box"), valid_volume(expected, "expected"));
  EXPECT_EQ(volume_outside(sum, expected), 0);
  EXPECT_EQ(volume_outside(expected, sum), 0);
}

TEST(Minkowski, CubePlusOctahedronHasTheMixedVolumeClosedForm) {
  // [-a,a]^3 + octahedron(r): 8a^3 + 24a^2 r + 12 a r^2 + 4r^3/3 (Steiner formula, L1 ball)
  const FT a = FT(1) / 2, r = FT(1) / 3;
  const Mesh sum = minkowski_sum(check_solid(make_cube(a)), check_solid(make_octahedron(r)));
  EXPECT_EQ(valid_volume(sum, "cube + octahedron"),
            8 * a * a * a + 24 * a * a * r + 12 * a * r * r + 4 * r * r * r / 3);
}

TEST(Minkowski, ConvexPlusConvexIsTheHullOfTheVertexSums) {
  const Mesh a = transformed(make_icosphere(1, FT(1)), Transformation(2, 0, 0, 0, 1, 0, 0, 0, 1));
  const Mesh b = parse_structuring_element("ball:r=1/3,level=0").mesh;
  std::vector<Point> sums;
  for (const Point& p : a.points)
    for (const Point& q : b.points) sums.push_back(p + (q - CGAL::ORIGIN));
  EXPECT_EQ(valid_volume(minkowski_sum(check_solid(a), check_solid(b)), "sum"),
            signed_volume(convex_hull(sums)));
}

TEST(Minkowski, NonConvexSecondOperandMatchesTheSwappedSum) {
  // A + B = B + A: the convex route (cube second) and the pair route (L-shape second) agree.
  const Mesh l = l_shape(), cube = make_cube(FT(1) / 4);
  MinkowskiStats stats;
  const FT pairs =
      valid_volume(minkowski_sum(check_solid(cube), check_solid(l), &stats), "cube + L");
  EXPECT_EQ(pairs, valid_volume(minkowski_sum(check_solid(l), check_solid(cube)), "L + cube"));
  EXPECT_EQ(stats.pieces, cube.triangles.size() * l.triangles.size() + cube.points.size());
  // the L is two 2x1x1 boxes overlapping in a unit cube; each grows by 1/2 along every axis
  const FT arm = FT(5) / 2 * FT(3) / 2 * FT(3) / 2, overlap = FT(3) / 2 * FT(3) / 2 * FT(3) / 2;
  EXPECT_EQ(pairs, 2 * arm - overlap);
}

TEST(Minkowski, ConvexHullOfFourPointsIsAnOutwardTetrahedron) {
  const Mesh hull = convex_hull({Point(0, 0, 0), Point(1, 0, 0), Point(0, 1, 0), Point(0, 0, 1)});
  EXPECT_EQ(hull.num_triangles(), 4u);
  EXPECT_EQ(valid_volume(hull, "tetrahedron"), FT(1) / 6);
}

// A hull is written in one order whatever the order of its input points and wherever the
// allocator put the hull's working structures: convex_hull_3 numbers its output by walking handles
// that are pointers, and a dilation of the unit cube by an octahedron came out in different orders
// under glibc's malloc with and without a progress bar.
TEST(Minkowski, ConvexHullIsWrittenInOneOrder) {
  // Points on the moment curve (t, t^2, t^3): no four on a plane, so the hull's triangles are
  // unique (a cyclic polytope), and only their order and numbering are the hull's choice. With
  // four points on a plane, the diagonal of their face may depend on the input's order.
  std::vector<Point> points;
  for (int t = -12; t <= 14; ++t) points.emplace_back(t, t * t, t * t * t);
  const Mesh first = convex_hull(points);
  ASSERT_GE(first.num_triangles(), 4u);
  for (std::size_t i = 1; i < first.points.size(); ++i)
    EXPECT_EQ(CGAL::compare_xyz(first.points[i - 1], first.points[i]), CGAL::SMALLER);
  for (const Triangle& t : first.triangles) EXPECT_LT(t[0], std::min(t[1], t[2]));
  EXPECT_TRUE(std::is_sorted(first.triangles.begin(), first.triangles.end()));
  std::vector<std::vector<char>> held;  // moves the allocator's next blocks elsewhere
  for (unsigned round = 0; round < 6; ++round) {
    std::rotate(points.begin(), points.begin() + 7, points.end());
    std::reverse(points.begin() + round, points.end());
    for (int k = 0; k < 50; ++k) held.emplace_back(std::size_t(16 + 40 * k + round * 8));
    const Mesh again = convex_hull(points);
    EXPECT_EQ(again.points, first.points) << "round " << round;
    EXPECT_EQ(again.triangles, first.triangles) << "round " << round;
  }
}

// Dilation and erosion by a convex SE come from the reduced convolution's pieces (prisms on the
// facets, pieces at convex edges and at vertices where the supporting vertex of B changes). They
// must give exactly the solid of the facet-hull formula A u (U_f conv(f + B)), computed here
// independently with boundary_sum, on inputs with reflex edges and saddle vertices, normals in
// general position and parallel to B's faces, and SEs holding the origin inside or on a face.
TEST(Minkowski, ReducedConvolutionGivesTheFacetHullSolid) {
  const Mesh torus = make_torus(8, 6, 1.0, 0.4);
  const Mesh tilted_torus = transformed(torus, quaternion_rotation(3, 1, 2, 1));
  const BooleanResult dented =
      compute_boolean(check_solid(make_icosphere(1, FT(1))), check_solid(make_cube(FT(1) / 2)),
                      BooleanOp::Difference);
  const std::vector<std::pair<std::string, Mesh>> inputs = {
      {"torus", torus}, {"tilted torus", tilted_torus}, {"L", l_shape()}, {"dented", dented.solid}};
  for (const std::string spec :
       {"cube:r=1/10", "octahedron:r=1/8", "ball:r=1/10,level=0", "cube:r=1/8,oz=1/8"}) {
    const StructuringElement se = parse_structuring_element(spec);
    for (const auto& [name, a] : inputs) {
      SCOPED_TRACE(name + " by " + spec);
      const Mesh dilated = dilation(check_solid(a), se);
      const Mesh by_hulls =
          compute_union({check_solid(boundary_sum(a, se.mesh, true)), check_solid(a)});
      EXPECT_EQ(valid_volume(dilated, "dilation"), valid_volume(by_hulls, "hull dilation"));
      EXPECT_EQ(volume_outside(dilated, by_hulls), 0);
      const Mesh eroded = erosion(check_solid(a), se);
      const BooleanResult eroded_by_hulls =
          compute_boolean(check_solid(a), check_solid(boundary_sum(a, reflected(se.mesh), true)),
                          BooleanOp::Difference);
      EXPECT_EQ(valid_volume(eroded, "erosion"),
                valid_volume(eroded_by_hulls.solid, "hull erosion"));
      EXPECT_EQ(volume_outside(eroded_by_hulls.solid, eroded), 0);
    }
  }
}

// A bumpy sphere: an icosphere whose vertices are pushed along their rays by a fixed pseudo-random
// factor in [0.8, 1.2] (exact rationals; a radial perturbation of a star-shaped surface stays
// embedded). Its facets' normals turn in every direction, so the reduced convolution glues
// irregular patches, some of which overlap themselves seen along their sweep direction and are
// split (convolution_internal.h), and chains of edges of every length.
Mesh bumpy_sphere(int level) {
  Mesh m = make_icosphere(level, 1);
  std::uint32_t x = 12345;
  for (Point& p : m.points) {
    x = x * 1103515245u + 12345u;
    const FT f = FT(1) + FT(int((x >> 16) % 41) - 20) / 100;
    p = Point(p.x() * f, p.y() * f, p.z() * f);
  }
  make_exact(m);
  return m;
}

TEST(Minkowski, GluedPiecesGiveTheFacetHullSolidOnABumpySurface) {
  const Mesh a = bumpy_sphere(2);
  ASSERT_TRUE(check_mesh(a).valid_solid());
  for (const std::string spec : {"cube:r=1/10", "octahedron:r=1/6"}) {
    SCOPED_TRACE(spec);
    const StructuringElement se = parse_structuring_element(spec);
    const Mesh dilated = dilation(check_solid(a), se);
    const Mesh by_hulls =
        compute_union({check_solid(boundary_sum(a, se.mesh, true)), check_solid(a)});
    EXPECT_EQ(valid_volume(dilated, "dilation"), valid_volume(by_hulls, "hull dilation"));
    EXPECT_EQ(volume_outside(dilated, by_hulls), 0);
    const Mesh eroded = erosion(check_solid(a), se);
    const BooleanResult eroded_by_hulls =
        compute_boolean(check_solid(a), check_solid(boundary_sum(a, reflected(se.mesh), true)),
                        BooleanOp::Difference);
    EXPECT_EQ(valid_volume(eroded, "erosion"), valid_volume(eroded_by_hulls.solid, "hull erosion"));
    EXPECT_EQ(volume_outside(eroded_by_hulls.solid, eroded), 0);
  }
}

// The convolution's pieces become one solid with A + c either by one winding arrangement (when
// they overlap shallowly) or by the union tree. Both routes, forced, must give the same solid,
// for dilations and erosions, on the bumpy sphere (irregular patches, reflex edges), a torus
// under a rational rotation and the dented sphere (facets parallel to a cube's faces, which an
// octahedron's and a ball's faces meet at edges and vertices), by elements small and large beside
// the facets.
TEST(Minkowski, ArrangementAndTreeRoutesGiveTheSameSolid) {
  using detail::PieceRoute;
  const BooleanResult dented =
      compute_boolean(check_solid(make_icosphere(1, FT(1))), check_solid(make_cube(FT(1) / 2)),
                      BooleanOp::Difference);
  const std::vector<std::pair<std::string, Mesh>> inputs = {
      {"bumpy", bumpy_sphere(2)},
      {"tilted torus", transformed(make_torus(8, 6, 1.0, 0.4), quaternion_rotation(3, 1, 2, 1))},
      {"dented", dented.solid}};
  for (const std::string spec : {"octahedron:r=1/20", "ball:r=1/3,level=1", "octahedron:r=1/2"}) {
    const StructuringElement se = parse_structuring_element(spec);
    for (const auto& [name, a] : inputs) {
      SCOPED_TRACE(name + " by " + spec);
      for (const bool erode : {false, true}) {
        const Mesh surface = erode ? reversed(a) : a;
        const Mesh b = erode ? reflected(se.mesh) : se.mesh;
        const Point c = detail::interior_point(b);
        const Mesh moved = translated(a, c - CGAL::ORIGIN);
        // The arrangement; the tree on checked pieces; the automatic route made to give the
        // arrangement up at once, so that the tree runs on the chain's unchecked pieces made valid.
        Mesh results[3];
        for (int k = 0; k < 3; ++k) {
          MinkowskiStats stats;
          const PieceRoute route = k == 0   ? PieceRoute::Arrangement
                                   : k == 1 ? PieceRoute::Tree
                                            : PieceRoute::Automatic;
          const std::optional<Mesh> result =
              detail::convolution_union(surface, b, c, moved, erode, route, &stats, 1e-9);
          ASSERT_TRUE(result.has_value());
          results[k] = *result;
          EXPECT_EQ(stats.arrangements, k == 0 ? 1u : 0u);
        }
        for (int k = 1; k < 3; ++k) {
          EXPECT_EQ(valid_volume(results[0], "by the arrangement"),
                    valid_volume(results[k], "by the tree"));
          if (!results[0].empty()) {
            EXPECT_EQ(volume_outside(results[0], results[k]), 0);
            EXPECT_EQ(volume_outside(results[k], results[0]), 0);
          }
        }
      }
    }
  }
}

// A sweep along an axis where the solid folds back many layers deep may run as two half sweeps
// (S_h = S_h/2 + S_h/2), each halved again while that thins its pairs: the same solid exactly.
// Eight thin plates 1/10 apart along x, turned off the axes: dilated by a segment of length 1/5
// every plate's sheets cross its neighbours'; as cavities in a ball, eroded, the same for the
// gaps. Made to halve beyond any pair count here (while halving thins the pairs).
TEST(Minkowski, HalvedSweepsGiveTheSameSolid) {
  const Mesh plate =
      transformed(make_icosphere(2, FT(1) / 2), Transformation(FT(1) / 10, 0, 0, 0, 1, 0, 0, 0, 1));
  Mesh row;
  for (int k = 0; k < 8; ++k)
    row = concatenate(row, translated(plate, Vector(FT(k) / 5 - FT(7) / 10, 0, 0)));
  const Mesh turned = transformed(row, quaternion_rotation(9, 1, 1, 0));
  const Mesh holed = concatenate(make_icosphere(2, FT(3)), reversed(turned));
  for (const bool erode : {false, true}) {
    SCOPED_TRACE(erode ? "erosion" : "dilation");
    const detail::LabelledSolid input = detail::labelled(erode ? holed : turned);
    std::size_t whole_runs = 0, halved_runs = 0;
    const FT h = FT(1) / 10;
    const Mesh whole = detail::segment_sweep(input, Vector(h, 0, 0), erode, 0, &whole_runs).mesh;
    const Mesh halved =
        detail::segment_sweep(input, Vector(h, 0, 0), erode, 1e-9, &halved_runs).mesh;
    EXPECT_EQ(whole_runs, 1u);
    EXPECT_GT(halved_runs, 4u);
    ASSERT_FALSE(whole.empty());
    EXPECT_EQ(valid_volume(whole, "whole sweep"), valid_volume(halved, "halved sweeps"));
    EXPECT_EQ(volume_outside(whole, halved), 0);
    EXPECT_EQ(volume_outside(halved, whole), 0);
  }
}

// The automatic route takes the arrangement for an element small beside the facets and the tree
// for one much larger (the stats say which ran).
TEST(Minkowski, AutomaticRouteFollowsTheElementsSize) {
  const Solid a = check_solid(bumpy_sphere(2));
  MorphologyStats small, large;
  const Solid by_small = dilation(a, parse_structuring_element("octahedron:r=1/20"), &small);
  const Solid by_large = dilation(a, parse_structuring_element("octahedron:r=4"), &large);
  EXPECT_EQ(small.arrangements, 1u);
  EXPECT_EQ(small.binary_unions, 0u);
  EXPECT_EQ(large.arrangements, 0u);
  EXPECT_GT(large.binary_unions, 0u);
  EXPECT_GT(signed_volume(by_large), signed_volume(by_small));
}

TEST(Morphology, ErosionToNothingIsAValidEmptyMesh) {
  const Mesh small = make_cube(FT(1) / 10);
  const Mesh eroded = erosion(check_solid(small), parse_structuring_element("cube:r=1/5"));
  EXPECT_TRUE(eroded.empty());
  EXPECT_EQ(opening(check_solid(small), parse_structuring_element("octahedron:r=1"))
                .mesh()
                .triangles.size(),
            0u);
}

TEST(Morphology, ErosionOfABoxByABoxShrinksItsHalfSizes) {
  const Mesh a = make_box(Point(0, 0, 0), Point(4, 3, 2));
  const Mesh eroded = erosion(check_solid(a), parse_structuring_element("box:x=1,y=1/2,z=1/4"));
  EXPECT_EQ(valid_volume(eroded, "eroded box"), FT(2) * 2 * FT(3) / 2);
  EXPECT_EQ(volume_outside(
                eroded, make_box(Point(1, FT(1) / 2, FT(1) / 4), Point(3, FT(5) / 2, FT(7) / 4))),
            0);
}

TEST(Morphology, OpeningIsInsideAndClosingContainsTheInputAndBothAreIdempotent) {
  const Mesh a = l_shape();
  for (const char* spec : {"cube:r=1/4", "octahedron:r=1/3", "ball:r=1/4,level=0"}) {
    const StructuringElement se = parse_structuring_element(spec);
    const Mesh opened = opening(check_solid(a), se), closed = closing(check_solid(a), se);
    const FT v_open = valid_volume(opened, "opening"), v_close = valid_volume(closed, "closing");
    EXPECT_EQ(volume_outside(opened, a), 0) << spec;
    EXPECT_EQ(volume_outside(a, closed), 0) << spec;
    EXPECT_LE(v_open, signed_volume(a));
    EXPECT_GE(v_close, signed_volume(a));
    EXPECT_EQ(valid_volume(opening(check_solid(opened), se), "open twice"), v_open) << spec;
    EXPECT_EQ(valid_volume(closing(check_solid(closed), se), "close twice"), v_close) << spec;
  }
}

TEST(Morphology, DilationAndErosionAreIncreasing) {
  const Mesh small = make_box(Point(0, 0, 0), Point(2, 1, 1));
  const Mesh large = l_shape();  // contains `small`
  const StructuringElement se = parse_structuring_element("octahedron:r=1/4");
  EXPECT_EQ(volume_outside(dilation(check_solid(small), se), dilation(check_solid(large), se)), 0);
  EXPECT_EQ(volume_outside(erosion(check_solid(small), se), erosion(check_solid(large), se)), 0);
  EXPECT_GT(signed_volume(dilation(check_solid(large), se)),
            signed_volume(dilation(check_solid(small), se)));
}

TEST(Morphology, ErosionIsTheComplementOfTheDilationOfTheComplement) {
  // In a frame M far larger than A + B: A eroded by B = A minus ((M minus A) dilated by -B).
  const Mesh a = l_shape();
  const StructuringElement se = parse_structuring_element("box:x=1/4,y=1/8,z=1/8,ox=1/16");
  const Mesh frame = make_box(Point(-3, -3, -3), Point(5, 5, 5));
  const BooleanResult complement =
      compute_boolean(check_solid(frame), check_solid(a), BooleanOp::Difference);
  StructuringElement minus_se = se;
  minus_se.mesh = reflected(se.mesh);
  const Mesh grown = dilation(check_solid(complement.solid), minus_se);
  const BooleanResult dual =
      compute_boolean(check_solid(a), check_solid(grown), BooleanOp::Difference);
  const Mesh eroded = erosion(check_solid(a), se);
  EXPECT_EQ(valid_volume(dual.solid, "dual"), valid_volume(eroded, "erosion"));
  EXPECT_EQ(volume_outside(dual.solid, eroded), 0);
  EXPECT_EQ(volume_outside(eroded, dual.solid), 0);
}

TEST(Morphology, OffCentreStructuringElementTranslatesTheResult) {
  // B not containing the origin: dilation by B + t is the dilation by B moved by t.
  const Mesh a = make_cube(FT(1));
  const StructuringElement far = parse_structuring_element("cube:r=1/4,ox=3");
  const StructuringElement centred = parse_structuring_element("cube:r=1/4");
  const Mesh d_far = dilation(check_solid(a), far);
  const Mesh d_moved = translated(dilation(check_solid(a), centred), Vector(3, 0, 0));
  EXPECT_EQ(valid_volume(d_far, "off-centre dilation"), FT(125) / 8);
  EXPECT_EQ(volume_outside(d_far, d_moved), 0);
  const Mesh e_far = erosion(check_solid(a), far);
  EXPECT_EQ(valid_volume(e_far, "off-centre erosion"), FT(27) / 8);
  EXPECT_EQ(volume_outside(e_far, translated(erosion(check_solid(a), centred), Vector(-3, 0, 0))),
            0);
}

TEST(Morphology, SeveralComponentsAndGenusOne) {
  const Mesh two = concatenate(make_cube(FT(1)), translated(make_cube(FT(1)), Vector(5, 0, 0)));
  const StructuringElement se = parse_structuring_element("cube:r=1/2");
  EXPECT_EQ(valid_volume(dilation(check_solid(two), se), "two cubes dilated"), 2 * FT(27));
  EXPECT_EQ(valid_volume(erosion(check_solid(two), se), "two cubes eroded"), 2 * FT(1));
  // a square ring (genus 1) dilated until its hole closes, eroded back: the closing fills it
  const BooleanResult ring = compute_boolean(check_solid(make_box(Point(0, 0, 0), Point(3, 3, 1))),
                                             check_solid(make_box(Point(1, 1, -1), Point(2, 2, 2))),
                                             BooleanOp::Difference);
  EXPECT_EQ(check_mesh(ring.solid).genus, 1);
  const Mesh closed =
      closing(check_solid(ring.solid), parse_structuring_element("box:x=1/2,y=1/2,z=1/8"));
  EXPECT_EQ(valid_volume(closed, "closed ring"), FT(9));
  EXPECT_EQ(check_mesh(closed).genus, 0);
  const Mesh thin =
      opening(check_solid(ring.solid), parse_structuring_element("box:x=1/4,y=1/4,z=1/4"));
  EXPECT_EQ(valid_volume(thin, "opened ring"), FT(8));
}

TEST(Morphology, NonConvexStructuringElement) {
  // dilating a point-like cube by an L-shaped SE gives (about) the L: exact against the swapped sum
  const Mesh a = make_cube(FT(1) / 8);
  StructuringElement l;
  l.shape = "mesh";
  l.mesh = translated(l_shape(), Vector(-1, -1, 0));
  l.convex = false;
  const Mesh dilated = dilation(check_solid(a), l);
  EXPECT_EQ(valid_volume(dilated, "dilated by L"),
            signed_volume(minkowski_sum(check_solid(l.mesh), check_solid(a))));
  const Mesh eroded = erosion(check_solid(make_box(Point(-2, -2, -1), Point(2, 2, 2))), l);
  // {x : x + L inside [-2,2]x[-2,2]x[-1,2]}: L spans [-1,1]^2 x [0,1] -> [-1,1]^2 x [-1,1]
  EXPECT_EQ(valid_volume(eroded, "eroded by L"), FT(8));
}

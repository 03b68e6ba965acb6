// SPDX-License-Identifier: GPL-3.0-or-later
// The check's pass over vertex stars (check_stars.h) against independent computations: its edge
// counts against a map of every edge's uses, and its proofs that stars are embedded against
// CGAL's triangle predicates over every pair of triangles at the vertex.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <optional>
#include <random>
#include <set>
#include <string>

#include "check/check_stars.h"
#include "check_test_support.h"
#include "exact/point_table.h"
#include "morphex/check.h"
#include "morphex/internal/fixtures.h"
#include "morphex/internal/union_find.h"
#include "tree/box_tree.h"

using namespace morphex;

namespace {

// What the pass reports, computed from a map of each edge to its uses.
struct EdgeCounts {
  detail::ManifoldEdges manifold;
  std::size_t border = 0, non_manifold = 0, non_manifold_vertices = 0;
  std::optional<VertexIndex> first_border_vertex, first_non_manifold_vertex;
  std::optional<std::uint32_t> first_misoriented_face;
};

EdgeCounts count_by_edge_map(const Mesh& m) {
  struct Use {
    std::uint32_t face;
    bool forward;
  };
  std::map<std::pair<VertexIndex, VertexIndex>, std::vector<Use>> uses;
  for (std::uint32_t f = 0; f < m.num_triangles(); ++f)
    for (int k = 0; k < 3; ++k) {
      const VertexIndex a = m.triangles[f][k], b = m.triangles[f][(k + 1) % 3];
      uses[{std::min(a, b), std::max(a, b)}].push_back({f, a < b});
    }
  EdgeCounts c;
  // Corners joined across manifold edges: one set per fan.
  UnionFind fans(3 * m.num_triangles());
  auto corner = [&](std::uint32_t f, VertexIndex v) {
    const Triangle& t = m.triangles[f];
    return 3 * f + (t[0] == v ? 0 : t[1] == v ? 1 : 2);
  };
  for (const auto& [edge, list] : uses) {
    if (list.size() == 1) {
      ++c.border;
      if (!c.first_border_vertex) c.first_border_vertex = edge.first;
    } else if (list.size() > 2) {
      ++c.non_manifold;
    } else {
      const std::uint32_t f = std::min(list[0].face, list[1].face),
                          g = std::max(list[0].face, list[1].face);
      if (list[0].forward == list[1].forward &&
          (!c.first_misoriented_face || f < *c.first_misoriented_face))
        c.first_misoriented_face = f;
      c.manifold.push_back({(std::uint64_t(edge.first) << 32) | edge.second, {f, g}});
      for (const VertexIndex v : {edge.first, edge.second}) fans.join(corner(f, v), corner(g, v));
    }
  }
  std::map<VertexIndex, std::set<std::uint32_t>> fans_at;
  for (std::uint32_t c3 = 0; c3 < 3 * m.num_triangles(); ++c3)
    fans_at[m.triangles[c3 / 3][c3 % 3]].insert(fans.find(c3));
  for (const auto& [v, sets] : fans_at)
    if (sets.size() > 1) {
      ++c.non_manifold_vertices;
      if (!c.first_non_manifold_vertex) c.first_non_manifold_vertex = v;
    }
  return c;
}

detail::VertexStars examine(const Mesh& m) {
  const detail::PointTable table(m, m, true);
  return detail::examine_vertex_stars(m, table, true);
}

using test_support::improper_pairs_by_brute_force;
using test_support::improper_pairs_by_check;
using test_support::Pairs;

void expect_same_counts(const Mesh& m, const std::string& what) {
  const detail::VertexStars s = examine(m);
  const EdgeCounts c = count_by_edge_map(m);
  EXPECT_EQ(s.manifold, c.manifold) << what;
  EXPECT_EQ(s.border_edges, c.border) << what;
  EXPECT_EQ(s.non_manifold_edges, c.non_manifold) << what;
  EXPECT_EQ(s.non_manifold_vertices, c.non_manifold_vertices) << what;
  EXPECT_EQ(s.first_border_vertex, c.first_border_vertex) << what;
  EXPECT_EQ(s.first_non_manifold_vertex, c.first_non_manifold_vertex) << what;
  EXPECT_EQ(s.first_misoriented_face, c.first_misoriented_face) << what;
}

// Two meshes as one, b's vertex i renamed to `glue[i]` of a where given (shared indices).
Mesh glued(const Mesh& a, const Mesh& b, const std::map<VertexIndex, VertexIndex>& glue) {
  Mesh m = a;
  std::vector<VertexIndex> index(b.num_vertices());
  for (VertexIndex i = 0; i < b.num_vertices(); ++i) {
    const auto it = glue.find(i);
    if (it != glue.end()) {
      index[i] = it->second;
    } else {
      index[i] = VertexIndex(m.points.size());
      m.points.push_back(b.points[i]);
    }
  }
  for (const Triangle& t : b.triangles)
    m.triangles.push_back({index[t[0]], index[t[1]], index[t[2]]});
  return m;
}

}  // namespace

// Closed, open, misoriented, non-manifold (edges and pinched vertices) and large stars (a
// cone's apex, beyond the small-star pairing): the same counts as a map of every edge's uses.
TEST(VertexStars, EdgeCountsAgreeWithAnEdgeMap) {
  const Mesh sphere = make_icosphere(2, 1);
  expect_same_counts(sphere, "icosphere");
  expect_same_counts(make_torus(12, 8, 2, 0.5), "torus");
  expect_same_counts(make_fan_cone(100, 1, 1), "fan cone");
  expect_same_counts(make_fan_prism(70, 1, 1), "fan prism");
  const Mesh tet = make_tetrahedron();
  expect_same_counts(glued(tet, tet, {{0, 0}}), "tetrahedra pinched at a vertex");
  expect_same_counts(glued(tet, tet, {{0, 0}, {1, 1}}), "tetrahedra on one edge");
  std::mt19937 random(7);
  for (int i = 0; i < 60; ++i) {
    Mesh m = i % 2 ? sphere : make_fan_cone(40, 1, 1);
    std::uniform_int_distribution<std::uint32_t> face(0, std::uint32_t(m.num_triangles() - 1));
    for (int k = 0; k < 1 + i % 4; ++k) {
      const std::uint32_t f = face(random);
      switch ((i + k) % 4) {
        case 0:
          m.triangles.erase(m.triangles.begin() + f);
          break;  // a hole
        case 1:
          std::swap(m.triangles[f][0], m.triangles[f][1]);
          break;  // flipped
        case 2:
          m.triangles.push_back(m.triangles[f]);
          break;  // doubled: non-manifold edges
        default:
          m.triangles.push_back({m.triangles[f][0], m.triangles[f][2], VertexIndex(0)});
      }
    }
    bool repeats = false;  // the pass requires distinct corners (the check handles the rest)
    for (const Triangle& t : m.triangles) repeats |= t[0] == t[1] || t[1] == t[2] || t[0] == t[2];
    if (!repeats) expect_same_counts(m, "mutation " + std::to_string(i));
  }
}

namespace {
// An icosphere with every vertex moved at random by up to `jitter`, and `pushed` vertices moved
// by up to `push` (sideways past their neighbours: stars that fold over themselves).
Mesh jittered_sphere(std::mt19937& random, double jitter, int pushed, double push, bool rational) {
  DoubleMesh d = to_double(make_icosphere(2, 1));
  std::uniform_real_distribution<double> unit(-1, 1);
  for (auto& p : d.points)
    for (double& x : p) x += jitter * unit(random);
  std::uniform_int_distribution<std::size_t> vertex(0, d.points.size() - 1);
  for (int k = 0; k < pushed; ++k)
    for (double& x : d.points[vertex(random)]) x += push * unit(random);
  Mesh m = from_double(d);
  if (rational)  // coordinates that are not doubles: the exact path of the proof
    for (Point& p : m.points) p = Point(p.x() / 3, p.y() / 3, p.z() / 3);
  return m;
}
}  // namespace

// Every star the pass proves embedded really is: no two of its triangles meet improperly
// (CGAL's triangle predicates over every pair at the vertex). The proofs hold on nearly every
// vertex of a smooth sphere and fail where pushed vertices fold their stars; the check's list of
// improper pairs stays that of all pairs tested one by one.
TEST(VertexStars, ProvedStarsAreEmbedded) {
  std::mt19937 random(2026);
  std::size_t proved = 0, unproved = 0, folded_cases = 0;
  for (int i = 0; i < 24; ++i) {
    const bool rational = i % 3 == 0;
    const Mesh m = jittered_sphere(random, 0.01, i % 4 == 0 ? 0 : 1 + i % 5, 0.8, rational);
    const detail::VertexStars s = examine(m);
    ASSERT_EQ(s.embedded.size(), m.num_vertices());
    std::vector<std::vector<std::uint32_t>> star(m.num_vertices());
    for (std::uint32_t f = 0; f < m.num_triangles(); ++f)
      for (const VertexIndex v : m.triangles[f]) star[v].push_back(f);
    for (VertexIndex v = 0; v < m.num_vertices(); ++v) {
      if (!s.embedded[v]) {
        ++unproved;
        continue;
      }
      ++proved;
      for (std::size_t a = 0; a < star[v].size(); ++a)
        for (std::size_t b = a + 1; b < star[v].size(); ++b)
          ASSERT_FALSE(triangles_intersect_improperly(m, star[v][a], star[v][b]))
              << "case " << i << ": vertex " << v << " proved, faces " << star[v][a] << ", "
              << star[v][b] << " meet improperly";
    }
    const Pairs expected = improper_pairs_by_brute_force(m);
    ASSERT_EQ(improper_pairs_by_check(m), expected) << "case " << i;
    folded_cases += !expected.empty();
  }
  EXPECT_GT(proved, 20 * 162 * 9 / 10);  // nearly all of 24 spheres' 162 vertices
  EXPECT_GT(unproved, 10);
  EXPECT_GT(folded_cases, 5) << proved << " proved, " << unproved << " unproved";
}

// A double cone over a rim that winds `turns` times around the axis: every edge is used twice in
// opposite directions, and each triangle turns the same way seen from above, yet for turns = 2
// the apexes' stars cover the plane twice and their triangles overlap. Only the winding count
// tells them apart from an embedded star.
TEST(VertexStars, StarsWoundTwiceAreNotProved) {
  for (const int n : {5, 7, 9, 31, 45}) {  // 45: beyond the small-star pairing
    // Flat cones too: every face then also turns one way along a diagonal, where the winding
    // count is what refuses the star.
    for (const int turns : {1, 2, -1, -2}) {
      const double height = turns > 0 ? 1 : 0.1;
      DoubleMesh d;
      d.points.push_back({0, 0, height});   // apex above
      d.points.push_back({0, 0, -height});  // apex below
      for (int k = 0; k < n; ++k) {
        const double a = 6.283185307179586 * std::abs(turns) * k / n;
        d.points.push_back({std::cos(a), std::sin(a), 0});
      }
      for (VertexIndex k = 0; k < VertexIndex(n); ++k) {
        const VertexIndex r = 2 + k, s = 2 + (k + 1) % VertexIndex(n);
        d.triangles.push_back({0, r, s});
        d.triangles.push_back({1, s, r});
      }
      // Divided by 3, the coordinates are no longer doubles: the proof then runs on doubles
      // known within an error, where the rim point on the x axis has the apexes' y exactly and
      // only the exact comparison gives that difference's sign.
      for (const bool rational : {false, true}) {
        Mesh m = from_double(d);
        if (rational) m = transformed(m, Transformation(CGAL::SCALING, FT(1) / 3));
        const detail::VertexStars stars = examine(m);
        const std::string what = std::to_string(n) + "-gon wound " +
                                 std::to_string(std::abs(turns)) + " times, height " +
                                 std::to_string(height) + (rational ? ", rational" : "");
        EXPECT_EQ(stars.embedded[0], std::abs(turns) == 1) << what;
        EXPECT_EQ(stars.embedded[1], std::abs(turns) == 1) << what;
        const Pairs expected = improper_pairs_by_brute_force(m);
        EXPECT_EQ(improper_pairs_by_check(m), expected) << what;
        EXPECT_EQ(expected.empty(), std::abs(turns) == 1) << what;
      }
    }
  }
}

namespace {
// No two triangles at a vertex the pass proved meet improperly (CGAL's triangle predicates over
// every pair of the mesh's triangles that have that vertex).
void expect_proved_stars_embedded(const Mesh& m, const detail::VertexStars& s,
                                  const std::string& what) {
  for (VertexIndex v = 0; v < m.num_vertices(); ++v) {
    if (!s.embedded[v]) continue;
    for (std::uint32_t a = 0; a < m.num_triangles(); ++a)
      for (std::uint32_t b = a + 1; b < m.num_triangles(); ++b) {
        const Triangle &ta = m.triangles[a], &tb = m.triangles[b];
        const bool at_v =
            (ta[0] == v || ta[1] == v || ta[2] == v) && (tb[0] == v || tb[1] == v || tb[2] == v);
        if (at_v)
          ASSERT_FALSE(triangles_intersect_improperly(m, a, b))
              << what << ": vertex " << v << " proved, faces " << a << ", " << b;
      }
  }
}
}  // namespace

// Where faces meet at right angles (a prism's rim: the cap perpendicular to every axis that
// suits the sides), no coordinate axis proves the star but a diagonal does; on the same shapes
// with vertices pushed to fold their stars, no folded star is taken as proved, and the check's
// improper pairs are those of all pairs tested one by one.
TEST(VertexStars, SharpStarsAreProvedAlongDiagonals) {
  const Mesh prism = make_fan_prism(40, 1, 1);
  const detail::VertexStars clean = examine(prism);
  std::size_t proved = 0;
  for (const std::uint8_t e : clean.embedded) proved += e;
  EXPECT_GE(proved, prism.num_vertices() - 2) << "rim vertices of a fan prism";  // all but apexes?
  std::mt19937 random(90);
  std::size_t folded_cases = 0;
  for (int i = 0; i < 30; ++i) {
    DoubleMesh d =
        to_double(i % 2 ? make_fan_prism(12 + i, 1, 1) : make_box(Point(0, 0, 0), Point(1, 2, 3)));
    std::uniform_real_distribution<double> unit(-1, 1);
    std::uniform_int_distribution<std::size_t> vertex(0, d.points.size() - 1);
    for (int k = 0; k < 1 + i % 3; ++k)
      for (double& x : d.points[vertex(random)]) x += (i % 5 == 0 ? 0.05 : 0.9) * unit(random);
    const Mesh m = from_double(d);
    const detail::VertexStars s = examine(m);
    expect_proved_stars_embedded(m, s, "case " + std::to_string(i));
    const Pairs expected = improper_pairs_by_brute_force(m);
    ASSERT_EQ(improper_pairs_by_check(m), expected) << "case " << i;
    folded_cases += !expected.empty();
  }
  EXPECT_GT(folded_cases, 5);
}

// A thin cone's tip turned off the axes (in doubles, and by a rational rotation whose points are
// only near their doubles): every face at the tip turns one way seen along the cone's axis, but
// along no coordinate axis or diagonal; the star's mean normal proves it. With the tip and a rim
// vertex pushed about at random (faces folded over others), nothing wrong is proved and the
// check's improper pairs are those of all pairs tested one by one.
TEST(VertexStars, SharpTipsTurnedOffTheAxesAreProvedAlongTheirNormals) {
  std::mt19937 random(11);
  std::uniform_real_distribution<double> angle(0.3, 1.2), unit(-1, 1);
  std::size_t tips = 0, folded_cases = 0;
  for (int i = 0; i < 16; ++i) {
    const int n = 7 + i;
    const VertexIndex tip = VertexIndex(n);  // make_fan_cone's apex
    DoubleMesh d = to_double(make_fan_cone(n, 1, 12));
    const bool folded = i % 4 == 3;
    if (folded) {
      d.points[tip] = {1.5 * unit(random), 1.5 * unit(random), 0.5};
      for (double& x : d.points[1 + i % 5]) x += 1.5 * unit(random);
    }
    const Mesh cone = from_double(d);
    const Mesh turned =
        i % 2 == 0 ? test_support::turned_and_rounded(cone, angle(random), angle(random))
                   : transformed(cone, quaternion_rotation(5 + i, 1 + i % 3, 3, 2 - i % 5));
    const detail::VertexStars s = examine(turned);
    if (!folded) {
      EXPECT_TRUE(s.embedded[tip]) << "case " << i;
      tips += s.embedded[tip];
    }
    expect_proved_stars_embedded(turned, s, "case " + std::to_string(i));
    const Pairs expected = improper_pairs_by_brute_force(turned);
    ASSERT_EQ(improper_pairs_by_check(turned), expected) << "case " << i;
    folded_cases += !expected.empty();
  }
  EXPECT_EQ(tips, 12u);
  EXPECT_GE(folded_cases, 3u);
}

// SPDX-License-Identifier: GPL-3.0-or-later
// What the self-intersection tests share: the improper pairs of a mesh two ways (by CGAL's
// triangle predicates over every pair, triangles_intersect_improperly, independent of the
// check's own tests, traversal and proofs; and as check_mesh lists them), the patches the check
// proves embedded, and meshes turned in doubles (flat faces become nearly flat).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <utility>
#include <vector>

#include "check/check_edge_fans.h"
#include "check/check_planar.h"
#include "exact/point_index.h"
#include "exact/point_table.h"
#include "morphex/check.h"
#include "morphex/internal/fixtures.h"
#include "tree/box_tree.h"

namespace morphex::test_support {

using Pairs = std::vector<std::pair<std::uint32_t, std::uint32_t>>;

// Each vertex's position as the check names it: the least index of the vertices there.
inline std::vector<detail::PointId> positions_of(const Mesh& m) {
  std::vector<detail::PointId> position(m.num_vertices());
  detail::PositionIndex index;
  for (VertexIndex v = 0; v < m.num_vertices(); ++v)
    position[v] = index.find_or_insert(m.points[v], v);
  return position;
}

// Every pair tested one by one, plus the pairs that cross along a segment several edges share by
// position (which no test of two triangles sees; check_edge_fans.h, tested on its own in
// Contacts.FoldsCrossingAlongASharedSegmentAreRefused): what the check's shortcuts must reproduce.
inline Pairs improper_pairs_by_brute_force(const Mesh& m) {
  Pairs pairs;
  for (std::uint32_t a = 0; a < m.num_triangles(); ++a)
    for (std::uint32_t b = a + 1; b < m.num_triangles(); ++b)
      if (triangles_intersect_improperly(m, a, b)) pairs.emplace_back(a, b);
  const detail::PointTable table(m, m, true);
  const std::vector<detail::PointId> position = positions_of(m);
  const Pairs crossing = detail::interleaved_edge_fans(m, table, position);
  pairs.insert(pairs.end(), crossing.begin(), crossing.end());
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  return pairs;
}

inline Pairs improper_pairs_by_check(const Mesh& m) {
  CheckOptions options;
  options.list_self_intersections = true;
  return check_mesh(m, options).self_intersecting_pairs;
}

// The patches the check proves embedded: exactly flat ones, then (near_flat) nearly flat ones.
inline detail::PlanarPatches proved_patches_of(const Mesh& m, bool near_flat) {
  const detail::PointTable table(m, m, true);
  const std::vector<detail::PointId> position = positions_of(m);
  const std::vector<std::uint8_t> degenerate(m.num_triangles(), 0);
  std::map<std::uint64_t, std::vector<std::uint32_t>> uses;
  for (std::uint32_t f = 0; f < m.num_triangles(); ++f)
    for (int k = 0; k < 3; ++k) {
      const VertexIndex a = m.triangles[f][k], b = m.triangles[f][(k + 1) % 3];
      uses[(std::uint64_t(std::min(a, b)) << 32) | std::max(a, b)].push_back(f);
    }
  detail::ManifoldEdges manifold;
  for (const auto& [key, faces] : uses)
    if (faces.size() == 2) manifold.push_back({key, {faces[0], faces[1]}});
  const detail::FacePlanes planes(m, table.input_near_doubles(), table.input_error());
  detail::PlanarPatches patches =
      detail::verified_planar_patches(m, table, planes, position, degenerate, manifold, 16);
  if (near_flat)
    detail::add_near_flat_patches(m, table, planes, position, degenerate, manifold, 16, patches);
  return patches;
}

// m turned about the z axis by `a` and then about the x axis by `b` radians in doubles, every
// coordinate rounded to a double: its flat faces are then flat only up to rounding.
inline Mesh turned_and_rounded(const Mesh& m, double a, double b) {
  DoubleMesh d;
  d.triangles = m.triangles;
  for (const Point& p : m.points) {
    const double x = CGAL::to_double(p.x()), y = CGAL::to_double(p.y()), z = CGAL::to_double(p.z());
    const double x1 = std::cos(a) * x - std::sin(a) * y, y1 = std::sin(a) * x + std::cos(a) * y;
    d.points.push_back(
        {x1, std::cos(b) * y1 - std::sin(b) * z, std::sin(b) * y1 + std::cos(b) * z});
  }
  return from_double(d);
}

// A fan prism of n segments (radius 2, height 1, caps fanned from one rim vertex) with its bottom
// cap broken or met by another solid, by `kind`: 0 a rim vertex moved inward in the cap's plane,
// 1 two rim vertices swapped, 2 a rim vertex lifted or sunk by 2^-30 up to 2^-2, 3 to 5 a
// tetrahedron through, onto or beside the cap, 6 another fan prism there. pick(lo, hi) draws the
// details.
template <class Pick>
Mesh fan_prism_case(int n, int kind, Pick&& pick) {
  Mesh m = make_fan_prism(n, 2.0, 1.0);
  if (kind == 0) {
    const VertexIndex v = VertexIndex(pick(1, n - 1));
    const FT shrink = FT(pick(1, 9)) / 10;
    m.points[v] = Point(m.points[v].x() * shrink, m.points[v].y() * shrink, 0);
  } else if (kind == 1) {
    std::swap(m.points[std::size_t(pick(1, n - 1))], m.points[std::size_t(pick(1, n - 1))]);
  } else if (kind == 2) {
    const VertexIndex v = VertexIndex(pick(1, n - 1));
    const double lift = std::ldexp(pick(0, 1) ? 1.0 : -1.0, -pick(2, 30));
    m.points[v] = Point(m.points[v].x(), m.points[v].y(), lift);
  } else {
    const Mesh other = kind == 6 ? make_fan_prism(pick(17, 24), 1.0, 1.0)
                                 : transformed(make_tetrahedron(),
                                               Transformation(CGAL::SCALING, FT(pick(1, 4)) / 2));
    const FT z = kind == 3 ? FT(pick(-2, 0)) / 2 : kind == 4 ? FT(0) : FT(pick(-1, 1)) / 2;
    m = concatenate(m, translated(other, Vector(FT(pick(-6, 6)) / 4, FT(pick(-6, 6)) / 4, z)));
  }
  return m;
}

}  // namespace morphex::test_support

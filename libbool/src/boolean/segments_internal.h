// SPDX-License-Identifier: GPL-3.0-or-later
// Plain data shared by step 3 (segments: step3_*.cpp) and step 4 (orientation: step4_orient.cpp).
//
// Step 3 leaves, for every candidate pair, its PairOutcome: nothing, a point, a segment from lo to
// hi along Na x Nb, or a coplanar overlap polygon, each point with the edges of both triangles it
// lies on. Step 4 turns the outcomes into per-facet cuts, orienting transversal segments.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "boolean/boolean_internal.h"

namespace morphex::detail {

constexpr PointId kNoPoint = std::numeric_limits<PointId>::max();

using Corners = std::array<PointId, 3>;

// The edges of triangle t (corners by id) that p lies on, for p in the closed triangle (in its
// plane, seen along the axis `dropped`).
std::uint8_t edges_through(const PointTable& table, int dropped, const Corners& t, PointId p);

// Two input edges (ids of their ends, each pair sorted): the name of the point where they cross.
using EdgeEdgeKey = std::pair<std::uint64_t, std::uint64_t>;
inline EdgeEdgeKey edge_edge_key(PointId a0, PointId a1, PointId b0, PointId b1) {
  return {edge_key(undirected(a0, a1)), edge_key(undirected(b0, b1))};
}

// How the final id of a point is found in the sequential naming pass.
enum class Naming : std::uint8_t {
  Known,     // its id is final
  EdgeEdge,  // by the two edges it lies on (`key`)
  Position,  // by exact position (soups)
};

// A point of a pair's intersection, with the edges of ta and of tb it lies on.
struct PairPoint {
  PointId id = kNoPoint;  // table id, or kNoPoint for a new coplanar crossing (`recipe`)
  Recipe recipe;
  Naming naming = Naming::Known;
  EdgeEdgeKey key{};
  std::uint8_t edges_a = 0, edges_b = 0;
};

// What one candidate pair leaves on its two facets.
struct PairOutcome {
  enum class Kind : std::uint8_t { None, Point, Segment, Polygon } kind = Kind::None;
  std::vector<PairPoint> points;  // Point: 1, Segment: 2 (from lo to hi), Polygon: its vertices
  bool transversal = false;       // a segment whose interior is inside both open triangles
};

// The signs of each triangle's corners against the other's plane.
struct PairSigns {
  std::int8_t a[3], b[3];  // ta's vertices against tb's plane, tb's against ta's
  bool separated = true, coplanar = false;
};

// What the phases of step 3 share: the two meshes (one soup twice in the n-ary union), the pairs,
// and every corner named by the id of its position (coincident corners of the two meshes share
// one, so predicates on them are decided by the ids alone).
struct PairContext {
  const Mesh* meshes[2];
  const Pairs& pairs;
  const IntersectOptions& options;
  PointTable& table;
  const std::vector<PointId>& rep;  // Intersection::vertex_rep

  Corners corners(int side, std::uint32_t facet) const {
    const Triangle& f = meshes[side]->triangles[facet];
    return {rep[table.vertex(side, f[0])], rep[table.vertex(side, f[1])],
            rep[table.vertex(side, f[2])]};
  }
  Corners corners_a(std::size_t k) const { return corners(0, pairs[k].first); }
  Corners corners_b(std::size_t k) const { return corners(1, pairs[k].second); }
  // The side under which B's facets are named in plane questions and crossing keys (0 in a soup).
  std::uint32_t b_side() const { return options.soup ? 0 : 1; }
};

// The interval normals of the facets in some pair, side by side: a facet meets many pairs, so its
// normal is computed once; but few facets of a large mesh are in any pair, and records indexed
// by facet would put each one written on a page of its own (a fresh page fault per call).
struct FacetNormals {
  std::vector<std::uint32_t> slot[2];   // by facet: its normal's index (facets in some pair)
  std::vector<ApproxVector> normal[2];  // by slot
  const ApproxVector& of(int side, std::uint32_t facet) const {
    return normal[side][slot[side][facet]];
  }
};

// Step 3, signs (step3_signs.cpp): each pair's corner signs, decided on intervals, plane labels
// and shared corners first, the remaining (plane, point) questions each evaluated exactly once;
// pairs whose triangles do not meet are marked separated.
std::vector<PairSigns> pair_signs(const PairContext& c, const FacetNormals& normals);

// Step 3, coplanar pairs (step3_coplanar.cpp): the overlap of two closed coplanar triangles
// (corners by id), nothing, a point, a segment's ends or a convex polygon, each vertex with the
// edges of ta and tb it lies on. `dropped` is the projection axis of their common plane.
std::vector<PairPoint> coplanar_overlap(const PointTable& table, const Corners& ta,
                                        const Corners& tb, int dropped, bool soup);

// Step 3's result, step 4's input: the point table and the ids of the input vertices that met
// (in `x`, whose cuts are still empty), the candidate pairs that no plane separates, and each one's
// outcome with final point ids.
struct PairFindings {
  Intersection x;
  Pairs pairs;
  std::vector<PairOutcome> outcomes;
  std::vector<PointId> merged;  // ids given to several input vertices at one position
};

}  // namespace morphex::detail

// SPDX-License-Identifier: GPL-3.0-or-later
// One pass over the vertex stars of a mesh (in parallel, each star on its own): the edges at
// each vertex by use (border, manifold, non-manifold, misoriented), whether the star is one fan,
// and, where every edge at the vertex is used twice in opposite directions, a proof that the
// star is embedded near the vertex, so that the self-intersection check need not test the pairs
// of triangles that share it.
//
// Why it is enough to look near the vertex: two triangles with a common vertex v meet in a
// convex set that holds v; if it holds any other point p, it holds the segment vp and so points
// arbitrarily close to v. Whether they meet beyond v (or beyond a common edge at v) is therefore
// decided by their angles at v, and a whole star is decided at once: project it along a
// coordinate axis; when every triangle of the star turns the same way in the projection and
// their angles cover the plane around v exactly once, the projected angles overlap nowhere but
// along common sides, so neither do the triangles (a triangle that turns one way is not parallel
// to the axis, so the projection is one-to-one on it).
//
// Covering exactly once is a count on one ray: when each edge at v is used twice in opposite
// directions, the angles at v chain into closed loops around it, each loop covers every
// direction the same number of times (half-open angles), and so the number of angles that hold
// the direction of one neighbour is the sum of the loops' windings.
#pragma once

#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "check/check_planar.h"
#include "exact/point_table.h"
#include "morphex/mesh.h"

namespace morphex::detail {

struct VertexStars {
  ManifoldEdges manifold;  // edges used by exactly two faces, sorted by key, faces in order
  // Pairs of faces to join into components besides the manifold edges' (non-manifold edges).
  std::vector<std::pair<std::uint32_t, std::uint32_t>> other_joins;
  std::size_t border_edges = 0, non_manifold_edges = 0, non_manifold_vertices = 0;
  std::optional<VertexIndex> first_border_vertex;        // the smallest end of a border edge
  std::optional<VertexIndex> first_non_manifold_vertex;  // whose faces form several fans
  std::optional<std::uint32_t> first_misoriented_face;   // the smaller face of such an edge
  // By vertex index, when proofs were asked for: 1 when any two triangles with that vertex meet
  // in nothing but it or their common edge through it (exact, on `table`'s predicates; a star
  // that needs a curved projection is simply left unproved).
  std::vector<std::uint8_t> embedded;
};

// Requires that no face repeats a vertex index; `table` holds the mesh's points with
// PointId = vertex index.
VertexStars examine_vertex_stars(const Mesh& mesh, const PointTable& table, bool prove);

}  // namespace morphex::detail

// SPDX-License-Identifier: GPL-3.0-or-later
// Adjacency for the coplanar merge (step7_merge_coplanar.cpp): the edges leaving each vertex of
// a surface, each edge's twin, and the vertices whose position another vertex shares.
#pragma once

#include <cstdint>
#include <limits>
#include <vector>

#include "boolean/boolean_internal.h"
#include "exact/point_table.h"

namespace morphex::detail {

inline constexpr std::uint32_t kNoFace = std::numeric_limits<std::uint32_t>::max();

// The edges leaving each vertex of the triangles `tri` (over `nv` vertices), listed contiguously
// by vertex, their ends apart from their faces, so that a twin is found in one short run of
// memory (a hash table of all edges, or the faces around the vertex, did not).
class VertexEdges {
 public:
  VertexEdges(const std::vector<Triangle>& tri, std::size_t nv);
  // The face across edge k of face f (tri[f][k] -> tri[f][k + 1]): the first edge leaving
  // tri[f][k + 1] for tri[f][k]. kNoFace on a border.
  std::uint32_t twin(std::uint32_t f, int k) const;
  // twin(f, k) at 3 f + k, for every face.
  std::vector<std::uint32_t> all_twins() const;
  // The faces around v, one per edge leaving it: [faces_begin(v), faces_end(v)).
  const std::uint32_t* faces_begin(VertexIndex v) const { return face_.data() + start_[v]; }
  const std::uint32_t* faces_end(VertexIndex v) const { return face_.data() + start_[v + 1]; }

 private:
  const std::vector<Triangle>& tri_;
  std::vector<std::uint32_t> start_;  // by vertex: its first edge; start_[nv] = 3 faces
  std::vector<VertexIndex> to_;       // by edge: its end (3 entries of padding past the last)
  std::vector<std::uint32_t> face_;   // by edge: its face
};

// For each vertex flagged in `of_interest`, whether another vertex has its position: the same
// point, or an equal one. The flagged vertices are bucketed by the grid cells their interval
// boxes cover (coincident points have overlapping boxes), and only vertices sharing a cell with a
// flagged one are compared exactly. The flagged ones are few (the candidates of a merge) and
// usually in one part of the surface: the other vertices are dropped by the box around them.
std::vector<std::uint8_t> coincident(const PointTable& table, const IdMesh& surface,
                                     const std::vector<std::uint8_t>& of_interest);

}  // namespace morphex::detail

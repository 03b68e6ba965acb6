// SPDX-License-Identifier: GPL-3.0-or-later
// Plain data passed between the phases of the Boolean (notation: morphex/boolean.h).
#pragma once

#include <cstdint>
#include <map>
#include <unordered_map>
#include <utility>
#include <vector>

#include "morphex/boolean.h"

namespace morphex::detail {

using PointId = std::uint32_t;
using Edge = std::pair<PointId, PointId>;  // undirected edges are stored (min, max)

inline Edge undirected(PointId a, PointId b) {
  return a < b ? Edge{a, b} : Edge{b, a};
}

// An edge (a, b) as one 64-bit key, for hash tables and sorted edge records: directed as given;
// pass undirected(a, b) for the undirected edge.
inline std::uint64_t edge_key(PointId a, PointId b) {
  return (std::uint64_t(a) << 32) | b;
}

struct EdgeHash {
  std::size_t operator()(const Edge& e) const {
    return std::hash<std::uint64_t>()((std::uint64_t(e.first) << 32) | e.second);
  }
};

// Step 2: pairs (ta, tb) whose boxes overlap.
std::vector<std::pair<std::uint32_t, std::uint32_t>> candidate_pairs(const Mesh& a, const Mesh& b);

// What the other mesh leaves on one input triangle.
// A transversal segment (its interior lies inside both open triangles), oriented by the seed's
// rule so that the other solid's interior is on its left, seen along the facet's normal.
struct OrientedSegment {
  PointId from, to;
};

struct FacetCut {
  std::vector<PointId> points;                 // intersection points lying on the facet
  std::vector<Edge> segments;                  // constraints
  std::vector<OrientedSegment> transversal;    // the subset that decides labels locally
  std::vector<std::uint32_t> coplanar_facets;  // facets of the other mesh coplanar and touching
};

// Step 3: all intersection points (shared by identity = exact position) and per-facet cuts.
// Point ids: A's vertices first, then B's, then constructed points; coincident input vertices
// share the id of the first one (`vertex_id`).
struct Intersection {
  std::vector<Point> points;
  std::vector<PointId> vertex_id[2];                    // input vertex -> point id
  std::unordered_map<std::uint32_t, FacetCut> cuts[2];  // facet -> cut
  std::size_t intersecting_pairs = 0;
  std::size_t constructed_points = 0;
};

// How the patches were labelled: by the seed's orientation rule or by an exact ray cast.
struct ClassifyCounts {
  std::size_t patches = 0, by_orientation_rule = 0, by_ray_cast = 0;
  std::size_t rule_conflicts = 0;  // segments of one patch that disagree: must stay 0
};
Intersection intersect(const Mesh& a, const Mesh& b,
                       const std::vector<std::pair<std::uint32_t, std::uint32_t>>& pairs);

// Step 5: the refined mesh A' or B'.
struct SubTriangle {
  std::array<PointId, 3> v;  // oriented as the input facet
  std::uint32_t facet;       // input facet it comes from
};
struct Refined {
  std::vector<SubTriangle> triangles;
  std::vector<Edge> on_other_surface;  // constrained edges: they separate patches
};
Refined retriangulate(const Mesh& mesh, int side, const Intersection& x);

// 0, 1 or 2: the axis along which the normal of triangle abc is largest, so that dropping that
// coordinate projects the triangle's plane without degeneracy (exact: it only selects coordinates).
int dominant_axis(const Point& a, const Point& b, const Point& c);

// Step 6: labels.
enum class Label : std::uint8_t { Outside, Inside, CoplanarSame, CoplanarOpposite };
// One label per sub-triangle of `refined` (a refinement of `mesh`, side 0 = A, 1 = B).
std::vector<Label> classify(const Mesh& mesh, const Mesh& other, int side, const Refined& refined,
                            const Intersection& x, ClassifyCounts& counts);

// Turns kept triangles over shared points into a closed 2-manifold: non-manifold edges are paired
// by exact radial order and each vertex gets one copy per fan.
Mesh separate_non_manifold(const std::vector<Point>& points, std::vector<Triangle>& faces);

// merge_coplanar_faces, told where each face comes from (`origin`, optional): faces cut from one
// input facet are coplanar by construction and need no predicate.
Mesh merge_coplanar_faces(const Mesh& solid, const std::vector<FaceOrigin>* origin);

// Step 7: selection, output, separation of non-manifold features.
Mesh assemble(const Intersection& x, const Refined refined[2], const std::vector<Label> labels[2],
              BooleanOp op, std::vector<FaceOrigin>* provenance);

}  // namespace morphex::detail

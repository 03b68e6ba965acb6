// SPDX-License-Identifier: GPL-3.0-or-later
// Plain data passed between the phases of the Boolean (notation: morphex/boolean.h).
//
// Points are named by ids of a PointTable (point_table.h): A's vertices, B's vertices, then the
// constructed points. Work is local to what the other mesh touches: only cut facets are
// re-triangulated, and the rest of each mesh is labelled and copied through its vertices.
#pragma once

#include <algorithm>
#include <cstdint>
#include <memory>
#include <optional>
#include <unordered_map>
#include <utility>
#include <vector>

#include "exact/point_table.h"
#include "morphex/boolean.h"
#include "morphex/internal/union_find.h"
#include "tree/box_frame.h"
#include "tree/box_tree.h"

namespace morphex::detail {

using Edge = std::pair<PointId, PointId>;  // undirected edges are stored (min, max)

inline Edge undirected(PointId a, PointId b) {
  return a < b ? Edge{a, b} : Edge{b, a};
}

// An edge (a, b) as one 64-bit key, for hash tables and sorted edge records: directed as given;
// pass undirected(a, b) for the undirected edge.
inline std::uint64_t edge_key(PointId a, PointId b) {
  return (std::uint64_t(a) << 32) | b;
}
inline std::uint64_t edge_key(const Edge& e) {
  return edge_key(e.first, e.second);
}

using Pairs = std::vector<std::pair<std::uint32_t, std::uint32_t>>;

// The box trees of the two operands, each built at most once per Boolean: by the input check,
// else by step 2 when it indexes that operand, else by step 6 when a patch of the other operand
// needs a ray cast. When step 2 boxes along the axes of a turned part, it builds trees of its own
// along them. The two sides' classifications run at once, each reading only the other side's
// slot.
class OperandTrees {
 public:
  // The point table of the two operands, set before any other call (its contiguous copy of the
  // vertices' intervals boxes them without reading each Point again); set again when it moves.
  void use_points(const PointTable* points) { points_ = points; }
  // The axes step 2 boxes both operands along (box_frame.h: a turned CAD part's own); the
  // coordinate axes unless set. Needs the point table.
  void use_frame(const BoxFrame& frame) { frame_ = frame; }
  // A tree over every triangle of that side's mesh, along the coordinate axes: step 6 casts rays
  // through it, and step 2 pairs with it when its frame is the coordinate axes.
  const TriangleTree& of(int side, const Mesh& mesh);
  // The tree step 2 pairs with: along its frame; whether it exists already.
  const TriangleTree& for_pairs(int side, const Mesh& mesh);
  bool has_pairs_tree(int side) const;
  // The boxes of that side's triangles along step 2's frame.
  std::vector<FloatBox> triangle_boxes_of(int side, const Mesh& mesh) const;
  // Vertex v of that side as step 2's frame sees it (the caller rounds upward).
  ApproxPoint corner(int side, VertexIndex v) const;
  // A tree over every triangle of that side's mesh along the coordinate axes, built elsewhere
  // (by the input check).
  void adopt(int side, std::shared_ptr<const TriangleTree> tree) {
    if (tree) tree_[side] = std::move(tree);
  }

 private:
  // The boxes of that side's vertices, by vertex index, along `frame`.
  std::vector<FloatBox> vertex_boxes(int side, const Mesh& mesh, const BoxFrame& frame) const;

  std::shared_ptr<const TriangleTree> tree_[2];  // shared with the Solid whose check built it
  std::optional<TriangleTree> framed_[2];
  const PointTable* points_ = nullptr;
  BoxFrame frame_;
};

// Step 2: pairs (ta, tb) whose boxes overlap; the trees it builds are kept in `trees`.
Pairs candidate_pairs(const Mesh& a, const Mesh& b, OperandTrees& trees);

// A point of a facet's cut, with the edges of that facet it lies on (bit i: the edge from corner i
// to corner i + 1), so that the facet's triangulation takes those collinearities from the
// combinatorics instead of evaluating them (they would always need the exact stage).
struct CutPoint {
  PointId id;
  std::uint8_t edges;
};

// The edge mask of corner k: the edges k - 1 and k meet there.
inline std::uint8_t corner_edges(int k) {
  return std::uint8_t((1u << k) | (1u << ((k + 2) % 3)));
}

// A transversal segment (its interior lies inside both open triangles), oriented by the seed's
// rule so that the other solid's interior is on its left, seen along the facet's normal.
struct OrientedSegment {
  PointId from, to;
};

// What the other mesh leaves on one input triangle.
struct FacetCut {
  std::vector<CutPoint> points;                // intersection points lying on the facet
  std::vector<Edge> segments;                  // constraints
  std::vector<OrientedSegment> transversal;    // the subset that decides labels locally
  std::vector<std::uint32_t> coplanar_facets;  // facets of the other mesh coplanar and touching
};

// Flags of a point id.
enum PointFlag : std::uint8_t {
  kOnSurface = 1,  // in some cut: on both surfaces
  kMerged = 2,     // several input vertices at this position were given this id
};

// Step 3 (step3_*.cpp): all intersection points, each with one id; step 4 (step4_orient.cpp): the
// per-facet cuts with transversal segments oriented.
struct Intersection {
  PointTable points;
  // Input id -> the id its position has: coincident input vertices near the other mesh (on facets
  // of candidate pairs) share the first one's id; every other vertex keeps its own.
  std::vector<PointId> vertex_rep;
  std::vector<std::uint8_t> flags;                          // PointFlag bits, by id
  std::vector<std::pair<std::uint32_t, FacetCut>> cuts[2];  // (facet, cut), sorted by facet
  std::size_t intersecting_pairs = 0;
  std::size_t constructed_points = 0;
  bool coplanar_overlaps = false;  // some coplanar facets overlap with positive area

  PointId vertex_id(int side, std::uint32_t v) const { return vertex_rep[points.vertex(side, v)]; }
  // The cut of a facet, or nullptr when the other mesh does not touch it.
  const FacetCut* cut(int side, std::uint32_t facet) const {
    const auto& c = cuts[side];
    const auto it =
        std::lower_bound(c.begin(), c.end(), facet,
                         [](const auto& entry, std::uint32_t f) { return entry.first < f; });
    return it != c.end() && it->first == facet ? &it->second : nullptr;
  }
  // A point where the output may be non-manifold: on both surfaces, or where input vertices met.
  bool special(PointId id) const { return flags[id] != 0; }
};

struct IntersectOptions {
  // a and b are one mesh, a soup of solids that may overlap (the n-ary union): the candidate
  // pairs are its own triangle pairs, and every constructed point is identified by its exact
  // position (in a soup, distinct constructions may coincide).
  bool soup = false;
  // Optional plane labels of a soup's triangles (winding.h): pairs with one label are coplanar.
  const std::vector<std::uint32_t>* planes = nullptr;
  // The table of a and b (PointTable(a, b, soup)) when the caller built it already: it becomes
  // the result's (moved from).
  PointTable* points = nullptr;
};
// Step 3 (step3_*.cpp): what each candidate pair leaves, every intersection point named once.
struct PairFindings;  // segments_internal.h
PairFindings intersect(const Mesh& a, const Mesh& b, const Pairs& pairs,
                       const IntersectOptions& options = {});
// Step 4 (step4_orient.cpp): the findings gathered per facet, transversal segments oriented.
Intersection orient_segments(PairFindings&& found);

// Step 5: the cut facets of one mesh re-triangulated (the other facets stay as they are).
struct SubTriangle {
  std::array<PointId, 3> v;  // oriented as the input facet
  std::uint32_t facet;       // input facet it comes from
};
struct Refined {
  std::vector<std::uint32_t> facets;  // the cut facets, in increasing order
  std::vector<SubTriangle> triangles;
  // Per sub-triangle: the first sub-triangle of its facet that it reaches without crossing a
  // constraint (the sub-triangles of one facet between constraints are one piece of a patch).
  std::vector<std::uint32_t> joined;
  // Per sub-triangle: its Label by the seed's orientation rule (it borders a transversal
  // segment), or -1.
  std::vector<std::int8_t> rule;
  // (undirected edge key, sub-triangle): unconstrained edges on the facet's boundary whose ends
  // are both special points. They join the sub-triangles of the facets on both sides, which a
  // common free vertex cannot.
  std::vector<std::pair<std::uint64_t, std::uint32_t>> open_boundary;
};
Refined retriangulate(const Mesh& mesh, int side, const Intersection& x);

// Patches: the input facets of one side that no cut touches, and the sub-triangles, joined when
// they meet without crossing the other surface. Nodes: facet f is f, sub-triangle i is
// num_triangles + i, and the free vertex with id p (not special) is num_triangles + subs + p.
// Facets and sub-triangles meet through free vertices (a free vertex's fan lies on one side of
// the other surface), inside a facet across unconstrained edges, and across the open boundary
// edges of cut facets. `component` (optional, per facet) keeps open boundary edges from joining
// facets of different components (pieces of a soup).
UnionFind connect_patches(const Mesh& mesh, int side, const Refined& refined, const Intersection& x,
                          const std::vector<std::uint32_t>* component = nullptr);

// Step 6: labels.
enum class Label : std::uint8_t { Outside, Inside, CoplanarSame, CoplanarOpposite };
struct Labels {
  std::vector<Label> facet;  // by input facet (only meaningful for facets no cut touches)
  std::vector<Label> sub;    // by sub-triangle of Refined
};
// How the patches were labelled: by the seed's orientation rule or by an exact ray cast.
struct ClassifyCounts {
  std::size_t patches = 0, by_orientation_rule = 0, by_ray_cast = 0;
  std::size_t rule_conflicts = 0;  // segments of one patch that disagree: must stay 0
};
// `trees` gives the other operand's tree (slot 1 - side) for the ray casts.
Labels classify(const Mesh& mesh, const Mesh& other, int side, const Refined& refined,
                const Intersection& x, OperandTrees& trees, ClassifyCounts& counts);

// A surface over point ids: vertex v is the point vertex_point[v] (the vertices of a separated
// non-manifold feature share a point).
struct IdMesh {
  std::vector<PointId> vertex_point;
  std::vector<Triangle> triangles;
};

// Turns faces over point ids into a closed 2-manifold surface: non-manifold edges are paired by
// exact radial order and each vertex gets one copy per fan. Only points whose `special` entry is
// not zero can be non-manifold, so only their corners are examined; every other id becomes one
// vertex. Faces split to separate an edge (at a midpoint added to `points`) are appended, with
// their origin appended to `origin` if given.
IdMesh separate_non_manifold(PointTable& points, const std::vector<Triangle>& faces,
                             const std::vector<std::uint8_t>& special,
                             std::vector<FaceOrigin>* origin = nullptr);
// The corners (3 f + k) of `faces` at special points as (point, corner), sorted.
using SpecialCorners = std::vector<std::pair<PointId, std::uint32_t>>;
SpecialCorners special_corners(const std::vector<Triangle>& faces,
                               const std::vector<std::uint8_t>& special);
// The same, given special_corners(faces, special).
IdMesh separate_non_manifold(PointTable& points, const std::vector<Triangle>& faces,
                             const std::vector<std::uint8_t>& special, SpecialCorners corners,
                             std::vector<FaceOrigin>* origin);

// merge_coplanar_faces on a surface over point ids, where face f lies in the plane of the
// triangle planes[plane_of[f]] (three point ids, oriented as the face): coplanarity is decided on
// those planes, once per plane and region.
// plane_of is updated to the merged surface's faces (a merged face lies in its region's plane).
// With `touched` (by face: 1 for a face a Boolean made or cut, 0 for an input facet kept whole),
// only vertices of touched faces may go: elsewhere a Boolean's result keeps its inputs' faces as
// they were, and the merge does not look there.
void merge_coplanar(const PointTable& points, IdMesh& surface,
                    const std::vector<std::array<PointId, 3>>& planes,
                    std::vector<std::uint32_t>& plane_of,
                    const std::vector<std::uint8_t>* touched = nullptr);

// The mesh with the surface's points (input points, lazily evaluated constructions).
Mesh materialize(const PointTable& points, const IdMesh& surface);

// Step 7: selection, separation of non-manifold features, coplanar merging when `merge` and
// coplanar facets met, output. `provenance`, if given, receives each output face's input facet
// (merging changes faces, so the caller asks for one or the other).
Mesh assemble(const Mesh& a, const Mesh& b, Intersection& x, const Refined refined[2],
              const Labels labels[2], BooleanOp op, bool merge,
              std::vector<FaceOrigin>* provenance);

}  // namespace morphex::detail

// SPDX-License-Identifier: GPL-3.0-or-later
// Pieces of the Minkowski machinery shared with morphology.cpp.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <unordered_map>
#include <vector>

#include "morphex/minkowski.h"
#include "morphex/shapes.h"

namespace morphex::detail {

// The facets of a mesh by directed edge u -> v, as its triangles list them.
class DirectedEdges {
 public:
  static constexpr std::uint32_t kNone = UINT32_MAX;
  explicit DirectedEdges(const Mesh& mesh);
  // The facet holding u -> v (the first one if several do), or kNone.
  std::uint32_t facet(VertexIndex u, VertexIndex v) const {
    const auto it = facet_.find(key(u, v));
    return it == facet_.end() ? kNone : it->second;
  }
  // Every directed edge occurs once and its reverse occurs too: edges have two facets each.
  bool paired() const { return paired_; }

 private:
  static std::uint64_t key(VertexIndex u, VertexIndex v) { return (std::uint64_t(u) << 32) | v; }
  std::unordered_map<std::uint64_t, std::uint32_t> facet_;
  bool paired_ = true;
};

// The vertex of t that is neither u nor v.
inline VertexIndex third_vertex(const Triangle& t, VertexIndex u, VertexIndex v) {
  return t[0] != u && t[0] != v ? t[0] : t[1] != u && t[1] != v ? t[1] : t[2];
}

// A triangle, or two coplanar alike-oriented triangles forming a strictly convex quadrilateral.
struct FacetGroup {
  std::vector<std::uint32_t> facets;
  std::vector<VertexIndex> vertices;
};
// The surface's facets in such groups, greedily in facet order: for convex B, (f1 u f2) + B is
// then one convex piece, half as many on meshes whose planar faces are split in triangles.
std::vector<FacetGroup> convex_facet_groups(const Mesh& surface);

// The components of a mesh by shared vertices, each with compact vertex indices.
std::vector<Mesh> connected_components(const Mesh& mesh);

// Exact: no face of the convex solid has the origin strictly on its outer side.
bool convex_contains_origin(const Mesh& convex);

// Exact convexity of a valid solid from its edges (connected, no reflex edge).
bool convex_by_edges(const Mesh& solid);

// The origin if it is strictly inside the convex solid, else its vertex centroid.
Point interior_point(const Mesh& convex);

// The convex pieces whose union with (A + c) is A + B, for the solid A bounded by `surface`, a
// convex B and c = interior_point(B) (convolution.cpp). Empty optional when an edge of the
// surface does not have exactly two facets, one each way. Without `solids`, a patch's sweep may
// overlap itself (see patch_pieces), and `unchecked` receives the indices of those sweeps: the
// pieces feed a winding arrangement as they are, and a union tree once those are made valid.
std::optional<std::vector<Mesh>> convolution_pieces(const Mesh& surface, const Mesh& b,
                                                    const Point& c, bool solids = true,
                                                    std::vector<std::size_t>* unchecked = nullptr);

// convolution_pieces and compute_union, with their times and counts added to `stats`.
std::optional<std::vector<Mesh>> timed_convolution_pieces(const Mesh& surface, const Mesh& b,
                                                          const Point& c, bool solids,
                                                          std::vector<std::size_t>* unchecked,
                                                          MinkowskiStats* stats);
Mesh timed_union(std::vector<Mesh> solids, MinkowskiStats* stats);

// How the convolution's pieces become one solid with A + c.
enum class PieceRoute {
  Automatic,    // the arrangement when the pieces overlap shallowly, else the tree
  Arrangement,  // one winding arrangement of A + c and every piece, however deep (tests)
  Tree,         // the balanced tree of exact binary unions (compute_union), then A + c
};
// (A + c) u U pieces (subtract: (A + c) minus U pieces) as one winding arrangement. The chain of
// A + c's boundary and the pieces' counts the prisms and solids holding a point: the union is
// where that count is >= 1; with the pieces reversed, the difference is. Faces shared by two
// pieces, or by a prism and A + c, cancel before any intersection. Nullopt, after the
// arrangement's cheap first steps, when the chain that is left has more than
// `max_pairs_per_triangle` candidate pairs per triangle (0: no limit). The automatic route allows
// kShallowPairs: beyond, the pieces overlap many layers deep (a B large beside the facets, a thin
// part of A eroded, facets parallel to B's faces) and the union tree, whose intermediate unions
// shed the buried sheets early, was faster on every case measured (docs/morphology-design.md).
constexpr double kShallowPairs = 20;
std::optional<Mesh> pieces_arrangement(const Mesh& moved_a, const std::vector<Mesh>& pieces,
                                       bool subtract, double max_pairs_per_triangle,
                                       MinkowskiStats* stats);
// Whether the arrangement is worth trying at all: B's radius about c at most kShallowRatio times
// the surface's median edge length (beyond, the pairs exceed the budget on every mesh measured).
constexpr double kShallowRatio = 4;
bool small_beside_facets(const Mesh& surface, const Mesh& b, const Point& c);
// (A + c) united with (or, subtract, minus) the convolution's pieces of `surface` (A's, or its
// reverse for an erosion) and B, by the chosen route; moved_a is A + c. The automatic route
// gives the arrangement up beyond `max_pairs_per_triangle` (tests make it give up at once).
// Empty optional when the pieces cannot be built (convolution_pieces).
std::optional<Mesh> convolution_union(const Mesh& surface, const Mesh& b, const Point& c,
                                      const Mesh& moved_a, bool subtract, PieceRoute route,
                                      MinkowskiStats* stats,
                                      double max_pairs_per_triangle = kShallowPairs);

// A zonotope: centre + [-h_1, h_1] + ... + [-h_k, h_k] (a box: three generators along the axes).
struct Zonotope {
  Point centre;
  std::vector<Vector> halves;  // h_i; boxes' along x, y, z in that order
};
// B as a zonotope, proved exactly from its edges and vertices (zonotope.cpp); nullopt for any
// other mesh, which takes the convolution.
std::optional<Zonotope> zonotope_of(const Mesh& b);
// centre + sum [-h_i, h_i] as a closed outward mesh; std::invalid_argument when the generators do
// not span 3 dimensions.
Mesh zonotope_mesh(const Point& centre, const std::vector<Vector>& halves);
// A solid with plane labels (morphex/winding.h): faces with one label lie in one plane. Chained
// sweeps pass them on, so that the coplanarity each sweep creates is known to the next.
struct LabelledSolid {
  Mesh mesh;
  std::vector<std::uint32_t> plane;
};
LabelledSolid labelled(const Mesh& m);  // every face its own label
// A + [-h, h] (or the erosion by it) for the segment of half vector h, as one winding_solid
// (segment_sweep.cpp); as two sweeps of h / 2 when its arrangement has more than
// `max_pairs_per_triangle` candidate pairs per triangle and halving thins them (sheets folded many
// layers deep; 0: never halved). `arrangements` (when given) counts the winding_solid calls,
// begun ones included.
constexpr double kDeepFoldPairs = 16;
LabelledSolid segment_sweep(const LabelledSolid& a, const Vector& half, bool erode,
                            double max_pairs_per_triangle = kDeepFoldPairs,
                            std::size_t* arrangements = nullptr);
// A + B or A - B for a zonotope B: the centre, then one sweep per generator.
LabelledSolid zonotope_morphology(LabelledSolid a, const Zonotope& z, bool erode);
Mesh zonotope_morphology(const Mesh& a, const Zonotope& z, bool erode);

// A + B for one connected B whose convexity is known.
Mesh sum_with_component(const Mesh& a, const Mesh& b, bool b_convex, MinkowskiStats* stats);

}  // namespace morphex::detail

// SPDX-License-Identifier: GPL-3.0-or-later
// Solids bounded by closed surfaces that may cross themselves: the region where the winding
// number of a weighted triangle chain reaches a threshold, exactly.
//
// A chain is a list of oriented triangles, each with an integer weight, whose boundary vanishes:
// along every segment of space, the triangles on it, counted with their weights and directions,
// cancel (every closed, consistently oriented mesh is one; so is the sum of the boundaries of
// several solids, each with a multiplicity). Its winding number w(x) at a point off the surface
// counts, with weights, how many times the surface wraps around x: 1 inside and 0 outside a
// valid solid; for a sum of solid boundaries, the number of solids holding x (minus those
// subtracted). winding_solid returns the valid solid bounding {x : w(x) >= threshold}:
//   - threshold 1 on one self-intersecting mesh: the region of positive winding (repair);
//   - threshold 1 on the boundaries of several solids: their union, at once;
//   - threshold k: the points covered k times; a solid minus others: (A) - (B1) - ... >= 1.
//
// The steps are the Boolean's (morphex/boolean.h), run on the chain against itself:
//   chain      positions merged, degenerate triangles dropped, equal triangles summed (a
//              triangle and its reverse cancel);
//   pairs      triangle pairs whose boxes overlap, neighbours that only share corners skipped;
//   segments   the exact intersection of every pair, each point named once by exact position,
//              and segments crossing inside a facet split where three sheets meet;
//   cuts       a constrained Delaunay triangulation of every cut facet;
//   winding    patches (pieces joined across edges that exactly two pieces share), the exact
//              winding number in front of each patch by one ray cast, and behind it from the
//              weights of the coplanar stack it lies in;
//   assembly   the pieces where the threshold is crossed, oriented outward, coplanar stacks
//              emitted once, non-manifold features separated, coplanar faces merged.
// Everything is exact: every decision is an exact predicate and every new point an exact
// construction from the input points. The result is a valid solid (possibly empty).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "morphex/mesh.h"

namespace morphex {

struct WindingOptions {
  int threshold = 1;  // keep {x : w(x) >= threshold}
  // Merge neighbouring coplanar result triangles (as the Boolean does): no new points.
  bool merge_coplanar = true;
  // When set: every pair of triangles (indices into the surface) that meets other than at common
  // corners or along a common edge, for example MeshReport::self_intersecting_pairs of the same
  // surface. The arrangement then intersects only these instead of searching all pairs.
  const std::vector<std::pair<std::uint32_t, std::uint32_t>>* pairs = nullptr;
  // Optional plane labels, one per surface triangle: triangles with one label lie in one plane,
  // which spares the exact tests that would find it (walls, translated planar regions; triangles
  // with different labels may still be coplanar). With `result_planes`, each result triangle gets
  // the label of the surface triangle it lies on, for the next operation of a chain.
  const std::vector<std::uint32_t>* planes = nullptr;
  std::vector<std::uint32_t>* result_planes = nullptr;
  // Optional groups, one per surface triangle (kNoGroup for none): triangles of one group are
  // known to meet only at common corners or along common edges (a translated piece of a valid
  // solid's surface), so their pairs are not searched. Ignored when `pairs` is given.
  const std::vector<std::uint32_t>* groups = nullptr;
  static constexpr std::uint32_t kNoGroup = UINT32_MAX;
};

struct WindingStats {
  std::size_t input_faces = 0;
  std::size_t merged_vertices = 0;   // vertices at a position that an earlier vertex had
  std::size_t degenerate_faces = 0;  // triangles without area, dropped
  std::size_t cancelled_faces = 0;   // triangles whose weights summed to zero with equal ones
  std::size_t candidate_pairs = 0;
  std::size_t intersecting_pairs = 0;
  std::size_t cut_facets = 0;
  std::size_t triple_points = 0;  // where segments cross inside a facet
  std::size_t patches = 0;
  double seconds_chain = 0, seconds_pairs = 0, seconds_segments = 0, seconds_cuts = 0,
         seconds_winding = 0, seconds_assembly = 0;
};

// The valid solid bounding {x : w(x) >= options.threshold} for the chain of `surface`'s
// triangles with `weights` (one per triangle; empty: every weight 1). Precondition: the chain
// is closed (see above); an open chain has no winding number and gives an unspecified result.
Mesh winding_solid(const Mesh& surface, const std::vector<int>& weights = {},
                   const WindingOptions& options = {}, WindingStats* stats = nullptr);

// winding_solid within a work budget: nullopt, after the cheap first two steps, when the chain's
// triangles (once equal ones are summed) have more than `max_pairs_per_triangle` candidate pairs
// each on average. The arrangement's cost follows the pairs it intersects, so a caller with
// another way to the same solid (morphology's union tree) can take it instead of a deep one.
std::optional<Mesh> winding_solid_within(double max_pairs_per_triangle, const Mesh& surface,
                                         const std::vector<int>& weights = {},
                                         const WindingOptions& options = {},
                                         WindingStats* stats = nullptr);

}  // namespace morphex

// SPDX-License-Identifier: GPL-3.0-or-later
// Plain data between the steps of winding_solid (morphex/winding.h).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "boolean/boolean_internal.h"
#include "boolean/segments_internal.h"
#include "morphex/winding.h"
#include "tree/box_tree.h"

namespace morphex::detail {

using Corners3 = std::array<PointId, 3>;

// A chain ready for the arrangement: distinct positions, triangles with area, none twice (in
// either orientation), each with a non-zero weight.
struct Chain {
  Mesh soup;
  std::vector<int> weight;
  std::vector<std::uint32_t> plane;    // per soup triangle: its plane label
  std::vector<std::uint32_t> face_of;  // per input triangle: its soup triangle, or kNoFace
  static constexpr std::uint32_t kNoFace = UINT32_MAX;
};
// `planes`: optional labels of coplanar triangles (without: every triangle its own label).
Chain prepare_chain(const Mesh& surface, const std::vector<int>& weights,
                    const std::vector<std::uint32_t>* planes, WindingStats& stats);

// Every pair of distinct triangles whose boxes overlap, each once, in an order that depends only
// on the tree; with `keys`, not the pairs that share a key (TriangleTree::for_each_self_pair).
Pairs self_pairs(const TriangleTree& tree, const TriangleTree::TriangleKeys* keys = nullptr);
// Per soup triangle, its input triangles' group (WindingOptions::groups) as its key, when they
// all have the same one.
TriangleTree::TriangleKeys group_keys(const Chain& chain, const std::vector<std::uint32_t>& groups);
// The listed pairs of input triangles as pairs of soup triangles (dropped ones left out).
Pairs known_pairs(const Chain& chain,
                  const std::vector<std::pair<std::uint32_t, std::uint32_t>>& of_input);

// The soup's cuts from both roles of its pairs as one list per facet (x.cuts[0]), with segments
// that cross inside a facet split at their crossing (a point of three sheets, named once by exact
// position). Returns the number of such points.
std::size_t merge_soup_cuts(const Mesh& soup, Intersection& x);

// A face the result may take: an uncut facet of the soup, or a sub-triangle of a cut one.
struct Member {
  std::array<PointId, 3> v;  // oriented as its facet
  std::uint32_t facet;
};
std::vector<Member> members_of(const Mesh& soup, const Refined& refined, const Intersection& x);

// Per member: +1 keep it, -1 keep it reversed, 0 drop it. Adds sample points to the table.
std::vector<std::int8_t> select_by_winding(const Chain& chain, const TriangleTree& tree,
                                           const std::vector<Member>& members, Intersection& x,
                                           int threshold, WindingStats& stats);

}  // namespace morphex::detail

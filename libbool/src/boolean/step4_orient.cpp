// SPDX-License-Identifier: GPL-3.0-or-later
// Step 4: the segments oriented, gathered per facet.
//
// Each facet's cut collects, from its pairs in pair order, the intersection points (with the
// facet's edges they lie on), the segments to insert as constraints, and the coplanar facets of
// the other mesh. A transversal segment (its interior inside both open triangles) is also kept
// oriented by the seed's rule, so that step 6 knows on which side of it the other solid lies.
// Facets are independent and built in parallel; the order within a facet is the pair order, so
// the result does not depend on the thread count.
#include <tbb/parallel_for.h>

#include "boolean/segments_internal.h"
#include "containers/id_pairs.h"

namespace morphex::detail {

namespace {

// Adds one pair's outcome to the cut of its facet on `side`.
void add_outcome(FacetCut& cut, int side, const PairOutcome& out, std::uint32_t other_facet) {
  for (const PairPoint& p : out.points)
    cut.points.push_back({p.id, side == 0 ? p.edges_a : p.edges_b});
  auto add_segment = [&](PointId p, PointId q) {
    if (p != q) cut.segments.push_back(undirected(p, q));
  };
  const auto& pts = out.points;
  switch (out.kind) {
    case PairOutcome::Kind::Segment:
      add_segment(pts[0].id, pts[1].id);
      if (out.transversal && pts[0].id != pts[1].id) {
        // lo -> hi runs along Na x Nb, so the seed's sign s is positive: B's interior is on the
        // left of lo -> hi in ta, A's on the left of hi -> lo in tb.
        if (side == 0)
          cut.transversal.push_back({pts[0].id, pts[1].id});
        else
          cut.transversal.push_back({pts[1].id, pts[0].id});
      }
      break;
    case PairOutcome::Kind::Polygon:
      // Coplanar overlap: its boundary separates, in each facet, the part that lies on the other
      // surface from the rest.
      for (std::size_t j = 0; j < pts.size(); ++j)
        add_segment(pts[j].id, pts[(j + 1) % pts.size()].id);
      cut.coplanar_facets.push_back(other_facet);
      break;
    default:
      break;
  }
}

// The summary counts and the point flags (merged vertices, points on the other surface).
void summarize(Intersection& x, const std::vector<PairOutcome>& outcomes,
               const std::vector<PointId>& merged) {
  for (const PairOutcome& out : outcomes) {
    x.intersecting_pairs += out.kind != PairOutcome::Kind::None;
    x.coplanar_overlaps = x.coplanar_overlaps || out.kind == PairOutcome::Kind::Polygon;
  }
  const PointTable& table = x.points;
  x.flags.assign(table.size(), 0);
  for (PointId id : merged) x.flags[id] |= kMerged;
  for (int side = 0; side < 2; ++side)
    for (const auto& [facet, cut] : x.cuts[side])
      for (const CutPoint& p : cut.points) x.flags[p.id] |= kOnSurface;
  for (PointId id = PointId(table.num_inputs()); id < table.size(); ++id)
    if (x.flags[id] & kOnSurface) ++x.constructed_points;
}

// The per-facet cuts of both sides from the pairs' outcomes (final ids given), built per facet in
// parallel from its pairs in pair order.
void build_cuts(Intersection& x, const Pairs& pairs, const std::vector<PairOutcome>& outcomes) {
  const std::size_t np = pairs.size();
  for (int side = 0; side < 2; ++side) {
    std::vector<std::pair<std::uint32_t, std::uint32_t>> facet_pair;  // (facet, pair)
    for (std::size_t k = 0; k < np; ++k)
      if (outcomes[k].kind != PairOutcome::Kind::None)
        facet_pair.emplace_back(side == 0 ? pairs[k].first : pairs[k].second, std::uint32_t(k));
    sort_id_pairs(facet_pair.begin(), facet_pair.end());
    std::vector<std::size_t> group;
    for (std::size_t i = 0; i < facet_pair.size(); ++i)
      if (i == 0 || facet_pair[i].first != facet_pair[i - 1].first) group.push_back(i);
    group.push_back(facet_pair.size());
    auto& cuts = x.cuts[side];
    cuts.resize(group.size() - 1);
    tbb::parallel_for(std::size_t(0), cuts.size(), [&](std::size_t g) {
      cuts[g].first = facet_pair[group[g]].first;
      for (std::size_t i = group[g]; i < group[g + 1]; ++i) {
        const std::uint32_t k = facet_pair[i].second;
        add_outcome(cuts[g].second, side, outcomes[k],
                    side == 0 ? pairs[k].second : pairs[k].first);
      }
    });
  }
}

}  // namespace

Intersection orient_segments(PairFindings&& found) {
  Intersection& x = found.x;
  build_cuts(x, found.pairs, found.outcomes);
  summarize(x, found.outcomes, found.merged);
  return std::move(x);
}

}  // namespace morphex::detail

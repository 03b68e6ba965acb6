// SPDX-License-Identifier: GPL-3.0-or-later
// The cuts of a soup: what every other triangle leaves on each facet, as one list per facet.
//
// Two solids' surfaces meet along curves that never cross inside a facet. In a soup, three sheets
// can meet at a point: on each of their facets, the segments left by the two others cross there.
// The crossing is constructed exactly on the facet (the 3D line of one segment meeting the plane
// through the other parallel to the facet's projection axis) and named by exact position, so the
// three facets that construct it in their own way share one point; both segments are split there,
// which is what the constrained triangulation needs (its constraints may touch, never cross).
#include <tbb/parallel_for.h>

#include <algorithm>
#include <numeric>

#include "winding/winding_internal.h"

namespace morphex::detail {
namespace {

// The cuts of both roles, merged per facet (each list is sorted by facet).
std::vector<std::pair<std::uint32_t, FacetCut>> merged_roles(Intersection& x) {
  std::vector<std::pair<std::uint32_t, FacetCut>> merged;
  auto& first = x.cuts[0];
  auto& second = x.cuts[1];
  merged.reserve(first.size() + second.size());
  std::size_t i = 0, j = 0;
  while (i < first.size() || j < second.size()) {
    if (j == second.size() || (i < first.size() && first[i].first < second[j].first)) {
      merged.push_back(std::move(first[i++]));
    } else if (i == first.size() || second[j].first < first[i].first) {
      merged.push_back(std::move(second[j++]));
    } else {
      FacetCut& into = first[i].second;
      FacetCut& from = second[j++].second;
      into.points.insert(into.points.end(), from.points.begin(), from.points.end());
      into.segments.insert(into.segments.end(), from.segments.begin(), from.segments.end());
      into.coplanar_facets.insert(into.coplanar_facets.end(), from.coplanar_facets.begin(),
                                  from.coplanar_facets.end());
      merged.push_back(std::move(first[i++]));
    }
  }
  first.clear();
  second.clear();
  for (auto& [facet, cut] : merged) {
    cut.transversal.clear();  // the seed's labels are for two solids; a soup is wound instead
    std::sort(cut.segments.begin(), cut.segments.end());
    cut.segments.erase(std::unique(cut.segments.begin(), cut.segments.end()), cut.segments.end());
    std::sort(cut.coplanar_facets.begin(), cut.coplanar_facets.end());
    cut.coplanar_facets.erase(std::unique(cut.coplanar_facets.begin(), cut.coplanar_facets.end()),
                              cut.coplanar_facets.end());
  }
  return merged;
}

// A proper crossing of segments i and j of one facet, at the construction `recipe`.
struct Crossing {
  std::uint32_t i, j;
  Recipe recipe;
  PointId id = 0;
};

// The proper crossings among the segments of one facet, seen along its projection axis.
std::vector<Crossing> crossings_of(const PointTable& table, const Corners3& corners,
                                   const FacetCut& cut) {
  std::vector<Crossing> out;
  const auto& s = cut.segments;
  if (s.size() < 2) return out;
  const int dropped = table.dominant_axis(corners[0], corners[1], corners[2]);
  const int u = dropped == 0 ? 1 : 0, v = dropped == 2 ? 1 : 2;
  // 2D boxes first: most segments of a facet are far apart.
  std::vector<std::array<double, 4>> box(s.size());
  for (std::size_t k = 0; k < s.size(); ++k) {
    const ApproxPoint &p = table.approx(s[k].first), &q = table.approx(s[k].second);
    box[k] = {std::min(p.cartesian(u).inf(), q.cartesian(u).inf()),
              std::max(p.cartesian(u).sup(), q.cartesian(u).sup()),
              std::min(p.cartesian(v).inf(), q.cartesian(v).inf()),
              std::max(p.cartesian(v).sup(), q.cartesian(v).sup())};
  }
  auto o = [&](PointId a, PointId b, PointId c) { return table.orientation_2(dropped, a, b, c); };
  for (std::uint32_t i = 0; i < s.size(); ++i)
    for (std::uint32_t j = i + 1; j < s.size(); ++j) {
      const auto [a, b] = s[i];
      const auto [c, d] = s[j];
      if (a == c || a == d || b == c || b == d) continue;
      if (box[i][1] < box[j][0] || box[j][1] < box[i][0] || box[i][3] < box[j][2] ||
          box[j][3] < box[i][2])
        continue;
      const CGAL::Sign oc = o(a, b, c), od = o(a, b, d);
      if (oc == CGAL::ZERO || od == CGAL::ZERO || oc == od) continue;
      const CGAL::Sign oa = o(c, d, a), ob = o(c, d, b);
      if (oa == CGAL::ZERO || ob == CGAL::ZERO || oa == ob) continue;
      Recipe r;
      r.kind = Recipe::Kind::EdgeProjectedLine;
      r.dropped = std::int8_t(dropped);
      r.p = a, r.q = b, r.a = c, r.b = d, r.c = c;
      out.push_back({i, j, r});
    }
  return out;
}

// Segment (a, b) split at the points `inner` strictly between its ends.
void split_segment(const PointTable& table, PointId a, PointId b, std::vector<PointId>& inner,
                   std::vector<Edge>& out) {
  // Along the segment, the points are ordered by any coordinate in which a and b differ.
  int axis = 0;
  while (axis < 2 && table.compare(axis, a, b) == CGAL::EQUAL) ++axis;
  const bool rising = table.compare(axis, a, b) == CGAL::SMALLER;
  std::sort(inner.begin(), inner.end(), [&](PointId p, PointId q) {
    const CGAL::Comparison_result c = table.compare(axis, p, q);
    return rising ? c == CGAL::SMALLER : c == CGAL::LARGER;
  });
  inner.erase(std::unique(inner.begin(), inner.end()), inner.end());
  PointId from = a;
  for (PointId m : inner) {
    out.push_back(undirected(from, m));
    from = m;
  }
  out.push_back(undirected(from, b));
}

}  // namespace

std::size_t merge_soup_cuts(const Mesh& soup, Intersection& x) {
  auto cuts = merged_roles(x);
  PointTable& table = x.points;
  auto corners = [&](std::uint32_t facet) {
    const Triangle& t = soup.triangles[facet];
    return Corners3{x.vertex_id(0, t[0]), x.vertex_id(0, t[1]), x.vertex_id(0, t[2])};
  };
  std::vector<std::vector<Crossing>> crossings(cuts.size());
  for_each_upward(cuts.size(), [&](std::size_t k) {
    crossings[k] = crossings_of(table, corners(cuts[k].first), cuts[k].second);
  });
  std::size_t count = 0;
  for (auto& list : crossings)
    for (Crossing& c : list) {
      c.id = table.add(c.recipe);
      ++count;
    }
  if (count > 0) {
    // Each crossing is constructed by every facet through it: name them by position, with the
    // points they may coincide with (vertices and the points already in cuts).
    std::vector<PointId> ids;
    for (PointId id = 0; id < table.num_inputs(); ++id)
      if (x.vertex_rep[id] == id) ids.push_back(id);
    for (const auto& [facet, cut] : cuts)
      for (const CutPoint& p : cut.points)
        if (!table.is_input(p.id)) ids.push_back(p.id);
    for (const auto& list : crossings)
      for (const Crossing& c : list) ids.push_back(c.id);
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
    const std::vector<PointId> first = coincident_representatives(table, ids);
    std::vector<PointId> named(table.size());
    std::iota(named.begin(), named.end(), PointId(0));
    for (std::size_t i = 0; i < ids.size(); ++i) named[ids[i]] = first[i];
    tbb::parallel_for(std::size_t(0), cuts.size(), [&](std::size_t k) {
      FacetCut& cut = cuts[k].second;
      for (CutPoint& p : cut.points) p.id = named[p.id];
      std::vector<std::vector<PointId>> inner(cut.segments.size());
      for (const Crossing& c : crossings[k]) {
        const PointId id = named[c.id];
        cut.points.push_back({id, 0});
        for (std::uint32_t s : {c.i, c.j})
          if (id != cut.segments[s].first && id != cut.segments[s].second) inner[s].push_back(id);
      }
      std::vector<Edge> segments;
      for (std::size_t s = 0; s < cut.segments.size(); ++s) {
        const PointId a = named[cut.segments[s].first], b = named[cut.segments[s].second];
        if (a == b) continue;
        if (inner[s].empty())
          segments.push_back(undirected(a, b));
        else
          split_segment(table, a, b, inner[s], segments);
      }
      std::sort(segments.begin(), segments.end());
      segments.erase(std::unique(segments.begin(), segments.end()), segments.end());
      cut.segments = std::move(segments);
    });
  }
  x.cuts[0] = std::move(cuts);
  x.flags.assign(table.size(), 0);
  for (const auto& [facet, cut] : x.cuts[0])
    for (const CutPoint& p : cut.points) x.flags[p.id] |= kOnSurface;
  return count;
}

}  // namespace morphex::detail

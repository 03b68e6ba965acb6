// SPDX-License-Identifier: GPL-3.0-or-later
// Step 6: labels. Sub-triangles are grouped into patches: connected without crossing an edge that
// lies on the other surface. The open interior of a patch never meets the other surface except by
// lying on it (coplanar overlaps are bounded by constraints), so one label decides all of it.
// A patch bordered by a transversal segment takes the seed's label from the segment's
// orientation (no construction, no search); every other patch (contacts along edges or at
// vertices, coplanar overlaps, components the other mesh never touches: nested or disjoint
// solids, which the seed's propagation could not reach) gets one exact test: coplanar patches
// compare normals with the facet they lie on, the others take the exact ray-cast winding number
// of a point inside one of their sub-triangles.
#include <algorithm>
#include <memory>
#include <type_traits>

#include "boolean_internal.h"
#include "filtered.h"
#include "morphex/spatial.h"
#include "projection_traits.h"
#include "union_find.h"

namespace morphex::detail {

namespace {

// Whether the centroid of pqr lies in the closed triangle abc, all in one plane seen along the
// coordinate axis `dropped`. det(a, b, centroid) = (det(a, b, p) + det(a, b, q) + det(a, b, r)) /
// 3, so no point is constructed; the sub-triangle lies entirely inside or outside the overlap, so
// its centroid is rarely near an edge and the interval stage nearly always decides.
template <int dropped>
bool centroid_in_triangle(const Point& a, const Point& b, const Point& c, const Point& p,
                          const Point& q, const Point& r) {
  constexpr int u = dropped == 0 ? 1 : 0, v = dropped == 2 ? 1 : 2;
  auto side = [&](const Point& e0, const Point& e1) {
    return filtered_sign(
        [](const auto& e0, const auto& e1, const auto& p, const auto& q, const auto& r) {
          // Concrete numbers, not expression templates: coordinates may be returned by value.
          using Number = std::decay_t<decltype(p.cartesian(0))>;
          auto det = [&](const auto& x) {
            const Number du = e1.cartesian(u) - e0.cartesian(u),
                         dv = e1.cartesian(v) - e0.cartesian(v);
            const Number xu = x.cartesian(u) - e0.cartesian(u),
                         xv = x.cartesian(v) - e0.cartesian(v);
            return Number(du * xv - dv * xu);
          };
          return Number(det(p) + det(q) + det(r));
        },
        e0, e1, p, q, r);
  };
  const CGAL::Sign turn = FilteredProjectedOrientation<dropped>()(a, b, c);
  for (const auto& [e0, e1] : {std::pair<const Point*, const Point*>{&a, &b}, {&b, &c}, {&c, &a}})
    if (side(*e0, *e1) == -turn) return false;
  return true;
}

// The label of one sub-triangle, by an exact test on its centroid.
Label label_of(const SubTriangle& s, const Mesh& mesh, const Mesh& other, int side,
               const Intersection& x, const TriangleTree& other_tree) {
  const Point &p = x.points[s.v[0]], &q = x.points[s.v[1]], &r = x.points[s.v[2]];
  const auto cut = x.cuts[side].find(s.facet);
  if (cut != x.cuts[side].end() && !cut->second.coplanar_facets.empty()) {
    const Triangle& f = mesh.triangles[s.facet];
    const Point &a = mesh.points[f[0]], &b = mesh.points[f[1]], &c = mesh.points[f[2]];
    const int dropped = dominant_axis(a, b, c);
    for (std::uint32_t t : cut->second.coplanar_facets) {
      const Triangle& g = other.triangles[t];
      const Point &d = other.points[g[0]], &e = other.points[g[1]], &h = other.points[g[2]];
      const bool inside = dropped == 0   ? centroid_in_triangle<0>(d, e, h, p, q, r)
                          : dropped == 1 ? centroid_in_triangle<1>(d, e, h, p, q, r)
                                         : centroid_in_triangle<2>(d, e, h, p, q, r);
      if (!inside) continue;
      // Same or opposite normals: the sign of ((b - a) x (c - a)) . ((e - d) x (h - d)).
      const auto same = filtered_sign(
          [](const auto& a, const auto& b, const auto& c, const auto& d, const auto& e,
             const auto& h) {
            return CGAL::cross_product(b - a, c - a) * CGAL::cross_product(e - d, h - d);
          },
          a, b, c, d, e, h);
      return same == CGAL::POSITIVE ? Label::CoplanarSame : Label::CoplanarOpposite;
    }
  }
  return winding_number(other, other_tree, CGAL::centroid(p, q, r)) != 0 ? Label::Inside
                                                                         : Label::Outside;
}

}  // namespace

namespace {

// (key, face) records sorted by key: a flat multimap without one allocation per edge.
using EdgeRecords = std::vector<std::pair<std::uint64_t, std::uint32_t>>;

template <class Visit>
void for_each_with_key(const EdgeRecords& records, std::uint64_t key, Visit&& visit) {
  auto it = std::lower_bound(records.begin(), records.end(), std::make_pair(key, std::uint32_t(0)));
  for (; it != records.end() && it->first == key; ++it) visit(it->second);
}

}  // namespace

std::vector<Label> classify(const Mesh& mesh, const Mesh& other, int side, const Refined& refined,
                            const Intersection& x, ClassifyCounts& counts) {
  const std::size_t n = refined.triangles.size();
  // Patches: sub-triangles joined across every edge that does not lie on the other surface.
  std::vector<std::uint64_t> barrier;
  barrier.reserve(refined.on_other_surface.size());
  for (const Edge& e : refined.on_other_surface) barrier.push_back(edge_key(e.first, e.second));
  std::sort(barrier.begin(), barrier.end());
  EdgeRecords undirected_edges;
  undirected_edges.reserve(3 * n);
  for (std::uint32_t i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) {
      const Edge e = undirected(refined.triangles[i].v[k], refined.triangles[i].v[(k + 1) % 3]);
      undirected_edges.emplace_back(edge_key(e.first, e.second), i);
    }
  std::sort(undirected_edges.begin(), undirected_edges.end());
  UnionFind patches(n);
  for (std::size_t i = 0; i < undirected_edges.size();) {
    std::size_t j = i + 1;
    while (j < undirected_edges.size() && undirected_edges[j].first == undirected_edges[i].first)
      ++j;
    if (!std::binary_search(barrier.begin(), barrier.end(), undirected_edges[i].first))
      for (std::size_t k = i + 1; k < j; ++k)
        patches.join(undirected_edges[k].second, undirected_edges[i].second);
    i = j;
  }

  // The seed's labels: the sub-triangle on the left of an oriented transversal segment is inside
  // the other solid, the one on its right outside. A segment split by further points in the CDT
  // is simply not used; its patches fall back to the ray cast.
  std::vector<std::int8_t> ruled(n, -1);
  {
    EdgeRecords directed;  // edges of the sub-triangles of cut facets
    for (std::uint32_t i = 0; i < n; ++i) {
      const SubTriangle& s = refined.triangles[i];
      if (!x.cuts[side].count(s.facet)) continue;
      for (int k = 0; k < 3; ++k) directed.emplace_back(edge_key(s.v[k], s.v[(k + 1) % 3]), i);
    }
    std::sort(directed.begin(), directed.end());
    auto mark = [&](PointId from, PointId to, std::uint32_t facet, Label label) {
      for_each_with_key(directed, edge_key(from, to), [&](std::uint32_t i) {
        if (refined.triangles[i].facet == facet) ruled[i] = std::int8_t(label);
      });
    };
    for (const auto& [facet, cut] : x.cuts[side])
      for (const OrientedSegment& s : cut.transversal) {
        mark(s.from, s.to, facet, Label::Inside);
        mark(s.to, s.from, facet, Label::Outside);
      }
  }

  // One label per patch: the rule when a segment borders it, else one exact test on the patch's
  // first sub-triangle (so the answer does not depend on any traversal order).
  counts = {};
  std::vector<std::uint32_t> root(n);
  std::vector<std::int8_t> patch_rule(n, -1);
  for (std::uint32_t i = 0; i < n; ++i) {
    root[i] = patches.find(i);
    if (ruled[i] < 0) continue;
    std::int8_t& rule = patch_rule[root[i]];
    if (rule >= 0 && rule != ruled[i]) ++counts.rule_conflicts;
    rule = ruled[i];
  }
  std::vector<Label> labels(n);
  std::vector<std::int8_t> patch_label(n, -1);
  std::unique_ptr<TriangleTree> other_tree;
  for (std::uint32_t i = 0; i < n; ++i) {
    std::int8_t& label = patch_label[root[i]];
    if (label < 0) {  // i is the patch's first sub-triangle
      ++counts.patches;
      if (patch_rule[root[i]] >= 0) {
        label = patch_rule[root[i]];
        ++counts.by_orientation_rule;
      } else {
        if (!other_tree && !other.empty()) other_tree = std::make_unique<TriangleTree>(other);
        label = std::int8_t(
            other.empty() ? Label::Outside
                          : label_of(refined.triangles[i], mesh, other, side, x, *other_tree));
        ++counts.by_ray_cast;
      }
    }
    labels[i] = Label(label);
  }
  return labels;
}

}  // namespace morphex::detail

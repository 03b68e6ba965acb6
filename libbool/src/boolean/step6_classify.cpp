// SPDX-License-Identifier: GPL-3.0-or-later
// Step 6: labels. Facets no cut touches and the sub-triangles of cut facets are grouped into
// patches: connected without crossing an edge that lies on the other surface. The open interior
// of a patch never meets the other surface except by lying on it (coplanar overlaps are bounded by
// constraints), so one label decides all of it.
//
// Patches are found in linear time without any edge table: the fan of a vertex that is not on the
// other surface lies on one side of it, so facets and sub-triangles are joined through their free
// vertices; inside a cut facet the CDT joins its sub-triangles; and the rare unconstrained edge
// between two points of the other surface on a facet's boundary joins the facets on its sides.
//
// A patch bordered by a transversal segment takes the seed's label from the segment's
// orientation (no construction, no search); every other patch (contacts along edges or at
// vertices, coplanar overlaps, components the other mesh never touches: nested or disjoint
// solids, which the seed's propagation could not reach) gets one exact test: coplanar patches
// compare normals with the facet they lie on, the others take the exact ray-cast winding number
// of a point inside one of their triangles.
#include <algorithm>
#include <type_traits>

#include "boolean/boolean_internal.h"
#include "exact/filtered.h"
#include "exact/projection_traits.h"
#include "tree/box_tree.h"

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

// The label of the triangle pqr lying on `facet` of `mesh`, by an exact test on its centroid.
Label label_of(const Point& p, const Point& q, const Point& r, std::uint32_t facet,
               const Mesh& mesh, const Mesh& other, int side, const Intersection& x,
               const TriangleTree& other_tree) {
  const FacetCut* cut = x.cut(side, facet);
  if (cut && !cut->coplanar_facets.empty()) {
    const Triangle& f = mesh.triangles[facet];
    const Point &a = mesh.points[f[0]], &b = mesh.points[f[1]], &c = mesh.points[f[2]];
    const int dropped = dominant_axis(a, b, c);
    for (std::uint32_t t : cut->coplanar_facets) {
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

UnionFind connect_patches(const Mesh& mesh, int side, const Refined& refined, const Intersection& x,
                          const std::vector<std::uint32_t>* component) {
  const std::size_t nf = mesh.num_triangles(), ns = refined.triangles.size();
  const std::size_t vertex_node = nf + ns;
  UnionFind patches(vertex_node + x.points.num_inputs());
  std::vector<std::uint8_t> cut(nf, 0);
  for (std::uint32_t f : refined.facets) cut[f] = 1;
  for (std::uint32_t f = 0; f < nf; ++f) {
    if (cut[f]) continue;
    for (VertexIndex v : mesh.triangles[f]) {
      const PointId id = x.vertex_id(side, v);
      if (!x.special(id)) patches.join(f, std::uint32_t(vertex_node + id));
    }
  }
  for (std::uint32_t i = 0; i < ns; ++i) {
    const std::uint32_t node = std::uint32_t(nf + i);
    patches.join(node, std::uint32_t(nf + refined.joined[i]));
    for (PointId id : refined.triangles[i].v)
      if (x.points.is_input(id) && !x.special(id))
        patches.join(node, std::uint32_t(vertex_node + id));
  }
  // The same boundary edge seen from the facets on both sides.
  std::vector<std::pair<std::uint64_t, std::uint32_t>> open = refined.open_boundary;
  auto group = [&](std::uint32_t sub) {
    return component ? (*component)[refined.triangles[sub].facet] : 0u;
  };
  std::sort(open.begin(), open.end(), [&](const auto& l, const auto& r) {
    return std::make_pair(l.first, group(l.second)) < std::make_pair(r.first, group(r.second));
  });
  for (std::size_t i = 1; i < open.size(); ++i)
    if (open[i].first == open[i - 1].first && group(open[i].second) == group(open[i - 1].second))
      patches.join(std::uint32_t(nf + open[i].second), std::uint32_t(nf + open[i - 1].second));
  return patches;
}

Labels classify(const Mesh& mesh, const Mesh& other, int side, const Refined& refined,
                const Intersection& x, OperandTrees& trees, ClassifyCounts& counts) {
  const std::size_t nf = mesh.num_triangles(), ns = refined.triangles.size();
  UnionFind patches = connect_patches(mesh, side, refined, x);
  const std::size_t nodes = patches.parent.size();

  // The seed's labels, gathered per patch.
  counts = {};
  std::vector<std::int8_t> patch_rule(nodes, -1);
  for (std::uint32_t i = 0; i < ns; ++i) {
    if (refined.rule[i] < 0) continue;
    std::int8_t& rule = patch_rule[patches.find(std::uint32_t(nf + i))];
    if (rule >= 0 && rule != refined.rule[i]) ++counts.rule_conflicts;
    rule = refined.rule[i];
  }

  // One label per patch: the rule when a segment borders it, else one exact test on the patch's
  // first facet or sub-triangle (so the answer does not depend on any traversal order).
  std::vector<std::uint8_t> cut(nf, 0);
  for (std::uint32_t f : refined.facets) cut[f] = 1;
  std::vector<std::int8_t> patch_label(nodes, -1);
  auto label = [&](std::uint32_t node, auto&& test) {
    std::int8_t& l = patch_label[patches.find(node)];
    if (l < 0) {
      ++counts.patches;
      const std::int8_t rule = patch_rule[patches.find(node)];
      if (rule >= 0) {
        l = rule;
        ++counts.by_orientation_rule;
      } else {
        l = std::int8_t(other.empty() ? Label::Outside : test(trees.of(1 - side, other)));
        ++counts.by_ray_cast;
      }
    }
    return Label(l);
  };
  Labels labels;
  labels.facet.assign(nf, Label::Outside);
  labels.sub.resize(ns);
  for (std::uint32_t f = 0; f < nf; ++f) {
    if (cut[f]) continue;
    labels.facet[f] = label(f, [&](const TriangleTree& tree) {
      const Triangle& t = mesh.triangles[f];
      return label_of(mesh.points[t[0]], mesh.points[t[1]], mesh.points[t[2]], f, mesh, other, side,
                      x, tree);
    });
  }
  for (std::uint32_t i = 0; i < ns; ++i) {
    const SubTriangle& s = refined.triangles[i];
    labels.sub[i] = label(std::uint32_t(nf + i), [&](const TriangleTree& tree) {
      return label_of(x.points.point(s.v[0]), x.points.point(s.v[1]), x.points.point(s.v[2]),
                      s.facet, mesh, other, side, x, tree);
    });
  }
  return labels;
}

}  // namespace morphex::detail

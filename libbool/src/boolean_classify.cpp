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
#include <unordered_map>
#include <unordered_set>

#include "boolean_internal.h"
#include "morphex/spatial.h"

namespace morphex::detail {

namespace {

Kernel::Triangle_3 input_triangle(const Mesh& m, std::uint32_t t) {
  const Triangle& f = m.triangles[t];
  return {m.points[f[0]], m.points[f[1]], m.points[f[2]]};
}

// The label of one sub-triangle, by an exact test on its centroid.
Label label_of(const SubTriangle& s, const Mesh& mesh, const Mesh& other, int side,
               const Intersection& x, const TriangleTree& other_tree) {
  const Point centroid = CGAL::centroid(x.points[s.v[0]], x.points[s.v[1]], x.points[s.v[2]]);
  const auto cut = x.cuts[side].find(s.facet);
  if (cut != x.cuts[side].end()) {
    const Kernel::Vector_3 normal =
        input_triangle(mesh, s.facet).supporting_plane().orthogonal_vector();
    for (std::uint32_t t : cut->second.coplanar_facets) {
      const Kernel::Triangle_3 facet = input_triangle(other, t);
      if (!facet.has_on(centroid)) continue;
      const auto same = CGAL::sign(normal * facet.supporting_plane().orthogonal_vector());
      return same == CGAL::POSITIVE ? Label::CoplanarSame : Label::CoplanarOpposite;
    }
  }
  return winding_number(other, other_tree, centroid) != 0 ? Label::Inside : Label::Outside;
}

}  // namespace

std::vector<Label> classify(const Mesh& mesh, const Mesh& other, int side, const Refined& refined,
                            const Intersection& x, ClassifyCounts& counts) {
  const std::size_t n = refined.triangles.size();
  std::unordered_set<Edge, EdgeHash> barrier(refined.on_other_surface.begin(),
                                             refined.on_other_surface.end());
  std::unordered_map<Edge, std::vector<std::uint32_t>, EdgeHash> faces_of_edge;
  faces_of_edge.reserve(n * 2);
  for (std::uint32_t i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) {
      const Edge e = undirected(refined.triangles[i].v[k], refined.triangles[i].v[(k + 1) % 3]);
      if (!barrier.count(e)) faces_of_edge[e].push_back(i);
    }

  // The seed's labels: the sub-triangle on the left of an oriented transversal segment is inside
  // the other solid, the one on its right outside. A segment split by further points in the CDT
  // is simply not used; its patches fall back to the ray cast.
  std::vector<std::int8_t> ruled(n, -1);
  {
    std::unordered_map<Edge, std::vector<std::uint32_t>, EdgeHash> directed;  // (from, to) -> faces
    for (std::uint32_t i = 0; i < n; ++i) {
      const SubTriangle& s = refined.triangles[i];
      if (!x.cuts[side].count(s.facet)) continue;
      for (int k = 0; k < 3; ++k) directed[{s.v[k], s.v[(k + 1) % 3]}].push_back(i);
    }
    auto mark = [&](PointId from, PointId to, std::uint32_t facet, Label label) {
      const auto it = directed.find({from, to});
      if (it == directed.end()) return;
      for (std::uint32_t i : it->second)
        if (refined.triangles[i].facet == facet) ruled[i] = std::int8_t(label);
    };
    for (const auto& [facet, cut] : x.cuts[side])
      for (const OrientedSegment& s : cut.transversal) {
        mark(s.from, s.to, facet, Label::Inside);
        mark(s.to, s.from, facet, Label::Outside);
      }
  }

  std::vector<Label> labels(n);
  std::vector<bool> seen(n, false);
  std::vector<std::uint32_t> stack, members;
  std::unique_ptr<TriangleTree> other_tree;
  counts = {};
  for (std::uint32_t seed = 0; seed < n; ++seed) {
    if (seen[seed]) continue;
    ++counts.patches;
    members.clear();
    seen[seed] = true;
    stack.push_back(seed);
    std::int8_t rule = -1;
    while (!stack.empty()) {
      const std::uint32_t i = stack.back();
      stack.pop_back();
      members.push_back(i);
      if (ruled[i] >= 0) {
        if (rule >= 0 && rule != ruled[i]) ++counts.rule_conflicts;
        rule = ruled[i];
      }
      for (int k = 0; k < 3; ++k) {
        const Edge e = undirected(refined.triangles[i].v[k], refined.triangles[i].v[(k + 1) % 3]);
        const auto it = faces_of_edge.find(e);
        if (it == faces_of_edge.end()) continue;
        for (std::uint32_t j : it->second)
          if (!seen[j]) {
            seen[j] = true;
            stack.push_back(j);
          }
      }
    }
    Label label;
    if (rule >= 0) {
      label = Label(rule);
      ++counts.by_orientation_rule;
    } else {
      if (!other_tree) other_tree = std::make_unique<TriangleTree>(other);
      label = other.empty() ? Label::Outside
                            : label_of(refined.triangles[seed], mesh, other, side, x, *other_tree);
      ++counts.by_ray_cast;
    }
    for (std::uint32_t i : members) labels[i] = label;
  }
  return labels;
}

}  // namespace morphex::detail

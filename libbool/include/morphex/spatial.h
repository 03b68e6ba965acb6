// SPDX-License-Identifier: GPL-3.0-or-later
// Spatial building blocks shared by the checks and the Boolean: a flat bounding-volume hierarchy
// over triangle boxes, exact improper-contact test between two triangles, exact point-in-solid.
#pragma once

#include <CGAL/Bbox_3.h>

#include <cstdint>
#include <vector>

#include "morphex/mesh.h"

namespace morphex {

// Boxes come from the interval approximation of the exact points, so they are conservative.
class TriangleTree {
 public:
  explicit TriangleTree(const Mesh& mesh);

  // Calls f(triangle index) for every triangle whose box overlaps `box`.
  template <class F>
  void for_each_overlap(const CGAL::Bbox_3& box, F&& f) const {
    traverse([&](const CGAL::Bbox_3& b) { return CGAL::do_overlap(b, box); }, f);
  }

  // Calls f(triangle index) for every triangle whose box the ray origin + t * direction (t >= 0)
  // may cross (conservative).
  template <class F>
  void for_each_on_ray(const CGAL::Bbox_3& origin, const std::array<double, 3>& direction,
                       F&& f) const;

  const CGAL::Bbox_3& box(std::uint32_t t) const { return boxes_[t]; }
  const std::vector<CGAL::Bbox_3>& boxes() const { return boxes_; }

 private:
  struct Node {
    CGAL::Bbox_3 box;
    std::uint32_t first = 0;  // first child (inner node) or first entry of order_ (leaf)
    std::uint32_t count = 0;  // number of triangles in a leaf, 0 for inner nodes
  };
  void build(std::uint32_t node, std::uint32_t begin, std::uint32_t end, int depth);
  // Visits the leaves' triangles whose boxes pass `keep`, pruning subtrees whose box fails it.
  template <class Keep, class F>
  void traverse(Keep&& keep, F&& f) const {
    if (nodes_.empty()) return;
    std::uint32_t stack[64];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const Node& node = nodes_[stack[--top]];
      if (!keep(node.box)) continue;
      if (node.count > 0) {
        for (std::uint32_t i = node.first; i < node.first + node.count; ++i)
          if (keep(boxes_[order_[i]])) f(order_[i]);
      } else {
        stack[top++] = node.first;
        stack[top++] = node.first + 1;
      }
    }
  }
  bool ray_may_hit(const CGAL::Bbox_3& box, const CGAL::Bbox_3& origin,
                   const std::array<double, 3>& direction) const;

  std::vector<CGAL::Bbox_3> boxes_;
  std::vector<std::uint32_t> order_;
  std::vector<Node> nodes_;
};

template <class F>
void TriangleTree::for_each_on_ray(const CGAL::Bbox_3& origin,
                                   const std::array<double, 3>& direction, F&& f) const {
  traverse([&](const CGAL::Bbox_3& b) { return ray_may_hit(b, origin, direction); }, f);
}

// Kernel triangle of a mesh face.
Kernel::Triangle_3 triangle_of(const Mesh& mesh, std::uint32_t t);

// True when the closed triangles i and j of `mesh` meet in anything other than nothing, one
// common vertex or one common edge, "common" meaning equal coordinates (so that separated
// non-manifold features, duplicated vertices at one position, are allowed to touch).
bool triangles_intersect_improperly(const Mesh& mesh, std::uint32_t i, std::uint32_t j);

// Exact winding number of `closed_mesh` around q, by ray casting with exact predicates; rays that
// graze an edge, a vertex or a face plane are replaced by another generic direction.
// Precondition: q is not on the surface (throws std::domain_error if it is).
int winding_number(const Mesh& closed_mesh, const TriangleTree& tree, const Point& q);

}  // namespace morphex

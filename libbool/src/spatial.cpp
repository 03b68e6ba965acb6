// SPDX-License-Identifier: GPL-3.0-or-later
#include "morphex/spatial.h"

#include <CGAL/intersections.h>

#include <algorithm>
#include <numeric>
#include <stdexcept>
#include <type_traits>

#include "filtered.h"

namespace morphex {

namespace {
constexpr std::uint32_t kLeafSize = 4;

double centre(const CGAL::Bbox_3& b, int axis) {
  return 0.5 * (b.min(axis) + b.max(axis));
}
}  // namespace

Kernel::Triangle_3 triangle_of(const Mesh& mesh, std::uint32_t t) {
  const Triangle& f = mesh.triangles[t];
  return {mesh.points[f[0]], mesh.points[f[1]], mesh.points[f[2]]};
}

TriangleTree::TriangleTree(const Mesh& mesh) {
  const std::uint32_t n = std::uint32_t(mesh.num_triangles());
  if (n == 0) return;
  boxes_.reserve(n);
  for (const Triangle& f : mesh.triangles)
    boxes_.push_back(mesh.points[f[0]].bbox() + mesh.points[f[1]].bbox() +
                     mesh.points[f[2]].bbox());
  order_.resize(n);
  std::iota(order_.begin(), order_.end(), 0);
  nodes_.reserve(2 * (n / kLeafSize + 1));
  nodes_.emplace_back();
  build(0, 0, n, 0);
}

// Children of an inner node are stored side by side, so the node keeps only the first's index.
void TriangleTree::build(std::uint32_t node, std::uint32_t begin, std::uint32_t end, int depth) {
  CGAL::Bbox_3 box = boxes_[order_[begin]];
  for (std::uint32_t i = begin + 1; i < end; ++i) box += boxes_[order_[i]];
  nodes_[node].box = box;
  // Depth is bounded so that the fixed traversal stack (64 entries) cannot overflow.
  if (end - begin <= kLeafSize || depth >= 30) {
    nodes_[node].first = begin;
    nodes_[node].count = end - begin;
    return;
  }
  int axis = 0;
  for (int a = 1; a < 3; ++a)
    if (box.max(a) - box.min(a) > box.max(axis) - box.min(axis)) axis = a;
  const std::uint32_t mid = begin + (end - begin) / 2;
  std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end,
                   [&](std::uint32_t x, std::uint32_t y) {
                     return centre(boxes_[x], axis) < centre(boxes_[y], axis);
                   });
  const std::uint32_t left = std::uint32_t(nodes_.size());
  nodes_[node].first = left;
  nodes_[node].count = 0;
  nodes_.emplace_back();
  nodes_.emplace_back();
  build(left, begin, mid, depth + 1);
  build(left + 1, mid, end, depth + 1);
}

// Slab test for every origin in the box `origin`, padded so that rounding can only add boxes.
bool TriangleTree::ray_may_hit(const CGAL::Bbox_3& box, const CGAL::Bbox_3& origin,
                               const std::array<double, 3>& d) const {
  double t_enter = 0, t_exit = std::numeric_limits<double>::infinity();
  for (int a = 0; a < 3; ++a) {
    const double pad = 1e-9 * (std::abs(box.min(a)) + std::abs(box.max(a)) +
                               std::abs(origin.min(a)) + std::abs(origin.max(a))) +
                       1e-300;
    const double lo = box.min(a) - pad, hi = box.max(a) + pad;
    if (d[a] == 0) {
      if (origin.max(a) < lo || origin.min(a) > hi) return false;
      continue;
    }
    double t0 = d[a] > 0 ? (lo - origin.max(a)) / d[a] : (hi - origin.min(a)) / d[a];
    double t1 = d[a] > 0 ? (hi - origin.min(a)) / d[a] : (lo - origin.max(a)) / d[a];
    t_enter = std::max(t_enter, t0 - 1e-9 * std::abs(t0));
    t_exit = std::min(t_exit, t1 + 1e-9 * std::abs(t1));
    if (t_enter > t_exit) return false;
  }
  return true;
}

namespace {

bool same_position(const Mesh& m, VertexIndex a, VertexIndex b) {
  return a == b || m.points[a] == m.points[b];
}

}  // namespace

bool triangles_intersect_improperly(const Mesh& mesh, std::uint32_t i, std::uint32_t j) {
  const Triangle& f = mesh.triangles[i];
  const Triangle& g = mesh.triangles[j];
  const Point* pf[3] = {&mesh.points[f[0]], &mesh.points[f[1]], &mesh.points[f[2]]};
  const Point* pg[3] = {&mesh.points[g[0]], &mesh.points[g[1]], &mesh.points[g[2]]};
  // Degenerate faces are reported on their own; CGAL's triangle predicates require proper ones.
  if (CGAL::collinear(*pf[0], *pf[1], *pf[2]) || CGAL::collinear(*pg[0], *pg[1], *pg[2]))
    return false;
  int shared = 0, sf = -1, sg = -1, sf2 = -1, sg2 = -1;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b)
      if (same_position(mesh, f[a], g[b])) {
        if (shared == 0) {
          sf = a;
          sg = b;
        } else {
          sf2 = a;
          sg2 = b;
        }
        ++shared;
      }
  // The tests build interval (then, if undecided, exact) triangles and segments from the points
  // directly: no lazy construction nodes for the many neighbouring pairs a mesh has.
  auto triangles_meet = [](const auto& a0, const auto& a1, const auto& a2, const auto& b0,
                           const auto& b1, const auto& b2) {
    using K = typename CGAL::Kernel_traits<std::decay_t<decltype(a0)>>::Kernel;
    return CGAL::do_intersect(typename K::Triangle_3(a0, a1, a2),
                              typename K::Triangle_3(b0, b1, b2));
  };
  auto segment_meets_triangle = [](const auto& s0, const auto& s1, const auto& t0, const auto& t1,
                                   const auto& t2) {
    using K = typename CGAL::Kernel_traits<std::decay_t<decltype(s0)>>::Kernel;
    return CGAL::do_intersect(typename K::Segment_3(s0, s1), typename K::Triangle_3(t0, t1, t2));
  };
  if (shared == 0)
    return detail::filtered_test(triangles_meet, *pf[0], *pf[1], *pf[2], *pg[0], *pg[1], *pg[2]);
  if (shared >= 3) return true;  // the same triangle twice
  if (shared == 1) {
    // Anything beyond the common vertex reaches the edge opposite it in one of the triangles.
    return detail::filtered_test(segment_meets_triangle, *pf[(sf + 1) % 3], *pf[(sf + 2) % 3],
                                 *pg[0], *pg[1], *pg[2]) ||
           detail::filtered_test(segment_meets_triangle, *pg[(sg + 1) % 3], *pg[(sg + 2) % 3],
                                 *pf[0], *pf[1], *pf[2]);
  }
  // A common edge: improper only when the triangles fold onto each other.
  const Point& p = *pf[sf];
  const Point& q = *pf[sf2];
  const Point& rf = *pf[3 - sf - sf2];
  const Point& rg = *pg[3 - sg - sg2];
  return CGAL::coplanar(p, q, rf, rg) && CGAL::coplanar_orientation(p, q, rf, rg) == CGAL::POSITIVE;
}

namespace {

// Generic directions: not parallel to any axis or to the diagonal planes of boxes.
constexpr std::array<double, 3> kDirections[] = {{1.0, 0.5773502691896257, 0.3119047619047619},
                                                 {-0.2718281828459045, 1.0, 0.7071067811865476},
                                                 {0.4142135623730951, -0.8660254037844386, 1.0},
                                                 {-1.0, -0.3183098861837907, 0.6931471805599453},
                                                 {0.1414213562373095, 0.7320508075688772, -1.0},
                                                 {0.9, -0.1234567890123457, -0.4567891234567891}};

enum class RayHit { Miss, Hit, Degenerate };

RayHit cross(const Kernel::Triangle_3& t, const Point& q, const Point& beyond,
             const Kernel::Vector_3& d, int& sign) {
  const auto side = CGAL::orientation(t[0], t[1], t[2], q);
  const auto facing = CGAL::orientation(t[0], t[1], t[2], t[0] + d);  // sign of normal . d
  if (side == CGAL::COPLANAR) {
    if (t.has_on(q)) throw std::domain_error("point lies on the surface");
    return facing == CGAL::COPLANAR ? RayHit::Degenerate : RayHit::Miss;
  }
  if (facing == CGAL::COPLANAR || facing == side) return RayHit::Miss;
  const auto s0 = CGAL::orientation(q, beyond, t[0], t[1]);
  const auto s1 = CGAL::orientation(q, beyond, t[1], t[2]);
  const auto s2 = CGAL::orientation(q, beyond, t[2], t[0]);
  const bool any_zero = s0 == CGAL::ZERO || s1 == CGAL::ZERO || s2 == CGAL::ZERO;
  const bool pos = s0 != CGAL::NEGATIVE && s1 != CGAL::NEGATIVE && s2 != CGAL::NEGATIVE;
  const bool neg = s0 != CGAL::POSITIVE && s1 != CGAL::POSITIVE && s2 != CGAL::POSITIVE;
  if (!pos && !neg) return RayHit::Miss;
  if (any_zero) return RayHit::Degenerate;  // through an edge or a vertex
  sign = facing == CGAL::POSITIVE ? 1 : -1;
  return RayHit::Hit;
}

}  // namespace

int winding_number(const Mesh& closed_mesh, const TriangleTree& tree, const Point& q) {
  const CGAL::Bbox_3 origin = q.bbox();
  for (const auto& dir : kDirections) {
    const Kernel::Vector_3 d(dir[0], dir[1], dir[2]);
    const Point beyond = q + d;
    int winding = 0;
    bool degenerate = false;
    tree.for_each_on_ray(origin, dir, [&](std::uint32_t t) {
      if (degenerate) return;
      int sign = 0;
      switch (cross(triangle_of(closed_mesh, t), q, beyond, d, sign)) {
        case RayHit::Hit:
          winding += sign;
          break;
        case RayHit::Degenerate:
          degenerate = true;
          break;
        case RayHit::Miss:
          break;
      }
    });
    if (!degenerate) return winding;
  }
  throw std::runtime_error("winding number: every ray direction was degenerate");
}

}  // namespace morphex

// SPDX-License-Identifier: GPL-3.0-or-later
// Spatial building blocks shared by the checks and the Boolean: a flat bounding-volume hierarchy
// over triangle boxes, exact improper-contact test between two triangles, exact point-in-solid.
// Private to libbool (the checks, the Boolean and the winding arrangement; tests use it white-box).
#pragma once

#include <CGAL/Bbox_3.h>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include <algorithm>
#include <array>
#include <cstdint>
#include <functional>
#include <limits>
#include <utility>
#include <vector>

#include "morphex/mesh.h"

namespace morphex {

// An axis-aligned box in single precision, rounded outward from the interval approximation of
// exact points: conservative, and half the size of a CGAL::Bbox_3.
struct FloatBox {
  float lo[3] = {std::numeric_limits<float>::infinity(), std::numeric_limits<float>::infinity(),
                 std::numeric_limits<float>::infinity()};
  float hi[3] = {-std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity(),
                 -std::numeric_limits<float>::infinity()};

  static FloatBox of(const Point& p);
  static FloatBox of(const Kernel::Approximate_kernel::Point_3& p);
  static FloatBox of(const CGAL::Bbox_3& b);
  FloatBox& operator+=(const FloatBox& o) {
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], o.lo[k]);
      hi[k] = std::max(hi[k], o.hi[k]);
    }
    return *this;
  }
  // Without branches: in tree traversals the outcome of each comparison is a coin toss, and
  // mispredicted branches cost more than the six comparisons.
  bool overlaps(const FloatBox& o) const {
    return bool((lo[0] <= o.hi[0]) & (o.lo[0] <= hi[0]) & (lo[1] <= o.hi[1]) & (o.lo[1] <= hi[1]) &
                (lo[2] <= o.hi[2]) & (o.lo[2] <= hi[2]));
  }
  CGAL::Bbox_3 bbox() const { return {lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]}; }
};

// The boxes of the triangles of `mesh` (of subset[i] when a subset is given), in parallel. Each
// vertex is boxed once when the triangles cover much of the mesh: a vertex is a corner of about
// six triangles, and boxing it reads its point, often a cache miss.
std::vector<FloatBox> triangle_boxes(const Mesh& mesh,
                                     const std::vector<std::uint32_t>* subset = nullptr);
// The same from the boxes of the vertices, by vertex index.
std::vector<FloatBox> triangle_boxes(const Mesh& mesh, const std::vector<FloatBox>& vertex_boxes,
                                     const std::vector<std::uint32_t>* subset = nullptr);

// A bounding-volume hierarchy over the triangles of a mesh, on conservative boxes. Built in
// linear time: triangles in Morton order of their box centres (a radix sort), grouped by
// kLeafSize into leaves, and levels of boxes above them, each box covering two of the level below
// (a pyramid). The build runs in parallel and its result does not depend on the thread count.
class TriangleTree {
 public:
  explicit TriangleTree(const Mesh& mesh);
  // Over the triangles `subset` of mesh only; traversals report the mesh's triangle indices.
  // box() and float_box() are not available on such a tree.
  TriangleTree(const Mesh& mesh, const std::vector<std::uint32_t>& subset);
  // The same two from the boxes of the vertices (by vertex index), for callers that build several
  // trees over one mesh.
  TriangleTree(const Mesh& mesh, const std::vector<FloatBox>& vertex_boxes);
  TriangleTree(const Mesh& mesh, const std::vector<FloatBox>& vertex_boxes,
               const std::vector<std::uint32_t>& subset);
  // Over the given boxes, box i reporting ids[i]; several boxes may report one id (pieces of a
  // long thin triangle, each boxed on its own), and then a traversal reports it once per box.
  TriangleTree(std::vector<FloatBox> boxes, const std::vector<std::uint32_t>& ids);
  // Over the triangles of two trees that together hold each triangle of a mesh of `num_triangles`
  // once, boxed along the same axes (the input check's two: the rest and the flat patches),
  // without boxing or sorting again: `first`'s order (taken over), then `second`'s. Each part
  // stays in Morton order; only the nodes over the seam, one per level, cover both. box() and
  // float_box() are available.
  TriangleTree(TriangleTree&& first, const TriangleTree& second, std::size_t num_triangles);

  // Calls f(triangle index) for every triangle whose box overlaps `box`.
  template <class F>
  void for_each_overlap(const FloatBox& box, F&& f) const;
  template <class F>
  void for_each_overlap(const CGAL::Bbox_3& box, F&& f) const {
    for_each_overlap(FloatBox::of(box), f);
  }

  // Calls f(triangle index) for every triangle whose box the ray origin + t * direction (t >= 0)
  // may cross (conservative).
  template <class F>
  void for_each_on_ray(const CGAL::Bbox_3& origin, const std::array<double, 3>& direction,
                       F&& f) const;

  // Every pair (i, j), i a triangle of a and j of b, whose boxes overlap; the two trees are
  // traversed together, in parallel, and the order depends only on the trees.
  static std::vector<std::pair<std::uint32_t, std::uint32_t>> overlapping_pairs(
      const TriangleTree& a, const TriangleTree& b);

  // Calls visit(task, i, j) once for every unordered pair of distinct triangles whose boxes
  // overlap, from parallel tasks numbered 0 .. self_pair_tasks() - 1 (one task's calls come from
  // one thread, in an order that depends only on the tree). Each task holds a TaskScope object
  // while it runs (a default-constructible guard, for per-task state such as the FPU mode).
  template <class TaskScope = int, class Visit>
  void for_each_self_pair(Visit&& visit) const {
    for_each_self_pair<TaskScope>(std::forward<Visit>(visit), nullptr);
  }
  // The same, without the pairs of triangles that have a common key: keys[t] holds up to three
  // keys of triangle t (by the mesh's index; kNoKey for none). The check passes the vertices
  // whose stars are proved embedded, so that the neighbours of a triangle, most of the pairs
  // whose boxes overlap, are dropped a whole leaf at a time instead of one by one.
  using TriangleKeys = std::vector<std::array<std::uint32_t, 3>>;
  static constexpr std::uint32_t kNoKey = 0xffffffffu;
  template <class TaskScope = int, class Visit>
  void for_each_self_pair(Visit&& visit, const TriangleKeys* keys) const;
  std::size_t self_pair_tasks() const;

  // The box of triangle t (a tree over the whole mesh).
  CGAL::Bbox_3 box(std::uint32_t t) const { return boxes_[t].bbox(); }
  const FloatBox& float_box(std::uint32_t t) const { return boxes_[t]; }
  std::size_t size() const { return order_.size(); }

  static constexpr std::uint32_t kLeafSize = 4;

 private:
  // Node i of level l covers nodes 2i and 2i + 1 of level l - 1; node i of level 0 (a leaf)
  // covers the triangles in positions [kLeafSize i, kLeafSize (i + 1)) of the Morton order.
  struct Node {
    std::uint32_t level, index;
  };
  const FloatBox& node_box(const Node& n) const { return levels_[n.level][n.index]; }
  std::uint32_t children(const Node& n, Node (&out)[2]) const {
    const std::uint32_t first = 2 * n.index, below = n.level - 1;
    out[0] = {below, first};
    out[1] = {below, first + 1};
    return first + 1 < levels_[below].size() ? 2 : 1;
  }
  // f(triangle, its box) for the triangles of a leaf.
  template <class F>
  void for_each_triangle(const Node& leaf, F&& f) const {
    const std::uint32_t end =
        std::min<std::uint32_t>(std::uint32_t(order_.size()), (leaf.index + 1) * kLeafSize);
    for (std::uint32_t i = leaf.index * kLeafSize; i < end; ++i) f(order_[i], sorted_boxes_[i]);
  }
  // Visits the leaves' triangles whose boxes pass a test, pruning subtrees whose box fails it:
  // `keep` tests one box (the root's), `keep4` four at once (bit i: the i-th passes; empty boxes
  // fail). A node is descended two levels at once, to its grandchildren, or from just above the
  // leaves to its two leaves; nodes on the stack have passed, and are pushed last first
  // (triangles are reported in the tree's order).
  template <class Keep, class Keep4, class F>
  void traverse(Keep&& keep, Keep4&& keep4, F&& f) const {
    if (levels_.empty()) return;
    Node stack[64];  // at most 3 pending nodes per 2 levels descended
    int top = 0;
    const Node root{std::uint32_t(levels_.size() - 1), 0};
    if (keep(node_box(root))) stack[top++] = root;
    auto push = [&](std::uint32_t level, std::uint32_t first, std::uint32_t hits) {
      while (hits != 0) {
        const std::uint32_t last = std::uint32_t(31 - __builtin_clz(hits));
        stack[top++] = {level, first + last};
        hits &= ~(1u << last);
      }
    };
    while (top > 0) {
      const Node node = stack[--top];
      if (node.level == 0) {
        const std::uint32_t first = node.index * kLeafSize;
        for (std::uint32_t hits = keep4(leaf_boxes_[node.index]); hits != 0; hits &= hits - 1)
          f(order_[first + std::uint32_t(__builtin_ctz(hits))]);
      } else if (node.level == 1) {  // its leaves 2i and 2i + 1: two of level 0's fours
        const std::uint32_t slots = 3u << (2 * (node.index & 1));
        push(0, 4 * (node.index / 2), keep4(quads_[0][node.index / 2]) & slots);
      } else {
        push(node.level - 2, 4 * node.index, keep4(quads_[node.level - 2][node.index]));
      }
    }
  }
  // Sorts the boxes of `ids` (the triangles' boxes, in that order) and builds the levels.
  void build(std::vector<FloatBox> boxes, const std::vector<std::uint32_t>* ids);
  // The leaves and the levels above them, from order_ and sorted_boxes_.
  void build_levels();
  bool ray_may_hit(const FloatBox& box, const CGAL::Bbox_3& origin,
                   const std::array<double, 3>& direction) const;
  // The level whose nodes are the parallel tasks of a traversal of the whole tree.
  std::uint32_t self_task_level() const;
  // Runs task(i) for i in [0, count), in parallel (TBB, kept out of this header).
  static void parallel_tasks(std::size_t count, const std::function<void(std::size_t)>& task);

  std::vector<FloatBox> boxes_;         // by triangle
  std::vector<std::uint32_t> order_;    // triangles in Morton order
  std::vector<FloatBox> sorted_boxes_;  // boxes_ in that order
  // Four boxes, coordinates side by side (structure of arrays), so that one box is tested against
  // all four at once; missing ones are empty.
  struct FourBoxes {
    alignas(16) float lo[3][4];
    alignas(16) float hi[3][4];
  };
  // Bit i set: the i-th of `four` overlaps `box`.
  static std::uint32_t overlaps(const FourBoxes& four, const FloatBox& box);
  // The boxes by leaf (the slots past the last triangle hold empty boxes).
  std::vector<FourBoxes> leaf_boxes_;
  // Bit i set: the box of the leaf's i-th triangle overlaps `box`.
  std::uint32_t leaf_overlaps(std::uint32_t leaf, const FloatBox& box) const {
    return overlaps(leaf_boxes_[leaf], box);
  }
  // By level, the node boxes four at a time: quads_[l][i] holds nodes 4i .. 4i + 3 of level l,
  // the grandchildren of node i of level l + 2. A traversal descends two levels at once with
  // one test of the four, instead of visiting the level between.
  std::vector<std::vector<FourBoxes>> quads_;
  // The keys by leaf, side by side like the boxes (kNoKey in empty slots).
  struct LeafKeys {
    alignas(16) std::uint32_t key[3][kLeafSize];
  };
  std::vector<LeafKeys> leaf_keys(const TriangleKeys& keys) const;
  // Bit i set: the leaf's i-th triangle has one of `keys` (kNoKey matches nothing).
  static std::uint32_t leaf_shares_key(const LeafKeys& leaf,
                                       const std::array<std::uint32_t, 3>& keys);
  std::vector<std::vector<FloatBox>> levels_;  // levels_.back() has the root alone
};

// Inline: they run once per triangle of a leaf in the traversals' innermost loops.
inline std::uint32_t TriangleTree::overlaps(const FourBoxes& l, const FloatBox& box) {
#if defined(__SSE2__)
  static_assert(kLeafSize == 4, "one SSE register per coordinate of a leaf");
  __m128 all = _mm_castsi128_ps(_mm_set1_epi32(-1));
  for (int k = 0; k < 3; ++k) {
    all = _mm_and_ps(all, _mm_cmple_ps(_mm_load_ps(l.lo[k]), _mm_set1_ps(box.hi[k])));
    all = _mm_and_ps(all, _mm_cmple_ps(_mm_set1_ps(box.lo[k]), _mm_load_ps(l.hi[k])));
  }
  return std::uint32_t(_mm_movemask_ps(all));
#else
  std::uint32_t mask = 0;
  for (std::uint32_t i = 0; i < 4; ++i) {
    bool overlap = true;
    for (int k = 0; k < 3; ++k)
      overlap = overlap && l.lo[k][i] <= box.hi[k] && box.lo[k] <= l.hi[k][i];
    mask |= std::uint32_t(overlap) << i;
  }
  return mask;
#endif
}

inline std::uint32_t TriangleTree::leaf_shares_key(const LeafKeys& leaf,
                                                   const std::array<std::uint32_t, 3>& keys) {
#if defined(__SSE2__)
  __m128i any = _mm_setzero_si128();
  for (const std::uint32_t key : keys) {
    if (key == kNoKey) continue;
    const __m128i k = _mm_set1_epi32(int(key));
    for (int j = 0; j < 3; ++j)
      any = _mm_or_si128(
          any, _mm_cmpeq_epi32(k, _mm_load_si128(reinterpret_cast<const __m128i*>(leaf.key[j]))));
  }
  return std::uint32_t(_mm_movemask_ps(_mm_castsi128_ps(any)));
#else
  std::uint32_t mask = 0;
  for (std::uint32_t i = 0; i < kLeafSize; ++i)
    for (const std::uint32_t key : keys)
      for (int j = 0; j < 3; ++j)
        if (key != kNoKey && leaf.key[j][i] == key) mask |= 1u << i;
  return mask;
#endif
}

template <class TaskScope, class Visit>
void TriangleTree::for_each_self_pair(Visit&& visit, const TriangleKeys* keys) const {
  if (levels_.empty()) return;
  const std::vector<LeafKeys> by_leaf = keys ? leaf_keys(*keys) : std::vector<LeafKeys>();
  const std::uint32_t task_level = self_task_level();
  const Node root{std::uint32_t(levels_.size() - 1), 0};
  // Positions in the Morton order covered by a node: a pair of nodes whose ranges are ordered the
  // other way round is met again with the roles swapped, so it is skipped.
  auto range = [&](const Node& n) {
    const std::uint32_t span = kLeafSize << n.level;
    return std::make_pair(n.index * span, (n.index + 1) * span);
  };
  parallel_tasks(std::size_t(levels_[task_level].size()), [&](std::size_t task) {
    [[maybe_unused]] const TaskScope scope{};
    // Node pairs on the stack have overlapping boxes: they are tested before they are pushed.
    std::pair<Node, Node> stack[256];  // at most 3 pending pairs per 2 levels descended
    int top = 0;
    const Node start{task_level, std::uint32_t(task)};
    if (node_box(start).overlaps(node_box(root))) stack[top++] = {start, root};
    while (top > 0) {
      const auto [na, nb] = stack[--top];
      if (range(nb).second <= range(na).first) continue;  // every position of nb is before na's
      if (na.level == 0 && nb.level == 0) {
        const std::uint32_t a_end = std::min<std::uint32_t>(std::uint32_t(order_.size()),
                                                            (na.index + 1) * kLeafSize),
                            b_end = std::min<std::uint32_t>(std::uint32_t(order_.size()),
                                                            (nb.index + 1) * kLeafSize);
        // One box against the four of the other leaf at once; positions up to i are dropped (each
        // pair once, i < j).
        const std::uint32_t b_first = nb.index * kLeafSize;
        for (std::uint32_t i = na.index * kLeafSize; i < a_end; ++i) {
          std::uint32_t hits = leaf_overlaps(nb.index, sorted_boxes_[i]);
          if (keys && hits != 0) hits &= ~leaf_shares_key(by_leaf[nb.index], (*keys)[order_[i]]);
          if (i + 1 > b_first) hits &= i + 1 - b_first >= 32 ? 0u : ~0u << (i + 1 - b_first);
          hits &= b_end - b_first >= 32 ? ~0u : (1u << (b_end - b_first)) - 1;
          for (; hits != 0; hits &= hits - 1)
            visit(task, order_[i], order_[b_first + std::uint32_t(__builtin_ctz(hits))]);
        }
        continue;
      }
      // Descend the higher node: two levels at once, to those of its grandchildren that overlap
      // the other node, when it has grandchildren.
      const bool a_higher = na.level >= nb.level;
      const Node high = a_higher ? na : nb, low = a_higher ? nb : na;
      if (high.level >= 2) {
        const std::uint32_t below = high.level - 2;
        for (std::uint32_t hits = overlaps(quads_[below][high.index], node_box(low)); hits != 0;
             hits &= hits - 1) {
          const Node g{below, 4 * high.index + std::uint32_t(__builtin_ctz(hits))};
          stack[top++] = a_higher ? std::make_pair(g, nb) : std::make_pair(na, g);
        }
        continue;
      }
      Node kids[2];
      const std::uint32_t count = children(high, kids);
      for (std::uint32_t k = 0; k < count; ++k)
        if (node_box(kids[k]).overlaps(node_box(low)))
          stack[top++] = a_higher ? std::make_pair(kids[k], nb) : std::make_pair(na, kids[k]);
    }
  });
}

template <class F>
void TriangleTree::for_each_overlap(const FloatBox& box, F&& f) const {
  traverse([&](const FloatBox& b) { return b.overlaps(box); },
           [&](const FourBoxes& four) { return overlaps(four, box); }, f);
}

template <class F>
void TriangleTree::for_each_on_ray(const CGAL::Bbox_3& origin,
                                   const std::array<double, 3>& direction, F&& f) const {
  auto keep = [&](const FloatBox& b) { return ray_may_hit(b, origin, direction); };
  traverse(
      keep,
      [&](const FourBoxes& four) {
        std::uint32_t hits = 0;
        for (std::uint32_t i = 0; i < 4; ++i) {
          FloatBox b;
          for (int k = 0; k < 3; ++k) b.lo[k] = four.lo[k][i], b.hi[k] = four.hi[k][i];
          if (b.lo[0] <= b.hi[0] && keep(b)) hits |= 1u << i;  // not an empty slot
        }
        return hits;
      },
      f);
}

// Interleaves the top 21 bits of three coordinates in [0, 1] (clamped): a position along the
// Morton space-filling curve.
std::uint64_t morton_code(const std::array<double, 3>& unit);
// The Morton code of the centre of `box` within `frame`.
std::uint64_t morton_code(const CGAL::Bbox_3& box, const CGAL::Bbox_3& frame);

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

// SPDX-License-Identifier: GPL-3.0-or-later
#include "tree/box_tree.h"

#include <CGAL/intersections.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <type_traits>

#if defined(__SSE2__)
#include <immintrin.h>
#endif

#include "exact/filtered.h"

namespace morphex {

namespace {

// The float next to a finite f toward -infinity (step -1) or +infinity (step +1), by its bits:
// std::nextafter is a library call, and boxes are rounded for every vertex of every Boolean.
float next_float(float f, int step) {
  if (f == 0) return float(step) * std::numeric_limits<float>::denorm_min();
  std::uint32_t bits;
  std::memcpy(&bits, &f, sizeof bits);
  bits += (f > 0) == (step > 0) ? 1u : std::uint32_t(-1);
  std::memcpy(&f, &bits, sizeof bits);
  return f;
}
float round_down(double d) {
  const float f = static_cast<float>(d);
  if (!(f > d)) return f;
  return std::isinf(f) ? std::numeric_limits<float>::max() : next_float(f, -1);
}
float round_up(double d) {
  const float f = static_cast<float>(d);
  if (!(f < d)) return f;
  return std::isinf(f) ? std::numeric_limits<float>::lowest() : next_float(f, +1);
}

// The bits of a 10-bit cell index spread two apart (bit i to bit 3 i), by table.
struct SpreadTable {
  std::uint32_t bits[1024];
  constexpr SpreadTable() : bits() {
    for (std::uint32_t v = 0; v < 1024; ++v)
      for (int i = 0; i < 10; ++i) bits[v] |= ((v >> i) & 1u) << (3 * i);
  }
  std::uint32_t operator[](std::uint32_t v) const { return bits[v]; }
};
constexpr SpreadTable kSpread{};

// Morton codes of box centres on a 1024^3 grid over a frame: 30 bits, enough to order the
// triangles of any mesh this library handles into compact leaves. The frame's scale is taken
// once (a product per coordinate instead of a quotient: this runs for every triangle of every
// tree).
struct MortonGrid {
  float lo[3], scale[3];
  explicit MortonGrid(const FloatBox& frame) {
    for (int k = 0; k < 3; ++k) {
      const float extent = frame.hi[k] - frame.lo[k];
      lo[k] = frame.lo[k];
      scale[k] = extent > 0 ? 1023.0f / extent : 0.0f;
    }
  }
  std::uint32_t code(const FloatBox& box) const {
    std::uint32_t code = 0;
    for (int k = 0; k < 3; ++k) {
      const float cell = (0.5f * (box.lo[k] + box.hi[k]) - lo[k]) * scale[k];
      // Beyond float range (infinite boxes) the cell is NaN or infinite: clamped, NaN to 0.
      const float clamped = cell >= 0.0f ? std::min(cell, 1023.0f) : 0.0f;
      code |= kSpread[static_cast<std::uint32_t>(clamped)] << k;
    }
    return code;
  }
};

// Stable least-significant-digit radix sort of (key << 32 | index) by the 30-bit key.
void radix_sort_by_key(std::vector<std::uint64_t>& items) {
  std::vector<std::uint64_t> buffer(items.size());
  for (int shift = 32; shift < 62; shift += 10) {
    std::uint32_t count[1025] = {};
    for (std::uint64_t x : items) ++count[((x >> shift) & 0x3ff) + 1];
    for (int d = 0; d < 1024; ++d) count[d + 1] += count[d];
    for (std::uint64_t x : items) buffer[count[(x >> shift) & 0x3ff]++] = x;
    items.swap(buffer);
  }
}

std::array<double, 3> unit_position(const CGAL::Bbox_3& box, const CGAL::Bbox_3& frame) {
  std::array<double, 3> unit;
  for (int k = 0; k < 3; ++k) {
    const double extent = frame.max(k) - frame.min(k);
    const double centre = 0.5 * (box.min(k) + box.max(k));
    unit[k] = extent > 0 ? (centre - frame.min(k)) / extent : 0.0;
  }
  return unit;
}

}  // namespace

FloatBox FloatBox::of(const CGAL::Bbox_3& b) {
  FloatBox out;
  for (int k = 0; k < 3; ++k) {
    out.lo[k] = round_down(b.min(k));
    out.hi[k] = round_up(b.max(k));
  }
  return out;
}

FloatBox FloatBox::of(const Point& p) {
  return of(CGAL::approx(p));
}

FloatBox FloatBox::of(const Kernel::Approximate_kernel::Point_3& a) {
  FloatBox out;
  for (int k = 0; k < 3; ++k) {
    out.lo[k] = round_down(a.cartesian(k).inf());
    out.hi[k] = round_up(a.cartesian(k).sup());
  }
  return out;
}

std::uint64_t morton_code(const std::array<double, 3>& unit) {
  auto spread = [](std::uint64_t v) {
    v &= 0x1fffff;
    v = (v | v << 32) & 0x1f00000000ffffULL;
    v = (v | v << 16) & 0x1f0000ff0000ffULL;
    v = (v | v << 8) & 0x100f00f00f00f00fULL;
    v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
    v = (v | v << 2) & 0x1249249249249249ULL;
    return v;
  };
  std::uint64_t code = 0;
  for (int i = 0; i < 3; ++i) {
    const double clamped = unit[i] >= 0 ? std::min(unit[i], 1.0) : 0.0;  // NaN: 0
    code |= spread(static_cast<std::uint64_t>(clamped * double(0x1fffff))) << i;
  }
  return code;
}

std::uint64_t morton_code(const CGAL::Bbox_3& box, const CGAL::Bbox_3& frame) {
  return morton_code(unit_position(box, frame));
}

Kernel::Triangle_3 triangle_of(const Mesh& mesh, std::uint32_t t) {
  const Triangle& f = mesh.triangles[t];
  return {mesh.points[f[0]], mesh.points[f[1]], mesh.points[f[2]]};
}

namespace {
constexpr std::size_t kGrain = 8192;

std::vector<FloatBox> vertex_boxes_of(const Mesh& mesh) {
  std::vector<FloatBox> boxes(mesh.num_vertices());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, boxes.size(), kGrain),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t v = r.begin(); v < r.end(); ++v)
                        boxes[v] = FloatBox::of(mesh.points[v]);
                    });
  return boxes;
}
}  // namespace

std::vector<FloatBox> triangle_boxes(const Mesh& mesh, const std::vector<FloatBox>& vertex_boxes,
                                     const std::vector<std::uint32_t>* subset) {
  const std::size_t n = subset ? subset->size() : mesh.num_triangles();
  std::vector<FloatBox> boxes(n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, kGrain),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t i = r.begin(); i < r.end(); ++i) {
                        const Triangle& f = mesh.triangles[subset ? (*subset)[i] : i];
                        FloatBox b = vertex_boxes[f[0]];
                        b += vertex_boxes[f[1]];
                        b += vertex_boxes[f[2]];
                        boxes[i] = b;
                      }
                    });
  return boxes;
}

std::vector<FloatBox> triangle_boxes(const Mesh& mesh, const std::vector<std::uint32_t>* subset) {
  const std::size_t n = subset ? subset->size() : mesh.num_triangles();
  if (3 * n >= mesh.num_vertices()) return triangle_boxes(mesh, vertex_boxes_of(mesh), subset);
  // A small part of a large mesh: its corners only.
  std::vector<FloatBox> boxes(n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, kGrain),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t i = r.begin(); i < r.end(); ++i)
                        for (const VertexIndex v : mesh.triangles[subset ? (*subset)[i] : i])
                          boxes[i] += FloatBox::of(mesh.points[v]);
                    });
  return boxes;
}

TriangleTree::TriangleTree(const Mesh& mesh) {
  if (mesh.num_triangles() == 0) return;
  boxes_ = triangle_boxes(mesh);
  build(boxes_, nullptr);
}

TriangleTree::TriangleTree(const Mesh& mesh, const std::vector<std::uint32_t>& subset) {
  if (!subset.empty()) build(triangle_boxes(mesh, &subset), &subset);
}

TriangleTree::TriangleTree(const Mesh& mesh, const std::vector<FloatBox>& vertex_boxes) {
  if (mesh.num_triangles() == 0) return;
  boxes_ = triangle_boxes(mesh, vertex_boxes);
  build(boxes_, nullptr);
}

TriangleTree::TriangleTree(const Mesh& mesh, const std::vector<FloatBox>& vertex_boxes,
                           const std::vector<std::uint32_t>& subset) {
  if (!subset.empty()) build(triangle_boxes(mesh, vertex_boxes, &subset), &subset);
}

TriangleTree::TriangleTree(std::vector<FloatBox> boxes, const std::vector<std::uint32_t>& ids) {
  if (!boxes.empty()) build(std::move(boxes), &ids);
}

void TriangleTree::build(std::vector<FloatBox> boxes, const std::vector<std::uint32_t>* ids) {
  const std::uint32_t n = std::uint32_t(boxes.size());
  FloatBox frame;
  for (const FloatBox& b : boxes) frame += b;
  const MortonGrid grid(frame);
  std::vector<std::uint64_t> keyed(n);
  tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, n, kGrain),
                    [&](const tbb::blocked_range<std::uint32_t>& r) {
                      for (std::uint32_t t = r.begin(); t < r.end(); ++t)
                        keyed[t] = (std::uint64_t(grid.code(boxes[t])) << 32) | t;
                    });
  radix_sort_by_key(keyed);
  order_.resize(n);
  sorted_boxes_.resize(n);
  tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, n, kGrain),
                    [&](const tbb::blocked_range<std::uint32_t>& r) {
                      for (std::uint32_t i = r.begin(); i < r.end(); ++i) {
                        const std::uint32_t position = std::uint32_t(keyed[i]);
                        order_[i] = ids ? (*ids)[position] : position;
                        sorted_boxes_[i] = boxes[position];
                      }
                    });
  build_levels();
}

TriangleTree::TriangleTree(TriangleTree&& first, const TriangleTree& second,
                           std::size_t num_triangles) {
  if (num_triangles == 0) return;
  order_ = std::move(first.order_);
  order_.insert(order_.end(), second.order_.begin(), second.order_.end());
  sorted_boxes_ = std::move(first.sorted_boxes_);
  sorted_boxes_.insert(sorted_boxes_.end(), second.sorted_boxes_.begin(),
                       second.sorted_boxes_.end());
  if (order_.size() != num_triangles)
    throw std::logic_error("TriangleTree: the joined trees do not hold each triangle once");
  boxes_.resize(num_triangles);
  for (std::size_t i = 0; i < order_.size(); ++i) boxes_[order_[i]] = sorted_boxes_[i];
  build_levels();
}

void TriangleTree::build_levels() {
  const std::uint32_t n = std::uint32_t(order_.size());
  leaf_boxes_.resize((n + kLeafSize - 1) / kLeafSize);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, leaf_boxes_.size(), kGrain / kLeafSize),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t leaf = r.begin(); leaf < r.end(); ++leaf)
                        for (std::uint32_t i = 0; i < kLeafSize; ++i) {
                          const std::size_t t = leaf * kLeafSize + i;
                          const FloatBox box = t < n ? sorted_boxes_[t] : FloatBox{};
                          for (int k = 0; k < 3; ++k) {
                            leaf_boxes_[leaf].lo[k][i] = box.lo[k];
                            leaf_boxes_[leaf].hi[k][i] = box.hi[k];
                          }
                        }
                    });
  levels_.emplace_back((n + kLeafSize - 1) / kLeafSize);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, levels_[0].size(), kGrain / kLeafSize),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t leaf = r.begin(); leaf < r.end(); ++leaf) {
                        FloatBox box;
                        const std::size_t end = std::min<std::size_t>(n, (leaf + 1) * kLeafSize);
                        for (std::size_t i = leaf * kLeafSize; i < end; ++i)
                          box += sorted_boxes_[i];
                        levels_[0][leaf] = box;
                      }
                    });
  while (levels_.back().size() > 1) {
    const std::vector<FloatBox>& below = levels_.back();
    std::vector<FloatBox> level((below.size() + 1) / 2);
    for (std::size_t i = 0; i < level.size(); ++i) {
      level[i] = below[2 * i];
      if (2 * i + 1 < below.size()) level[i] += below[2 * i + 1];
    }
    levels_.push_back(std::move(level));
  }
  quads_.resize(levels_.size());
  for (std::size_t l = 0; l < levels_.size(); ++l) {
    const std::vector<FloatBox>& level = levels_[l];
    quads_[l].resize((level.size() + 3) / 4);
    for (std::size_t i = 0; i < 4 * quads_[l].size(); ++i) {
      const FloatBox box = i < level.size() ? level[i] : FloatBox{};
      for (int k = 0; k < 3; ++k) {
        quads_[l][i / 4].lo[k][i % 4] = box.lo[k];
        quads_[l][i / 4].hi[k][i % 4] = box.hi[k];
      }
    }
  }
}

std::vector<std::pair<std::uint32_t, std::uint32_t>> TriangleTree::overlapping_pairs(
    const TriangleTree& a, const TriangleTree& b) {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
  if (a.levels_.empty() || b.levels_.empty()) return pairs;
  // Independent tasks: the nodes of a level of `a` wide enough to keep every thread busy, each
  // traversed together with all of `b`; their pairs are concatenated in node order.
  std::uint32_t task_level = std::uint32_t(a.levels_.size() - 1);
  while (task_level > 0 && a.levels_[task_level].size() < 256) --task_level;
  const Node root_b{std::uint32_t(b.levels_.size() - 1), 0};
  std::vector<std::vector<std::pair<std::uint32_t, std::uint32_t>>> found(
      a.levels_[task_level].size());
  tbb::parallel_for(std::uint32_t(0), std::uint32_t(found.size()), [&](std::uint32_t task) {
    auto& out = found[task];
    // Node pairs on the stack have overlapping boxes: children are tested before they are pushed.
    std::pair<Node, Node> stack[256];
    int top = 0;
    const Node start{task_level, task};
    if (a.node_box(start).overlaps(b.node_box(root_b))) stack[top++] = {start, root_b};
    while (top > 0) {
      // (not a structured binding: the leaf loop below captures the nodes, which C++17 allows
      // only for variables)
      const Node na = stack[top - 1].first, nb = stack[top - 1].second;
      --top;
      if (na.level == 0 && nb.level == 0) {
        a.for_each_triangle(na, [&](std::uint32_t t, const FloatBox& box_t) {
          std::uint32_t hits = b.leaf_overlaps(nb.index, box_t);
          for (std::uint32_t i = 0; hits != 0; ++i, hits >>= 1)
            if (hits & 1u) out.emplace_back(t, b.order_[nb.index * kLeafSize + i]);
        });
        continue;
      }
      // Descend the higher node (the one covering more triangles): two levels at once, to those
      // of its grandchildren that overlap the other node, when it has grandchildren.
      if (std::max(na.level, nb.level) >= 2) {
        const bool a_higher = na.level >= nb.level;
        const TriangleTree& high = a_higher ? a : b;
        const Node h = a_higher ? na : nb;
        const std::uint32_t below = h.level - 2;
        for (std::uint32_t hits =
                 overlaps(high.quads_[below][h.index], a_higher ? b.node_box(nb) : a.node_box(na));
             hits != 0; hits &= hits - 1) {
          const Node g{below, 4 * h.index + std::uint32_t(__builtin_ctz(hits))};
          stack[top++] = a_higher ? std::make_pair(g, nb) : std::make_pair(na, g);
        }
        continue;
      }
      Node kids[2];
      if (na.level >= nb.level) {
        const FloatBox& box_b = b.node_box(nb);
        const std::uint32_t count = a.children(na, kids);
        for (std::uint32_t k = 0; k < count; ++k)
          if (a.node_box(kids[k]).overlaps(box_b)) stack[top++] = {kids[k], nb};
      } else {
        const FloatBox& box_a = a.node_box(na);
        const std::uint32_t count = b.children(nb, kids);
        for (std::uint32_t k = 0; k < count; ++k)
          if (box_a.overlaps(b.node_box(kids[k]))) stack[top++] = {na, kids[k]};
      }
    }
  });
  std::size_t total = 0;
  for (const auto& f : found) total += f.size();
  pairs.reserve(total);
  for (const auto& f : found) pairs.insert(pairs.end(), f.begin(), f.end());
  return pairs;
}

std::vector<TriangleTree::LeafKeys> TriangleTree::leaf_keys(const TriangleKeys& keys) const {
  std::vector<LeafKeys> by_leaf(leaf_boxes_.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, by_leaf.size(), kGrain / kLeafSize),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t leaf = r.begin(); leaf < r.end(); ++leaf)
                        for (std::uint32_t i = 0; i < kLeafSize; ++i) {
                          const std::size_t t = leaf * kLeafSize + i;
                          for (int k = 0; k < 3; ++k)
                            by_leaf[leaf].key[k][i] =
                                t < order_.size() ? keys[order_[t]][k] : kNoKey;
                        }
                    });
  return by_leaf;
}

std::uint32_t TriangleTree::self_task_level() const {
  std::uint32_t level = std::uint32_t(levels_.size() - 1);
  while (level > 0 && levels_[level].size() < 256) --level;
  return level;
}

std::size_t TriangleTree::self_pair_tasks() const {
  return levels_.empty() ? 0 : levels_[self_task_level()].size();
}

void TriangleTree::parallel_tasks(std::size_t count, const std::function<void(std::size_t)>& task) {
  tbb::parallel_for(std::size_t(0), count, [&](std::size_t i) { task(i); });
}

// Slab test for every origin in the box `origin`, padded so that rounding can only add boxes.
bool TriangleTree::ray_may_hit(const FloatBox& float_box, const CGAL::Bbox_3& origin,
                               const std::array<double, 3>& d) const {
  const CGAL::Bbox_3 box = float_box.bbox();
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
  throw std::logic_error("winding number: every ray direction was degenerate");
}

}  // namespace morphex

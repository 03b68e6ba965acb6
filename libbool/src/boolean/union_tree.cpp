// SPDX-License-Identifier: GPL-3.0-or-later
// Union of many solids: a balanced tree of exact binary unions over a Morton order.
#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <numeric>
#include <stdexcept>

#include "morphex/boolean.h"
#include "morphex/internal/solid_access.h"
#include "morphex/internal/valid_operations.h"
#include "morphex/progress.h"
#include "tree/box_tree.h"

namespace morphex {
namespace {

CGAL::Bbox_3 bbox_of(const Mesh& mesh) {
  CGAL::Bbox_3 box;
  for (const Point& p : mesh.points) box += p.bbox();
  return box;
}

struct Operand {
  Mesh mesh;
  CGAL::Bbox_3 box;
};

bool boxes_overlap(const CGAL::Bbox_3& a, const CGAL::Bbox_3& b) {
  // Touching boxes count as overlapping: solids that touch must go through the exact union.
  return CGAL::do_overlap(a, b);
}

struct Counters {
  std::atomic<std::size_t> binary_unions{0}, disjoint_merges{0};
  // Triangles of the first i operands: a node's union is weighed by the input triangles below it
  // (its work grows with them), so the progress bar does not race through the many small unions
  // at the leaves and then stall at the root.
  std::vector<double> triangles_before;
  ProgressCounter* progress = nullptr;
  double weight(std::size_t begin, std::size_t end) const {
    return triangles_before[end] - triangles_before[begin];
  }
};

// The sum of the weights of the internal nodes of unite's tree over [begin, end).
double tree_weight(const Counters& counters, std::size_t begin, std::size_t end) {
  if (end - begin < 2) return 0;
  const std::size_t middle = begin + (end - begin) / 2;
  return counters.weight(begin, end) + tree_weight(counters, begin, middle) +
         tree_weight(counters, middle, end);
}

Operand unite_node(std::vector<Operand>& items, std::size_t begin, std::size_t end,
                   Counters& counters);

Operand unite(std::vector<Operand>& items, std::size_t begin, std::size_t end, Counters& counters) {
  if (end - begin == 1) return std::move(items[begin]);
  Operand out = unite_node(items, begin, end, counters);
  counters.progress->add(counters.weight(begin, end));
  return out;
}

Operand unite_node(std::vector<Operand>& items, std::size_t begin, std::size_t end,
                   Counters& counters) {
  const std::size_t middle = begin + (end - begin) / 2;
  Operand left, right;
  // Small subtrees are not worth a task; the cut-off keeps scheduling overhead negligible.
  if (end - begin >= 8)
    tbb::parallel_invoke([&] { left = unite(items, begin, middle, counters); },
                         [&] { right = unite(items, middle, end, counters); });
  else {
    left = unite(items, begin, middle, counters);
    right = unite(items, middle, end, counters);
  }
  Operand out;
  out.box = left.box + right.box;
  if (left.mesh.empty()) {
    out.mesh = std::move(right.mesh);
  } else if (right.mesh.empty()) {
    out.mesh = std::move(left.mesh);
  } else if (!boxes_overlap(left.box, right.box)) {
    ++counters.disjoint_merges;
    out.mesh = std::move(left.mesh);
    const auto offset = VertexIndex(out.mesh.points.size());
    out.mesh.points.insert(out.mesh.points.end(), right.mesh.points.begin(),
                           right.mesh.points.end());
    for (const Triangle& t : right.mesh.triangles)
      out.mesh.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
  } else {
    ++counters.binary_unions;
    out.mesh = detail::boolean_of_valid(left.mesh, right.mesh, BooleanOp::Union).mesh;
  }
  return out;
}

}  // namespace

namespace detail {

Mesh union_of_valid(std::vector<Mesh> solids, UnionStats* stats) {
  std::vector<Operand> items;
  items.reserve(solids.size());
  CGAL::Bbox_3 all;
  for (Mesh& m : solids) {
    if (m.empty()) continue;
    Operand op{std::move(m), {}};
    op.box = bbox_of(op.mesh);
    all += op.box;
    items.push_back(std::move(op));
  }
  if (items.empty()) return {};

  std::vector<std::uint64_t> codes(items.size());
  for (std::size_t i = 0; i < items.size(); ++i) codes[i] = morton_code(items[i].box, all);
  std::vector<std::size_t> order(items.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t x, std::size_t y) { return codes[x] < codes[y]; });
  std::vector<Operand> sorted;
  sorted.reserve(items.size());
  for (std::size_t i : order) sorted.push_back(std::move(items[i]));

  Counters counters;
  counters.triangles_before.assign(sorted.size() + 1, 0);
  for (std::size_t i = 0; i < sorted.size(); ++i)
    counters.triangles_before[i + 1] =
        counters.triangles_before[i] + double(sorted[i].mesh.triangles.size());
  ProgressCounter progress(tree_weight(counters, 0, sorted.size()));
  counters.progress = &progress;
  Operand result = unite(sorted, 0, sorted.size(), counters);
  if (stats) {
    stats->binary_unions = counters.binary_unions;
    stats->disjoint_merges = counters.disjoint_merges;
  }
  return std::move(result.mesh);
}

}  // namespace detail

Solid compute_union(const std::vector<Solid>& solids, UnionStats* stats) {
  std::vector<Mesh> meshes;  // the tree takes its operands over (the disjoint merges extend them)
  meshes.reserve(solids.size());
  for (const Solid& solid : solids) meshes.push_back(solid.mesh());
  return detail::trusted_solid(detail::union_of_valid(std::move(meshes), stats));
}

}  // namespace morphex

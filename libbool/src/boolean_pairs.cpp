// SPDX-License-Identifier: GPL-3.0-or-later
// Step 2: candidate triangle pairs. The tree is built on the mesh with fewer triangles (the seed's
// O((n + m) log n) bound) and queried with the boxes of the other.
#include "boolean_internal.h"
#include "morphex/spatial.h"

namespace morphex::detail {

namespace {
CGAL::Bbox_3 triangle_box(const Mesh& m, std::uint32_t t) {
  const Triangle& f = m.triangles[t];
  return m.points[f[0]].bbox() + m.points[f[1]].bbox() + m.points[f[2]].bbox();
}
}  // namespace

std::vector<std::pair<std::uint32_t, std::uint32_t>> candidate_pairs(const Mesh& a, const Mesh& b) {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
  const bool tree_on_a = a.num_triangles() <= b.num_triangles();
  const Mesh& indexed = tree_on_a ? a : b;
  const Mesh& queries = tree_on_a ? b : a;
  if (indexed.empty() || queries.empty()) return pairs;
  const TriangleTree tree(indexed);
  for (std::uint32_t q = 0; q < queries.num_triangles(); ++q) {
    tree.for_each_overlap(triangle_box(queries, q), [&](std::uint32_t t) {
      pairs.emplace_back(tree_on_a ? t : q, tree_on_a ? q : t);
    });
  }
  return pairs;
}

}  // namespace morphex::detail

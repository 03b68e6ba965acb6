// SPDX-License-Identifier: GPL-3.0-or-later
// find_rounding_damage (rounding_check.h).
#include "rounding_check.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>

#include "check_internal.h"
#include "morphex/union_find.h"
#include "spatial.h"

namespace morphex::detail {
namespace {

using Pairs = std::vector<std::pair<std::uint32_t, std::uint32_t>>;

// Faces with a moved corner, and which faces those are.
std::vector<std::uint32_t> affected_faces(const Mesh& m, const std::vector<std::uint8_t>& moved,
                                          std::vector<std::uint8_t>& is_affected) {
  std::vector<std::uint32_t> out;
  is_affected.assign(m.num_triangles(), 0);
  for (std::uint32_t f = 0; f < m.num_triangles(); ++f) {
    const Triangle& t = m.triangles[f];
    if (moved[t[0]] || moved[t[1]] || moved[t[2]]) {
      is_affected[f] = 1;
      out.push_back(f);
    }
  }
  return out;
}

bool flat(const Mesh& m, const Triangle& t) {
  const Point &a = m.points[t[0]], &b = m.points[t[1]], &c = m.points[t[2]];
  return a == b || b == c || c == a || CGAL::collinear(a, b, c);
}

// Pairs (i, j), i affected, whose boxes overlap; each once, flat faces left out (the winding
// chain drops them).
Pairs candidate_pairs(const Mesh& m, const std::vector<std::uint32_t>& affected,
                      const std::vector<std::uint8_t>& is_affected,
                      const std::vector<std::uint8_t>& is_flat) {
  std::vector<FloatBox> vertex_boxes(m.num_vertices());
  tbb::parallel_for(std::size_t(0), m.num_vertices(),
                    [&](std::size_t v) { vertex_boxes[v] = FloatBox::of(m.points[v]); });
  const TriangleTree tree(m, vertex_boxes);
  const std::vector<FloatBox> boxes = triangle_boxes(m, vertex_boxes, &affected);
  tbb::enumerable_thread_specific<Pairs> found;
  tbb::parallel_for(std::size_t(0), affected.size(), [&](std::size_t k) {
    const std::uint32_t i = affected[k];
    if (is_flat[i]) return;
    Pairs& local = found.local();
    tree.for_each_overlap(boxes[k], [&](std::uint32_t j) {
      if (j == i || is_flat[j] || (is_affected[j] && j < i)) return;
      local.emplace_back(std::min(i, j), std::max(i, j));
    });
  });
  Pairs all;
  for (const Pairs& p : found) all.insert(all.end(), p.begin(), p.end());
  std::sort(all.begin(), all.end());
  return all;
}

// Shells (components through shared vertices) holding an affected face whose rounded volume has
// another sign than the exact one.
std::size_t turned_shells(const Mesh& exact, const Mesh& rounded,
                          const std::vector<std::uint8_t>& is_affected) {
  UnionFind sets(exact.num_vertices());
  for (const Triangle& t : exact.triangles) {
    sets.join(t[0], t[1]);
    sets.join(t[0], t[2]);
  }
  std::vector<std::uint32_t> shell_of(exact.num_vertices(), UINT32_MAX);
  std::vector<std::uint8_t> touched;
  std::vector<std::vector<std::uint32_t>> faces;
  for (std::uint32_t f = 0; f < exact.num_triangles(); ++f) {
    const std::uint32_t root = sets.find(exact.triangles[f][0]);
    if (shell_of[root] == UINT32_MAX) {
      shell_of[root] = std::uint32_t(faces.size());
      faces.emplace_back();
      touched.push_back(0);
    }
    faces[shell_of[root]].push_back(f);
    touched[shell_of[root]] |= is_affected[f];
  }
  auto shell = [](const Mesh& m, const std::vector<std::uint32_t>& fs) {
    Mesh s;
    s.points = m.points;  // shared handles: no coordinates are copied
    for (const std::uint32_t f : fs) s.triangles.push_back(m.triangles[f]);
    return s;
  };
  std::size_t turned = 0;
  for (std::size_t c = 0; c < faces.size(); ++c) {
    if (!touched[c]) continue;
    const Mesh whole = faces.size() == 1 ? Mesh{} : shell(exact, faces[c]);
    const Mesh& e = faces.size() == 1 ? exact : whole;
    const Mesh r = faces.size() == 1 ? rounded : shell(rounded, faces[c]);
    turned += signed_volume_sign(e) != signed_volume_sign(r);
  }
  return turned;
}

}  // namespace

RoundingDamage find_rounding_damage(const Mesh& exact, const DoubleMesh& rounded,
                                    const std::vector<std::uint8_t>& moved) {
  RoundingDamage damage;
  const Mesh m = from_double(rounded);
  std::vector<std::uint8_t> is_affected;
  const std::vector<std::uint32_t> affected = affected_faces(m, moved, is_affected);
  if (affected.empty()) return damage;
  std::vector<std::uint8_t> is_flat(m.num_triangles(), 0);
  for (const std::uint32_t f : affected) damage.flattened_faces += is_flat[f] = flat(m, m.triangles[f]);
  damage.pairs = improper_pairs(m, candidate_pairs(m, affected, is_affected, is_flat));
  damage.turned_shells = turned_shells(exact, m, is_affected);
  damage.broken = damage.flattened_faces > 0 || !damage.pairs.empty() || damage.turned_shells > 0;
  return damage;
}

}  // namespace morphex::detail

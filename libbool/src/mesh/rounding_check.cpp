// SPDX-License-Identifier: GPL-3.0-or-later
// find_rounding_damage (rounding_check.h). Two ways, by how much rounding moved:
//   - most of the mesh (floats from doubles: every vertex moves): the whole check, whose proofs
//     of vertex stars and flat patches settle neighbouring faces in bulk;
//   - a little of it (doubles from a Boolean of doubles: only the intersection's points move):
//     only the faces with a moved corner, against the faces whose boxes reach them, in a compact
//     copy of the faces involved. Linear passes over the rest, no tree over it.
#include "mesh/rounding_check.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>

#include "check/check_internal.h"
#include "morphex/check.h"
#include "morphex/internal/union_find.h"
#include "tree/box_tree.h"

namespace morphex::detail {
namespace {

using Pairs = std::vector<std::pair<std::uint32_t, std::uint32_t>>;
using Epick = CGAL::Exact_predicates_inexact_constructions_kernel;

Epick::Point_3 at(const DoubleMesh& m, VertexIndex v) {
  return {m.points[v][0], m.points[v][1], m.points[v][2]};
}

FloatBox box_of(const DoubleMesh& m, const Triangle& t) {
  CGAL::Bbox_3 b;
  for (const VertexIndex v : t) b += at(m, v).bbox();
  return FloatBox::of(b);
}

// A face without area in doubles: two corners at one position, or three on a line. Exact.
bool flat(const DoubleMesh& m, const Triangle& t) {
  const Epick::Point_3 a = at(m, t[0]), b = at(m, t[1]), c = at(m, t[2]);
  return a == b || b == c || c == a || CGAL::collinear(a, b, c);
}

// Pairs (i, j), one of them affected and not flat, whose boxes overlap; each once, i < j.
Pairs candidate_pairs(const DoubleMesh& m, const std::vector<std::uint32_t>& affected,
                      const std::vector<std::uint8_t>& is_affected,
                      const std::vector<std::uint8_t>& is_flat) {
  std::vector<FloatBox> boxes;
  std::vector<std::uint32_t> ids;
  for (const std::uint32_t f : affected)
    if (!is_flat[f]) {
      boxes.push_back(box_of(m, m.triangles[f]));
      ids.push_back(f);
    }
  const TriangleTree tree(std::move(boxes), ids);
  tbb::enumerable_thread_specific<Pairs> found;
  tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, std::uint32_t(m.triangles.size()), 2048),
                    [&](const auto& range) {
                      Pairs& local = found.local();
                      for (std::uint32_t j = range.begin(); j != range.end(); ++j) {
                        if (is_flat[j]) continue;
                        tree.for_each_overlap(box_of(m, m.triangles[j]), [&](std::uint32_t i) {
                          // Two affected faces meet twice: kept from the smaller one's side.
                          if (i != j && (!is_affected[j] || j < i))
                            local.emplace_back(std::min(i, j), std::max(i, j));
                        });
                      }
                    });
  Pairs all;
  for (const Pairs& p : found) all.insert(all.end(), p.begin(), p.end());
  std::sort(all.begin(), all.end());
  return all;
}

// The check's exact test on the faces of `pairs` only, copied into a compact mesh.
Pairs improper_among(const DoubleMesh& m, const Pairs& pairs) {
  std::vector<std::uint32_t> face_id(m.triangles.size(), UINT32_MAX);
  std::vector<VertexIndex> vertex_id(m.points.size(), UINT32_MAX);
  Mesh compact;
  auto add_face = [&](std::uint32_t f) {
    if (face_id[f] != UINT32_MAX) return face_id[f];
    Triangle t;
    for (int k = 0; k < 3; ++k) {
      const VertexIndex v = m.triangles[f][k];
      if (vertex_id[v] == UINT32_MAX) {
        vertex_id[v] = VertexIndex(compact.points.size());
        compact.points.emplace_back(m.points[v][0], m.points[v][1], m.points[v][2]);
      }
      t[k] = vertex_id[v];
    }
    face_id[f] = std::uint32_t(compact.triangles.size());
    compact.triangles.push_back(t);
    return face_id[f];
  };
  Pairs local;
  local.reserve(pairs.size());
  for (const auto& [i, j] : pairs) local.emplace_back(add_face(i), add_face(j));
  std::vector<std::uint32_t> original(compact.triangles.size());
  for (std::uint32_t f = 0; f < m.triangles.size(); ++f)
    if (face_id[f] != UINT32_MAX) original[face_id[f]] = f;
  Pairs out;
  for (const auto& [a, b] : improper_pairs(compact, local))
    out.emplace_back(std::min(original[a], original[b]), std::max(original[a], original[b]));
  std::sort(out.begin(), out.end());
  return out;
}

// Shells (components through shared vertices) holding an affected face whose rounded volume has
// another sign than the exact one: one pass of interval sums per shell, exact only where the
// interval does not decide.
std::size_t turned_shells(const Mesh& exact, const DoubleMesh& rounded,
                          const std::vector<std::uint8_t>& is_affected) {
  UnionFind sets(exact.num_vertices());
  for (const Triangle& t : exact.triangles) {
    sets.join(t[0], t[1]);
    sets.join(t[0], t[2]);
  }
  std::vector<std::uint32_t> shell_of(exact.num_vertices(), UINT32_MAX);
  std::vector<std::uint32_t> face_shell(exact.num_triangles());
  std::size_t shells = 0;
  for (std::uint32_t f = 0; f < exact.num_triangles(); ++f) {
    const std::uint32_t root = sets.find(exact.triangles[f][0]);
    if (shell_of[root] == UINT32_MAX) shell_of[root] = std::uint32_t(shells++);
    face_shell[f] = shell_of[root];
  }
  using I = CGAL::Interval_nt<false>;
  std::vector<I> before(shells, I(0)), after(shells, I(0));
  std::vector<std::uint8_t> touched(shells, 0);
  {
    CGAL::Protect_FPU_rounding<true> rounding;
    auto det = [](const auto& a, const auto& b, const auto& c) {
      return a[0] * (b[1] * c[2] - b[2] * c[1]) + a[1] * (b[2] * c[0] - b[0] * c[2]) +
             a[2] * (b[0] * c[1] - b[1] * c[0]);
    };
    for (std::uint32_t f = 0; f < exact.num_triangles(); ++f) {
      const std::uint32_t s = face_shell[f];
      touched[s] |= is_affected[f];
      const Triangle& t = exact.triangles[f];
      std::array<I, 3> e[3], r[3];
      for (int k = 0; k < 3; ++k) {
        const auto& p = CGAL::approx(exact.points[t[k]]);
        e[k] = {p.x(), p.y(), p.z()};
        r[k] = {I(rounded.points[t[k]][0]), I(rounded.points[t[k]][1]), I(rounded.points[t[k]][2])};
      }
      before[s] += det(e[0], e[1], e[2]);
      after[s] += det(r[0], r[1], r[2]);
    }
  }
  std::size_t turned = 0;
  for (std::size_t s = 0; s < shells; ++s) {
    if (!touched[s]) continue;
    const CGAL::Uncertain<CGAL::Sign> b = CGAL::sign(before[s]), a = CGAL::sign(after[s]);
    if (CGAL::is_certain(b) && CGAL::is_certain(a)) {
      turned += CGAL::get_certain(b) != CGAL::get_certain(a);
      continue;
    }
    Mesh e, r;  // undecided: the shell's two volumes exactly
    e.points = exact.points;
    r = from_double(rounded);
    r.triangles.clear();
    for (std::uint32_t f = 0; f < exact.num_triangles(); ++f)
      if (face_shell[f] == s) {
        e.triangles.push_back(exact.triangles[f]);
        r.triangles.push_back(exact.triangles[f]);
      }
    turned += signed_volume_sign(e) != signed_volume_sign(r);
  }
  return turned;
}

RoundingDamage whole_check(const DoubleMesh& rounded) {
  CheckOptions options;
  options.volume = false;
  options.list_self_intersections = true;
  const MeshReport report = check_mesh(from_double(rounded), options);
  RoundingDamage damage;
  damage.broken = !report.valid_solid();
  damage.flattened_faces = report.degenerate_faces;
  damage.turned_shells = report.outward ? 0 : 1;
  damage.pairs = report.self_intersecting_pairs;
  return damage;
}

}  // namespace

RoundingDamage find_rounding_damage(const Mesh& exact, const DoubleMesh& rounded,
                                    const std::vector<std::uint8_t>& moved) {
  RoundingDamage damage;
  std::vector<std::uint8_t> is_affected(rounded.triangles.size(), 0);
  std::vector<std::uint32_t> affected;
  for (std::uint32_t f = 0; f < rounded.triangles.size(); ++f) {
    const Triangle& t = rounded.triangles[f];
    if (moved[t[0]] || moved[t[1]] || moved[t[2]]) {
      is_affected[f] = 1;
      affected.push_back(f);
    }
  }
  if (affected.empty()) return damage;
  // Past an eighth of the faces, the check's bulk proofs beat testing pair by pair.
  if (8 * affected.size() > rounded.triangles.size()) return whole_check(rounded);
  std::vector<std::uint8_t> is_flat(rounded.triangles.size(), 0);
  for (const std::uint32_t f : affected)
    damage.flattened_faces += is_flat[f] = flat(rounded, rounded.triangles[f]);
  damage.pairs = improper_among(rounded, candidate_pairs(rounded, affected, is_affected, is_flat));
  damage.turned_shells = turned_shells(exact, rounded, is_affected);
  damage.broken = damage.flattened_faces > 0 || !damage.pairs.empty() || damage.turned_shells > 0;
  return damage;
}

}  // namespace morphex::detail

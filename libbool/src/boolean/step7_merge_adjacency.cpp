// SPDX-License-Identifier: GPL-3.0-or-later
// Adjacency for the coplanar merge (merge_adjacency.h).
#include "boolean/merge_adjacency.h"

#include <CGAL/Bbox_3.h>

#include <algorithm>
#include <cmath>
#include <unordered_map>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "containers/flat_map.h"

namespace morphex::detail {

namespace {

// The first of the `count` ends at `to` equal to u, or `count` when none is. Four ends are
// compared at once: scanning a vertex's five to seven edges one by one, the loop's exit at an
// unpredictable place costs more than the comparisons (a mispredicted branch per vertex), so a
// few extra comparisons buy a predictable loop. `to` has 3 readable entries past the last.
inline std::uint32_t first_equal(const VertexIndex* to, std::uint32_t count, VertexIndex u) {
#if defined(__SSE2__)
  const __m128i key = _mm_set1_epi32(int(u));
  for (std::uint32_t i = 0; i < count; i += 4) {
    const __m128i four = _mm_loadu_si128(reinterpret_cast<const __m128i*>(to + i));
    std::uint32_t hits =
        std::uint32_t(_mm_movemask_ps(_mm_castsi128_ps(_mm_cmpeq_epi32(key, four))));
    if (count - i < 4) hits &= (1u << (count - i)) - 1;
    if (hits != 0) return i + std::uint32_t(__builtin_ctz(hits));
  }
  return count;
#else
  std::uint32_t i = 0;
  while (i < count && to[i] != u) ++i;
  return i;
#endif
}

}  // namespace

VertexEdges::VertexEdges(const std::vector<Triangle>& tri, std::size_t nv)
    : tri_(tri), start_(nv + 1, 0), to_(3 * tri.size() + 3, kNoFace), face_(3 * tri.size()) {
  for (const Triangle& t : tri)
    for (VertexIndex v : t) ++start_[v + 1];
  for (std::size_t v = 0; v < nv; ++v) start_[v + 1] += start_[v];
  std::vector<std::uint32_t> fill(start_.begin(), start_.end() - 1);
  for (std::uint32_t f = 0; f < tri.size(); ++f)
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t slot = fill[tri[f][k]]++;
      to_[slot] = tri[f][(k + 1) % 3];
      face_[slot] = f;
    }
}

std::uint32_t VertexEdges::twin(std::uint32_t f, int k) const {
  const VertexIndex u = tri_[f][k], v = tri_[f][(k + 1) % 3];
  const std::uint32_t count = start_[v + 1] - start_[v];
  const std::uint32_t i = first_equal(to_.data() + start_[v], count, u);
  return i < count ? face_[start_[v] + i] : kNoFace;
}

std::vector<std::uint32_t> VertexEdges::all_twins() const {
  std::vector<std::uint32_t> twins(3 * tri_.size());
  for (std::uint32_t f = 0; f < tri_.size(); ++f)
    for (int k = 0; k < 3; ++k) twins[3 * f + k] = twin(f, k);
  return twins;
}

// For each vertex flagged in `of_interest`, whether another vertex has its position: the same
// point, or an equal one. The flagged vertices are bucketed by the grid cells their interval
// boxes cover (coincident points have overlapping boxes), and only vertices sharing a cell with a
// flagged one are compared exactly. The flagged ones are few (the candidates of a merge) and
// usually in one part of the surface: the other vertices are dropped by the box around them.
std::vector<std::uint8_t> coincident(const PointTable& table, const IdMesh& surface,
                                     const std::vector<std::uint8_t>& of_interest) {
  const std::size_t nv = surface.vertex_point.size();
  std::vector<std::uint8_t> shared(nv, 0);
  // Double boxes: coordinates beyond float range stay finite.
  auto box_of = [&](VertexIndex v) { return table.approx(surface.vertex_point[v]).bbox(); };
  std::vector<VertexIndex> flagged;
  std::vector<CGAL::Bbox_3> flagged_box;
  CGAL::Bbox_3 frame;  // around the flagged boxes
  for (VertexIndex v = 0; v < nv; ++v)
    if (of_interest[v]) {
      flagged.push_back(v);
      flagged_box.push_back(box_of(v));
      frame += flagged_box.back();
    }
  if (flagged.empty()) return shared;
  // Cells about 2^-20 of the flagged boxes' extent: far wider than any point's interval box, so
  // that a box covers one cell, rarely two along an axis.
  double cell = 0;
  for (int k = 0; k < 3; ++k) cell = std::max(cell, frame.max(k) - frame.min(k));
  cell = cell > 0 ? std::ldexp(cell, -20) : 1;
  const bool finite = std::isfinite(cell);  // else every box counts as wide
  auto cell_range = [&](const CGAL::Bbox_3& b, std::int64_t(&lo)[3], std::int64_t(&hi)[3]) {
    if (!finite) return std::numeric_limits<std::int64_t>::max();
    std::int64_t count = 1;
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::int64_t(std::floor((std::max(b.min(k), frame.min(k)) - frame.min(k)) / cell));
      hi[k] = std::int64_t(std::floor((std::min(b.max(k), frame.max(k)) - frame.min(k)) / cell));
      count *= std::min<std::int64_t>(hi[k] - lo[k] + 1, 1 << 20);
    }
    return count;
  };
  // Boxes over a few cells (constructions whose intervals are wide) are compared directly.
  constexpr std::int64_t kMaxCells = 8;
  auto for_each_cell = [&](const std::int64_t(&lo)[3], const std::int64_t(&hi)[3], auto&& visit) {
    for (std::int64_t x = lo[0]; x <= hi[0]; ++x)
      for (std::int64_t y = lo[1]; y <= hi[1]; ++y)
        for (std::int64_t z = lo[2]; z <= hi[2]; ++z)
          visit(mix64(std::uint64_t(x) * 0x9e3779b97f4a7c15ull ^ std::uint64_t(y) << 21 ^
                      std::uint64_t(z) << 42));
  };
  // i: a flagged vertex's place in `flagged`.
  auto compare = [&](VertexIndex u, const CGAL::Bbox_3& box, std::uint32_t i) {
    const VertexIndex v = flagged[i];
    if (v != u && CGAL::do_overlap(box, flagged_box[i]) &&
        table.equal(surface.vertex_point[u], surface.vertex_point[v]))
      shared[v] = 1;
  };
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> cells;
  std::vector<std::uint32_t> wide_flagged;
  for (std::uint32_t i = 0; i < flagged.size(); ++i) {
    std::int64_t lo[3], hi[3];
    if (cell_range(flagged_box[i], lo, hi) > kMaxCells)
      wide_flagged.push_back(i);
    else
      for_each_cell(lo, hi, [&](std::uint64_t key) { cells[key].push_back(i); });
  }
  for (VertexIndex u = 0; u < nv; ++u) {
    const CGAL::Bbox_3 box = box_of(u);
    if (!CGAL::do_overlap(box, frame)) continue;  // meets no flagged box
    for (const std::uint32_t i : wide_flagged) compare(u, box, i);
    std::int64_t lo[3], hi[3];
    if (cell_range(box, lo, hi) > kMaxCells) {
      for (std::uint32_t i = 0; i < flagged.size(); ++i) compare(u, box, i);
      continue;
    }
    for_each_cell(lo, hi, [&](std::uint64_t key) {
      const auto it = cells.find(key);
      if (it == cells.end()) return;
      for (const std::uint32_t i : it->second) compare(u, box, i);
    });
  }
  return shared;
}

}  // namespace morphex::detail

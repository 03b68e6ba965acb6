// SPDX-License-Identifier: GPL-3.0-or-later
// Faces around a segment that several edges share by position. A separated non-manifold edge (two
// pairs of faces on one segment, each pair an edge of its own between vertex copies) bounds a
// solid only when each pair's faces are next to each other around the segment, the solid wedge
// between them holding no other face. Pairs that interleave cross each other along the segment:
// no two triangles meet improperly, yet the shells overlap (two solids sharing three edges of a
// corner, one cutting into the other). Around the segment, solid and empty wedges alternate, and
// the two faces of each edge must not separate the two faces of another.
#include "check/check_edge_fans.h"

#include <algorithm>
#include <cstdint>
#include <tuple>

#include "exact/around_edge.h"

namespace morphex::detail {

namespace {

// One face on a segment between positions lo < hi.
struct OnSegment {
  std::uint64_t segment;  // (lo, hi) positions
  std::uint64_t edge;     // the face's own edge there, by vertex index (min, max)
  std::uint32_t face;
  PointId third;  // position of the face's third corner
  bool runs_up;   // the face runs lo -> hi
  bool operator<(const OnSegment& o) const {
    return std::tie(segment, face) < std::tie(o.segment, o.face);
  }
};

std::uint64_t pack(std::uint32_t a, std::uint32_t b) {
  return (std::uint64_t(std::min(a, b)) << 32) | std::max(a, b);
}

// The faces on segments with an end at a position that several vertices share: only there can
// distinct edges lie on one segment.
std::vector<OnSegment> faces_on_shared_segments(const Mesh& mesh,
                                                const std::vector<PointId>& position) {
  const std::size_t nv = mesh.num_vertices();
  std::vector<std::uint8_t> shared(nv, 0);  // by position (a vertex index), then by vertex
  bool any = false;
  for (VertexIndex v = 0; v < nv; ++v)
    if (position[v] != v) any = shared[position[v]] = 1;
  std::vector<OnSegment> out;
  if (!any) return out;
  for (VertexIndex v = 0; v < nv; ++v) shared[v] = shared[position[v]];
  for (std::uint32_t f = 0; f < mesh.num_triangles(); ++f) {
    const Triangle& t = mesh.triangles[f];
    for (int k = 0; k < 3; ++k) {
      const VertexIndex a = t[k], b = t[(k + 1) % 3];
      if (!shared[a] && !shared[b]) continue;
      const PointId pa = position[a], pb = position[b], pc = position[t[(k + 2) % 3]];
      if (pa == pb || pc == pa || pc == pb) continue;  // a degenerate face, reported on its own
      out.push_back({pack(pa, pb), pack(a, b), f, pc, pa < pb});
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

// The faces of each edge, a fold of the surface along the segment, enclose the folds they meet
// between them, never half of one: as chords of the circle around the segment, on[begin, end)
// in angular order, they nest like parentheses. Each fold that closes around one still open is
// reported with it. Linear after a sort, however many faces a crafted file puts on one segment.
template <class Report>
void report_crossing_folds(const std::vector<OnSegment>& on, std::size_t begin, std::size_t end,
                           Report&& report) {
  const std::size_t k = end - begin;
  std::vector<std::pair<std::uint64_t, std::size_t>> by_edge;  // (edge, place in the order)
  by_edge.reserve(k);
  for (std::size_t i = 0; i < k; ++i) by_edge.emplace_back(on[begin + i].edge, i);
  std::sort(by_edge.begin(), by_edge.end());
  constexpr std::size_t kNoMate = SIZE_MAX;
  std::vector<std::size_t> mate(k, kNoMate);  // a border or non-manifold edge has none
  for (std::size_t i = 0, j; i < k; i = j) {
    for (j = i + 1; j < k && by_edge[j].first == by_edge[i].first;) ++j;
    if (j - i != 2) continue;  // reported on its own
    mate[by_edge[i].second] = by_edge[i + 1].second;
    mate[by_edge[i + 1].second] = by_edge[i].second;
  }
  std::vector<std::size_t> open;  // folds whose second face is still to come, innermost last
  std::vector<std::uint8_t> closed(k, 0);
  for (std::size_t i = 0; i < k; ++i) {
    if (mate[i] == kNoMate) continue;
    if (mate[i] > i) {
      open.push_back(i);
      continue;
    }
    while (closed[open.back()]) open.pop_back();  // closed out of turn, below the top
    if (open.back() == mate[i]) {
      open.pop_back();
    } else {
      report(on[begin + i].face, on[begin + open.back()].face);  // they cross
      closed[mate[i]] = 1;
    }
  }
}

}  // namespace

std::vector<std::pair<std::uint32_t, std::uint32_t>> interleaved_edge_fans(
    const Mesh& mesh, const PointTable& table, const std::vector<PointId>& position) {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> found;
  auto report = [&](std::uint32_t f, std::uint32_t g) {
    found.emplace_back(std::min(f, g), std::max(f, g));
  };
  std::vector<OnSegment> on = faces_on_shared_segments(mesh, position);
  for (std::size_t begin = 0; begin < on.size();) {
    std::size_t end = begin + 1;
    while (end < on.size() && on[end].segment == on[begin].segment) ++end;
    if (end - begin > 2) {
      const auto lo = PointId(on[begin].segment >> 32), hi = PointId(on[begin].segment);
      const auto first = on.begin() + std::ptrdiff_t(begin),
                 last = on.begin() + std::ptrdiff_t(end);
      // Counter-clockwise around lo -> hi from the face of least index.
      const AroundEdge order{table, lo, hi, on[begin].third};
      std::sort(first, last,
                [&](const OnSegment& x, const OnSegment& y) { return order(x.third, y.third); });
      // Solid and empty wedges alternate: neighbours run the segment opposite ways.
      for (std::size_t i = begin; i < end; ++i) {
        const OnSegment& next = on[i + 1 == end ? begin : i + 1];
        if (next.runs_up == on[i].runs_up) report(on[i].face, next.face);
      }
      report_crossing_folds(on, begin, end, report);
    }
    begin = end;
  }
  std::sort(found.begin(), found.end());
  found.erase(std::unique(found.begin(), found.end()), found.end());
  return found;
}

}  // namespace morphex::detail

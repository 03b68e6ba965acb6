// SPDX-License-Identifier: GPL-3.0-or-later
// separate_touching (separate_touching.h).
#include "mesh/separate_touching.h"

#include <algorithm>
#include <cstdint>
#include <vector>

#include "morphex/internal/union_find.h"

namespace morphex::detail {
namespace {

// Half-edge (f, k) runs from corner k of face f to corner k + 1.
struct Use {
  std::uint64_t edge;  // (min, max) vertex
  std::uint32_t half;  // 3 f + k
  bool operator<(const Use& o) const { return edge < o.edge || (edge == o.edge && half < o.half); }
};

// Angle order around the directed axis lo -> hi of the faces' third vertices, counter-clockwise
// from `ref`'s half-plane. Exact predicates.
struct AroundAxis {
  const Point &lo, &hi, &ref;
  int half(const Point& w) const {
    const CGAL::Orientation s = CGAL::orientation(lo, hi, ref, w);
    if (s != CGAL::ZERO) return s == CGAL::POSITIVE ? 0 : 1;
    return CGAL::coplanar_orientation(lo, hi, ref, w) == CGAL::POSITIVE ? 0 : 1;
  }
  bool operator()(const Point& p, const Point& q) const {
    const int hp = half(p), hq = half(q);
    if (hp != hq) return hp < hq;
    return CGAL::orientation(lo, hi, p, q) == CGAL::POSITIVE;
  }
};

class Separator {
 public:
  explicit Separator(Mesh& mesh) : mesh_(mesh), corners_(3 * mesh.triangles.size()) {}

  std::size_t run() {
    std::vector<Use> uses;
    uses.reserve(3 * mesh_.triangles.size());
    for (std::uint32_t h = 0; h < 3 * mesh_.triangles.size(); ++h) {
      const VertexIndex a = from(h), b = to(h);
      uses.push_back({(std::uint64_t(std::min(a, b)) << 32) | std::max(a, b), h});
    }
    std::sort(uses.begin(), uses.end());
    // Only a closed, consistently oriented surface is separated: elsewhere fans are not defined
    // and the check must see the file's own problems.
    std::vector<std::size_t> runs = {0};
    for (std::size_t i = 0, j; i < uses.size(); i = j) {
      for (j = i; j < uses.size() && uses[j].edge == uses[i].edge;) ++j;
      if (!balanced(uses, i, j)) return 0;
      runs.push_back(j);
    }
    for (std::size_t r = 0; r + 1 < runs.size(); ++r) join_across(uses, runs[r], runs[r + 1]);
    return split_vertices();
  }

 private:
  VertexIndex from(std::uint32_t h) const { return mesh_.triangles[h / 3][h % 3]; }
  VertexIndex to(std::uint32_t h) const { return mesh_.triangles[h / 3][(h + 1) % 3]; }
  VertexIndex third(std::uint32_t h) const { return mesh_.triangles[h / 3][(h + 2) % 3]; }
  // The corner of half-edge h's face at vertex v (an end of h).
  std::uint32_t corner_at(std::uint32_t h, VertexIndex v) const {
    return from(h) == v ? h : 3 * (h / 3) + (h + 1) % 3;
  }

  // Joins the corners at both ends of two half-edges that run one edge in opposite directions.
  void mate(std::uint32_t g, std::uint32_t h) {
    corners_.join(corner_at(g, from(g)), corner_at(h, from(g)));
    corners_.join(corner_at(g, to(g)), corner_at(h, to(g)));
  }

  // The edge of uses [i, j) is run as often one way as the other, between distinct vertices.
  bool balanced(const std::vector<Use>& uses, std::size_t i, std::size_t j) const {
    const VertexIndex lo = VertexIndex(uses[i].edge >> 32), hi = VertexIndex(uses[i].edge);
    std::size_t forward = 0;
    for (std::size_t t = i; t < j; ++t) forward += from(uses[t].half) == lo;
    return lo != hi && 2 * forward == j - i;
  }

  void join_across(const std::vector<Use>& uses, std::size_t i, std::size_t j) {
    const VertexIndex lo = VertexIndex(uses[i].edge >> 32), hi = VertexIndex(uses[i].edge);
    if (j - i == 2) return mate(uses[i].half, uses[i + 1].half);
    std::vector<std::uint32_t> hs;
    for (std::size_t t = i; t < j; ++t) hs.push_back(uses[t].half);
    const Point &a = mesh_.points[lo], &b = mesh_.points[hi];
    const AroundAxis order{a, b, mesh_.points[third(hs[0])]};
    std::sort(hs.begin(), hs.end(), [&](std::uint32_t x, std::uint32_t y) {
      return order(mesh_.points[third(x)], mesh_.points[third(y)]);
    });
    // Each face running lo -> hi bounds, with the face just before it, a wedge of the solid.
    for (std::size_t t = 0; t < hs.size(); ++t)
      if (from(hs[t]) == lo) mate(hs[t], hs[(t + hs.size() - 1) % hs.size()]);
  }

  // One vertex per fan of corners: the first fan of a vertex keeps its index, the others get
  // copies of its point.
  std::size_t split_vertices() {
    const std::size_t before = mesh_.points.size();
    std::vector<std::uint32_t> fan_of_vertex(before, UINT32_MAX);
    std::vector<VertexIndex> vertex_of_fan(corners_.parent.size(), UINT32_MAX);
    for (std::uint32_t c = 0; c < corners_.parent.size(); ++c) {
      const VertexIndex v = mesh_.triangles[c / 3][c % 3];
      const std::uint32_t fan = corners_.find(c);
      if (vertex_of_fan[fan] == UINT32_MAX) {
        if (fan_of_vertex[v] == UINT32_MAX) {
          fan_of_vertex[v] = fan;
          vertex_of_fan[fan] = v;
        } else {
          vertex_of_fan[fan] = VertexIndex(mesh_.points.size());
          mesh_.points.push_back(mesh_.points[v]);
        }
      }
      mesh_.triangles[c / 3][c % 3] = vertex_of_fan[fan];
    }
    return mesh_.points.size() - before;
  }

  Mesh& mesh_;
  UnionFind corners_;  // over corners 3 f + k: one set per fan
};

}  // namespace

std::size_t separate_touching(Mesh& mesh) {
  return Separator(mesh).run();
}

}  // namespace morphex::detail

// SPDX-License-Identifier: GPL-3.0-or-later
// Building the pieces of the reduced convolution: prisms, patch sweeps and swept triangles
// (convolution_internal.h says why they are glued).
#include <tbb/parallel_for.h>

#include <array>
#include <functional>
#include <map>
#include <unordered_map>

#include "convolution_internal.h"
#include "morphex/check.h"
#include "morphex/internal/union_find.h"

namespace morphex::detail {

Point sum_point(const Point& p, const Point& q) {
  const auto &a = CGAL::exact(p), &b = CGAL::exact(q);
  return point_from_exact({a.x() + b.x(), a.y() + b.y(), a.z() + b.z()});
}

Mesh prism(const std::array<Point, 3>& p, const Triangle& ids, const Point& s, const Point& c) {
  Mesh m;
  for (const Point& q : p) m.points.push_back(sum_point(q, c));
  for (const Point& q : p) m.points.push_back(sum_point(q, s));
  m.triangles = {{0, 2, 1}, {3, 4, 5}};
  for (VertexIndex i = 0; i < 3; ++i) {
    const VertexIndex j = (i + 1) % 3;
    if (ids[i] < ids[j]) {
      m.triangles.push_back({i, j, j + 3});
      m.triangles.push_back({i, j + 3, i + 3});
    } else {
      m.triangles.push_back({i, j, i + 3});
      m.triangles.push_back({j, j + 3, i + 3});
    }
  }
  return m;
}

Mesh tetrahedron(const std::array<Point, 4>& q) {
  const CGAL::Orientation o = CGAL::orientation(q[0], q[1], q[2], q[3]);
  if (o == CGAL::COPLANAR) return {};
  Mesh m;
  m.points.assign(q.begin(), q.end());
  // (q0, q1, q2) sees q3 on its positive side: that face points inward.
  m.triangles = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {2, 0, 3}};
  if (o == CGAL::NEGATIVE)
    for (Triangle& t : m.triangles) std::swap(t[1], t[2]);
  return m;
}

std::vector<std::vector<std::uint32_t>> same_support_patches(
    const Mesh& surface, const DirectedEdges& edges,
    const std::vector<std::vector<VertexIndex>>& support, const std::vector<std::uint8_t>& whole) {
  const std::size_t nf = surface.triangles.size();
  UnionFind sets(nf);
  for (std::uint32_t f = 0; f < nf; ++f) {
    if (whole[f]) continue;
    const Triangle& t = surface.triangles[f];
    for (int i = 0; i < 3; ++i) {
      const std::uint32_t g = edges.facet(t[(i + 1) % 3], t[i]);
      if (g != DirectedEdges::kNone && g > f && !whole[g] && support[g] == support[f])
        sets.join(f, g);
    }
  }
  std::vector<std::uint32_t> slot(nf, UINT32_MAX);
  std::vector<std::vector<std::uint32_t>> patches;
  for (std::uint32_t f = 0; f < nf; ++f) {
    if (whole[f]) continue;
    std::uint32_t& k = slot[sets.find(f)];
    if (k == UINT32_MAX) {
      k = std::uint32_t(patches.size());
      patches.emplace_back();
    }
    patches[k].push_back(f);
  }
  return patches;
}

namespace {

// The union of the prisms f + [c, s] of a patch as one closed mesh: the patch at c (reversed), the
// patch at s, and the prism walls over the patch's border edges, split as prism() splits them.
// Inner walls cancel in pairs, so the winding number of this surface counts the prisms covering a
// point: when it is a valid solid (the patch seen along s - c does not overlap itself), that count
// is 0 or 1 and the sweep is exactly the prisms' union.
Mesh sweep(const Mesh& surface, const std::vector<std::uint32_t>& patch, const Point& s,
           const Point& c) {
  const auto& p = surface.points;
  std::unordered_map<VertexIndex, VertexIndex> local;  // surface vertex -> copy at c; +1 at s
  Mesh m;
  const auto copy = [&](VertexIndex v) {
    auto [it, added] = local.emplace(v, VertexIndex(m.points.size()));
    if (added) {
      m.points.push_back(sum_point(p[v], c));
      m.points.push_back(sum_point(p[v], s));
    }
    return it->second;
  };
  std::unordered_map<std::uint64_t, int> directed;  // patch edges u -> v
  const auto key = [](VertexIndex u, VertexIndex v) { return (std::uint64_t(u) << 32) | v; };
  for (std::uint32_t f : patch) {
    const Triangle& t = surface.triangles[f];
    const VertexIndex a = copy(t[0]), b = copy(t[1]), d = copy(t[2]);
    m.triangles.push_back({a, d, b});
    m.triangles.push_back({a + 1, b + 1, d + 1});
    for (int i = 0; i < 3; ++i) ++directed[key(t[i], t[(i + 1) % 3])];
  }
  for (std::uint32_t f : patch) {
    const Triangle& t = surface.triangles[f];
    for (int i = 0; i < 3; ++i) {
      const VertexIndex u = t[i], v = t[(i + 1) % 3];
      if (directed.count(key(v, u))) continue;  // an inner edge: its walls cancel
      const VertexIndex i0 = local.at(u), j0 = local.at(v);
      if (u < v) {
        m.triangles.push_back({i0, j0, j0 + 1});
        m.triangles.push_back({i0, j0 + 1, i0 + 1});
      } else {
        m.triangles.push_back({i0, j0, i0 + 1});
        m.triangles.push_back({j0, j0 + 1, i0 + 1});
      }
    }
  }
  return m;
}

}  // namespace

void patch_pieces(const Mesh& surface, const DirectedEdges& edges, std::vector<std::uint32_t> patch,
                  const Point& s, const Point& c, bool solids, std::vector<Mesh>& out) {
  if (patch.size() == 1) {
    const Triangle& t = surface.triangles[patch[0]];
    const auto& p = surface.points;
    out.push_back(prism({p[t[0]], p[t[1]], p[t[2]]}, t, s, c));
    return;
  }
  Mesh m = sweep(surface, patch, s, c);
  if (!solids || check_mesh(m, kValidityOnly).valid_solid()) {
    out.push_back(std::move(m));
    return;
  }
  // Breadth-first order over the patch's own adjacency.
  std::unordered_map<std::uint32_t, bool> seen;
  for (std::uint32_t f : patch) seen.emplace(f, false);
  std::vector<std::uint32_t> order;
  for (std::uint32_t start : patch) {
    if (seen.at(start)) continue;
    seen[start] = true;
    order.push_back(start);
    for (std::size_t k = order.size() - 1; k < order.size(); ++k) {
      const Triangle& t = surface.triangles[order[k]];
      for (int i = 0; i < 3; ++i) {
        const auto it = seen.find(edges.facet(t[(i + 1) % 3], t[i]));
        if (it != seen.end() && !it->second) {
          it->second = true;
          order.push_back(it->first);
        }
      }
    }
  }
  const auto half = order.begin() + std::ptrdiff_t(order.size() / 2);
  patch_pieces(surface, edges, {order.begin(), half}, s, c, solids, out);
  patch_pieces(surface, edges, {half, order.end()}, s, c, solids, out);
}

namespace {

// The triangle t swept along the monotone chain w0, ..., wk: three copies of every w, the caps
// at w0 (reversed) and wk, and one pair of triangles per side of t per segment. Inner caps would
// be shared by two prisms with opposite orientations: they are left out.
Mesh swept_triangle(const Mesh& surface, const std::vector<VertexIndex>& chain,
                    const std::array<Point, 3>& t) {
  Mesh m;
  for (VertexIndex w : chain)
    for (const Point& corner : t) m.points.push_back(sum_point(surface.points[w], corner));
  const auto last = VertexIndex(3 * (chain.size() - 1));
  m.triangles = {{0, 2, 1}, {last, last + 1, last + 2}};
  for (VertexIndex base = 0; base < last; base += 3)
    for (VertexIndex i = 0; i < 3; ++i) {
      const VertexIndex j = (i + 1) % 3;
      m.triangles.push_back({base + i, base + j, base + j + 3});
      m.triangles.push_back({base + i, base + j + 3, base + i + 3});
    }
  return m;
}

}  // namespace

void triangle_edge_pieces(const Mesh& surface, const std::vector<TriangleEdge>& edges,
                          const std::vector<Point>& b, const Point& c, std::vector<Mesh>& out) {
  const auto& p = surface.points;
  // Edges by triangle, each directed from low to high along the triangle's normal.
  std::map<std::pair<VertexIndex, VertexIndex>, std::vector<std::pair<VertexIndex, VertexIndex>>>
      by_triangle;
  for (const TriangleEdge& e : edges) {
    const Point &t0 = c, &t1 = b[e.s0], &t2 = b[e.s1];
    const CGAL::Orientation o = CGAL::orientation(t0, t1, t2, t0 + (p[e.v] - p[e.u]));
    if (o == CGAL::COPLANAR) continue;  // flat
    by_triangle[{e.s0, e.s1}].push_back(o == CGAL::POSITIVE ? std::pair(e.u, e.v)
                                                            : std::pair(e.v, e.u));
  }
  for (const auto& [key, directed] : by_triangle) {
    const std::array<Point, 3> t = {c, b[key.first], b[key.second]};
    std::unordered_map<VertexIndex, std::vector<VertexIndex>> next;  // low -> highs
    std::unordered_map<VertexIndex, int> incoming;
    for (const auto& [low, high] : directed) {
      next[low].push_back(high);
      ++incoming[high];
    }
    // A chain goes on through w when w ends exactly one edge and starts exactly one.
    const auto passes = [&](VertexIndex w) {
      const auto it = next.find(w);
      return incoming.count(w) && incoming.at(w) == 1 && it != next.end() && it->second.size() == 1;
    };
    for (const auto& [low, high] : directed) {
      if (passes(low)) continue;  // inside a chain that starts elsewhere
      std::vector<VertexIndex> chain = {low, high};
      while (passes(chain.back())) chain.push_back(next.at(chain.back()).front());
      out.push_back(swept_triangle(surface, chain, t));
    }
  }
}

namespace {

// The points of A + c, found by exact position (keyed by their coordinates in doubles, which are
// equal for equal exact points).
class MovedSurface {
 public:
  MovedSurface(const Mesh& surface, const Point& c) {
    points_.reserve(surface.points.size());
    for (const Point& p : surface.points) {
      points_.push_back(sum_point(p, c));
      index_.emplace(key(points_.back()), VertexIndex(points_.size() - 1));
    }
  }
  bool contains(const Point& q) const {
    const auto [first, last] = index_.equal_range(key(q));
    for (auto it = first; it != last; ++it)
      if (points_[it->second] == q) return true;
    return false;
  }

 private:
  struct Hash {
    std::size_t operator()(const std::array<double, 3>& k) const {
      const std::hash<double> h;
      return h(k[0]) ^ (h(k[1]) * 0x9e3779b97f4a7c15ull) ^ (h(k[2]) * 0xc2b2ae3d27d4eb4full);
    }
  };
  static std::array<double, 3> key(const Point& q) {
    const auto& e = CGAL::exact(q);
    return {CGAL::to_double(e.x()), CGAL::to_double(e.y()), CGAL::to_double(e.z())};
  }
  std::vector<Point> points_;
  std::unordered_multimap<std::array<double, 3>, VertexIndex, Hash> index_;
};

// Whether w, u, x, v (in this cyclic order) is a parallelogram: u - w = x - v, exactly (in
// intervals first: most neighbouring triangles of a piece are not one).
bool parallelogram(const Point& w, const Point& u, const Point& x, const Point& v) {
  {
    CGAL::Protect_FPU_rounding<true> rounding;
    const auto &aw = CGAL::approx(w), &au = CGAL::approx(u), &ax = CGAL::approx(x),
               &av = CGAL::approx(v);
    for (int k = 0; k < 3; ++k) {
      const CGAL::Uncertain<bool> differ =
          (au.cartesian(k) - aw.cartesian(k)) != (ax.cartesian(k) - av.cartesian(k));
      if (CGAL::is_certain(differ) && CGAL::get_certain(differ)) return false;
    }
  }
  const auto &ew = CGAL::exact(w), &eu = CGAL::exact(u), &ex = CGAL::exact(x), &ev = CGAL::exact(v);
  for (int k = 0; k < 3; ++k)
    if (eu.cartesian(k) - ew.cartesian(k) != ex.cartesian(k) - ev.cartesian(k)) return false;
  return true;
}

void split_quads_alike(Mesh& m, const MovedSurface& moved) {
  const std::size_t nt = m.triangles.size();
  const auto& p = m.points;
  const auto key = [](VertexIndex u, VertexIndex v) { return (std::uint64_t(u) << 32) | v; };
  std::unordered_map<std::uint64_t, std::uint32_t> by_edge;
  by_edge.reserve(3 * nt);
  for (std::uint32_t i = 0; i < nt; ++i)
    for (int k = 0; k < 3; ++k)
      by_edge.emplace(key(m.triangles[i][k], m.triangles[i][(k + 1) % 3]), i);
  std::vector<std::uint8_t> done(nt, 0);
  for (std::uint32_t i = 0; i < nt; ++i)
    for (int k = 0; k < 3 && !done[i]; ++k) {
      const Triangle t = m.triangles[i];
      const VertexIndex u = t[k], v = t[(k + 1) % 3], w = t[(k + 2) % 3];
      const auto it = by_edge.find(key(v, u));
      if (it == by_edge.end() || it->second == i || done[it->second]) continue;
      const std::uint32_t j = it->second;
      const VertexIndex x = third_vertex(m.triangles[j], u, v);
      // Triangles (u, v, w) and (v, u, x): the quadrilateral w, u, x, v.
      // (A parallelogram is planar; one with area is strictly convex.)
      if (!parallelogram(p[w], p[u], p[x], p[v]) || CGAL::collinear(p[w], p[x], p[u])) continue;
      done[i] = done[j] = 1;
      if (moved.contains(p[w]) && moved.contains(p[u]) && moved.contains(p[x]) &&
          moved.contains(p[v]))
        continue;
      const std::array<VertexIndex, 4> corners = {w, u, x, v};
      int smallest = 0;
      for (int q = 1; q < 4; ++q)
        if (CGAL::compare_xyz(p[corners[q]], p[corners[smallest]]) == CGAL::SMALLER) smallest = q;
      if (smallest % 2 == 0) {  // the diagonal w-x instead of u-v
        m.triangles[i] = {w, u, x};
        m.triangles[j] = {x, v, w};
      }
    }
}

}  // namespace

void split_shared_quads_alike(std::vector<Mesh>& pieces, const Mesh& surface, const Point& c) {
  const MovedSurface moved(surface, c);
  tbb::parallel_for(std::size_t(0), pieces.size(),
                    [&](std::size_t i) { split_quads_alike(pieces[i], moved); });
}

}  // namespace morphex::detail

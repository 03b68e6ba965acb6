// SPDX-License-Identifier: GPL-3.0-or-later
// Step 3, coplanar pairs: the overlap of two coplanar triangles, by clipping tb with ta's edge
// lines in their common plane (seen along a dropped coordinate axis). New vertices are crossings of
// an edge of tb with an edge line of ta, kept as recipes of input points; their exact values are
// computed only if a predicate needs them. Every vertex carries the edges of ta and tb it lies on,
// so the facets' triangulations take those collinearities from the combinatorics.
#include <algorithm>
#include <memory>

#include "boolean/segments_internal.h"

namespace morphex::detail {

namespace {

// A vertex of the polygon being clipped: a point of the table, or a crossing of an edge of tb with
// an edge line of ta made for this polygon (exact value computed only if a predicate needs it).
struct PolygonVertex {
  PointId id = kNoPoint;
  Recipe recipe;
  ApproxPoint approx;
  mutable std::shared_ptr<const Homogeneous> exact;
  std::int8_t edge_a = -1, edge_b = -1;  // a crossing: the edges of ta and tb it lies on
  std::int8_t leaving = 0;               // the polygon edge to the next vertex lies on the line
                                         // of tb's edge j (j) or of ta's edge i (3 + i)
};

class CoplanarClipper {
 public:
  CoplanarClipper(const PointTable& table, const Corners& ta, const Corners& tb, int dropped,
                  bool soup)
      : table_(table), ta_(ta), tb_(tb), dropped_(dropped), soup_(soup) {}

  // The overlap of the two closed triangles: nothing, a point, a segment's ends or a convex
  // polygon, each vertex with the edges of ta and tb it lies on.
  std::vector<PairPoint> overlap() const {
    const int turn = orientation(table_vertex(ta_[0]), table_vertex(ta_[1]), table_vertex(ta_[2]));
    std::vector<PolygonVertex> polygon;
    for (int j = 0; j < 3; ++j) {
      PolygonVertex v = table_vertex(tb_[j]);
      v.leaving = std::int8_t(j);
      polygon.push_back(v);
    }
    std::vector<PolygonVertex> clipped;
    std::vector<int> side;
    for (int i = 0; i < 3 && !polygon.empty(); ++i) {
      const PolygonVertex a = table_vertex(ta_[i]), b = table_vertex(ta_[(i + 1) % 3]);
      side.resize(polygon.size());
      for (std::size_t k = 0; k < polygon.size(); ++k)
        side[k] = turn * orientation(a, b, polygon[k]);
      clipped.clear();
      for (std::size_t k = 0; k < polygon.size(); ++k) {
        const std::size_t next = (k + 1) % polygon.size();
        if (side[k] >= 0) {
          PolygonVertex v = polygon[k];
          if (side[k] == 0 && side[next] < 0) v.leaving = std::int8_t(3 + i);
          clipped.push_back(v);
        }
        if (side[k] * side[next] < 0) {
          PolygonVertex v = crossing(i, polygon[k].leaving);
          v.leaving = side[k] > 0 ? std::int8_t(3 + i) : polygon[k].leaving;
          clipped.push_back(v);
        }
      }
      std::swap(polygon, clipped);
    }
    // Touching contacts leave repeated points and flat polygons: reduce to distinct points, and
    // a polygon without area to the ends of its segment.
    std::vector<PolygonVertex> distinct;
    for (const PolygonVertex& v : polygon)
      if (distinct.empty() || !same(v, distinct.back())) distinct.push_back(v);
    while (distinct.size() > 1 && same(distinct.front(), distinct.back())) distinct.pop_back();
    if (distinct.size() >= 3) {
      bool flat = true;
      for (std::size_t k = 2; k < distinct.size() && flat; ++k)
        flat = orientation(distinct[0], distinct[1], distinct[k]) == 0;
      if (flat) {
        // The extreme points along the segment's line, by lexicographic order (monotone along
        // any line).
        const auto [lo, hi] = std::minmax_element(
            distinct.begin(), distinct.end(),
            [&](const PolygonVertex& p, const PolygonVertex& q) { return less_xyz(p, q); });
        distinct = {*lo, *hi};
      }
    }
    std::vector<PairPoint> out;
    for (const PolygonVertex& v : distinct) out.push_back(pair_point(v));
    return out;
  }

 private:
  PolygonVertex table_vertex(PointId id) const {
    PolygonVertex v;
    v.id = id;
    v.approx = table_.approx(id);
    return v;
  }

  const Homogeneous& exact(const PolygonVertex& v) const {
    if (v.id != kNoPoint) return table_.exact(v.id);
    if (!v.exact) {
      const Recipe& r = v.recipe;
      v.exact = std::make_shared<const Homogeneous>(
          construct_homogeneous(r, table_.exact(r.p), table_.exact(r.q), table_.exact(r.a),
                                table_.exact(r.b), table_.exact(r.a)));
    }
    return *v.exact;
  }

  int orientation(const PolygonVertex& p, const PolygonVertex& q, const PolygonVertex& r) const {
    const int u = dropped_ == 0 ? 1 : 0, v = dropped_ == 2 ? 1 : 2;
    if (p.id != kNoPoint && q.id != kNoPoint && r.id != kNoPoint)
      return table_.orientation_2(dropped_, p.id, q.id, r.id);
    {
      CGAL::Protect_FPU_rounding<true> rounding;
      const auto o =
          CGAL::orientationC2(p.approx.cartesian(u), p.approx.cartesian(v), q.approx.cartesian(u),
                              q.approx.cartesian(v), r.approx.cartesian(u), r.approx.cartesian(v));
      if (CGAL::is_certain(o)) return CGAL::get_certain(o);
    }
    const Homogeneous &hp = exact(p), &hq = exact(q), &hr = exact(r);
    const mpz_class d = hp[u] * (hq[v] * hr[3] - hq[3] * hr[v]) -
                        hp[v] * (hq[u] * hr[3] - hq[3] * hr[u]) +
                        hp[3] * (hq[u] * hr[v] - hq[v] * hr[u]);
    return sgn(d);
  }

  bool less_xyz(const PolygonVertex& p, const PolygonVertex& q) const {
    for (int axis = 0; axis < 3; ++axis) {
      {
        CGAL::Protect_FPU_rounding<true> rounding;
        const CGAL::Uncertain<CGAL::Comparison_result> c =
            CGAL::compare(p.approx.cartesian(axis), q.approx.cartesian(axis));
        if (CGAL::is_certain(c)) {
          if (CGAL::get_certain(c) != CGAL::EQUAL) return CGAL::get_certain(c) == CGAL::SMALLER;
          continue;
        }
      }
      const Homogeneous &hp = exact(p), &hq = exact(q);
      const int c = sgn(hp[axis] * hq[3] - hq[axis] * hp[3]);
      if (c != 0) return c < 0;
    }
    return false;
  }

  // Distinct vertices of one polygon are distinct positions, except equal table ids and equal
  // crossings (one pair of edges).
  static bool same(const PolygonVertex& p, const PolygonVertex& q) {
    if (p.id != kNoPoint || q.id != kNoPoint) return p.id == q.id;
    return p.edge_a == q.edge_a && p.edge_b == q.edge_b;
  }

  // Where the polygon edge lying on line `tag` crosses ta's edge line i.
  PolygonVertex crossing(int i, int tag) const {
    if (tag >= 3) {
      // Two of ta's edge lines meet at their common corner.
      const int other = tag - 3;
      return table_vertex(ta_[other == (i + 1) % 3 ? (i + 1) % 3 : i]);
    }
    PolygonVertex v;
    v.recipe.kind = Recipe::Kind::EdgeProjectedLine;
    v.recipe.dropped = std::int8_t(dropped_);
    v.recipe.p = tb_[tag];
    v.recipe.q = tb_[(tag + 1) % 3];
    v.recipe.a = ta_[i];
    v.recipe.b = ta_[(i + 1) % 3];
    v.approx = table_.approximate(v.recipe);
    v.edge_a = std::int8_t(i);
    v.edge_b = std::int8_t(tag);
    // The crossing lies strictly inside tb's edge, but it may be one of ta's corners on line i
    // (tb's edge passing through it): corner k lies on lines k - 1 and k, so test the other one.
    for (const int k : {i, (i + 1) % 3}) {
      const int line = k == i ? (k + 2) % 3 : k;
      if (orientation(table_vertex(ta_[line]), table_vertex(ta_[(line + 1) % 3]), v) == 0)
        return table_vertex(ta_[k]);
    }
    return v;
  }

  PairPoint pair_point(const PolygonVertex& v) const {
    PairPoint out;
    if (v.id != kNoPoint) {
      out.id = v.id;
      out.edges_a = edges_of(ta_, v.id);
      out.edges_b = edges_of(tb_, v.id);
      return out;
    }
    out.recipe = v.recipe;
    out.naming = soup_ ? Naming::Position : Naming::EdgeEdge;
    out.key = edge_edge_key(ta_[v.edge_a], ta_[(v.edge_a + 1) % 3], tb_[v.edge_b],
                            tb_[(v.edge_b + 1) % 3]);
    out.edges_a = std::uint8_t(1u << v.edge_a);
    out.edges_b = std::uint8_t(1u << v.edge_b);
    return out;
  }

  std::uint8_t edges_of(const Corners& ids, PointId id) const {
    for (int k = 0; k < 3; ++k)
      if (ids[k] == id) return corner_edges(k);
    return edges_through(table_, dropped_, ids, id);
  }

  const PointTable& table_;
  const Corners &ta_, &tb_;  // corners by the ids of their positions
  int dropped_;
  bool soup_;
};

}  // namespace

std::vector<PairPoint> coplanar_overlap(const PointTable& table, const Corners& ta,
                                        const Corners& tb, int dropped, bool soup) {
  return CoplanarClipper(table, ta, tb, dropped, soup).overlap();
}

}  // namespace morphex::detail

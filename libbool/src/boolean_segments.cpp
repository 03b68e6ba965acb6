// SPDX-License-Identifier: GPL-3.0-or-later
// Step 3: exact intersection of each candidate pair, each intersection point named once.
//
// The vertices of each triangle are classified against the other's plane with orientation
// predicates (no construction): all on one side, none meet. Non-coplanar pairs: each triangle cuts
// a chord on the other's plane whose ends are its vertices on that plane or its edges crossing
// it; an edge/plane crossing is one table entry per (edge, facet), shared by both facets of the
// edge, kept as its recipe (its exact value is computed only if a predicate needs it). The two
// chords lie on the planes' common line and their overlap, ordered by exact predicates along that
// line, is the intersection: a segment, a point, or nothing. Coplanar pairs clip one triangle by
// the other in their common plane (the overlap polygon).
//
// Point identity is combinatorial, so no point is evaluated to be named. Coincident input vertices
// near the other mesh share one id (found by exact position, on doubles for file input). A
// crossing of an edge with the open interior of the other facet can coincide with no other point
// of valid solids, so it keeps its table id. A crossing that lands on an edge of the other facet is
// named by the two edges, and one that lands on a corner is that corner. In a soup (the n-ary
// union) constructions may coincide, so there every constructed point is named by exact position.
//
// Unlike the seed, point-only contacts are kept (as Steiner points) and coplanar overlaps insert
// their boundary, so every sub-triangle ends up entirely inside, outside or on the other surface.
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <array>
#include <limits>
#include <memory>
#include <numeric>
#include <tuple>

#include "boolean_internal.h"
#include "filtered.h"
#include "flat_map.h"
#include "triangle_overlap.h"

namespace morphex::detail {

namespace {

constexpr PointId kNoPoint = std::numeric_limits<PointId>::max();

using Corners = std::array<PointId, 3>;

Corners corners_of(const PointTable& table, const Mesh& mesh, int side, std::uint32_t facet) {
  const Triangle& f = mesh.triangles[facet];
  return {table.vertex(side, f[0]), table.vertex(side, f[1]), table.vertex(side, f[2])};
}

int corner_of_edges(std::uint8_t edges) {
  for (int k = 0; k < 3; ++k)
    if (corner_edges(k) == edges) return k;
  return -1;
}

int popcount(std::uint8_t bits) {
  return (bits & 1) + ((bits >> 1) & 1) + ((bits >> 2) & 1);
}

// The edges of triangle t that p lies on, for p in the closed triangle (in its plane, seen along
// the axis `dropped`).
std::uint8_t edges_through(const PointTable& table, int dropped, const Corners& t, PointId p) {
  std::uint8_t edges = 0;
  for (int i = 0; i < 3; ++i)
    if (table.orientation_2(dropped, t[i], t[(i + 1) % 3], p) == CGAL::ZERO) edges |= 1u << i;
  return edges;
}

// A crossing of an input edge (u, v), u < v (ids of the edge's ends), with the plane of a facet of
// the other mesh. Every crossing is one table entry, whichever of the edge's facets needs it (the
// seed's "every intersection point once").
struct CrossingKey {
  std::uint32_t side, facet;  // the edge's mesh (0 in a soup) and the other mesh's facet
  PointId u, v;
  bool operator<(const CrossingKey& o) const {
    return std::tie(side, facet, u, v) < std::tie(o.side, o.facet, o.u, o.v);
  }
  bool operator==(const CrossingKey& o) const {
    return side == o.side && facet == o.facet && u == o.u && v == o.v;
  }
};

// Two input edges (ids of their ends, each pair sorted): the name of the point where they cross.
using EdgeEdgeKey = std::pair<std::uint64_t, std::uint64_t>;
struct EdgeEdgeHash {
  std::size_t operator()(const EdgeEdgeKey& k) const {
    return std::size_t(mix64(k.first ^ mix64(k.second)));
  }
};
EdgeEdgeKey edge_edge_key(PointId a0, PointId a1, PointId b0, PointId b1) {
  return {edge_key(undirected(a0, a1)), edge_key(undirected(b0, b1))};
}

// How the final id of a point is found in the sequential pass.
enum class Naming : std::uint8_t {
  Known,     // its id is final
  EdgeEdge,  // by the two edges it lies on (`key`)
  Position,  // by exact position (soups)
};

// A point of a pair's intersection, with the edges of ta and of tb it lies on.
struct PairPoint {
  PointId id = kNoPoint;  // table id, or kNoPoint for a new coplanar crossing (`recipe`)
  Recipe recipe;
  Naming naming = Naming::Known;
  EdgeEdgeKey key{};
  std::uint8_t edges_a = 0, edges_b = 0;
};

// One end of the chord a triangle cuts on the other triangle's plane.
struct ChordEnd {
  PointId id;
  std::int8_t role;   // 0: vertex of ta, 1: crossing of an edge of ta, 2, 3: the same for tb
  std::int8_t index;  // the vertex's corner, or the crossing edge (edge i: corners i, i + 1)
  std::uint32_t crossing = 0;
};

// What one candidate pair leaves on its two facets, before final ids are given.
struct PairOutcome {
  enum class Kind : std::uint8_t { None, Point, Segment, Polygon } kind = Kind::None;
  std::vector<PairPoint> points;  // Point: 1, Segment: 2 (from lo to hi), Polygon: its vertices
  bool transversal = false;       // a segment whose interior is inside both open triangles
};

struct PairSigns {
  std::int8_t a[3], b[3];  // ta's vertices against tb's plane, tb's against ta's
  bool separated = true, coplanar = false;
};

// Edges of a triangle whose ends lie strictly on opposite sides of the other plane.
template <class Visit>
void for_each_crossing_edge(const std::int8_t (&signs)[3], Visit&& visit) {
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    if (signs[i] != 0 && signs[j] != 0 && signs[i] != signs[j]) visit(i, j);
  }
}

// ---- Coplanar pairs: the overlap polygon by clipping tb with ta's edge lines.

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
  CoplanarClipper(const PointTable& table, const Corners& ta, const Corners& tb,
                  const Corners& ta_ids, const Corners& tb_ids, int dropped, bool soup)
      : table_(table),
        ta_(ta),
        tb_(tb),
        ta_ids_(ta_ids),
        tb_ids_(tb_ids),
        dropped_(dropped),
        soup_(soup) {}

  // The overlap of the two closed triangles: nothing, a point, a segment's ends or a convex
  // polygon, each vertex with the edges of ta and tb it lies on.
  std::vector<PairPoint> overlap() const {
    const int turn = orientation(table_vertex(ta_[0]), table_vertex(ta_[1]), table_vertex(ta_[2]));
    std::vector<PolygonVertex> polygon;
    for (int j = 0; j < 3; ++j) {
      PolygonVertex v = table_vertex(tb_ids_[j]);
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
      return table_vertex(ta_ids_[other == (i + 1) % 3 ? (i + 1) % 3 : i]);
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
        return table_vertex(ta_ids_[k]);
    }
    return v;
  }

  PairPoint pair_point(const PolygonVertex& v) const {
    PairPoint out;
    if (v.id != kNoPoint) {
      out.id = v.id;
      out.edges_a = edges_of(ta_ids_, v.id);
      out.edges_b = edges_of(tb_ids_, v.id);
      return out;
    }
    out.recipe = v.recipe;
    out.naming = soup_ ? Naming::Position : Naming::EdgeEdge;
    out.key = edge_edge_key(ta_ids_[v.edge_a], ta_ids_[(v.edge_a + 1) % 3], tb_ids_[v.edge_b],
                            tb_ids_[(v.edge_b + 1) % 3]);
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
  const Corners &ta_, &tb_;          // raw ids, for recipes and predicates
  const Corners &ta_ids_, &tb_ids_;  // the same corners by their final ids
  int dropped_;
  bool soup_;
};

}  // namespace

// The phases run in parallel where the pairs are independent and end with one sequential pass in
// pair order that gives final ids, so the result is the same for any number of threads:
//   1. identity of the input vertices near the other mesh;
//   2. orientation signs of each pair (separated pairs stop here);
//   3. the distinct edge/plane crossings the pairs need, as table entries, and the edges of the
//      other facet each one lies on;
//   4. each pair's chord overlap (a segment, a point or nothing), or its coplanar overlap;
//   5. final ids and the per-facet cuts.
Intersection intersect(const Mesh& a, const Mesh& b, const Pairs& pairs,
                       const IntersectOptions& options) {
  Intersection x;
  x.points = PointTable(a, b, options.soup);
  PointTable& table = x.points;
  const Mesh* meshes[2] = {&a, &b};
  const std::size_t np = pairs.size();
  const std::size_t num_inputs = table.num_inputs();

  // 1. Coincident vertices near the other mesh get the first one's id, so that a position has
  // one name wherever the two meshes meet (and where separated features of one mesh touch).
  // Coincident points have overlapping interval boxes: near vertices sorted by their boxes' lower
  // x bound are swept for overlaps, and only those are compared exactly.
  x.vertex_rep.resize(num_inputs);
  std::iota(x.vertex_rep.begin(), x.vertex_rep.end(), PointId(0));
  std::vector<PointId> merged;
  {
    std::vector<std::uint8_t> near(num_inputs, 0);
    for (const auto& [ia, ib] : pairs) {
      for (VertexIndex v : a.triangles[ia]) near[table.vertex(0, v)] = 1;
      for (VertexIndex v : b.triangles[ib]) near[table.vertex(1, v)] = 1;
    }
    std::vector<PointId> ids;
    for (PointId id = 0; id < num_inputs; ++id)
      if (near[id]) ids.push_back(id);
    const std::vector<PointId> first = coincident_representatives(table, ids);
    for (std::size_t i = 0; i < ids.size(); ++i) {
      if (first[i] != ids[i]) merged.push_back(first[i]);
      x.vertex_rep[ids[i]] = first[i];
    }
  }
  auto rep = [&](PointId id) { return x.vertex_rep[id]; };

  // Corners by the ids of their positions: predicates on coincident corners of the two meshes
  // (identical meshes, shared vertices) are then decided by the ids alone.
  auto corner_ids = [&](int side, std::uint32_t facet) {
    const Corners raw = corners_of(table, *meshes[side], side, facet);
    return Corners{rep(raw[0]), rep(raw[1]), rep(raw[2])};
  };

  // 2. Signs, and the exact overlap test of the pairs that are not coplanar. The signs are
  // (vertex, facet plane) questions that neighbouring pairs share: intervals decide most; the
  // undecided ones (coplanar pieces in morphology) are gathered and each evaluated exactly once.
  const std::uint32_t b_side = options.soup ? 0 : 1;
  constexpr std::int8_t kUndecided = 2;
  // A question: the facet (side, index) whose plane, and the point.
  auto question = [&](std::uint32_t side, std::uint32_t facet, PointId point) {
    return (std::uint64_t((side << 31) | facet) << 32) | point;
  };
  // A facet meets many pairs: its interval normal is computed once, and a vertex's side of its
  // plane is then one interval dot product rather than a 3x3 determinant.
  std::vector<ApproxVector> normals[2];
  {
    std::vector<std::uint8_t> used[2];
    for (int side = 0; side < 2; ++side) used[side].assign(meshes[side]->num_triangles(), 0);
    for (const auto& [ia, ib] : pairs) used[0][ia] = used[1][ib] = 1;
    for (int side = 0; side < 2; ++side) {
      normals[side].resize(used[side].size());
      for_each_upward(used[side].size(), [&](std::size_t f) {
        if (!used[side][f]) return;
        const Corners t = corner_ids(side, std::uint32_t(f));
        normals[side][f] = table.approx_normal(t[0], t[1], t[2]);
      });
    }
  }
  // Labelled soups: the planes through each vertex are those of its faces. A vertex on the plane
  // of a label its faces carry is on it, with no question asked (an intersection point of an
  // earlier operation lies on the planes that made it; a translate, on their translates).
  std::vector<std::uint32_t> label_start, label_at;
  if (options.planes) {
    label_start.assign(num_inputs + 1, 0);
    for (std::uint32_t f = 0; f < a.triangles.size(); ++f)
      for (VertexIndex v : a.triangles[f]) ++label_start[rep(v) + 1];
    for (std::size_t v = 0; v < num_inputs; ++v) label_start[v + 1] += label_start[v];
    label_at.resize(label_start.back());
    std::vector<std::uint32_t> fill(label_start.begin(), label_start.end() - 1);
    for (std::uint32_t f = 0; f < a.triangles.size(); ++f)
      for (VertexIndex v : a.triangles[f]) label_at[fill[rep(v)]++] = (*options.planes)[f];
  }
  auto on_labelled_plane = [&](PointId vertex, std::uint32_t facet) {
    if (!options.planes || vertex >= num_inputs) return false;
    const std::uint32_t label = (*options.planes)[facet];
    return std::find(label_at.begin() + label_start[vertex],
                     label_at.begin() + label_start[vertex + 1], label) !=
           label_at.begin() + label_start[vertex + 1];
  };
  std::vector<PairSigns> signs(np);
  for_each_upward(np, [&](std::size_t k) {
    const auto [ia, ib] = pairs[k];
    const Corners ta = corner_ids(0, ia), tb = corner_ids(1, ib);
    PairSigns& s = signs[k];
    if (options.planes && (*options.planes)[ia] == (*options.planes)[ib]) {
      // Known to lie in one plane: every sign is zero, with no question asked.
      for (int i = 0; i < 3; ++i) s.a[i] = s.b[i] = 0;
      s.separated = false;
      return;
    }
    auto against = [&](const Corners& t, const Corners& other, std::uint32_t other_facet,
                       const ApproxVector& normal, std::int8_t(&out)[3]) {
      for (int i = 0; i < 3; ++i) {
        const auto o = t[i] == other[0] || t[i] == other[1] || t[i] == other[2]
                           ? CGAL::make_uncertain(CGAL::ZERO)
                           : table.side_filter(normal, other[0], t[i]);
        out[i] = o.is_certain()                         ? std::int8_t(o.make_certain())
                 : on_labelled_plane(t[i], other_facet) ? std::int8_t(0)
                                                        : kUndecided;
      }
      return out[0] != 0 && out[0] != kUndecided && out[0] == out[1] && out[1] == out[2];
    };
    s.separated = against(ta, tb, ib, normals[1][ib], s.a) || against(tb, ta, ia, normals[0][ia], s.b);
  });
  std::vector<std::uint64_t> questions;
  for (std::size_t k = 0; k < np; ++k) {
    if (signs[k].separated) continue;
    const auto [ia, ib] = pairs[k];
    const Corners ta = corner_ids(0, ia), tb = corner_ids(1, ib);
    for (int i = 0; i < 3; ++i) {
      if (signs[k].a[i] == kUndecided) questions.push_back(question(b_side, ib, ta[i]));
      if (signs[k].b[i] == kUndecided) questions.push_back(question(0, ia, tb[i]));
    }
  }
  tbb::parallel_sort(questions.begin(), questions.end());
  questions.erase(std::unique(questions.begin(), questions.end()), questions.end());
  // Questions come sorted by plane: each plane's exact equation is computed once for its group.
  std::vector<std::int8_t> answers(questions.size());
  std::vector<std::size_t> plane_groups;
  for (std::size_t i = 0; i < questions.size(); ++i)
    if (i == 0 || (questions[i] >> 32) != (questions[i - 1] >> 32)) plane_groups.push_back(i);
  plane_groups.push_back(questions.size());
  tbb::parallel_for(std::size_t(0), plane_groups.size() - 1, [&](std::size_t g) {
    const std::uint32_t plane = std::uint32_t(questions[plane_groups[g]] >> 32);
    const std::uint32_t side = plane >> 31, facet = plane & 0x7fffffffu;
    const Corners f = corner_ids(options.soup ? 0 : int(side), facet);
    if (plane_groups[g + 1] - plane_groups[g] < 8) {  // a plane equation pays off for many
      for (std::size_t i = plane_groups[g]; i < plane_groups[g + 1]; ++i)
        answers[i] = std::int8_t(table.orientation_exact(f[0], f[1], f[2], PointId(questions[i])));
      return;
    }
    const PointTable::Plane equation = table.exact_plane(f[0], f[1], f[2]);
    for (std::size_t i = plane_groups[g]; i < plane_groups[g + 1]; ++i)
      answers[i] = std::int8_t(table.plane_side(equation, PointId(questions[i])));
  });
  auto answer = [&](std::uint64_t q) {
    return answers[std::lower_bound(questions.begin(), questions.end(), q) - questions.begin()];
  };
  // In a soup, neighbouring triangles share corners. They meet only there when the other corners
  // of one lie strictly on one side of the other's plane; the corners need no cut.
  auto meet_at_corners = [&](const Corners& ta, const Corners& tb, const PairSigns& s) {
    auto beyond = [](const Corners& t, const Corners& other, const std::int8_t(&x)[3]) {
      int side = 0;
      bool shared = false;
      for (int i = 0; i < 3; ++i) {
        if (t[i] == other[0] || t[i] == other[1] || t[i] == other[2]) {
          shared = true;
          continue;
        }
        if (x[i] == 0 || (side != 0 && x[i] != side)) return false;
        side = x[i];
      }
      return shared && side != 0;
    };
    if (beyond(ta, tb, s.a) || beyond(tb, ta, s.b)) return true;
    // Coplanar neighbours: apart when the line of an edge of one through a common corner has the
    // other strictly on its far side (the one with the edge lies on its near closed side).
    for (int i = 0; i < 3; ++i)
      if (s.a[i] != 0 || s.b[i] != 0) return false;
    const int dropped = table.dominant_axis(ta[0], ta[1], ta[2]);
    auto shared = [](const Corners& t, PointId p) { return p == t[0] || p == t[1] || p == t[2]; };
    for (const auto& [own, other] : {std::pair(&ta, &tb), std::pair(&tb, &ta)})
      for (int e = 0; e < 3; ++e) {
        const PointId x = (*own)[e], y = (*own)[(e + 1) % 3], z = (*own)[(e + 2) % 3];
        if (!shared(*other, x) && !shared(*other, y)) continue;
        const CGAL::Sign near = table.orientation_2(dropped, x, y, z);
        bool apart = true;
        for (PointId w : *other)
          if (w != x && w != y && table.orientation_2(dropped, x, y, w) != -near) apart = false;
        if (apart) return true;
      }
    return false;
  };
  const TriangleOverlap overlap(table);
  for_each_upward(np, [&](std::size_t k) {
    PairSigns& s = signs[k];
    if (s.separated) return;
    const auto [ia, ib] = pairs[k];
    const Corners ta = corner_ids(0, ia), tb = corner_ids(1, ib);
    for (int i = 0; i < 3; ++i) {
      if (s.a[i] == kUndecided) s.a[i] = answer(question(b_side, ib, ta[i]));
      if (s.b[i] == kUndecided) s.b[i] = answer(question(0, ia, tb[i]));
    }
    auto one_side = [](const std::int8_t(&x)[3]) {
      return x[0] != 0 && x[0] == x[1] && x[1] == x[2];
    };
    s.separated = one_side(s.a) || one_side(s.b) || (options.soup && meet_at_corners(ta, tb, s));
    if (s.separated) return;
    s.coplanar = s.a[0] == 0 && s.a[1] == 0 && s.a[2] == 0;
    s.separated = !s.coplanar && !overlap(ta, tb, s.a, s.b);
  });

  // 3. Crossings.
  auto crossing_key = [&](int side, const Corners& t, int i, int j, std::uint32_t other_facet) {
    const PointId u = rep(t[i]), v = rep(t[j]);
    return CrossingKey{side == 0 ? 0 : b_side, other_facet, std::min(u, v), std::max(u, v)};
  };
  // Per pair, the crossing edges of both triangles (at most two each), gathered in parallel.
  std::vector<std::uint32_t> first_key(np + 1, 0);
  tbb::parallel_for(std::size_t(0), np, [&](std::size_t k) {
    if (signs[k].separated || signs[k].coplanar) return;
    std::uint32_t count = 0;
    for_each_crossing_edge(signs[k].a, [&](int, int) { ++count; });
    for_each_crossing_edge(signs[k].b, [&](int, int) { ++count; });
    first_key[k + 1] = count;
  });
  for (std::size_t k = 0; k < np; ++k) first_key[k + 1] += first_key[k];
  std::vector<CrossingKey> keys(first_key[np]);
  tbb::parallel_for(std::size_t(0), np, [&](std::size_t k) {
    if (signs[k].separated || signs[k].coplanar) return;
    const std::uint32_t ia = pairs[k].first, ib = pairs[k].second;  // captured below
    const Corners ta = corner_ids(0, ia), tb = corner_ids(1, ib);
    std::uint32_t slot = first_key[k];
    for_each_crossing_edge(signs[k].a,
                           [&](int i, int j) { keys[slot++] = crossing_key(0, ta, i, j, ib); });
    for_each_crossing_edge(signs[k].b,
                           [&](int i, int j) { keys[slot++] = crossing_key(1, tb, i, j, ia); });
  });
  tbb::parallel_sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  auto facet_corners = [&](const CrossingKey& key) {
    // The facet belongs to the mesh the edge is not from (in a soup, to the soup).
    const int facet_side = options.soup ? 0 : 1 - int(key.side);
    return corner_ids(facet_side, key.facet);
  };
  std::vector<Recipe> recipes(keys.size());
  tbb::parallel_for(std::size_t(0), keys.size(), [&](std::size_t c) {
    const Corners f = facet_corners(keys[c]);
    recipes[c] = {Recipe::Kind::EdgePlane, -1, keys[c].u, keys[c].v, f[0], f[1], f[2]};
  });
  const PointId first_crossing = table.add_all(recipes);
  // The edges of its facet each crossing lies on: the crossing of line uv with the facet's plane
  // is on the line of the facet's edge (f_i, f_i+1) exactly when uv and that edge are coplanar.
  std::vector<std::uint8_t> crossing_edges(keys.size(), 0);
  for_each_upward(keys.size(), [&](std::size_t c) {
    const Corners f = facet_corners(keys[c]);
    for (int i = 0; i < 3; ++i)
      if (table.orientation(keys[c].u, keys[c].v, f[i], f[(i + 1) % 3]) == CGAL::ZERO)
        crossing_edges[c] |= std::uint8_t(1u << i);
  });
  auto crossing_index = [&](const CrossingKey& key) {
    return std::uint32_t(std::lower_bound(keys.begin(), keys.end(), key) - keys.begin());
  };

  // 4. Outcomes.
  std::vector<PairOutcome> outcomes(np);
  for_each_upward(np, [&](std::size_t k) {
    if (signs[k].separated) return;
    const auto [ia, ib] = pairs[k];
    const Corners ta = corner_ids(0, ia), tb = corner_ids(1, ib);
    const Corners &ta_ids = ta, &tb_ids = tb;
    PairOutcome& out = outcomes[k];
    if (signs[k].coplanar) {
      const int dropped = table.dominant_axis(ta[0], ta[1], ta[2]);
      out.points = CoplanarClipper(table, ta, tb, ta_ids, tb_ids, dropped, options.soup).overlap();
      switch (out.points.size()) {
        case 0:
          break;
        case 1:
          out.kind = PairOutcome::Kind::Point;
          break;
        case 2:
          out.kind = PairOutcome::Kind::Segment;  // along a line of both planes: not transversal
          break;
        default:
          out.kind = PairOutcome::Kind::Polygon;
      }
      return;
    }
    // The chord each triangle cuts on the other's plane: its vertices on that plane and its
    // crossing edges. Both chords lie on the planes' common line; their overlap is ta n tb.
    auto chord = [&](int side, const Corners& t, const Corners& ids, const std::int8_t(&s)[3],
                     std::uint32_t other_facet) {
      std::array<ChordEnd, 3> ends;
      std::size_t count = 0;
      for (int i = 0; i < 3; ++i)
        if (s[i] == 0) ends[count++] = {ids[i], std::int8_t(2 * side), std::int8_t(i)};
      for_each_crossing_edge(s, [&](int i, int j) {
        const std::uint32_t c = crossing_index(crossing_key(side, t, i, j, other_facet));
        ends[count++] = {PointId(first_crossing + c), std::int8_t(2 * side + 1), std::int8_t(i), c};
      });
      return std::make_pair(ends, count);
    };
    const auto [ca, na] = chord(0, ta, ta_ids, signs[k].a, ib);
    const auto [cb, nb] = chord(1, tb, tb_ids, signs[k].b, ia);
    const ApproxVector line = CGAL::cross_product(normals[0][ia], normals[1][ib]);
    auto order = [&](const ChordEnd& p, const ChordEnd& q) {  // sign of q - p along the line
      return p.id == q.id ? CGAL::ZERO : table.along_line(line, ta, tb, p.id, q.id);
    };
    auto sorted = [&](const std::array<ChordEnd, 3>& e, std::size_t count) {
      const ChordEnd& last = e[count - 1];
      return order(e[0], last) == CGAL::NEGATIVE ? std::make_pair(last, e[0])
                                                 : std::make_pair(e[0], last);
    };
    const auto [a1, a2] = sorted(ca, na);
    const auto [b1, b2] = sorted(cb, nb);
    const ChordEnd& lo = order(a1, b1) == CGAL::POSITIVE ? b1 : a1;  // the later start
    const ChordEnd& hi = order(a2, b2) == CGAL::POSITIVE ? a2 : b2;  // the earlier end
    const auto extent = order(lo, hi);
    if (extent == CGAL::NEGATIVE) return;

    // Where each end lies on the two triangles, and how its final id is found.
    auto pair_point = [&](const ChordEnd& e) {
      PairPoint p;
      p.id = e.id;
      const bool of_a = e.role < 2;
      const Corners& own = of_a ? ta_ids : tb_ids;
      const Corners& other = of_a ? tb_ids : ta_ids;
      const Corners& other_raw = of_a ? tb : ta;
      std::uint8_t own_edges, other_edges;
      if (e.role % 2 == 0) {  // a vertex of its triangle, in the other's plane
        own_edges = corner_edges(e.index);
        other_edges = edges_through(
            table, table.dominant_axis(other_raw[0], other_raw[1], other_raw[2]), other, e.id);
      } else {  // an edge crossing the other's plane
        own_edges = std::uint8_t(1u << e.index);
        other_edges = crossing_edges[e.crossing];
        switch (popcount(other_edges)) {
          case 0:  // inside the other facet: unique in valid solids
            if (options.soup) p.naming = Naming::Position;
            break;
          case 1: {  // on an edge of the other facet: named by the two edges
            const CrossingKey& key = keys[e.crossing];
            int j = 0;
            while (!(other_edges & (1u << j))) ++j;
            const PointId o0 = other[j], o1 = other[(j + 1) % 3];
            p.naming = options.soup ? Naming::Position : Naming::EdgeEdge;
            p.key =
                of_a ? edge_edge_key(key.u, key.v, o0, o1) : edge_edge_key(o0, o1, key.u, key.v);
            break;
          }
          default:  // at a corner of the other facet
            p.id = other[corner_of_edges(other_edges)];
        }
      }
      p.edges_a = of_a ? own_edges : other_edges;
      p.edges_b = of_a ? other_edges : own_edges;
      return p;
    };
    out.points.push_back(pair_point(lo));
    if (extent == CGAL::ZERO) {
      // In a soup, neighbours touching only at a common corner: nothing to cut.
      const PointId p = out.points[0].id;
      if (options.soup && p != kNoPoint && out.points[0].naming == Naming::Known &&
          (p == ta[0] || p == ta[1] || p == ta[2]) && (p == tb[0] || p == tb[1] || p == tb[2])) {
        out.points.clear();
        return;
      }
      out.kind = PairOutcome::Kind::Point;
      return;
    }
    out.points.push_back(pair_point(hi));
    out.kind = PairOutcome::Kind::Segment;
    // lo -> hi runs along Na x Nb, so the seed's sign is positive; a segment along an edge of
    // either triangle is not transversal (the local picture involves more facets).
    const PairPoint &p = out.points[0], &q = out.points[1];
    out.transversal = !(p.edges_a & q.edges_a) && !(p.edges_b & q.edges_b);
  });

  // 5. Sequential, in pair order: final ids do not depend on the thread count.
  FlatMap<EdgeEdgeKey, PointId, EdgeEdgeHash> edge_edge;
  std::vector<PointId> positioned;  // soups: constructions named by exact position, below
  auto final_id = [&](const PairPoint& p) {
    PointId id = p.id;
    switch (p.naming) {
      case Naming::Known:
        return id;
      case Naming::EdgeEdge: {
        const PointId* known = edge_edge.find(p.key);
        if (known) return *known;
        if (id == kNoPoint) id = table.add(p.recipe);
        edge_edge.emplace(p.key, id);
        return id;
      }
      case Naming::Position:
        if (id == kNoPoint) id = table.add(p.recipe);
        positioned.push_back(id);
        return id;
    }
    return id;
  };
  for (std::size_t k = 0; k < np; ++k)
    for (PairPoint& p : outcomes[k].points)
      if (p.naming != Naming::Known) {
        p.id = final_id(p);
        if (p.naming == Naming::EdgeEdge) p.naming = Naming::Known;
      }
  if (options.soup) {
    // Constructions of a soup may coincide with each other or with vertices: each position is
    // named by its least id.
    std::sort(positioned.begin(), positioned.end());
    positioned.erase(std::unique(positioned.begin(), positioned.end()), positioned.end());
    std::vector<PointId> ids;
    for (PointId id = 0; id < num_inputs; ++id)
      if (rep(id) == id) ids.push_back(id);
    ids.insert(ids.end(), positioned.begin(), positioned.end());
    const std::vector<PointId> first = coincident_representatives(table, ids);
    std::vector<PointId> named(table.size(), kNoPoint);
    for (std::size_t i = 0; i < ids.size(); ++i) named[ids[i]] = first[i];
    for (std::size_t k = 0; k < np; ++k)
      for (PairPoint& p : outcomes[k].points)
        if (p.naming == Naming::Position) {
          p.id = named[p.id];
          p.naming = Naming::Known;
        }
  }

  // The cuts, built per facet in parallel from its pairs in pair order.
  for (int side = 0; side < 2; ++side) {
    std::vector<std::pair<std::uint32_t, std::uint32_t>> facet_pair;  // (facet, pair)
    for (std::size_t k = 0; k < np; ++k)
      if (outcomes[k].kind != PairOutcome::Kind::None)
        facet_pair.emplace_back(side == 0 ? pairs[k].first : pairs[k].second, std::uint32_t(k));
    tbb::parallel_sort(facet_pair.begin(), facet_pair.end());
    std::vector<std::size_t> group;
    for (std::size_t i = 0; i < facet_pair.size(); ++i)
      if (i == 0 || facet_pair[i].first != facet_pair[i - 1].first) group.push_back(i);
    group.push_back(facet_pair.size());
    auto& cuts = x.cuts[side];
    cuts.resize(group.size() - 1);
    tbb::parallel_for(std::size_t(0), cuts.size(), [&](std::size_t g) {
      cuts[g].first = facet_pair[group[g]].first;
      FacetCut& cut = cuts[g].second;
      for (std::size_t i = group[g]; i < group[g + 1]; ++i) {
        const std::uint32_t k = facet_pair[i].second;
        const PairOutcome& out = outcomes[k];
        for (const PairPoint& p : out.points)
          cut.points.push_back({p.id, side == 0 ? p.edges_a : p.edges_b});
        auto add_segment = [&](PointId p, PointId q) {
          if (p != q) cut.segments.push_back(undirected(p, q));
        };
        const auto& pts = out.points;
        switch (out.kind) {
          case PairOutcome::Kind::Segment:
            add_segment(pts[0].id, pts[1].id);
            if (out.transversal && pts[0].id != pts[1].id) {
              // The seed's rule with s > 0: B's interior is on the left of lo -> hi in ta, A's
              // on the left of hi -> lo in tb.
              if (side == 0)
                cut.transversal.push_back({pts[0].id, pts[1].id});
              else
                cut.transversal.push_back({pts[1].id, pts[0].id});
            }
            break;
          case PairOutcome::Kind::Polygon:
            // Coplanar overlap: its boundary separates, in each facet, the part that lies on the
            // other surface from the rest.
            for (std::size_t j = 0; j < pts.size(); ++j)
              add_segment(pts[j].id, pts[(j + 1) % pts.size()].id);
            cut.coplanar_facets.push_back(side == 0 ? pairs[k].second : pairs[k].first);
            break;
          default:
            break;
        }
      }
    });
  }
  for (std::size_t k = 0; k < np; ++k) {
    x.intersecting_pairs += outcomes[k].kind != PairOutcome::Kind::None;
    x.coplanar_overlaps = x.coplanar_overlaps || outcomes[k].kind == PairOutcome::Kind::Polygon;
  }

  x.flags.assign(table.size(), 0);
  for (PointId id : merged) x.flags[id] |= kMerged;
  for (int side = 0; side < 2; ++side)
    for (const auto& [facet, cut] : x.cuts[side])
      for (const CutPoint& p : cut.points) x.flags[p.id] |= kOnSurface;
  for (PointId id = PointId(num_inputs); id < table.size(); ++id)
    if (x.flags[id] & kOnSurface) ++x.constructed_points;
  return x;
}

}  // namespace morphex::detail

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
//
// This file drives the step (vertex identity, crossings, chords, naming); the signs are in
// step3_signs.cpp, the coplanar overlaps in step3_coplanar.cpp, what they share in
// segments_internal.h.
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <memory>
#include <numeric>
#include <tuple>

#include "boolean/segments_internal.h"
#include "containers/block_offsets.h"
#include "containers/flat_map.h"
#include "exact/filtered.h"

namespace morphex::detail {

std::uint8_t edges_through(const PointTable& table, int dropped, const Corners& t, PointId p) {
  std::uint8_t edges = 0;
  for (int i = 0; i < 3; ++i)
    if (table.orientation_2(dropped, t[i], t[(i + 1) % 3], p) == CGAL::ZERO) edges |= 1u << i;
  return edges;
}

namespace {

int corner_of_edges(std::uint8_t edges) {
  for (int k = 0; k < 3; ++k)
    if (corner_edges(k) == edges) return k;
  return -1;
}

int popcount(std::uint8_t bits) {
  return (bits & 1) + ((bits >> 1) & 1) + ((bits >> 2) & 1);
}

struct EdgeEdgeHash {
  std::size_t operator()(const EdgeEdgeKey& k) const {
    return std::size_t(mix64(k.first ^ mix64(k.second)));
  }
};

// Edges of a triangle whose ends lie strictly on opposite sides of the other plane.
template <class Visit>
void for_each_crossing_edge(const std::int8_t (&signs)[3], Visit&& visit) {
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    if (signs[i] != 0 && signs[j] != 0 && signs[i] != signs[j]) visit(i, j);
  }
}

// The facets of each side in some pair: marked in parallel (a facet is in many of the pairs,
// which can be millions).
using UsedFacets = std::array<std::vector<std::uint8_t>, 2>;
UsedFacets used_facets(const Mesh& a, const Mesh& b, const Pairs& pairs) {
  std::unique_ptr<std::atomic<std::uint8_t>[]> marks[2] = {
      std::make_unique<std::atomic<std::uint8_t>[]>(a.num_triangles()),
      std::make_unique<std::atomic<std::uint8_t>[]>(b.num_triangles())};
  tbb::parallel_for(std::size_t(0), pairs.size(), [&](std::size_t k) {
    marks[0][pairs[k].first].store(1, std::memory_order_relaxed);
    marks[1][pairs[k].second].store(1, std::memory_order_relaxed);
  });
  UsedFacets used;
  const std::size_t sizes[2] = {a.num_triangles(), b.num_triangles()};
  for (int side = 0; side < 2; ++side) {
    used[side].resize(sizes[side]);
    tbb::parallel_for(std::size_t(0), sizes[side], [&](std::size_t f) {
      used[side][f] = marks[side][f].load(std::memory_order_relaxed);
    });
  }
  return used;
}

// 1. Coincident vertices near the other mesh get the first one's id (Intersection::vertex_rep),
// so that a position has one name wherever the two meshes meet (and where separated features of
// one mesh touch). Coincident points have overlapping interval boxes: near vertices sorted by
// their boxes' lower x bound are swept for overlaps, and only those are compared exactly.
// Returns the representatives that stand for more than one vertex.
std::vector<PointId> identify_vertices(Intersection& x, const Mesh& a, const Mesh& b,
                                       const UsedFacets& used) {
  const PointTable& table = x.points;
  const std::size_t num_inputs = table.num_inputs();
  x.vertex_rep.resize(num_inputs);
  std::iota(x.vertex_rep.begin(), x.vertex_rep.end(), PointId(0));
  std::vector<std::uint8_t> near(num_inputs, 0);
  const Mesh* meshes[2] = {&a, &b};
  for (int side = 0; side < 2; ++side)
    for (std::uint32_t f = 0; f < used[side].size(); ++f)
      if (used[side][f])
        for (VertexIndex v : meshes[side]->triangles[f]) near[table.vertex(side, v)] = 1;
  std::vector<PointId> ids;
  for (PointId id = 0; id < num_inputs; ++id)
    if (near[id]) ids.push_back(id);
  const std::vector<PointId> first = coincident_representatives(table, ids);
  std::vector<PointId> merged;
  for (std::size_t i = 0; i < ids.size(); ++i) {
    if (first[i] != ids[i]) merged.push_back(first[i]);
    x.vertex_rep[ids[i]] = first[i];
  }
  return merged;
}

// A facet meets many pairs: its interval normal is computed once, and a point's side of its
// plane is then one interval dot product rather than a 3x3 determinant.
FacetNormals facet_normals(const PairContext& c, const UsedFacets& used) {
  FacetNormals normals;
  for (int side = 0; side < 2; ++side) {
    std::vector<std::uint32_t>& slot = normals.slot[side];
    std::vector<std::uint32_t> facets;  // by slot
    slot.resize(used[side].size());
    for (std::uint32_t f = 0; f < used[side].size(); ++f) {
      slot[f] = std::uint32_t(facets.size());
      if (used[side][f]) facets.push_back(f);
    }
    normals.normal[side].resize(facets.size());
    for_each_upward(facets.size(), [&](std::size_t i) {
      const Corners t = c.corners(side, facets[i]);
      normals.normal[side][i] = c.table.approx_normal(t[0], t[1], t[2]);
    });
  }
  return normals;
}

// A crossing of an input edge (u, v), u < v (ids of the edge's ends), with the plane of a facet of
// the other mesh. Every crossing is one table entry, whichever of the edge's facets needs it (the
// seed's "every intersection point once").
struct CrossingKey {
  std::uint32_t side, facet;  // the edge's mesh (0 in a soup) and the other mesh's facet
  PointId u, v;
  // Ordered by (side, facet, u, v) as one 128-bit number: without the branches of a field by
  // field comparison (the keys are sorted, then searched once per crossing edge of every pair).
  unsigned __int128 packed() const {
    return (static_cast<unsigned __int128>((std::uint64_t(side) << 32) | facet) << 64) |
           ((std::uint64_t(u) << 32) | v);
  }
  bool operator<(const CrossingKey& o) const { return packed() < o.packed(); }
  bool operator==(const CrossingKey& o) const {
    return side == o.side && facet == o.facet && u == o.u && v == o.v;
  }
};

// 2. The distinct edge/plane crossings the pairs need, added to the table as recipes, with the
// edges of the other facet each one lies on.
class Crossings {
 public:
  Crossings(const PairContext& c, const std::vector<PairSigns>& signs) : c_(c) {
    collect_keys(signs);
    std::vector<Recipe> recipes(keys_.size());
    tbb::parallel_for(std::size_t(0), keys_.size(), [&](std::size_t i) {
      const Corners f = facet_corners(keys_[i]);
      recipes[i] = {Recipe::Kind::EdgePlane, -1, keys_[i].u, keys_[i].v, f[0], f[1], f[2]};
    });
    first_ = c.table.add_all(recipes);
    // The crossing of line uv with the facet's plane is on the line of the facet's edge
    // (f_i, f_i+1) exactly when uv and that edge are coplanar.
    edges_.assign(keys_.size(), 0);
    for_each_upward(keys_.size(), [&](std::size_t i) {
      const Corners f = facet_corners(keys_[i]);
      for (int e = 0; e < 3; ++e)
        if (c.table.orientation(keys_[i].u, keys_[i].v, f[e], f[(e + 1) % 3]) == CGAL::ZERO)
          edges_[i] |= std::uint8_t(1u << e);
    });
  }

  // The crossing of edge (t[i], t[j]) of a facet on `side` with the plane of `other_facet`.
  CrossingKey key(int side, const Corners& t, int i, int j, std::uint32_t other_facet) const {
    return CrossingKey{side == 0 ? 0 : c_.b_side(), other_facet, std::min(t[i], t[j]),
                       std::max(t[i], t[j])};
  }
  std::uint32_t index(const CrossingKey& key) const {
    return std::uint32_t(std::lower_bound(keys_.begin(), keys_.end(), key) - keys_.begin());
  }
  const CrossingKey& key_at(std::uint32_t index) const { return keys_[index]; }
  PointId id(std::uint32_t index) const { return PointId(first_ + index); }
  // The edges of the crossed facet that crossing `index` lies on.
  std::uint8_t edges(std::uint32_t index) const { return edges_[index]; }

 private:
  // Per pair, the crossing edges of both triangles (at most two each), gathered in parallel.
  void collect_keys(const std::vector<PairSigns>& signs) {
    const std::size_t np = signs.size();
    std::vector<std::uint32_t> first_key(np + 1, 0);
    auto crossing = [&](std::size_t k) { return !signs[k].separated && !signs[k].coplanar; };
    tbb::parallel_for(std::size_t(0), np, [&](std::size_t k) {
      if (!crossing(k)) return;
      std::uint32_t count = 0;
      for_each_crossing_edge(signs[k].a, [&](int, int) { ++count; });
      for_each_crossing_edge(signs[k].b, [&](int, int) { ++count; });
      first_key[k + 1] = count;
    });
    for (std::size_t k = 0; k < np; ++k) first_key[k + 1] += first_key[k];
    keys_.resize(first_key[np]);
    tbb::parallel_for(std::size_t(0), np, [&](std::size_t k) {
      if (!crossing(k)) return;
      const auto [ia, ib] = c_.pairs[k];
      const Corners ta = c_.corners_a(k), tb = c_.corners_b(k);
      std::uint32_t slot = first_key[k];
      for_each_crossing_edge(signs[k].a,
                             [&](int i, int j) { keys_[slot++] = key(0, ta, i, j, ib); });
      for_each_crossing_edge(signs[k].b,
                             [&](int i, int j) { keys_[slot++] = key(1, tb, i, j, ia); });
    });
    tbb::parallel_sort(keys_.begin(), keys_.end());
    keys_.erase(std::unique(keys_.begin(), keys_.end()), keys_.end());
  }

  // The facet belongs to the mesh the edge is not from (in a soup, to the soup).
  Corners facet_corners(const CrossingKey& key) const {
    return c_.corners(c_.options.soup ? 0 : 1 - int(key.side), key.facet);
  }

  const PairContext& c_;
  std::vector<CrossingKey> keys_;
  std::vector<std::uint8_t> edges_;
  PointId first_ = 0;
};

// 3a. A coplanar pair: the overlap of the two triangles in their plane.
void coplanar_outcome(const PairContext& c, std::size_t k, PairOutcome& out) {
  const Corners ta = c.corners_a(k), tb = c.corners_b(k);
  const int dropped = c.table.dominant_axis(ta[0], ta[1], ta[2]);
  out.points = coplanar_overlap(c.table, ta, tb, dropped, c.options.soup);
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
}

// One end of the chord a triangle cuts on the other triangle's plane.
struct ChordEnd {
  PointId id;
  std::int8_t role;   // 0: vertex of ta, 1: crossing of an edge of ta, 2, 3: the same for tb
  std::int8_t index;  // the vertex's corner, or the crossing edge (edge i: corners i, i + 1)
  std::uint32_t crossing = 0;
};

// The chord triangle t (on `side`) cuts on the plane of `other_facet`: its corners on that plane
// and its crossing edges.
std::pair<std::array<ChordEnd, 3>, std::size_t> chord(const Crossings& crossings, int side,
                                                      const Corners& t, const std::int8_t (&s)[3],
                                                      std::uint32_t other_facet) {
  std::array<ChordEnd, 3> ends;
  std::size_t count = 0;
  for (int i = 0; i < 3; ++i)
    if (s[i] == 0) ends[count++] = {t[i], std::int8_t(2 * side), std::int8_t(i)};
  for_each_crossing_edge(s, [&](int i, int j) {
    const std::uint32_t index = crossings.index(crossings.key(side, t, i, j, other_facet));
    ends[count++] = {crossings.id(index), std::int8_t(2 * side + 1), std::int8_t(i), index};
  });
  return {ends, count};
}

// Where a chord end lies on the two triangles, and how its final id is found. A crossing inside
// the other facet is unique in valid solids; one on an edge of the other facet is named by the two
// edges; one at a corner of the other facet is that corner. In a soup, constructions are named by
// position.
PairPoint chord_point(const PairContext& c, const Crossings& crossings, const Corners& ta,
                      const Corners& tb, const ChordEnd& e) {
  PairPoint p;
  p.id = e.id;
  const bool of_a = e.role < 2;
  const Corners& other = of_a ? tb : ta;
  std::uint8_t own_edges, other_edges;
  if (e.role % 2 == 0) {  // a vertex of its triangle, in the other's plane
    own_edges = corner_edges(e.index);
    other_edges =
        edges_through(c.table, c.table.dominant_axis(other[0], other[1], other[2]), other, e.id);
  } else {  // an edge crossing the other's plane
    own_edges = std::uint8_t(1u << e.index);
    other_edges = crossings.edges(e.crossing);
    switch (popcount(other_edges)) {
      case 0:
        if (c.options.soup) p.naming = Naming::Position;
        break;
      case 1: {
        const CrossingKey& key = crossings.key_at(e.crossing);
        int j = 0;
        while (!(other_edges & (1u << j))) ++j;
        const PointId o0 = other[j], o1 = other[(j + 1) % 3];
        p.naming = c.options.soup ? Naming::Position : Naming::EdgeEdge;
        p.key = of_a ? edge_edge_key(key.u, key.v, o0, o1) : edge_edge_key(o0, o1, key.u, key.v);
        break;
      }
      default:
        p.id = other[corner_of_edges(other_edges)];
    }
  }
  p.edges_a = of_a ? own_edges : other_edges;
  p.edges_b = of_a ? other_edges : own_edges;
  return p;
}

// 3b. A transversal pair: both chords lie on the planes' common line and their overlap, ordered
// by exact predicates along that line, is ta n tb: a segment from lo to hi along Na x Nb, a point,
// or nothing.
void chord_outcome(const PairContext& c, const Crossings& crossings, const PairSigns& s,
                   const ApproxVector& line, std::size_t k, PairOutcome& out) {
  const auto [ia, ib] = c.pairs[k];
  const Corners ta = c.corners_a(k), tb = c.corners_b(k);
  const auto [ca, na] = chord(crossings, 0, ta, s.a, ib);
  const auto [cb, nb] = chord(crossings, 1, tb, s.b, ia);
  auto order = [&](const ChordEnd& p, const ChordEnd& q) {  // sign of q - p along the line
    return p.id == q.id ? CGAL::ZERO : c.table.along_line(line, ta, tb, p.id, q.id);
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

  out.points.push_back(chord_point(c, crossings, ta, tb, lo));
  if (extent == CGAL::ZERO) {
    // In a soup, neighbours touching only at a common corner: nothing to cut.
    const PairPoint& p = out.points[0];
    auto corner = [&](const Corners& t) { return p.id == t[0] || p.id == t[1] || p.id == t[2]; };
    if (c.options.soup && p.id != kNoPoint && p.naming == Naming::Known && corner(ta) &&
        corner(tb)) {
      out.points.clear();
      return;
    }
    out.kind = PairOutcome::Kind::Point;
    return;
  }
  out.points.push_back(chord_point(c, crossings, ta, tb, hi));
  out.kind = PairOutcome::Kind::Segment;
  // A segment along an edge of either triangle is not transversal (the local picture involves
  // more facets).
  const PairPoint &p = out.points[0], &q = out.points[1];
  out.transversal = !(p.edges_a & q.edges_a) && !(p.edges_b & q.edges_b);
}

// 3c. Final ids, sequentially in pair order so that they do not depend on the thread count:
// points on two edges are named by the edges, and in a soup every construction by its exact
// position (the least id at that position, vertices included).
void name_points(Intersection& x, std::vector<PairOutcome>& outcomes, bool soup) {
  PointTable& table = x.points;
  FlatMap<EdgeEdgeKey, PointId, EdgeEdgeHash> edge_edge;
  std::vector<PointId> positioned;
  auto final_id = [&](const PairPoint& p) {
    PointId id = p.id;
    if (p.naming == Naming::EdgeEdge) {
      if (const PointId* known = edge_edge.find(p.key)) return *known;
      if (id == kNoPoint) id = table.add(p.recipe);
      edge_edge.emplace(p.key, id);
    } else if (p.naming == Naming::Position) {
      if (id == kNoPoint) id = table.add(p.recipe);
      positioned.push_back(id);
    }
    return id;
  };
  for (PairOutcome& out : outcomes)
    for (PairPoint& p : out.points)
      if (p.naming != Naming::Known) {
        p.id = final_id(p);
        if (p.naming == Naming::EdgeEdge) p.naming = Naming::Known;
      }
  if (!soup) return;
  std::sort(positioned.begin(), positioned.end());
  positioned.erase(std::unique(positioned.begin(), positioned.end()), positioned.end());
  std::vector<PointId> ids;
  for (PointId id = 0; id < table.num_inputs(); ++id)
    if (x.vertex_rep[id] == id) ids.push_back(id);
  ids.insert(ids.end(), positioned.begin(), positioned.end());
  const std::vector<PointId> first = coincident_representatives(table, ids);
  std::vector<PointId> named(table.size(), kNoPoint);
  for (std::size_t i = 0; i < ids.size(); ++i) named[ids[i]] = first[i];
  for (PairOutcome& out : outcomes)
    for (PairPoint& p : out.points)
      if (p.naming == Naming::Position) {
        p.id = named[p.id];
        p.naming = Naming::Known;
      }
}

// The indices of the pairs whose triangles no plane separates, in order (in parallel blocks).
std::vector<std::uint32_t> unseparated(const std::vector<PairSigns>& signs) {
  constexpr std::size_t kBlock = 1 << 14;
  const std::vector<std::size_t> first =
      block_offsets(signs.size(), kBlock, [&](std::size_t begin, std::size_t end) {
        return std::size_t(std::count_if(signs.begin() + begin, signs.begin() + end,
                                         [](const PairSigns& s) { return !s.separated; }));
      });
  std::vector<std::uint32_t> live(first.back());
  tbb::parallel_for(std::size_t(0), first.size() - 1, [&](std::size_t b) {
    std::size_t slot = first[b];
    for (std::size_t k = b * kBlock; k < std::min(signs.size(), (b + 1) * kBlock); ++k)
      if (!signs[k].separated) live[slot++] = std::uint32_t(k);
  });
  return live;
}

}  // namespace

// The phases run in parallel where the pairs are independent and end with one sequential pass in
// pair order that gives final ids, so the result is the same for any number of threads.
PairFindings intersect(const Mesh& a, const Mesh& b, const Pairs& pairs,
                       const IntersectOptions& options) {
  PairFindings found;
  Intersection& x = found.x;
  x.points = options.points ? std::move(*options.points) : PointTable(a, b, options.soup);
  const UsedFacets used = used_facets(a, b, pairs);
  found.merged = identify_vertices(x, a, b, used);
  // Corners are named by the ids of their positions from here on: predicates on coincident
  // corners of the two meshes (identical meshes, shared vertices) are decided by the ids alone.
  const PairContext c{{&a, &b}, pairs, options, x.points, x.vertex_rep};
  const FacetNormals normals = facet_normals(c, used);
  const std::vector<PairSigns> signs = pair_signs(c, normals);
  const Crossings crossings(c, signs);

  // Most candidate pairs are separated by a plane (only their boxes overlap: 1.5 million of them
  // between two finely tessellated parallel plates): the outcomes, and the passes over them, are
  // for the pairs left, in their order.
  const std::vector<std::uint32_t> live = unseparated(signs);
  Pairs& live_pairs = found.pairs;
  std::vector<PairOutcome>& outcomes = found.outcomes;
  live_pairs.resize(live.size());
  outcomes.resize(live.size());
  for_each_upward(live.size(), [&](std::size_t j) {
    const std::uint32_t k = live[j];
    live_pairs[j] = pairs[k];
    if (signs[k].coplanar) return coplanar_outcome(c, k, outcomes[j]);
    const ApproxVector line =
        CGAL::cross_product(normals.of(0, pairs[k].first), normals.of(1, pairs[k].second));
    chord_outcome(c, crossings, signs[k], line, k, outcomes[j]);
  });
  name_points(x, outcomes, options.soup);
  return found;
}

}  // namespace morphex::detail

// SPDX-License-Identifier: GPL-3.0-or-later
// Step 3: exact intersection of each candidate pair, each intersection point stored once.
//
// The vertices of each triangle are classified against the other's plane with orientation
// predicates (no construction): all on one side, none meet. Non-coplanar pairs: each triangle cuts
// a chord on the other's plane whose ends are its vertices on that plane or its edges crossing
// it; an edge/plane crossing is constructed once per (edge, facet) and shared by both facets of the
// edge. The two chords lie on the planes' common line and their overlap, ordered by exact
// predicates along that line, is the intersection: a segment, a point, or nothing. Coplanar pairs
// clip one triangle by the other in their common plane (the overlap polygon). Points are stored
// once by exact position.
// Unlike the seed, point-only contacts are kept (as Steiner points) and coplanar overlaps insert
// their boundary, so every sub-triangle ends up entirely inside, outside or on the other surface.
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <limits>
#include <tuple>

#include "boolean_internal.h"
#include "filtered.h"
#include "point_index.h"
#include "projection_traits.h"

namespace morphex::detail {

namespace {

class PointStore {
 public:
  explicit PointStore(Intersection& x) : x_(x), index_(x.points) {}
  PointId id(const Point& p) { return index_.id(p); }
  void reserve(std::size_t points) { index_.reserve(points); }
  std::size_t size() const { return x_.points.size(); }

 private:
  Intersection& x_;
  PointIndex index_;
};

// A triangle as references to its mesh's points. CGAL's lazy Triangle_3 would allocate a node
// per triangle and per vertex access, and copy exact coordinates on every exact fallback.
struct Corners {
  const Point* p[3];
  const Point& operator[](int i) const { return *p[i]; }
};

Corners triangle(const Mesh& m, std::uint32_t t) {
  const Triangle& f = m.triangles[t];
  return {{&m.points[f[0]], &m.points[f[1]], &m.points[f[2]]}};
}

// sign(((a1 - a0) x (a2 - a0)) x ((b1 - b0) x (b2 - b0)) . (q - p)): the order of p and q along
// the common line of the two planes, oriented by Na x Nb.
CGAL::Sign along_common_line(const Corners& ta, const Corners& tb, const Point& p, const Point& q) {
  return filtered_sign(
      [](const auto& a0, const auto& a1, const auto& a2, const auto& b0, const auto& b1,
         const auto& b2, const auto& p, const auto& q) {
        return CGAL::cross_product(CGAL::cross_product(a1 - a0, a2 - a0),
                                   CGAL::cross_product(b1 - b0, b2 - b0)) *
               (q - p);
      },
      ta[0], ta[1], ta[2], tb[0], tb[1], tb[2], p, q);
}

// The signs of t's vertices against the plane of `other`; true when all three are strictly on
// one side (the triangles cannot meet).
bool signs_against_plane(const Corners& t, const Corners& other, std::int8_t (&signs)[3]) {
  for (int i = 0; i < 3; ++i) signs[i] = std::int8_t(orient3d(other[0], other[1], other[2], t[i]));
  return signs[0] != 0 && signs[0] == signs[1] && signs[1] == signs[2];
}

bool on_an_edge(const Corners& t, const Point& p, const Point& q) {
  for (int i = 0; i < 3; ++i)
    if (collinear3d(t[i], t[(i + 1) % 3], p) && collinear3d(t[i], t[(i + 1) % 3], q)) return true;
  return false;
}

// Step 4, the seed's rule: with s = sign((Na x Nb) . (p2 - p1)), the interior of B lies on the
// left of (p1, p2) in ta when s > 0, and the interior of A on the left of (p1, p2) in tb when
// s < 0. Only for transversal segments (ZERO otherwise): on an edge, the local picture involves
// more facets.
CGAL::Sign transversal_orientation(const Corners& ta, const Corners& tb, const Point& from,
                                   const Point& to) {
  if (on_an_edge(ta, from, to) || on_an_edge(tb, from, to)) return CGAL::ZERO;
  return along_common_line(ta, tb, from, to);
}

void add_transversal(CGAL::Sign sign, PointId p1, PointId p2, FacetCut& ca, FacetCut& cb) {
  if (p1 == p2 || sign == CGAL::ZERO) return;
  const bool positive = sign == CGAL::POSITIVE;
  ca.transversal.push_back(positive ? OrientedSegment{p1, p2} : OrientedSegment{p2, p1});
  cb.transversal.push_back(positive ? OrientedSegment{p2, p1} : OrientedSegment{p1, p2});
}

void add_segment(FacetCut& cut, PointId p, PointId q) {
  cut.points.push_back(p);
  cut.points.push_back(q);
  if (p != q) cut.segments.push_back(undirected(p, q));
}

// The plane of a facet in homogeneous integer coordinates: A X + B Y + C Z + D W = 0 for the
// homogeneous points (X, Y, Z, W) on it (the 4D cross product of its corners).
struct ExactPlane {
  std::array<mpz_class, 4> coefficients;
};

Homogeneous homogeneous_point(const Point& p) {
  return detail::homogeneous_point(CGAL::exact(p));
}

ExactPlane exact_plane(const Homogeneous& a, const Homogeneous& b, const Homogeneous& c) {
  auto det3 = [&](int i, int j, int k) -> mpz_class {
    return a[i] * (b[j] * c[k] - b[k] * c[j]) - a[j] * (b[i] * c[k] - b[k] * c[i]) +
           a[k] * (b[i] * c[j] - b[j] * c[i]);
  };
  return {{det3(1, 2, 3), -det3(0, 2, 3), det3(0, 1, 3), -det3(0, 1, 2)}};
}

// The point where segment pq crosses the plane, when p and q are strictly on opposite sides:
// with d the plane's linear form, it is d(q) p - d(p) q in homogeneous coordinates (integers, so
// the only gcds are the three that put the coordinates in lowest terms). Stored as an evaluated
// leaf, so that neither the predicates that meet it later nor the exact output walk a lazy
// construction graph.
Point plane_crossing(const ExactPlane& plane, const Homogeneous& hp, const Homogeneous& hq) {
  const auto& c = plane.coefficients;
  const mpz_class dp = c[0] * hp[0] + c[1] * hp[1] + c[2] * hp[2] + c[3] * hp[3];
  const mpz_class dq = c[0] * hq[0] + c[1] * hq[1] + c[2] * hq[2] + c[3] * hq[3];
  Homogeneous r;
  for (int i = 0; i < 4; ++i) r[i] = dq * hp[i] - dp * hq[i];
  auto coordinate = [&](int i) {
    mpq_class x(r[i], r[3]);
    x.canonicalize();
    return x;
  };
  return point_from_exact(
      Kernel::Exact_kernel::Point_3(coordinate(0), coordinate(1), coordinate(2)));
}

Point plane_crossing(const ExactPlane& plane, const Point& p, const Point& q) {
  return plane_crossing(plane, homogeneous_point(p), homogeneous_point(q));
}

// Homogeneous coordinates of the input vertices the crossings need, each converted once (a vertex
// serves every crossing of its edges and every plane of its facets).
class HomogeneousVertices {
 public:
  HomogeneousVertices(const Mesh& mesh, std::vector<VertexIndex> vertices)
      : vertices_(std::move(vertices)) {
    std::sort(vertices_.begin(), vertices_.end());
    vertices_.erase(std::unique(vertices_.begin(), vertices_.end()), vertices_.end());
    forms_.resize(vertices_.size());
    tbb::parallel_for(std::size_t(0), vertices_.size(), [&](std::size_t i) {
      forms_[i] = homogeneous_point(mesh.points[vertices_[i]]);
    });
  }
  const Homogeneous& operator()(VertexIndex v) const {
    return forms_[std::lower_bound(vertices_.begin(), vertices_.end(), v) - vertices_.begin()];
  }

 private:
  std::vector<VertexIndex> vertices_;
  std::vector<Homogeneous> forms_;
};

// The vertical plane through the line ab of the coordinate plane that drops axis `dropped`: the
// points whose projection lies on that line. Crossing it with a segment of the common plane of
// two coplanar triangles gives the exact point where the segment meets the line.
ExactPlane plane_through_projected_line(int dropped, const Point& a, const Point& b) {
  const auto ha = homogeneous_point(a), hb = homogeneous_point(b);
  const int u = dropped == 0 ? 1 : 0, v = dropped == 2 ? 1 : 2;
  ExactPlane plane;
  plane.coefficients[dropped] = 0;
  plane.coefficients[u] = ha[v] * hb[3] - ha[3] * hb[v];
  plane.coefficients[v] = ha[3] * hb[u] - ha[u] * hb[3];
  plane.coefficients[3] = ha[u] * hb[v] - ha[v] * hb[u];
  return plane;
}

// The overlap of two coplanar, non-degenerate triangles: tb clipped by the three edges of ta in
// the coordinate plane that drops the dominant axis of their normal (an exact projection: it
// only selects coordinates). Kept vertices stay the input points; each new vertex is one exact
// crossing. Returns nothing, one point, the two ends of a segment, or a convex polygon.
template <int dropped>
std::vector<Point> coplanar_overlap(const Corners& ta, const Corners& tb) {
  const FilteredProjectedOrientation<dropped> orient;
  const int turn = orient(ta[0], ta[1], ta[2]);  // +1 or -1: ta is not degenerate
  std::vector<Point> polygon = {tb[0], tb[1], tb[2]}, clipped;
  for (int i = 0; i < 3 && !polygon.empty(); ++i) {
    const Point &a = ta[i], &b = ta[(i + 1) % 3];
    clipped.clear();
    std::vector<int> side(polygon.size());
    for (std::size_t k = 0; k < polygon.size(); ++k) side[k] = turn * orient(a, b, polygon[k]);
    for (std::size_t k = 0; k < polygon.size(); ++k) {
      const std::size_t next = (k + 1) % polygon.size();
      if (side[k] >= 0) clipped.push_back(polygon[k]);
      if (side[k] * side[next] < 0)
        clipped.push_back(
            plane_crossing(plane_through_projected_line(dropped, a, b), polygon[k], polygon[next]));
    }
    std::swap(polygon, clipped);
  }
  // Touching contacts leave repeated points and flat polygons: reduce to distinct points, and a
  // polygon without area to the ends of its segment.
  std::vector<Point> distinct;
  for (const Point& p : polygon)
    if (distinct.empty() || p != distinct.back()) distinct.push_back(p);
  while (distinct.size() > 1 && distinct.front() == distinct.back()) distinct.pop_back();
  if (distinct.size() < 3) return distinct;
  bool flat = true;
  for (std::size_t k = 2; k < distinct.size() && flat; ++k)
    flat = orient(distinct[0], distinct[1], distinct[k]) == CGAL::COLLINEAR;
  if (!flat) return distinct;
  // The extreme points along the segment's line, by exact lexicographic order (which is monotone
  // along any line).
  const auto [lo, hi] = std::minmax_element(
      distinct.begin(), distinct.end(),
      [](const Point& p, const Point& q) { return CGAL::compare_xyz(p, q) == CGAL::SMALLER; });
  return {*lo, *hi};
}

std::vector<Point> coplanar_overlap(const Corners& ta, const Corners& tb) {
  switch (dominant_axis(ta[0], ta[1], ta[2])) {
    case 0:
      return coplanar_overlap<0>(ta, tb);
    case 1:
      return coplanar_overlap<1>(ta, tb);
    default:
      return coplanar_overlap<2>(ta, tb);
  }
}

// A crossing of an input edge (u, v), u < v, of mesh `side` with the plane of facet `facet` of
// the other mesh. Every crossing is constructed once, whichever of the edge's facets needs it
// (the seed's "every intersection point once").
struct CrossingKey {
  std::uint32_t side, facet;
  VertexIndex u, v;
  bool operator<(const CrossingKey& o) const {
    return std::tie(side, facet, u, v) < std::tie(o.side, o.facet, o.u, o.v);
  }
  bool operator==(const CrossingKey& o) const {
    return side == o.side && facet == o.facet && u == o.u && v == o.v;
  }
};

// One end of the chord a triangle cuts on the other triangle's plane: an input vertex (its point
// id is known) or a crossing (its id is given in the final, sequential pass).
struct ChordEnd {
  const Point* point;
  PointId vertex = kNoPoint;
  std::uint32_t crossing = kNoPoint;
  bool same(const ChordEnd& o) const {
    return vertex != kNoPoint ? vertex == o.vertex : crossing == o.crossing;
  }
  static constexpr std::uint32_t kNoPoint = std::numeric_limits<std::uint32_t>::max();
};

// Edges of `f` whose ends lie strictly on opposite sides of the other plane.
template <class Visit>
void for_each_crossing_edge(const Triangle& f, const std::int8_t (&signs)[3], Visit&& visit) {
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    if (signs[i] != 0 && signs[j] != 0 && signs[i] != signs[j]) visit(i, j);
  }
}

// What one candidate pair leaves on its two facets, before point ids are given.
struct PairOutcome {
  enum class Kind : std::uint8_t { None, Point, Segment, Polygon } kind = Kind::None;
  ChordEnd lo, hi;             // Point: lo; Segment: lo -> hi (non-coplanar pairs)
  std::vector<Point> polygon;  // coplanar pairs: the point, segment ends or overlap polygon
  CGAL::Sign orientation = CGAL::ZERO;  // transversal segments: sign((Na x Nb) . (hi - lo))
};

struct PairSigns {
  std::int8_t a[3], b[3];  // ta's vertices against tb's plane, tb's against ta's
  bool separated = true, coplanar = false;
};

}  // namespace

// The phases run in parallel where the pairs are independent and end with one sequential pass in
// pair order that gives point ids, so the result is the same for any number of threads:
//   1. orientation signs of each pair (separated pairs stop here);
//   2. the distinct edge/plane crossings the pairs need, each constructed once;
//   3. each pair's chord overlap (a segment, a point or nothing), or its coplanar overlap;
//   4. point ids and the per-facet cuts.
Intersection intersect(const Mesh& a, const Mesh& b,
                       const std::vector<std::pair<std::uint32_t, std::uint32_t>>& pairs) {
  Intersection x;
  PointStore store(x);
  const Mesh* meshes[2] = {&a, &b};
  store.reserve(a.num_vertices() + b.num_vertices());
  for (int side = 0; side < 2; ++side) {
    x.vertex_id[side].reserve(meshes[side]->num_vertices());
    for (const Point& p : meshes[side]->points) x.vertex_id[side].push_back(store.id(p));
  }
  const std::size_t input_points = store.size();
  const std::size_t np = pairs.size();

  std::vector<PairSigns> signs(np);
  tbb::parallel_for(std::size_t(0), np, [&](std::size_t k) {
    const auto [ia, ib] = pairs[k];
    const Corners ta = triangle(a, ia), tb = triangle(b, ib);
    PairSigns& s = signs[k];
    if (signs_against_plane(ta, tb, s.a) || signs_against_plane(tb, ta, s.b)) return;
    s.separated = false;
    s.coplanar = s.a[0] == 0 && s.a[1] == 0 && s.a[2] == 0;
  });

  std::vector<CrossingKey> keys;
  for (std::size_t k = 0; k < np; ++k) {
    if (signs[k].separated || signs[k].coplanar) continue;
    const auto [ia, ib] = pairs[k];
    for_each_crossing_edge(a.triangles[ia], signs[k].a, [&](int i, int j) {
      const VertexIndex u = a.triangles[ia][i], v = a.triangles[ia][j];
      keys.push_back({0, ib, std::min(u, v), std::max(u, v)});
    });
    for_each_crossing_edge(b.triangles[ib], signs[k].b, [&](int i, int j) {
      const VertexIndex u = b.triangles[ib][i], v = b.triangles[ib][j];
      keys.push_back({1, ia, std::min(u, v), std::max(u, v)});
    });
  }
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  // Keys of one facet are adjacent: each group computes that facet's plane once.
  std::vector<std::size_t> group_begin;
  for (std::size_t i = 0; i < keys.size(); ++i)
    if (i == 0 || keys[i].side != keys[i - 1].side || keys[i].facet != keys[i - 1].facet)
      group_begin.push_back(i);
  group_begin.push_back(keys.size());
  std::vector<VertexIndex> used[2];  // per mesh: edge ends and plane corners
  for (const CrossingKey& k : keys) {
    used[k.side].push_back(k.u);
    used[k.side].push_back(k.v);
    for (VertexIndex v : meshes[1 - k.side]->triangles[k.facet]) used[1 - k.side].push_back(v);
  }
  const HomogeneousVertices homogeneous_of[2] = {{a, std::move(used[0])}, {b, std::move(used[1])}};
  std::vector<Point> crossing_points(keys.size());
  tbb::parallel_for(std::size_t(0), group_begin.size() - 1, [&](std::size_t g) {
    const CrossingKey& first = keys[group_begin[g]];
    const HomogeneousVertices& edge_ends = homogeneous_of[first.side];
    const HomogeneousVertices& corners = homogeneous_of[1 - first.side];
    const Triangle& f = meshes[1 - first.side]->triangles[first.facet];
    const ExactPlane plane = exact_plane(corners(f[0]), corners(f[1]), corners(f[2]));
    for (std::size_t i = group_begin[g]; i < group_begin[g + 1]; ++i)
      crossing_points[i] = plane_crossing(plane, edge_ends(keys[i].u), edge_ends(keys[i].v));
  });

  std::vector<PairOutcome> outcomes(np);
  tbb::parallel_for(std::size_t(0), np, [&](std::size_t k) {
    if (signs[k].separated) return;
    const auto [ia, ib] = pairs[k];
    const Corners ta = triangle(a, ia), tb = triangle(b, ib);
    PairOutcome& out = outcomes[k];
    if (!signs[k].coplanar) {
      // The chord each triangle cuts on the other's plane: its vertices on that plane and its
      // crossing edges. Both chords lie on the planes' common line; their overlap is ta n tb.
      auto chord = [&](std::uint32_t side, std::uint32_t facet, const Corners& t,
                       const std::int8_t(&s)[3], std::uint32_t other_facet) {
        const Triangle& f = meshes[side]->triangles[facet];
        std::array<ChordEnd, 3> ends;
        std::size_t count = 0;
        for (int i = 0; i < 3; ++i)
          if (s[i] == 0) ends[count++] = {&t[i], x.vertex_id[side][f[i]]};
        for_each_crossing_edge(f, s, [&](int i, int j) {
          const CrossingKey key{side, other_facet, std::min(f[i], f[j]), std::max(f[i], f[j])};
          const auto c =
              std::uint32_t(std::lower_bound(keys.begin(), keys.end(), key) - keys.begin());
          ends[count++] = {&crossing_points[c], ChordEnd::kNoPoint, c};
        });
        return std::make_pair(ends, count);
      };
      const auto [ca, na] = chord(0, ia, ta, signs[k].a, ib);
      const auto [cb, nb] = chord(1, ib, tb, signs[k].b, ia);
      auto order = [&](const ChordEnd& p, const ChordEnd& q) {  // sign of q - p along the line
        return p.same(q) ? CGAL::ZERO : along_common_line(ta, tb, *p.point, *q.point);
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
      out.lo = lo;
      out.hi = hi;
      if (extent == CGAL::ZERO) {
        out.kind = PairOutcome::Kind::Point;
        return;
      }
      out.kind = PairOutcome::Kind::Segment;
      out.orientation = transversal_orientation(ta, tb, *lo.point, *hi.point);
      return;
    }
    out.polygon = coplanar_overlap(ta, tb);
    switch (out.polygon.size()) {
      case 0:
        return;
      case 1:
        out.kind = PairOutcome::Kind::Point;
        return;
      case 2:
        out.kind = PairOutcome::Kind::Segment;
        out.orientation = transversal_orientation(ta, tb, out.polygon[0], out.polygon[1]);
        return;
      default:
        out.kind = PairOutcome::Kind::Polygon;
    }
  });

  // Sequential, in pair order: point ids do not depend on the thread count.
  std::vector<PointId> crossing_id(keys.size(), ChordEnd::kNoPoint);
  auto id_of = [&](const ChordEnd& e) {
    if (e.vertex != ChordEnd::kNoPoint) return e.vertex;
    PointId& id = crossing_id[e.crossing];
    if (id == ChordEnd::kNoPoint) id = store.id(*e.point);
    return id;
  };
  for (std::size_t k = 0; k < np; ++k) {
    PairOutcome& out = outcomes[k];
    if (out.kind == PairOutcome::Kind::None) continue;
    const auto [ia, ib] = pairs[k];
    ++x.intersecting_pairs;
    FacetCut& ca = x.cuts[0][ia];
    FacetCut& cb = x.cuts[1][ib];
    std::vector<PointId> ids;
    if (!out.polygon.empty())
      for (const Point& p : out.polygon) ids.push_back(store.id(p));
    else if (out.kind == PairOutcome::Kind::Point)
      ids = {id_of(out.lo)};
    else
      ids = {id_of(out.lo), id_of(out.hi)};
    switch (out.kind) {
      case PairOutcome::Kind::Point:
        ca.points.push_back(ids[0]);
        cb.points.push_back(ids[0]);
        break;
      case PairOutcome::Kind::Segment:
        add_segment(ca, ids[0], ids[1]);
        add_segment(cb, ids[0], ids[1]);
        add_transversal(out.orientation, ids[0], ids[1], ca, cb);
        break;
      case PairOutcome::Kind::Polygon:
        // Coplanar overlap: its boundary separates, in each facet, the part that lies on the
        // other surface from the rest.
        for (std::size_t i = 0; i < ids.size(); ++i) {
          add_segment(ca, ids[i], ids[(i + 1) % ids.size()]);
          add_segment(cb, ids[i], ids[(i + 1) % ids.size()]);
        }
        ca.coplanar_facets.push_back(ib);
        cb.coplanar_facets.push_back(ia);
        break;
      case PairOutcome::Kind::None:
        break;
    }
  }
  x.constructed_points = store.size() - input_points;
  return x;
}

}  // namespace morphex::detail

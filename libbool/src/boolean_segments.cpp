// SPDX-License-Identifier: GPL-3.0-or-later
// Step 3: exact intersection of each candidate pair, each intersection point stored once.
//
// The vertices of each triangle are classified against the other's plane with orientation
// predicates (no construction): all on one side, none meet. Non-coplanar pairs: each triangle cuts
// a chord on the other's plane whose ends are its vertices on that plane or its edges crossing
// it; an edge/plane crossing is constructed once per (edge, facet) and shared by both facets of the
// edge. The two chords lie on the planes' common line and their overlap, ordered by exact
// predicates along that line, is the intersection: a segment, a point, or nothing. Coplanar pairs
// take CGAL's exact triangle/triangle intersection (the overlap polygon). Points are stored once
// by exact position.
// Unlike the seed, point-only contacts are kept (as Steiner points) and coplanar overlaps insert
// their boundary, so every sub-triangle ends up entirely inside, outside or on the other surface.
#include <CGAL/intersections.h>

#include <map>
#include <tuple>

#include "boolean_internal.h"
#include "point_index.h"

namespace morphex::detail {

namespace {

class PointStore {
 public:
  explicit PointStore(Intersection& x) : x_(x), index_(x.points) {}
  PointId id(const Point& p) { return index_.id(p); }
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
  Kernel::Triangle_3 lazy() const { return {*p[0], *p[1], *p[2]}; }
};

Corners triangle(const Mesh& m, std::uint32_t t) {
  const Triangle& f = m.triangles[t];
  return {{&m.points[f[0]], &m.points[f[1]], &m.points[f[2]]}};
}

// The sign of an expression of points, evaluated on their interval approximations and, only
// when those cannot decide, on their exact coordinates: a filtered predicate without lazy nodes.
template <class Expression, class... Points>
CGAL::Sign filtered_sign(const Expression& expression, const Points&... points) {
  {
    CGAL::Protect_FPU_rounding<true> rounding;
    const CGAL::Uncertain<CGAL::Sign> s = CGAL::sign(expression(CGAL::approx(points)...));
    if (CGAL::is_certain(s)) return CGAL::get_certain(s);
  }
  return CGAL::sign(expression(CGAL::exact(points)...));
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

// All three vertices of `t` strictly on one side of the plane of `other`.
bool separated_by_plane(const Corners& t, const Corners& other) {
  const auto s0 = CGAL::orientation(other[0], other[1], other[2], t[0]);
  if (s0 == CGAL::COPLANAR) return false;
  return CGAL::orientation(other[0], other[1], other[2], t[1]) == s0 &&
         CGAL::orientation(other[0], other[1], other[2], t[2]) == s0;
}

bool on_an_edge(const Corners& t, const Point& p, const Point& q) {
  for (int i = 0; i < 3; ++i)
    if (CGAL::collinear(t[i], t[(i + 1) % 3], p) && CGAL::collinear(t[i], t[(i + 1) % 3], q))
      return true;
  return false;
}

// Step 4, the seed's rule: with s = sign((Na x Nb) . (p2 - p1)), the interior of B lies on the
// left of (p1, p2) in ta when s > 0, and the interior of A on the left of (p1, p2) in tb when
// s < 0. Only for transversal segments: on an edge, the local picture involves more facets.
void orient_transversal(const Corners& ta, const Corners& tb,
                        const Point& from, const Point& to, PointId p1, PointId p2, FacetCut& ca,
                        FacetCut& cb) {
  if (p1 == p2 || on_an_edge(ta, from, to) || on_an_edge(tb, from, to)) return;
  const auto sign = along_common_line(ta, tb, from, to);
  if (sign == CGAL::ZERO) return;
  const bool positive = sign == CGAL::POSITIVE;
  ca.transversal.push_back(positive ? OrientedSegment{p1, p2} : OrientedSegment{p2, p1});
  cb.transversal.push_back(positive ? OrientedSegment{p2, p1} : OrientedSegment{p1, p2});
}

// The plane of a facet as n . x = k with n = (t1 - t0) x (t2 - t0), exact.
struct ExactPlane {
  Kernel::Exact_kernel::Vector_3 n;
  Kernel::Exact_kernel::FT k;
};

ExactPlane exact_plane(const Corners& t) {
  const auto &t0 = CGAL::exact(t[0]), &t1 = CGAL::exact(t[1]), &t2 = CGAL::exact(t[2]);
  ExactPlane plane{CGAL::cross_product(t1 - t0, t2 - t0), 0};
  plane.k = plane.n * (t0 - CGAL::ORIGIN);
  return plane;
}

// The point where segment pq crosses the plane, when p and q are strictly on opposite sides:
// with d(x) = n . x - k, it is (d(p) q - d(q) p) / (d(p) - d(q)). Computed once on the exact
// coordinates and stored evaluated, so that neither the predicates that meet it later nor the
// exact output walk a lazy construction graph.
Point plane_crossing(const ExactPlane& plane, const Point& p, const Point& q) {
  using EK = Kernel::Exact_kernel;
  const EK::Point_3 &ep = CGAL::exact(p), &eq = CGAL::exact(q);
  const EK::FT dp = plane.n * (ep - CGAL::ORIGIN) - plane.k;
  const EK::FT dq = plane.n * (eq - CGAL::ORIGIN) - plane.k;
  const EK::FT denominator = dp - dq;
  return point_from_exact(EK::Point_3((dp * eq.x() - dq * ep.x()) / denominator,
                                      (dp * eq.y() - dq * ep.y()) / denominator,
                                      (dp * eq.z() - dq * ep.z()) / denominator));
}

// One end of the chord a triangle cuts on the other triangle's plane.
struct ChordEnd {
  PointId id;
  Point point;
};

// Constructs each crossing of an input edge with a facet's plane once, whichever of the edge's
// two facets asks first (the seed's "every intersection point once").
class EdgePlaneCrossings {
 public:
  EdgePlaneCrossings(PointStore& store) : store_(store) {}
  ChordEnd get(int side, VertexIndex u, VertexIndex v, std::uint32_t other_facet, const Point& pu,
               const Point& pv, const Corners& other) {
    const auto key = std::make_tuple(side, std::min(u, v), std::max(u, v), other_facet);
    const auto it = memo_.find(key);
    if (it != memo_.end()) return it->second;
    auto plane = planes_[1 - side].find(other_facet);
    if (plane == planes_[1 - side].end())
      plane = planes_[1 - side].emplace(other_facet, exact_plane(other)).first;
    const Point p = plane_crossing(plane->second, pu, pv);
    const ChordEnd end{store_.id(p), p};
    memo_.emplace(key, end);
    return end;
  }

 private:
  PointStore& store_;
  std::map<std::tuple<int, VertexIndex, VertexIndex, std::uint32_t>, ChordEnd> memo_;
  std::unordered_map<std::uint32_t, ExactPlane> planes_[2];  // per mesh, facet -> plane
};

// The chord t cuts on the plane of `other` from the signs of t's vertices against that plane:
// vertices on the plane are ends as they are; edges whose ends have opposite signs are crossed.
std::vector<ChordEnd> chord(int side, const Triangle& f, const Corners& t,
                            const CGAL::Orientation (&signs)[3], std::uint32_t other_facet,
                            const Corners& other, const Intersection& x,
                            EdgePlaneCrossings& crossings) {
  std::vector<ChordEnd> ends;
  for (int i = 0; i < 3; ++i) {
    if (signs[i] == CGAL::COPLANAR) ends.push_back({x.vertex_id[side][f[i]], t[i]});
    const int j = (i + 1) % 3;
    if (signs[i] != CGAL::COPLANAR && signs[j] != CGAL::COPLANAR && signs[i] != signs[j])
      ends.push_back(crossings.get(side, f[i], f[j], other_facet, t[i], t[j], other));
  }
  return ends;
}

void add_segment(FacetCut& cut, PointId p, PointId q) {
  cut.points.push_back(p);
  cut.points.push_back(q);
  if (p != q) cut.segments.push_back(undirected(p, q));
}

}  // namespace

Intersection intersect(const Mesh& a, const Mesh& b,
                       const std::vector<std::pair<std::uint32_t, std::uint32_t>>& pairs) {
  Intersection x;
  PointStore store(x);
  const Mesh* meshes[2] = {&a, &b};
  for (int side = 0; side < 2; ++side) {
    x.vertex_id[side].reserve(meshes[side]->num_vertices());
    for (const Point& p : meshes[side]->points) x.vertex_id[side].push_back(store.id(p));
  }
  const std::size_t input_points = store.size();

  EdgePlaneCrossings crossings(store);
  for (const auto& [ia, ib] : pairs) {
    const Corners ta = triangle(a, ia), tb = triangle(b, ib);
    if (separated_by_plane(ta, tb) || separated_by_plane(tb, ta)) continue;
    CGAL::Orientation sa[3], sb[3];
    for (int i = 0; i < 3; ++i) {
      sa[i] = CGAL::orientation(tb[0], tb[1], tb[2], ta[i]);
      sb[i] = CGAL::orientation(ta[0], ta[1], ta[2], tb[i]);
    }
    const bool coplanar =
        sa[0] == CGAL::COPLANAR && sa[1] == CGAL::COPLANAR && sa[2] == CGAL::COPLANAR;
    if (!coplanar) {
      // Both chords lie on the line of the two planes: their overlap along it is ta n tb.
      const std::vector<ChordEnd> ca_ends = chord(0, a.triangles[ia], ta, sa, ib, tb, x, crossings);
      const std::vector<ChordEnd> cb_ends = chord(1, b.triangles[ib], tb, sb, ia, ta, x, crossings);
      auto order = [&](const ChordEnd& p, const ChordEnd& q) {  // sign of q - p along the line
        return p.id == q.id ? CGAL::ZERO : along_common_line(ta, tb, p.point, q.point);
      };
      auto sorted = [&](const std::vector<ChordEnd>& e) {
        const ChordEnd& last = e.back();
        return order(e.front(), last) == CGAL::NEGATIVE ? std::make_pair(last, e.front())
                                                        : std::make_pair(e.front(), last);
      };
      const auto [a1, a2] = sorted(ca_ends);
      const auto [b1, b2] = sorted(cb_ends);
      const ChordEnd& lo = order(a1, b1) == CGAL::POSITIVE ? b1 : a1;  // the later start
      const ChordEnd& hi = order(a2, b2) == CGAL::POSITIVE ? a2 : b2;  // the earlier end
      const auto extent = order(lo, hi);
      if (extent == CGAL::NEGATIVE) continue;
      ++x.intersecting_pairs;
      FacetCut& ca = x.cuts[0][ia];
      FacetCut& cb = x.cuts[1][ib];
      if (extent == CGAL::ZERO) {
        ca.points.push_back(lo.id);
        cb.points.push_back(lo.id);
      } else {
        add_segment(ca, lo.id, hi.id);
        add_segment(cb, lo.id, hi.id);
        orient_transversal(ta, tb, lo.point, hi.point, lo.id, hi.id, ca, cb);
      }
      continue;
    }
    const auto result = CGAL::intersection(ta.lazy(), tb.lazy());
    if (!result) continue;
    ++x.intersecting_pairs;
    FacetCut& ca = x.cuts[0][ia];
    FacetCut& cb = x.cuts[1][ib];
    if (const Point* p = boost::get<Point>(&*result)) {
      const PointId id = store.id(*p);
      ca.points.push_back(id);
      cb.points.push_back(id);
    } else if (const auto* s = boost::get<Kernel::Segment_3>(&*result)) {
      const PointId p = store.id(s->source()), q = store.id(s->target());
      add_segment(ca, p, q);
      add_segment(cb, p, q);
      orient_transversal(ta, tb, s->source(), s->target(), p, q, ca, cb);
    } else {
      // Coplanar overlap: a triangle or a polygon. Its boundary separates, in each facet, the
      // part that lies on the other surface from the rest.
      std::vector<Point> polygon;
      if (const auto* t = boost::get<Kernel::Triangle_3>(&*result))
        polygon = {t->vertex(0), t->vertex(1), t->vertex(2)};
      else
        polygon = boost::get<std::vector<Point>>(*result);
      std::vector<PointId> ids;
      for (const Point& p : polygon) ids.push_back(store.id(p));
      for (std::size_t i = 0; i < ids.size(); ++i) {
        add_segment(ca, ids[i], ids[(i + 1) % ids.size()]);
        add_segment(cb, ids[i], ids[(i + 1) % ids.size()]);
      }
      ca.coplanar_facets.push_back(ib);
      cb.coplanar_facets.push_back(ia);
    }
  }
  x.constructed_points = store.size() - input_points;
  return x;
}

}  // namespace morphex::detail

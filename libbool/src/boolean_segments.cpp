// SPDX-License-Identifier: GPL-3.0-or-later
// Step 3: exact intersection of each candidate pair, each intersection point stored once.
//
// The pair is first decided with orientation predicates only (no construction): triangles with all
// three vertices strictly on one side of the other's plane do not meet. Pairs that meet are
// intersected exactly; every point is identified by its exact position, so a point on an edge
// shared by two facets, or on an edge of the other mesh, is constructed once and shared.
// Unlike the seed, point-only contacts are kept (as Steiner points) and coplanar overlaps insert
// their boundary, so every sub-triangle ends up entirely inside, outside or on the other surface.
#include <CGAL/intersections.h>

#include <map>

#include "boolean_internal.h"

namespace morphex::detail {

namespace {

struct LessXYZ {
  bool operator()(const Point& p, const Point& q) const {
    return CGAL::compare_xyz(p, q) == CGAL::SMALLER;
  }
};

class PointStore {
 public:
  explicit PointStore(Intersection& x) : x_(x) {}
  PointId id(const Point& p) {
    auto [it, inserted] = index_.emplace(p, PointId(x_.points.size()));
    if (inserted) x_.points.push_back(p);
    return it->second;
  }
  std::size_t size() const { return x_.points.size(); }

 private:
  Intersection& x_;
  std::map<Point, PointId, LessXYZ> index_;
};

Kernel::Triangle_3 triangle(const Mesh& m, std::uint32_t t) {
  const Triangle& f = m.triangles[t];
  return {m.points[f[0]], m.points[f[1]], m.points[f[2]]};
}

// All three vertices of `t` strictly on one side of the plane of `other`.
bool separated_by_plane(const Kernel::Triangle_3& t, const Kernel::Triangle_3& other) {
  const auto s0 = CGAL::orientation(other[0], other[1], other[2], t[0]);
  if (s0 == CGAL::COPLANAR) return false;
  return CGAL::orientation(other[0], other[1], other[2], t[1]) == s0 &&
         CGAL::orientation(other[0], other[1], other[2], t[2]) == s0;
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

  for (const auto& [ia, ib] : pairs) {
    const Kernel::Triangle_3 ta = triangle(a, ia), tb = triangle(b, ib);
    if (separated_by_plane(ta, tb) || separated_by_plane(tb, ta)) continue;
    const auto result = CGAL::intersection(ta, tb);
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

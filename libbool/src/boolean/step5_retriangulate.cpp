// SPDX-License-Identifier: GPL-3.0-or-later
// Step 5: each cut facet becomes a constrained Delaunay triangulation of its corners and the
// intersection points on it, constrained by its segments. The CDT works in the coordinate plane
// that drops the dominant axis of the facet's normal: an exact projection (it only selects
// coordinates) that keeps the facet non-degenerate. Its points are table ids: predicates run on
// their intervals and fall back to exact homogeneous integers, and the orientation of three points
// on one edge of the facet (every crossing of the facet's own edges is on one) is known without
// evaluating anything. The CDT also yields what classification needs: the sub-triangles joined
// without crossing a constraint, the labels the seed's rule gives beside transversal segments,
// and the unconstrained boundary edges that join the facet to its neighbours.
#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>

#include <tbb/parallel_for.h>

#include <algorithm>

#include "boolean/boolean_internal.h"
#include "exact/table_traits.h"

namespace morphex::detail {

namespace {

// The sub-triangles of one cut facet, with indices local to the facet.
struct FacetPieces {
  std::vector<SubTriangle> triangles;
  std::vector<std::uint32_t> joined;
  std::vector<std::int8_t> rule;
  std::vector<std::pair<std::uint64_t, std::uint32_t>> open_boundary;
};

// The seed's label of a sub-triangle (oriented as its facet) from the transversal segments on its
// edges: the other solid's interior is on the left of each segment.
std::int8_t rule_of(const std::array<PointId, 3>& v, const FacetCut& cut) {
  for (const OrientedSegment& s : cut.transversal)
    for (int k = 0; k < 3; ++k) {
      if (v[k] == s.from && v[(k + 1) % 3] == s.to) return std::int8_t(Label::Inside);
      if (v[k] == s.to && v[(k + 1) % 3] == s.from) return std::int8_t(Label::Outside);
    }
  return -1;
}

template <int dropped>
void triangulate(const Intersection& x, const std::array<CutPoint, 3>& corners,
                 const std::vector<CutPoint>& points, const FacetCut& cut, std::uint32_t facet,
                 FacetPieces& out) {
  using Traits = TableTraits<dropped>;
  using Vb = CGAL::Triangulation_vertex_base_2<Traits>;
  using Fbb = CGAL::Triangulation_face_base_with_info_2<std::uint32_t, Traits>;
  using Fb = CGAL::Constrained_triangulation_face_base_2<Traits, Fbb>;
  using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
  // Valid inputs never produce crossing constraints; if they do, CGAL throws instead of silently
  // constructing a point the other mesh would not share.
  using Cdt = CGAL::Constrained_Delaunay_triangulation_2<
      Traits, Tds, CGAL::No_constraint_intersection_requiring_constructions_tag>;
  const PointTable& table = x.points;
  FacetLines lines(table, {corners[0].id, corners[1].id, corners[2].id});
  Cdt cdt{Traits(&table, &lines)};
  std::vector<std::pair<PointId, typename Cdt::Vertex_handle>> handles;
  handles.reserve(points.size());
  // Inserted along the plane's first coordinate, each located from the one before: cut points
  // come in chains along the other surface, and located from an arbitrary face each would walk
  // across the whole chain, through thin triangles of nearly collinear points whose
  // orientations need exact arithmetic (a flat face of long thin facets crossing a coarse
  // facet puts hundreds of them on one nearly straight line). The order is only a heuristic.
  constexpr int u = dropped == 0 ? 1 : 0;
  std::vector<std::pair<double, std::uint32_t>> order;
  order.reserve(points.size());
  for (std::uint32_t i = 0; i < points.size(); ++i)
    order.emplace_back(table.approx(points[i].id).cartesian(u).inf(), i);
  std::sort(order.begin(), order.end());
  typename Cdt::Face_handle hint;
  for (const auto& [key, i] : order) {
    const auto v = cdt.insert(TablePoint{points[i].id, points[i].edges}, hint);
    hint = v->face();
    handles.emplace_back(points[i].id, v);
  }
  std::sort(handles.begin(), handles.end(),
            [](const auto& a, const auto& b) { return a.first < b.first; });
  auto handle = [&](PointId id) {
    return std::lower_bound(handles.begin(), handles.end(), id,
                            [](const auto& h, PointId key) { return h.first < key; })
        ->second;
  };
  for (const Edge& s : cut.segments) cdt.insert_constraint(handle(s.first), handle(s.second));

  const bool flip =
      table.orientation_2(dropped, corners[0].id, corners[1].id, corners[2].id) == CGAL::NEGATIVE;
  std::uint32_t count = 0;
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) f->info() = count++;
  UnionFind local(count);
  out.triangles.reserve(count);
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
    const std::uint32_t i = f->info();
    std::array<PointId, 3> v{f->vertex(0)->point().id, f->vertex(1)->point().id,
                             f->vertex(2)->point().id};
    if (flip) std::swap(v[1], v[2]);
    out.triangles.push_back({v, facet});
    out.rule.push_back(cut.transversal.empty() ? std::int8_t(-1) : rule_of(v, cut));
    for (int k = 0; k < 3; ++k) {
      if (f->is_constrained(k)) continue;
      const auto n = f->neighbor(k);
      if (!cdt.is_infinite(n)) {
        local.join(i, n->info());
        continue;
      }
      const PointId p = f->vertex(Cdt::cw(k))->point().id, q = f->vertex(Cdt::ccw(k))->point().id;
      if (x.special(p) && x.special(q))
        out.open_boundary.emplace_back(edge_key(undirected(p, q)), i);
    }
  }
  out.joined.resize(count);
  for (std::uint32_t i = 0; i < count; ++i) out.joined[i] = local.find(i);
}

// The commonest cut (about a third of the cut facets of two crossing surfaces): one segment from
// the interior of one edge to the interior of another. It leaves a triangle and a convex
// quadrilateral, split along its Delaunay diagonal, which is what the CDT would build. Returns
// false, leaving `out` untouched, for any other cut.
bool cut_by_one_segment(const Intersection& x, const std::array<CutPoint, 3>& corners,
                        const std::vector<CutPoint>& points, const FacetCut& cut, std::uint32_t t,
                        FacetPieces& out) {
  if (points.size() != 5 || cut.segments.size() != 1) return false;
  const CutPoint* ends[2];
  int count = 0;
  for (const CutPoint& p : points)
    if (p.id != corners[0].id && p.id != corners[1].id && p.id != corners[2].id) {
      if (count == 2) return false;
      ends[count++] = &p;
    }
  if (count != 2) return false;
  auto single_edge = [](std::uint8_t edges) {
    return edges == 1 ? 0 : edges == 2 ? 1 : edges == 4 ? 2 : -1;
  };
  const int edge_p = single_edge(ends[0]->edges), edge_q = single_edge(ends[1]->edges);
  if (edge_p < 0 || edge_q < 0 || edge_p == edge_q ||
      cut.segments[0] != undirected(ends[0]->id, ends[1]->id))
    return false;
  // The boundary in the facet's orientation: each corner, then the end on its outgoing edge.
  std::array<PointId, 5> boundary;
  int at_p = 0, at_q = 0, n = 0;
  for (int k = 0; k < 3; ++k) {
    boundary[n++] = corners[k].id;
    if (edge_p == k) at_p = n, boundary[n++] = ends[0]->id;
    if (edge_q == k) at_q = n, boundary[n++] = ends[1]->id;
  }
  // The two chains of the boundary between the segment's ends: three points (the triangle) and
  // four (the quadrilateral), each closed by the segment.
  auto chain = [&](int from, int to, std::array<PointId, 4>& c) {
    int length = 0;
    for (int i = from;; i = (i + 1) % 5) {
      c[length++] = boundary[i];
      if (i == to) return length;
    }
  };
  std::array<PointId, 4> first{}, second{};
  const bool first_is_triangle = chain(at_p, at_q, first) == 3;
  chain(at_q, at_p, second);
  const std::array<PointId, 4>& piece = first_is_triangle ? first : second;
  const std::array<PointId, 4>& other = first_is_triangle ? second : first;
  const PointTable& table = x.points;
  const int dropped = table.dominant_axis(corners[0].id, corners[1].id, corners[2].id);
  const bool flip =
      table.orientation_2(dropped, corners[0].id, corners[1].id, corners[2].id) == CGAL::NEGATIVE;
  const PointId a = other[0], b = other[1], c = other[2], d = other[3];
  const bool diagonal_bd =
      delaunay_diagonal_is_bd(table, dropped, flip ? CGAL::NEGATIVE : CGAL::POSITIVE, a, b, c, d);
  const std::array<std::array<PointId, 3>, 3> triangles = {
      std::array<PointId, 3>{piece[0], piece[1], piece[2]},
      diagonal_bd ? std::array<PointId, 3>{a, b, d} : std::array<PointId, 3>{a, b, c},
      diagonal_bd ? std::array<PointId, 3>{b, c, d} : std::array<PointId, 3>{a, c, d}};
  for (std::uint32_t i = 0; i < 3; ++i) {
    const auto& v = triangles[i];
    out.triangles.push_back({v, t});
    out.joined.push_back(i == 0 ? 0 : 1);
    out.rule.push_back(cut.transversal.empty() ? std::int8_t(-1) : rule_of(v, cut));
    // Its edges on the facet's boundary: consecutive boundary points.
    for (int k = 0; k < 3; ++k) {
      const PointId p = v[k], q = v[(k + 1) % 3];
      const auto at = std::find(boundary.begin(), boundary.end(), p) - boundary.begin();
      if (boundary[(at + 1) % 5] == q && x.special(p) && x.special(q))
        out.open_boundary.emplace_back(edge_key(undirected(p, q)), i);
    }
  }
  return true;
}

void cut_facet(const Mesh& mesh, int side, const Intersection& x, std::uint32_t t,
               FacetPieces& out) {
  const Triangle& f = mesh.triangles[t];
  const std::array<CutPoint, 3> corners = {CutPoint{x.vertex_id(side, f[0]), corner_edges(0)},
                                           CutPoint{x.vertex_id(side, f[1]), corner_edges(1)},
                                           CutPoint{x.vertex_id(side, f[2]), corner_edges(2)}};
  const FacetCut& cut = *x.cut(side, t);
  // Distinct points by id, the known edges of each merged.
  std::vector<CutPoint> points(corners.begin(), corners.end());
  points.insert(points.end(), cut.points.begin(), cut.points.end());
  std::sort(points.begin(), points.end(),
            [](const CutPoint& p, const CutPoint& q) { return p.id < q.id; });
  std::size_t n = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (n > 0 && points[n - 1].id == points[i].id)
      points[n - 1].edges |= points[i].edges;
    else
      points[n++] = points[i];
  }
  points.resize(n);

  if (points.size() == 3) {
    // Touched only at its corners or along its edges (coplanar neighbours, contacts): the facet
    // stays whole.
    const std::array<PointId, 3> v = {corners[0].id, corners[1].id, corners[2].id};
    out.triangles.push_back({v, t});
    out.joined.push_back(0);
    out.rule.push_back(-1);
    for (int k = 0; k < 3; ++k) {
      const Edge e = undirected(v[k], v[(k + 1) % 3]);
      const bool constrained =
          std::find(cut.segments.begin(), cut.segments.end(), e) != cut.segments.end();
      if (!constrained && x.special(e.first) && x.special(e.second))
        out.open_boundary.emplace_back(edge_key(e), 0);
    }
    return;
  }
  if (cut_by_one_segment(x, corners, points, cut, t, out)) return;
  switch (x.points.dominant_axis(corners[0].id, corners[1].id, corners[2].id)) {
    case 0:
      triangulate<0>(x, corners, points, cut, t, out);
      break;
    case 1:
      triangulate<1>(x, corners, points, cut, t, out);
      break;
    default:
      triangulate<2>(x, corners, points, cut, t, out);
  }
}

}  // namespace

Refined retriangulate(const Mesh& mesh, int side, const Intersection& x) {
  // Cut facets are independent: their CDTs run in parallel, each into its own pieces, and are
  // concatenated in facet order so that the result does not depend on the thread count.
  Refined out;
  out.facets.reserve(x.cuts[side].size());
  for (const auto& entry : x.cuts[side]) out.facets.push_back(entry.first);
  std::sort(out.facets.begin(), out.facets.end());
  std::vector<FacetPieces> pieces(out.facets.size());
  for_each_upward(out.facets.size(),
                  [&](std::size_t i) { cut_facet(mesh, side, x, out.facets[i], pieces[i]); });
  std::size_t total = 0;
  for (const FacetPieces& p : pieces) total += p.triangles.size();
  out.triangles.reserve(total);
  out.joined.reserve(total);
  out.rule.reserve(total);
  for (FacetPieces& p : pieces) {
    const auto offset = std::uint32_t(out.triangles.size());
    out.triangles.insert(out.triangles.end(), p.triangles.begin(), p.triangles.end());
    for (std::uint32_t j : p.joined) out.joined.push_back(offset + j);
    out.rule.insert(out.rule.end(), p.rule.begin(), p.rule.end());
    for (const auto& [key, i] : p.open_boundary) out.open_boundary.emplace_back(key, offset + i);
  }
  return out;
}

}  // namespace morphex::detail

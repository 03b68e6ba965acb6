// SPDX-License-Identifier: GPL-3.0-or-later
// Re-triangulating a planar region of the coplanar merge from its boundary: a constrained
// Delaunay triangulation in the coordinate plane its plane projects to without folding, keeping
// the faces inside the boundary. Most regions the merge changes are one triangle or a
// quadrilateral (a cut facet's corner regained, two faces joined across a removed crease point);
// those are filled directly, as the triangulation would, without building one.
#include "boolean/merge_triangulate.h"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <queue>

#include "exact/table_traits.h"

namespace morphex::detail {

namespace {

// The new triangles of a set of faces, from its boundary (edges over surface vertices), or nullopt
// when it must stay as it is.
template <int dropped>
std::optional<std::vector<Triangle>> triangulate_region(
    const PointTable& table, const IdMesh& surface,
    const std::vector<std::pair<VertexIndex, VertexIndex>>& boundary, const Triangle& seed,
    const std::array<PointId, 3>& plane) {
  using Traits = TableTraits<dropped>;
  using Vb = CGAL::Triangulation_vertex_base_with_info_2<VertexIndex, Traits>;
  // Each face's depth: its number of boundary crossings from the unbounded face (-1: not yet).
  using Fbb = CGAL::Triangulation_face_base_with_info_2<int, Traits>;
  using Fb = CGAL::Constrained_triangulation_face_base_2<Traits, Fbb>;
  using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
  using Cdt = CGAL::Constrained_Delaunay_triangulation_2<
      Traits, Tds, CGAL::No_constraint_intersection_requiring_constructions_tag>;
  // Every point lies in the region's plane, an input facet's: their recipes tell many collinear
  // boundary points apart without their exact coordinates (facet_lines.h).
  FacetLines lines(table, plane);
  Cdt cdt{Traits(&table, &lines)};
  auto insert = [&](VertexIndex v) -> std::optional<typename Cdt::Vertex_handle> {
    const std::size_t before = cdt.number_of_vertices();
    auto h = cdt.insert(TablePoint{surface.vertex_point[v], 0});
    if (cdt.number_of_vertices() > before)
      h->info() = v;
    else if (h->info() != v)
      return std::nullopt;  // two vertices at one position: a separated non-manifold feature
    return h;
  };
  try {
    for (const auto& [u, w] : boundary) {
      const auto a = insert(u), b = insert(w);
      if (!a || !b) return std::nullopt;
      cdt.insert_constraint(*a, *b);
    }
  } catch (const std::exception&) {
    return std::nullopt;  // crossing constraints would need new points: keep the faces
  }
  // Inside = odd number of boundary crossings from the unbounded face.
  for (auto f = cdt.all_faces_begin(); f != cdt.all_faces_end(); ++f) f->info() = -1;
  std::queue<typename Cdt::Face_handle> frontier;
  std::vector<typename Cdt::Face_handle> next_level{cdt.infinite_face()};
  for (int level = 0; !next_level.empty(); ++level) {
    std::vector<typename Cdt::Face_handle> crossing;
    for (auto f : next_level)
      if (f->info() < 0) {
        f->info() = level;
        frontier.push(f);
      }
    next_level.clear();
    while (!frontier.empty()) {
      auto f = frontier.front();
      frontier.pop();
      for (int i = 0; i < 3; ++i) {
        auto n = f->neighbor(i);
        if (n->info() >= 0) continue;
        if (f->is_constrained(i))
          crossing.push_back(n);
        else {
          n->info() = level;
          frontier.push(n);
        }
      }
    }
    next_level = std::move(crossing);
  }
  const auto& p = surface.vertex_point;
  const bool flip =
      table.orientation_2(dropped, p[seed[0]], p[seed[1]], p[seed[2]]) == CGAL::NEGATIVE;
  std::vector<Triangle> out;
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
    if (f->info() < 0 || f->info() % 2 == 0) continue;  // unreached faces count as outside
    Triangle t{f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()};
    if (flip) std::swap(t[1], t[2]);
    out.push_back(t);
  }
  return out;
}

// The boundary as one loop of three or four vertices in order, or an empty array.
std::vector<VertexIndex> short_loop(const Boundary& boundary) {
  const std::size_t n = boundary.size();
  if (n < 3 || n > 4) return {};
  std::vector<VertexIndex> loop = {boundary[0].first};
  VertexIndex at = boundary[0].second;
  while (at != loop[0]) {
    if (loop.size() == n || std::find(loop.begin(), loop.end(), at) != loop.end()) return {};
    loop.push_back(at);
    const auto next = std::find_if(boundary.begin(), boundary.end(),
                                   [&](const auto& e) { return e.first == at; });
    if (next == boundary.end()) return {};
    at = next->second;
  }
  if (loop.size() != n) return {};
  return loop;
}

// A loop of three vertices is its triangle: its area is the region's, so it is not degenerate,
// and the boundary runs as the faces do. A loop of four is split along a diagonal that leaves
// two triangles turning as the seed does, the Delaunay one when both do. false (out untouched)
// for any other boundary, or a quadrilateral neither diagonal splits.
bool fill_short_loop(const PointTable& table, const IdMesh& surface, int dropped,
                     const std::array<PointId, 3>& plane, const Boundary& boundary,
                     const Triangle& seed, std::vector<Triangle>& out) {
  const std::vector<VertexIndex> loop = short_loop(boundary);
  if (loop.empty()) return false;
  if (loop.size() == 3) {
    out.push_back({loop[0], loop[1], loop[2]});
    return true;
  }
  const auto& p = surface.vertex_point;
  FacetLines lines(table, plane);
  const CGAL::Sign turn = table.orientation_2(dropped, p[seed[0]], p[seed[1]], p[seed[2]], &lines);
  auto turns = [&](VertexIndex a, VertexIndex b, VertexIndex c) {
    return table.orientation_2(dropped, p[a], p[b], p[c], &lines) == turn;
  };
  const VertexIndex a = loop[0], b = loop[1], c = loop[2], d = loop[3];
  const bool ac = turns(a, b, c) && turns(a, c, d), bd = turns(b, c, d) && turns(b, d, a);
  if (!ac && !bd) return false;
  const bool use_bd =
      !ac || (bd && delaunay_diagonal_is_bd(table, dropped, turn, p[a], p[b], p[c], p[d]));
  if (use_bd) {
    out.push_back({b, c, d});
    out.push_back({b, d, a});
  } else {
    out.push_back({a, b, c});
    out.push_back({a, c, d});
  }
  return true;
}

}  // namespace

std::optional<std::vector<Triangle>> triangulate_in_plane(const PointTable& table,
                                                          const IdMesh& surface,
                                                          const std::array<PointId, 3>& plane,
                                                          const Boundary& boundary,
                                                          const Triangle& seed) {
  const int dropped = table.dominant_axis(plane[0], plane[1], plane[2]);
  std::vector<Triangle> few;
  if (fill_short_loop(table, surface, dropped, plane, boundary, seed, few)) return few;
  switch (dropped) {
    case 0:
      return triangulate_region<0>(table, surface, boundary, seed, plane);
    case 1:
      return triangulate_region<1>(table, surface, boundary, seed, plane);
    default:
      return triangulate_region<2>(table, surface, boundary, seed, plane);
  }
}

}  // namespace morphex::detail

// SPDX-License-Identifier: GPL-3.0-or-later
// Step 5: each cut facet becomes a constrained Delaunay triangulation of its corners and the
// intersection points on it, constrained by its segments. The CDT works in the coordinate plane
// that drops the dominant axis of the facet's normal: an exact projection (it only selects
// coordinates) that keeps the facet non-degenerate.
#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <tbb/parallel_for.h>

#include <algorithm>

#include "boolean_internal.h"
#include "projection_traits.h"

namespace morphex::detail {

namespace {

template <class Traits>
struct FacetCdt {
  using Vb = CGAL::Triangulation_vertex_base_with_info_2<PointId, Traits>;
  using Fb = CGAL::Constrained_triangulation_face_base_2<Traits>;
  using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
  // Valid inputs never produce crossing constraints; if they do, CGAL throws instead of
  // silently constructing a point we did not share with the other mesh.
  using Cdt = CGAL::Constrained_Delaunay_triangulation_2<
      Traits, Tds, CGAL::No_constraint_intersection_requiring_constructions_tag>;

  static void run(const std::array<PointId, 3>& corners, const FacetCut& cut, const Intersection& x,
                  std::uint32_t facet, Refined& out) {
    Cdt cdt;
    auto insert = [&](PointId id) {
      auto v = cdt.insert(x.points[id]);
      v->info() = id;
      return v;
    };
    for (PointId id : corners) insert(id);
    for (PointId id : cut.points) insert(id);
    for (const Edge& s : cut.segments) {
      auto p = insert(s.first), q = insert(s.second);
      cdt.insert_constraint(p, q);
    }
    const auto orient = Traits().orientation_2_object();
    const bool flip =
        orient(x.points[corners[0]], x.points[corners[1]], x.points[corners[2]]) == CGAL::NEGATIVE;
    for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
      std::array<PointId, 3> v{f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()};
      if (flip) std::swap(v[1], v[2]);
      out.triangles.push_back({v, facet});
      for (int i = 0; i < 3; ++i)
        if (f->is_constrained(i)) {
          const PointId p = f->vertex(Cdt::cw(i))->info(), q = f->vertex(Cdt::ccw(i))->info();
          out.on_other_surface.push_back(undirected(p, q));
        }
    }
  }
};

}  // namespace

int dominant_axis(const Point& a, const Point& b, const Point& c) {
  // The largest |normal coordinate|, ties to the lower axis; intervals decide unless two
  // components are (nearly) equal in size, then the exact normal does.
  {
    CGAL::Protect_FPU_rounding<true> rounding;
    const auto &pa = CGAL::approx(a), &pb = CGAL::approx(b), &pc = CGAL::approx(c);
    const auto n = CGAL::cross_product(pb - pa, pc - pa);
    const CGAL::Interval_nt<false> ax = CGAL::abs(n.x()), ay = CGAL::abs(n.y()),
                                   az = CGAL::abs(n.z());
    try {
      if (ax >= ay && ax >= az) return 0;
      return ay >= az ? 1 : 2;
    } catch (const CGAL::Uncertain_conversion_exception&) {
      // two components too close to order with intervals
    }
  }
  const auto &ea = CGAL::exact(a), &eb = CGAL::exact(b), &ec = CGAL::exact(c);
  const auto n = CGAL::cross_product(eb - ea, ec - ea);
  const auto ax = CGAL::abs(n.x()), ay = CGAL::abs(n.y()), az = CGAL::abs(n.z());
  if (ax >= ay && ax >= az) return 0;
  return ay >= az ? 1 : 2;
}

Refined retriangulate(const Mesh& mesh, int side, const Intersection& x) {
  // Cut facets are independent: their CDTs run in parallel, each into its own Refined, and are
  // concatenated in facet order so that the result does not depend on the thread count.
  std::vector<std::uint32_t> cut_facets;
  cut_facets.reserve(x.cuts[side].size());
  for (const auto& entry : x.cuts[side]) cut_facets.push_back(entry.first);
  std::sort(cut_facets.begin(), cut_facets.end());
  std::vector<Refined> pieces(cut_facets.size());
  tbb::parallel_for(std::size_t(0), cut_facets.size(), [&](std::size_t i) {
    const std::uint32_t t = cut_facets[i];
    const Triangle& f = mesh.triangles[t];
    const std::array<PointId, 3> corners{x.vertex_id[side][f[0]], x.vertex_id[side][f[1]],
                                         x.vertex_id[side][f[2]]};
    const FacetCut& cut = x.cuts[side].at(t);
    // Touched only at its corners or along its edges (coplanar neighbours, contacts): the facet
    // stays whole, its touched edges marked on the other surface.
    const bool only_corners = std::all_of(cut.points.begin(), cut.points.end(), [&](PointId p) {
      return p == corners[0] || p == corners[1] || p == corners[2];
    });
    if (only_corners) {
      pieces[i].triangles.push_back({corners, t});
      pieces[i].on_other_surface = cut.segments;
      return;
    }
    switch (dominant_axis(x.points[corners[0]], x.points[corners[1]], x.points[corners[2]])) {
      case 0:
        FacetCdt<FilteredProjectionTraits<0>>::run(corners, cut, x, t, pieces[i]);
        break;
      case 1:
        FacetCdt<FilteredProjectionTraits<1>>::run(corners, cut, x, t, pieces[i]);
        break;
      default:
        FacetCdt<FilteredProjectionTraits<2>>::run(corners, cut, x, t, pieces[i]);
    }
  });

  Refined out;
  out.triangles.reserve(mesh.num_triangles());
  std::size_t next_cut = 0;
  for (std::uint32_t t = 0; t < mesh.num_triangles(); ++t) {
    if (next_cut < cut_facets.size() && cut_facets[next_cut] == t) {
      Refined& piece = pieces[next_cut++];
      out.triangles.insert(out.triangles.end(), piece.triangles.begin(), piece.triangles.end());
      out.on_other_surface.insert(out.on_other_surface.end(), piece.on_other_surface.begin(),
                                  piece.on_other_surface.end());
      continue;
    }
    const Triangle& f = mesh.triangles[t];
    out.triangles.push_back(
        {{x.vertex_id[side][f[0]], x.vertex_id[side][f[1]], x.vertex_id[side][f[2]]}, t});
  }
  return out;
}

}  // namespace morphex::detail

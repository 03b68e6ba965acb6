// SPDX-License-Identifier: GPL-3.0-or-later
#include "peers.h"
#include "morphex/internal/stopwatch.h"

#include "nef.h"  // before minkowski_sum_3.h, which needs the Nef headers first

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/IO/polygon_soup_io.h>
#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/repair_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/minkowski_sum_3.h>

#include <chrono>
#include <exception>

#include "surface_mesh.h"

namespace morphex::peers {
namespace {

namespace PMP = CGAL::Polygon_mesh_processing;

}  // namespace

PeerResult nef_boolean(const Mesh& a, const Mesh& b, BooleanOp op) {
  const Stopwatch start;
  const NefPolyhedron na = to_nef(a), nb = to_nef(b);
  const NefPolyhedron r = op == BooleanOp::Union          ? na + nb
                          : op == BooleanOp::Intersection ? na * nb
                                                          : na - nb;
  const double seconds = start.seconds();
  return {signed_volume(from_nef(r)), seconds};
}

std::optional<PeerResult> corefinement_boolean(const Mesh& a, const Mesh& b, BooleanOp op) {
  SurfaceMesh sa = to_surface_mesh(a), sb = to_surface_mesh(b), out;
  bool ok = false;
  const Stopwatch start;
  try {
    ok = op == BooleanOp::Union          ? PMP::corefine_and_compute_union(sa, sb, out)
         : op == BooleanOp::Intersection ? PMP::corefine_and_compute_intersection(sa, sb, out)
                                         : PMP::corefine_and_compute_difference(sa, sb, out);
  } catch (const std::exception&) {
    ok = false;
  }
  const double seconds = start.seconds();
  if (!ok) return std::nullopt;
  return PeerResult{PMP::volume(out), seconds};
}

PeerResult nef_minkowski_sum(const Mesh& a, const Mesh& b) {
  NefPolyhedron na = to_nef(a), nb = to_nef(b);
  const Stopwatch start;
  const NefPolyhedron sum = CGAL::minkowski_sum_3(na, nb);
  const double seconds = start.seconds();
  return {signed_volume(from_nef(sum)), seconds};
}

bool cgal_does_self_intersect(const Mesh& mesh) {
  return PMP::does_self_intersect(to_surface_mesh(mesh));
}

ForeignRead cgal_read_back(const std::string& path) {
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  ForeignRead out;
  std::vector<K::Point_3> points;
  std::vector<std::vector<std::size_t>> polygons;
  if (!CGAL::IO::read_polygon_soup(path, points, polygons)) return out;
  out.read = true;
  PMP::merge_duplicate_points_in_polygon_soup(points, polygons);
  PMP::orient_polygon_soup(points, polygons);
  CGAL::Surface_mesh<K::Point_3> sm;
  PMP::polygon_soup_to_polygon_mesh(points, polygons, sm);
  out.closed = CGAL::is_closed(sm);
  out.self_intersecting = PMP::does_self_intersect(sm);
  for (auto f : sm.faces()) {
    const auto h = sm.halfedge(f);
    const auto &a = sm.point(sm.source(h)), &b = sm.point(sm.target(h)),
               &c = sm.point(sm.target(sm.next(h)));
    out.volume += CGAL::scalar_product(a - CGAL::ORIGIN,
                                       CGAL::cross_product(b - CGAL::ORIGIN, c - CGAL::ORIGIN)) /
                  6;
  }
  return out;
}

}  // namespace morphex::peers

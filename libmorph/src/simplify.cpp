// SPDX-License-Identifier: GPL-3.0-or-later
// Edge-collapse simplification to a facet budget, retried with a larger budget until the copy is
// a valid solid.
#include "morphex/simplify.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Bounded_normal_change_filter.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Count_stop_predicate.h>
#include <CGAL/Surface_mesh_simplification/edge_collapse.h>

#include <cmath>
#include <stdexcept>

#include "morphex/check.h"
#include "morphex/winding.h"

namespace morphex {
namespace {

using Epick = CGAL::Exact_predicates_inexact_constructions_kernel;
using SurfaceMesh = CGAL::Surface_mesh<Epick::Point_3>;
namespace SMS = CGAL::Surface_mesh_simplification;

SurfaceMesh to_surface_mesh(const DoubleMesh& m) {
  SurfaceMesh sm;
  std::vector<SurfaceMesh::Vertex_index> v;
  v.reserve(m.points.size());
  for (const auto& p : m.points) v.push_back(sm.add_vertex(Epick::Point_3(p[0], p[1], p[2])));
  for (const Triangle& t : m.triangles)
    if (sm.add_face(v[t[0]], v[t[1]], v[t[2]]) == SurfaceMesh::null_face())
      throw std::invalid_argument("simplify: the surface is not an oriented 2-manifold");
  return sm;
}

DoubleMesh to_double_mesh(const SurfaceMesh& sm) {
  DoubleMesh out;
  std::vector<VertexIndex> index(sm.number_of_vertices() + sm.number_of_removed_vertices());
  for (SurfaceMesh::Vertex_index v : sm.vertices()) {
    index[v] = VertexIndex(out.points.size());
    const auto& p = sm.point(v);
    out.points.push_back({p.x(), p.y(), p.z()});
  }
  for (SurfaceMesh::Face_index f : sm.faces()) {
    Triangle t{};
    int k = 0;
    for (SurfaceMesh::Vertex_index v : vertices_around_face(sm.halfedge(f), sm)) t[k++] = index[v];
    out.triangles.push_back(t);
  }
  return out;
}

bool positive_valid_solid(const Mesh& m) {
  return !m.empty() && check_mesh(m, kValidityOnly).valid_solid() &&
         signed_volume_sign(m) == CGAL::POSITIVE;
}

}  // namespace

namespace {

// Every coordinate rounded to a multiple of `grid` (a power of two), or the mesh as it is.
DoubleMesh on_grid(DoubleMesh mesh, double grid) {
  if (grid > 0)
    for (auto& p : mesh.points)
      for (double& c : p) c = std::round(c / grid) * grid;
  return mesh;
}

}  // namespace

Mesh simplified_solid(const DoubleMesh& mesh, std::size_t max_facets, SimplifyReport* report,
                      double grid) {
  SimplifyReport r;
  r.input_facets = mesh.triangles.size();
  Mesh result;
  // A closed triangle mesh has 3/2 edges per facet; the collapse counts edges.
  for (std::size_t budget = std::max<std::size_t>(max_facets, 8); budget < r.input_facets;
       budget *= 2) {
    ++r.attempts;
    SurfaceMesh sm = to_surface_mesh(mesh);
    SMS::Count_stop_predicate<SurfaceMesh> stop(budget * 3 / 2);
    SMS::Bounded_normal_change_filter<> no_flips;
    SMS::edge_collapse(sm, stop, CGAL::parameters::filter(no_flips));
    result = from_double(on_grid(to_double_mesh(sm), grid));
    if (positive_valid_solid(result)) {
      r.simplified = true;
      break;
    }
    // A collapse made far parts of the surface cross or touch: the copy is still closed and
    // oriented, so the region it winds around positively is a valid solid near it.
    Mesh repaired = winding_solid(result);
    if (positive_valid_solid(repaired)) {
      result = std::move(repaired);
      r.simplified = r.repaired = true;
      break;
    }
  }
  if (!r.simplified) {
    result = from_double(on_grid(mesh, grid));
    if (grid > 0 && !positive_valid_solid(result)) result = from_double(mesh);
    if (!positive_valid_solid(result))
      throw std::invalid_argument("simplify: the input is not a valid solid with positive volume");
  }
  r.output_facets = result.triangles.size();
  if (report) *report = r;
  return result;
}

}  // namespace morphex

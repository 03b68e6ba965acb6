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
#include <optional>
#include <stdexcept>
#include <unordered_map>

#include "morphex/check.h"
#include "morphex/winding.h"

namespace morphex {
namespace {

using Epick = CGAL::Exact_predicates_inexact_constructions_kernel;
using SurfaceMesh = CGAL::Surface_mesh<Epick::Point_3>;
namespace SMS = CGAL::Surface_mesh_simplification;

// Inputs with more facets than this (and 16 times the budget) are clustered first.
constexpr std::size_t kClusterAbove = 20000;

SurfaceMesh to_surface_mesh(const DoubleMesh& m) {
  SurfaceMesh sm;
  std::vector<SurfaceMesh::Vertex_index> v;
  v.reserve(m.points.size());
  for (const auto& p : m.points) v.push_back(sm.add_vertex(Epick::Point_3(p[0], p[1], p[2])));
  for (const Triangle& t : m.triangles)
    if (sm.add_face(v[t[0]], v[t[1]], v[t[2]]) == SurfaceMesh::null_face())
      throw InvalidSolid("simplify", "the surface is not an oriented 2-manifold");
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

// Vertex clustering: the vertices in each cell of a grid become one, at their mean, and faces
// that lose a corner vanish. The result is still a closed chain (a face's image under the map of
// its corners), which winding_solid turns into a valid solid; a coarse start for edge collapse on
// inputs many times the budget, in linear time. Empty when the cluster collapses to nothing.
std::optional<DoubleMesh> clustered_solid(const DoubleMesh& mesh, std::size_t target_facets) {
  double area = 0;
  for (const Triangle& t : mesh.triangles) {
    const auto &a = mesh.points[t[0]], &b = mesh.points[t[1]], &c = mesh.points[t[2]];
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]},
                 v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    area += 0.5 * std::sqrt(std::pow(u[1] * v[2] - u[2] * v[1], 2) +
                            std::pow(u[2] * v[0] - u[0] * v[2], 2) +
                            std::pow(u[0] * v[1] - u[1] * v[0], 2));
  }
  // A surface cell of side s holds about s^2 of area; a closed surface has two faces per vertex.
  const double cell = std::sqrt(2 * area / double(target_facets));
  if (!(cell > 0)) return std::nullopt;
  std::unordered_map<std::uint64_t, VertexIndex> index;
  std::vector<std::array<double, 4>> sum;  // x, y, z, count
  std::vector<VertexIndex> of(mesh.points.size());
  for (std::size_t v = 0; v < mesh.points.size(); ++v) {
    std::uint64_t key = 0;
    for (double c : mesh.points[v])
      key =
          (key << 21) | (std::uint64_t(std::int64_t(std::floor(c / cell)) + (1 << 20)) & 0x1fffff);
    const auto [it, added] = index.emplace(key, VertexIndex(sum.size()));
    if (added) sum.push_back({0, 0, 0, 0});
    auto& s = sum[it->second];
    for (int k = 0; k < 3; ++k) s[k] += mesh.points[v][k];
    s[3] += 1;
    of[v] = it->second;
  }
  Mesh chain;
  for (const auto& s : sum) chain.points.emplace_back(s[0] / s[3], s[1] / s[3], s[2] / s[3]);
  for (const Triangle& t : mesh.triangles) {
    const Triangle c = {of[t[0]], of[t[1]], of[t[2]]};
    if (c[0] != c[1] && c[1] != c[2] && c[0] != c[2]) chain.triangles.push_back(c);
  }
  const Mesh solid = winding_solid(chain);
  if (solid.empty()) return std::nullopt;
  return to_double(solid);
}

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
  // Far above the budget, the collapse starts from a clustered copy: edge collapse costs about a
  // microsecond per input facet and grows without bound with the input, clustering does not.
  const DoubleMesh* source = &mesh;
  std::optional<DoubleMesh> coarse;
  if (r.input_facets > kClusterAbove && r.input_facets > 16 * max_facets) {
    coarse = clustered_solid(mesh, 8 * std::max<std::size_t>(max_facets, 8));
    if (coarse) {
      source = &*coarse;
      r.clustered = true;
    }
  }
  // A closed triangle mesh has 3/2 edges per facet; the collapse counts edges.
  for (std::size_t budget = std::max<std::size_t>(max_facets, 8); budget < source->triangles.size();
       budget *= 2) {
    ++r.attempts;
    SurfaceMesh sm = to_surface_mesh(*source);
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
  if (!r.simplified && coarse) {
    result = from_double(on_grid(*coarse, grid));
    r.simplified = positive_valid_solid(result);
  }
  if (!r.simplified) {
    result = from_double(on_grid(mesh, grid));
    if (grid > 0 && !positive_valid_solid(result)) result = from_double(mesh);
    if (!positive_valid_solid(result))
      throw InvalidSolid("simplify", "the input is not a valid solid with positive volume");
  }
  r.output_facets = result.triangles.size();
  if (report) *report = r;
  return result;
}

}  // namespace morphex

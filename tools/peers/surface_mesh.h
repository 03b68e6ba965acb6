// SPDX-License-Identifier: GPL-3.0-or-later
// Copies a morphex Mesh into a CGAL::Surface_mesh with the same exact points, for callers that
// compare with CGAL's own algorithms (tests and benchmarks). Header-only: libbool itself never
// depends on Surface_mesh.
#pragma once

#include <CGAL/Surface_mesh.h>

#include <vector>

#include "morphex/mesh.h"

namespace morphex {

using SurfaceMesh = CGAL::Surface_mesh<Point>;

inline SurfaceMesh to_surface_mesh(const Mesh& mesh) {
  SurfaceMesh out;
  std::vector<SurfaceMesh::Vertex_index> vertices;
  vertices.reserve(mesh.num_vertices());
  for (const Point& p : mesh.points) vertices.push_back(out.add_vertex(p));
  for (const Triangle& t : mesh.triangles)
    out.add_face(vertices[t[0]], vertices[t[1]], vertices[t[2]]);
  return out;
}

}  // namespace morphex

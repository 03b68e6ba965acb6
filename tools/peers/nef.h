// SPDX-License-Identifier: GPL-3.0-or-later
// Conversions to and from CGAL Nef polyhedra, the independent exact method that tests and
// benchmarks compare with. Header-only: the morphex libraries never use Nef polyhedra.
#pragma once

#include <CGAL/Nef_polyhedron_3.h>
#include <CGAL/boost/graph/convert_nef_polyhedron_to_polygon_mesh.h>

#include <map>

#include "surface_mesh.h"

namespace morphex {

using NefPolyhedron = CGAL::Nef_polyhedron_3<Kernel>;

inline NefPolyhedron to_nef(const Mesh& mesh) {
  SurfaceMesh sm = to_surface_mesh(mesh);
  return NefPolyhedron(sm);
}

inline Mesh from_nef(const NefPolyhedron& nef) {
  SurfaceMesh out;
  CGAL::convert_nef_polyhedron_to_polygon_mesh(nef, out, /*triangulate_all_faces=*/true);
  Mesh m;
  std::map<SurfaceMesh::Vertex_index, VertexIndex> index;
  for (auto v : out.vertices()) {
    index[v] = VertexIndex(m.points.size());
    m.points.push_back(out.point(v));
  }
  for (auto f : out.faces()) {
    Triangle t;
    int k = 0;
    for (auto v : CGAL::vertices_around_face(out.halfedge(f), out)) t[k++] = index[v];
    m.triangles.push_back(t);
  }
  return m;
}

}  // namespace morphex

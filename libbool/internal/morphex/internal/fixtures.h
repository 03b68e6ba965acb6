// SPDX-License-Identifier: GPL-3.0-or-later
// Meshes for tests and benchmarks only (not installed): shapes that stress particular cases of the
// check and the Boolean. Defined in libbool (mesh/shapes.cpp) beside the public shapes.
#pragma once

#include <utility>
#include <vector>

#include "morphex/shapes.h"
#include "morphex/solid.h"

namespace morphex {

// A prism over the regular `segments`-gon of `radius` in z = 0, height `height`, whose caps are
// fans from the polygon's first vertex, as CAD exporters triangulate flat faces: long thin facets
// that all meet at one vertex.
Mesh make_fan_prism(int segments, double radius, double height);
// A cone over the same polygon with its apex at height `height` above the centre, the base a fan
// from the polygon's first vertex: long thin facets on the side too, all meeting at the apex.
Mesh make_fan_cone(int segments, double radius, double height);

// `count` thin tetrahedra around the segment from (0,0,0) to (0,0,1), one in each of `count` equal
// wedges: a valid mesh of `count` shells that all share that segment and its ends by position,
// the worst case for a check that relates shells pair by pair.
Mesh make_tetrahedra_on_segment(int count);

// Unit cubes [0,1]^3 and a translated copy touching it along a face, an edge, a vertex.
std::pair<Mesh, Mesh> make_cubes_sharing_face();
std::pair<Mesh, Mesh> make_cubes_sharing_edge();
std::pair<Mesh, Mesh> make_cubes_sharing_vertex();

// Each mesh checked (check_solid), for calls that take many solids (compute_union).
inline std::vector<Solid> solids_of(const std::vector<Mesh>& meshes) {
  std::vector<Solid> solids;
  solids.reserve(meshes.size());
  for (const Mesh& mesh : meshes) solids.push_back(check_solid(mesh));
  return solids;
}

}  // namespace morphex

// SPDX-License-Identifier: GPL-3.0-or-later
// Validity of a mesh as the boundary of a solid, and its exact measures.
#pragma once

#include <CGAL/Bbox_3.h>

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "morphex/mesh.h"

namespace morphex {

struct CheckOptions {
  bool self_intersections = true;  // the only part that is not linear time
  // The exact volume in the report. Without it, `volume` stays 0 and only the signs the
  // orientation test needs are computed, by an interval sum that is exact whenever it decides.
  bool volume = true;
  // Also list every pair of faces that meets improperly (MeshReport::self_intersecting_pairs),
  // for a repair that then needs to intersect only those.
  bool list_self_intersections = false;
};
// Everything valid_solid() needs, without the exact volume.
inline constexpr CheckOptions kValidityOnly{true, false};

struct MeshReport {
  std::size_t vertices = 0, triangles = 0, components = 0;
  std::size_t border_edges = 0, non_manifold_edges = 0, non_manifold_vertices = 0;
  std::size_t degenerate_faces = 0;
  bool consistently_oriented = true;  // every manifold edge is used once in each direction
  bool outward = true;                // each shell's volume sign matches its nesting depth
  std::size_t self_intersections = 0;
  std::optional<std::pair<std::uint32_t, std::uint32_t>> first_self_intersection;
  // Every such pair (i < j, sorted), when CheckOptions::list_self_intersections asks for them.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> self_intersecting_pairs;
  long genus = 0;  // sum over closed shells of (2 - chi) / 2; -1 when not a closed 2-manifold
  CGAL::Bbox_3 bbox;
  FT volume = 0;  // exact signed volume (0 when CheckOptions::volume is off)

  // Where the first problem of each kind is, for error messages.
  std::optional<VertexIndex> first_border_vertex, first_non_manifold_vertex;
  std::optional<std::uint32_t> first_degenerate_face, first_misoriented_face;

  bool closed() const { return border_edges == 0; }
  bool valid_solid() const {
    return closed() && non_manifold_edges == 0 && non_manifold_vertices == 0 &&
           consistently_oriented && outward && degenerate_faces == 0 && self_intersections == 0;
  }
};

MeshReport check_mesh(const Mesh& mesh, const CheckOptions& options = {});

// The first problem in words, e.g. "mesh is not closed: 12 border edges, first at vertex 41";
// empty for a valid solid.
std::string describe_problems(const MeshReport& report);

}  // namespace morphex

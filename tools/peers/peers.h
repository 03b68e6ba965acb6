// SPDX-License-Identifier: GPL-3.0-or-later
// CGAL's own exact methods (Epeck) as independent oracles for the tests and as peers for the
// benchmarks: Nef polyhedra, Polygon_mesh_processing corefinement, minkowski_sum_3 and the
// self-intersection test. They live in one translation unit so that their heavy templates are
// compiled once, and never inside libbool or libmorph.
#pragma once

#include <optional>
#include <string>

#include "morphex/boolean.h"
#include "morphex/mesh.h"

namespace morphex::peers {

struct PeerResult {
  FT volume;       // exact signed volume of the result
  double seconds;  // time of the peer's own operation (see each function for what is included)
};

// Nef polyhedra: a op b. The time includes the conversions to Nef, which Nef cannot do without.
PeerResult nef_boolean(const Mesh& a, const Mesh& b, BooleanOp op);

// corefine_and_compute_union / intersection / difference. The time is that call alone.
// Empty when CGAL refuses (for example when the result would not be 2-manifold).
std::optional<PeerResult> corefinement_boolean(const Mesh& a, const Mesh& b, BooleanOp op);

// minkowski_sum_3 on Nef polyhedra. The time is the sum alone, without the conversions.
PeerResult nef_minkowski_sum(const Mesh& a, const Mesh& b);

// Polygon_mesh_processing::does_self_intersect.
bool cgal_does_self_intersect(const Mesh& mesh);

// A mesh file as another tool sees it: read by CGAL's polygon soup readers (not morphex's),
// duplicate points merged, oriented as a soup (which duplicates the vertices where a solid
// touches itself), made a Surface_mesh over doubles.
struct ForeignRead {
  bool read = false;  // CGAL could read the file
  bool closed = false;
  bool self_intersecting = false;  // does_self_intersect (faces meeting at a copied vertex count)
  double volume = 0;               // signed, from the doubles read
};
ForeignRead cgal_read_back(const std::string& path);

}  // namespace morphex::peers

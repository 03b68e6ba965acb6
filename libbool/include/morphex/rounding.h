// SPDX-License-Identifier: GPL-3.0-or-later
// Rounding an exact mesh to floating-point coordinates so that it stays a valid solid.
//
// Plain formats store doubles (OFF, OBJ, PLY), 32-bit floats (STL, glb) or lib3mf's decimals of
// floats (3MF). Rounding each coordinate to the nearest value of the format moves every vertex by
// at most half a unit in the last place (ulp) of its magnitude, and that alone can break a solid:
// two vertices become one, a thin face flattens to a line, faces a fraction of an ulp apart cross.
// round_mesh resolves what rounding broke, in the spirit of iterative snap rounding (Lazard and
// Valque, "Removing self-intersections in 3D meshes while preserving floating-point
// coordinates"):
//
//   1. round every vertex to the grid;
//   2. check the rounded mesh exactly, only where rounding moved something: faces that lost their
//      area, pairs of faces that now meet improperly, shells that turned over;
//   3. if anything broke, take the rounded mesh as a closed chain (rounding identifies vertices
//      but never opens an edge: the image of a closed chain is closed) and compute exactly the
//      solid it winds around (morphex/winding.h), intersecting only the broken pairs; its new
//      vertices are exact intersection points, so go to 1 with it.
//
// Each round moves the surface by at most one rounding (half an ulp of the coordinates'
// magnitude per coordinate), so the result lies within `rounds` such roundings of the exact
// solid; RoundingReport measures the displacement and the volume change. Features thinner than
// the grid's spacing may collapse; the result is still a valid solid, possibly empty (reported).
// The refusals (LossyOutputError, io.h): a coordinate outside the format's range, and rounds that
// do not settle (below).
#pragma once

#include <cstddef>

#include "morphex/mesh.h"

namespace morphex {

// What a reader of the written file will see for each coordinate.
enum class RoundingGrid {
  Double,   // OFF, OBJ, PLY: the nearest double
  Float,    // STL, glb: the nearest 32-bit float
  ThreeMf,  // 3MF: lib3mf prints floats with six decimals, read back as floats
};

struct RoundingOptions {
  RoundingGrid grid = RoundingGrid::Double;
  // Measure the volume change (exact volumes of the input and of the result: costs a pass of
  // exact arithmetic over both).
  bool measure_volume = false;
  // Rounds of round-check-resolve before giving up (never reached in practice: every round only
  // touches what the previous one created).
  std::size_t max_rounds = 32;
};

struct RoundingReport {
  std::size_t moved_vertices = 0;   // vertices whose exact coordinates were not on the grid
  std::size_t rounds = 0;           // rounds that found something broken and resolved it
  std::size_t broken_pairs = 0;     // improper pairs resolved, over all rounds
  std::size_t flattened_faces = 0;  // faces that rounding left without area, over all rounds
  double max_displacement = 0;  // largest coordinate change of a rounded vertex, summed over rounds
  // Volume change, when measured: rounded minus exact, and relative to the exact volume.
  double volume_change = 0, relative_volume_change = 0;
  bool volume_measured = false;
  bool collapsed = false;  // the rounded solid is empty: the input was thinner than the grid
  // The input was not a valid solid and rounding broke something: rounded as it is, unresolved.
  bool not_a_solid = false;
  // Where the time went, over all rounds: rounding the points, finding what broke, resolving it.
  double seconds_round = 0, seconds_check = 0, seconds_resolve = 0;
  bool changed_topology() const { return rounds > 0; }
};

struct RoundedMesh {
  DoubleMesh mesh;  // a valid solid whose coordinates are all on the grid (floats held as doubles)
  RoundingReport report;
};

// `mesh` is meant to be a valid solid (a morphex result, or a checked input); any other mesh is
// rounded vertex by vertex and reported (RoundingReport::not_a_solid) when that changed it.
// Throws LossyOutputError (io.h) when a coordinate does not fit the grid's range, or when the
// rounds do not settle within options.max_rounds: seen once, on 3MF's coarse grid, where the
// assembly separates a contact along an edge at the edge's midpoint and the midpoint rounds back
// onto an end of the edge.
RoundedMesh round_mesh(const Mesh& mesh, const RoundingOptions& options = {});

// The grid value a coordinate rounds to (nearest double, then nearest float, then lib3mf's
// decimals); may be infinite when out of range.
double round_coordinate(const FT& value, RoundingGrid grid);

}  // namespace morphex

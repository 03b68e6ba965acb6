// SPDX-License-Identifier: GPL-3.0-or-later
// Exact repair: the valid solid bounded by a closed mesh that crosses or touches itself, repeats
// vertices or faces, or has faces without area.
//
// The mesh is read as a chain of oriented triangles (morphex/winding.h): after vertices at one
// position are merged, every edge must be run as often one way as the other (the mesh is closed
// and consistently oriented, possibly with non-manifold edges); what it bounds is then the
// region of positive winding number, which winding_solid computes exactly with the Boolean's
// phases. A surface oriented inward (negative volume) is turned first. Nothing is rounded: the
// result's points are the input's and exact intersections of its edges and faces.
//
// What is refused (InputError, the message names the first culprit, in the merged numbering of
// the input's vertices): an edge used more often one way than the other by faces that all run it
// one way (a face turned against its neighbours: "inconsistent orientation"), or otherwise (a
// border or a hole: "not closed"); a mesh whose winding region is empty; a mesh whose faces meet
// in so many pairs that the exact arrangement would exceed the work budget ("repair would exceed
// its budget", see RepairOptions::budget), before the arrangement is built.
#pragma once

#include <cstddef>

#include "morphex/mesh.h"
#include "morphex/solid.h"

namespace morphex {

struct RepairOptions {
  bool merge_coplanar = true;  // merge neighbouring coplanar result triangles (no new points)
  // The bound on the work of the exact arrangement, relative to the input, so that an untrusted
  // file cannot exhaust the memory (a 149 KB soup of 500 crossing tetrahedra took 10 GB). The
  // work is W = the sum over faces of d^2, d the number of faces a face meets improperly: it
  // bounds the crossings of the cuts inside each face, and time and memory grew with it (300
  // such tetrahedra: W = 2.8e7, 25 s, 1.5 GB). A mesh with W above max(budget x input faces,
  // kRepairMinimumWork) is refused; 0: no bound. Meshes that cross themselves along curves
  // (overlapping shells, folds) have small d and stay far below it.
  double budget = 1000;
};
inline constexpr double kRepairMinimumWork = 1e6;  // small meshes are never refused for work

struct RepairReport {
  std::size_t input_faces = 0, output_faces = 0;
  std::size_t merged_vertices = 0;     // vertices at the position of an earlier vertex
  std::size_t duplicate_faces = 0;     // faces repeated with the same corners and orientation
  std::size_t degenerate_faces = 0;    // faces without area, removed
  std::size_t cancelled_faces = 0;     // faces summed with an equal face (repeated or opposite)
  std::size_t intersecting_pairs = 0;  // pairs of faces that cross or touch, resolved
  std::size_t components_in = 0, components_out = 0;
  bool reversed = false;  // the surface was oriented inward and was turned
  bool changed = false;   // false: the input was already a valid solid and is returned as it is
};

struct RepairResult {
  Solid solid;
  RepairReport report;
};

// Throws InputError (without a file name: the caller prefixes it) for what cannot be repaired or
// would exceed the budget.
RepairResult repair_mesh(const Mesh& mesh, const RepairOptions& options = {});

}  // namespace morphex

// SPDX-License-Identifier: GPL-3.0-or-later
// From the meshes real collections hold (triangle soups, open surfaces, flipped, duplicated and
// degenerate faces, cracks, overlapping parts, inward meshes) to a valid solid.
//
// The method, and why: the exact repair (morphex/repair.h) already takes any closed chain of
// triangles to the solid it winds around, exactly, resolving self-intersections, overlaps,
// duplicates and inward orientation. What real files lack is the closed chain itself: their
// faces are oriented at random, their borders do not meet (a crack of 1e-6, a missing patch) or
// they are soups. So solidify makes a closed chain with CGAL's polygon-soup tools and the
// exact repair does the rest:
//   1. a valid solid is returned as it is;
//   2. a closed chain goes to the exact repair, each of its parts (components once equal
//      positions are one vertex) turned outward first: in a wild mesh a part is material, so a
//      cavity shell of an invalid mesh is filled (a valid mesh keeps its cavities: step 1);
//   3. otherwise: vertices closer than the weld tolerance merged (cracks), repeated and
//      degenerate faces dropped (repair_polygon_soup), faces oriented consistently where the
//      soup allows it, non-manifold vertices split (orient_polygon_soup), borders that coincide
//      stitched (stitch_borders), every remaining hole filled by a triangulation of its border
//      (triangulate_hole, no new points), each closed part turned outward, then the exact repair
//      of the union of the parts (the region of positive winding).
// The generalized winding number on the arrangement's cells (Jacobson et al. 2013) handles large
// holes more gracefully, at the cost of a floating-point threshold and a full arrangement of the
// soup; filling holes by their borders keeps every decision exact and costs the arrangement of
// the broken pairs only. A surface that bounds no volume (one sheet, a polyline) fails with
// InputError "bounds no volume".
#pragma once

#include <cstddef>
#include <string>

#include "morphex/mesh.h"
#include "morphex/repair.h"
#include "morphex/solid.h"

namespace morphex {

struct SolidifyOptions {
  // Vertices closer than this fraction of the bounding-box diagonal are merged before the chain
  // is built (cracks left by exporters); 0 merges only equal positions.
  double weld_tolerance = 1e-5;
  bool fill_holes = true;
  // The exact repair's options, its work budget among them (morphex/repair.h).
  RepairOptions repair;
};

struct SolidifyReport {
  std::string method;  // "unchanged", "repair" (a closed chain) or "soup" (the soup tools first)
  std::size_t input_faces = 0, output_faces = 0;
  std::size_t welded_vertices = 0;     // merged into a vertex within the tolerance
  std::size_t dropped_faces = 0;       // repeated or without area
  std::size_t filled_holes = 0;        // borders closed by a triangulation
  std::size_t turned_parts = 0;        // closed parts oriented inward, turned
  std::size_t intersecting_pairs = 0;  // resolved by the exact repair
  bool changed = false;
};

struct SolidifyResult {
  Solid solid;
  SolidifyReport report;
};

// Throws InputError (without a file name: the caller prefixes it) when no volume is bounded or the
// repair would exceed its work budget.
SolidifyResult solidify(const Mesh& mesh, const SolidifyOptions& options = {});

// One line for people and index records: "unchanged", "repaired: 3 intersecting pairs", "soup:
// welded 12 vertices, filled 2 holes, turned 1 part".
std::string describe(const SolidifyReport& report);

}  // namespace morphex

// SPDX-License-Identifier: GPL-3.0-or-later
// Exact Boolean operations on closed triangle meshes, after Leconte, Barki and Dupont.
//
// Notation shared by every phase (libbool/src/stepN_*.cpp, docs/boolean-design.md):
//   A, B       the two input solids; ta, tb a triangle of A, of B.
//   cut facet  an input triangle that meets the other mesh (any contact).
//   segment    a constraint between two intersection points, lying in both ta and tb.
//   A', B'     A and B with every cut facet replaced by its constrained Delaunay triangulation.
//   patch      sub-triangles of A' (or B') connected without crossing the other surface.
//   label      where a patch lies: inside, outside, on the other surface with the same normal
//              (coplanar-same) or with the opposite one (coplanar-opposite).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "morphex/mesh.h"
#include "morphex/solid.h"

namespace morphex {

enum class BooleanOp { Union, Intersection, Difference };  // Difference is A minus B

// "union", "intersection", "difference"; throws InputError otherwise.
BooleanOp parse_boolean_op(const std::string& name);
const char* to_string(BooleanOp op);

struct BooleanOptions {
  bool provenance = false;  // fill BooleanResult::provenance
  // Merge neighbouring coplanar result triangles and drop the vertices that are not corners
  // (merge_coplanar_faces): no new coordinates, far fewer faces after coplanar overlaps.
  bool merge_coplanar = true;
  // Evaluate every constructed coordinate before returning. Off by default: coordinates are
  // exact either way, and constructed points are CGAL lazy exact values, computed (in lowest
  // terms) when a predicate, a volume or an exact file needs them, as CGAL's own constructions
  // are; make_exact() evaluates a whole mesh later.
  bool exact_output = false;
};

struct PhaseSeconds {
  double pairs = 0, segments = 0, retriangulate = 0, classify = 0, assemble = 0;
};

struct BooleanStats {
  std::size_t candidate_pairs = 0;     // triangle pairs whose boxes overlap
  std::size_t intersecting_pairs = 0;  // pairs that really touch
  std::size_t cut_facets_a = 0, cut_facets_b = 0;
  std::size_t segments = 0;             // constraint segments inserted (both meshes)
  std::size_t intersection_points = 0;  // distinct new points constructed
  std::size_t patches = 0;
  std::size_t patches_by_orientation_rule = 0;  // labelled by the seed's segment orientation
  std::size_t patches_by_ray_cast = 0;          // labelled by an exact point-in-solid test
  std::size_t orientation_conflicts = 0;        // transversal segments of one patch disagreeing (0)
  PhaseSeconds seconds;
};

struct FaceOrigin {
  std::uint8_t mesh;   // 0 for A, 1 for B
  std::uint32_t face;  // triangle index in that input
};

struct BooleanResult {
  Solid solid;  // possibly empty
  BooleanStats stats;
  std::vector<FaceOrigin> provenance;  // one per output triangle when requested
};

// The operands are Solids (morphex/solid.h): checked once where they entered, so the operation
// has nothing to refuse. When check_solid made them, the Boolean reuses the check's box trees.
BooleanResult compute_boolean(const Solid& a, const Solid& b, BooleanOp op,
                              const BooleanOptions& options = {});

// Re-triangulates every maximal region of neighbouring coplanar, equally oriented triangles of a
// valid solid without its removable vertices: those inside a region, and those on a straight crease
// between two regions. Exact (only existing points are used); the solid is unchanged as a set.
// Regions where two distinct vertices share a position (separated non-manifold features) are kept.
Solid merge_coplanar_faces(const Solid& solid);

struct UnionStats {
  std::size_t binary_unions = 0;    // compute_boolean calls made
  std::size_t disjoint_merges = 0;  // unions of operands with disjoint boxes, done by concatenation
};

// The union of many closed solids (they may overlap, touch or nest) as one valid solid.
// The solids are sorted along a space-filling curve and united in a balanced binary tree, so each
// binary union meets neighbouring pieces and intermediate results stay small; independent subtrees
// run in parallel with TBB. The tree depends only on the input, so the result is identical for any
// number of threads. The other way to unite many solids at once is winding_solid on their
// concatenated boundaries (morphex/winding.h): one arrangement of every piece, kept where the
// winding number is >= 1.
Solid compute_union(const std::vector<Solid>& solids, UnionStats* stats = nullptr);

}  // namespace morphex

// SPDX-License-Identifier: GPL-3.0-or-later
// Exact Minkowski sums of closed triangle meshes.
//
// When A and B are both convex, A + B is the convex hull of the vertex sums, computed directly.
// For convex B and any A, A + B = (A + c) u (convex pieces of the reduced convolution): a prism
// f + [c, s] on each facet f (s the vertex of B supporting f's normal), and small hulls at convex
// edges and at vertices where that vertex of B changes (docs/morphology-design.md). For non-convex
// B (connected), with any point b0 of B:
//   A + B = (A + b0)  u  (dA + B),         dA + B = union over facets f of A of (f + B),
// f + B = (f + dB) u (p_f + B) for any point p_f of f, and f + dB = union over facets g of B of
// conv(f + g). A B with several components is summed component by component. One winding
// arrangement of A + c and the convolution's pieces closes them into one valid solid when they
// overlap shallowly (B small beside A's facets), compute_union's tree of binary unions otherwise
// (docs/morphology-design.md, "One arrangement of the pieces").
#pragma once

#include <cstddef>

#include "morphex/mesh.h"
#include "morphex/solid.h"

namespace morphex {

struct MinkowskiStats {
  std::size_t pieces = 0;           // convex pieces (and translated copies) united
  std::size_t piece_triangles = 0;  // their triangles in total
  std::size_t binary_unions = 0;
  std::size_t arrangements = 0;  // pieces closed by one winding arrangement instead of a tree
  double seconds_pieces = 0, seconds_union = 0;
};

// A + B, a valid solid (empty when either is).
Solid minkowski_sum(const Solid& a, const Solid& b, MinkowskiStats* stats = nullptr);

// How the pieces are united: the balanced tree of binary unions (compute_union, the default:
// intermediate unions shed the overlap early) or one winding arrangement of all of them
// (winding_solid on their concatenated boundaries), which bench_morph --nary measures: exact too,
// but slower on these fat, heavily overlapping hulls (every piece/piece pair is intersected at
// once; the convolution's thin pieces, whose shared faces cancel, are another matter).
enum class PieceUnion { BinaryTree, Arrangement };

// dA + B: the union of the sums of every facet of `surface` with the solid b (the "offset shell"
// of the facet-hull formula; dilation and erosion by a non-convex B use it, and the tests check
// the reduced convolution against it). `b_convex` selects the convex-hull route.
Mesh boundary_sum(const Mesh& surface, const Mesh& b, bool b_convex,
                  MinkowskiStats* stats = nullptr, PieceUnion method = PieceUnion::BinaryTree);

}  // namespace morphex

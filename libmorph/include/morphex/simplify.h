// SPDX-License-Identifier: GPL-3.0-or-later
// A coarser valid solid close to a given one, for descriptors whose cost must not grow with the
// facet count of the input.
//
// Inputs of more than 20,000 facets and 16 times the budget are first clustered on a grid (the
// vertices of a cell merged at their mean, which leaves a closed chain that winding_solid makes a
// valid solid), so that the collapse starts from about 8 times the budget. The copy is then made
// by edge collapse (CGAL Surface_mesh_simplification, Lindstrom-Turk cost and
// placement, collapses that would flip a facet normal refused) on double coordinates, then taken
// exactly and checked. A collapse can make far parts of the surface cross: such a copy is
// replaced by the region it winds around positively (winding_solid, exact), and when even that
// is not a valid solid with volume, the copy is made again with twice the budget, up to the input
// itself. The morphology run on the copy is exact; only the copy is an approximation of the input.
#pragma once

#include <cstddef>

#include "morphex/mesh.h"

namespace morphex {

struct SimplifyReport {
  std::size_t input_facets = 0, output_facets = 0;
  std::size_t attempts = 0;  // budgets tried (the first one, then doubled)
  bool simplified = false;   // false: the input came back unchanged (small enough, or no coarser
                             // copy was a valid solid)
  bool repaired = false;     // the collapsed copy crossed itself and was replaced by its
                             // positive-winding region
  bool clustered = false;    // a large input was first clustered on a grid (a closed chain made
                             // a valid solid by winding_solid), then collapsed
};

// A valid solid with at most about `max_facets` facets (never more than the input's) near the
// double-precision surface `mesh`. Precondition: `mesh` is a closed oriented 2-manifold whose
// exact copy is a valid solid; throws InvalidSolid when even that copy is not one.
// With `grid` (a power of two), every coordinate of the copy is rounded to a multiple of it
// before the copy is checked: exact arithmetic on the copy and its translates by radii on the same
// grid then works with short dyadic numbers.
Mesh simplified_solid(const DoubleMesh& mesh, std::size_t max_facets,
                      SimplifyReport* report = nullptr, double grid = 0);

}  // namespace morphex

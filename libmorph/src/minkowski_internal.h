// SPDX-License-Identifier: GPL-3.0-or-later
// Pieces of the Minkowski machinery shared with morphology.cpp.
#pragma once

#include <vector>

#include "morphex/minkowski.h"

namespace morphex::detail {

// The components of a mesh by shared vertices, each with compact vertex indices.
std::vector<Mesh> connected_components(const Mesh& mesh);

// Exact: no face of the convex solid has the origin strictly on its outer side.
bool convex_contains_origin(const Mesh& convex);

// A + B for one connected B whose convexity is known.
Mesh sum_with_component(const Mesh& a, const Mesh& b, bool b_convex, MinkowskiStats* stats);

// Throws std::invalid_argument("<which> is not a valid solid: ...").
void require_valid(const Mesh& mesh, const char* which);

}  // namespace morphex::detail

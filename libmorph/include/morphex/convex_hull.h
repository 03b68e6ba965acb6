// SPDX-License-Identifier: GPL-3.0-or-later
// Convex hulls of exact points as solids, and convexity of a solid: what the structuring elements
// and the Minkowski sums both build on.
#pragma once

#include <vector>

#include "morphex/mesh.h"

namespace morphex {

// The convex hull of a point set as a closed outward triangle mesh (exact; empty when the points
// do not span a solid).
Mesh convex_hull(const std::vector<Point>& points);

// Exact convexity of a valid closed solid: its volume equals its hull's.
bool is_convex(const Mesh& solid);

}  // namespace morphex

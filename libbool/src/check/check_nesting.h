// SPDX-License-Identifier: GPL-3.0-or-later
// The check's orientation test for a mesh of several shells (check_nesting.cpp).
#pragma once

#include <cstdint>
#include <vector>

#include "exact/point_table.h"
#include "morphex/mesh.h"

namespace morphex::detail {

// Whether every shell has the orientation its nesting asks: positive volume when it lies inside
// an even number of the other shells, negative (a cavity) inside an odd number. `component_of`
// numbers the faces' `count` shells; `position[v]` is the least vertex index at v's position.
// Precondition: a closed, consistently oriented mesh without self-intersections or degenerate
// faces, where shells touch only at shared positions.
bool shells_nest_outward(const Mesh& mesh, const std::vector<PointId>& position,
                         const std::vector<std::uint32_t>& component_of, std::size_t count);

}  // namespace morphex::detail

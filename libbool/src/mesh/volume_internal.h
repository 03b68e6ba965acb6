// SPDX-License-Identifier: GPL-3.0-or-later
// The volume's sign for callers that already hold the mesh's coordinates as doubles.
#pragma once

#include <array>
#include <vector>

#include "morphex/mesh.h"

namespace morphex::detail {

// signed_volume_sign(mesh), its first stage reading `doubles` (vertex v's coordinates, each
// within `error` of the exact one, as PointTable::input_near_doubles() gives them; empty when
// unknown) instead of the points: contiguous doubles instead of a pointer per corner, and a
// rational mesh (a rotated input, a Boolean's output) decided without its intervals.
CGAL::Sign signed_volume_sign(const Mesh& mesh, const std::vector<std::array<double, 3>>& doubles,
                              double error);

}  // namespace morphex::detail

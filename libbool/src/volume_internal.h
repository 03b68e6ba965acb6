// SPDX-License-Identifier: GPL-3.0-or-later
// The volume's sign for callers that already hold the mesh's coordinates as doubles.
#pragma once

#include <array>
#include <vector>

#include "morphex/mesh.h"

namespace morphex::detail {

// signed_volume_sign(mesh), its first stage reading `doubles` (vertex v's exact coordinates,
// as PointTable::input_doubles() gives them; empty when some are not doubles) instead of the
// points: contiguous doubles instead of a pointer per corner.
CGAL::Sign signed_volume_sign(const Mesh& mesh, const std::vector<std::array<double, 3>>& doubles);

}  // namespace morphex::detail

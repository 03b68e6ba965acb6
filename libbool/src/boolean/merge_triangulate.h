// SPDX-License-Identifier: GPL-3.0-or-later
// The coplanar merge's re-triangulation of one planar region from its boundary
// (step7_merge_triangulate.cpp).
#pragma once

#include <array>
#include <optional>
#include <utility>
#include <vector>

#include "boolean/boolean_internal.h"
#include "exact/point_table.h"

namespace morphex::detail {

// Directed edges between surface vertices, each oriented as in the face it bounds.
using Boundary = std::vector<std::pair<VertexIndex, VertexIndex>>;

// The triangles filling `boundary`, oriented as `seed` (a face of the region), all in the plane
// of the input facet `plane`; nullopt when the region must stay as it is (two of its vertices at
// one position, or constraints that would cross).
std::optional<std::vector<Triangle>> triangulate_in_plane(const PointTable& table,
                                                          const IdMesh& surface,
                                                          const std::array<PointId, 3>& plane,
                                                          const Boundary& boundary,
                                                          const Triangle& seed);

}  // namespace morphex::detail

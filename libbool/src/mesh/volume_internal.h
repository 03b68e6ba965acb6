// SPDX-License-Identifier: GPL-3.0-or-later
// The volume's sign for callers that already hold the mesh's coordinates as doubles, and the
// exact volume's sum for meshes over many denominators.
#pragma once

#include <gmpxx.h>

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

// signed_volume(mesh) of a closed surface whose every edge is used by two faces, once each way (a
// cycle): the same value, by three products per face instead of nine (volume.cpp). Anything else
// gives a wrong value.
FT signed_volume_of_cycle(const Mesh& mesh);

// Six times the exact signed volume, for meshes whose vertices lie over many different
// denominators (volume_factored.cpp): the sum of rationals without a gcd per addition.
mpq_class factored_volume_times_6(const Mesh& mesh);

}  // namespace morphex::detail

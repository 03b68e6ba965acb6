// SPDX-License-Identifier: GPL-3.0-or-later
// The check's test of segments that several edges share by position (check_edge_fans.cpp).
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "exact/point_table.h"
#include "morphex/mesh.h"

namespace morphex::detail {

// Pairs of faces (i < j) on a segment shared by several edges (ends at positions that several
// vertices share; `position[v]` is the least vertex index at v's position) whose pairs interleave
// around it: each such pair is a crossing, reported as a self-intersection. Empty, after one pass
// over the vertices, when no two vertices share a position.
std::vector<std::pair<std::uint32_t, std::uint32_t>> interleaved_edge_fans(
    const Mesh& mesh, const PointTable& table, const std::vector<PointId>& position);

}  // namespace morphex::detail

// SPDX-License-Identifier: GPL-3.0-or-later
// What rounding an exact valid solid broke (rounding.cpp), looked for only where rounding moved
// something: the rest of the rounded mesh is the exact solid's, valid already.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "morphex/mesh.h"

namespace morphex::detail {

struct RoundingDamage {
  bool broken = false;  // anything at all: the rounded mesh is not a valid solid
  std::size_t flattened_faces = 0;
  std::size_t turned_shells = 0;  // shells whose volume changed sign
  // Pairs of faces of the rounded mesh that meet improperly (i < j), for winding_solid.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
  bool none() const { return !broken; }
};

// `exact` is a valid solid, `rounded` its vertices on a grid (faces unchanged, `moved[v]` set
// where vertex v changed). Exact: predicates on the rounded doubles.
//   - a face with a moved corner that lost its area (corners on one position or one line);
//   - a pair of faces, one with a moved corner, whose boxes overlap and that meet improperly (the
//     check's exact test, by position: coincident vertices are one);
//   - a shell with a moved vertex whose volume changed sign (turned over without crossing).
// Vertices merged by rounding are no damage by themselves: they are the contacts a valid solid
// may have, and the pairs around them are tested.
RoundingDamage find_rounding_damage(const Mesh& exact, const DoubleMesh& rounded,
                                    const std::vector<std::uint8_t>& moved);

}  // namespace morphex::detail

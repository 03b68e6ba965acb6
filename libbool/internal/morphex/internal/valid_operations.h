// SPDX-License-Identifier: GPL-3.0-or-later
// The Boolean and the union tree on meshes the calling library knows to be valid solids (its own
// intermediate results: Minkowski pieces, translated copies), without wrapping each in a Solid.
// Not installed: users pass Solids (morphex/solid.h).
#pragma once

#include <vector>

#include "morphex/boolean.h"

namespace morphex::detail {

struct MeshBoolean {
  Mesh mesh;
  BooleanStats stats;
  std::vector<FaceOrigin> provenance;
};

// compute_boolean's work on two valid solids; `tree_a`/`tree_b` are the check's trees when known.
MeshBoolean boolean_of_valid(const Mesh& a, const Mesh& b, BooleanOp op,
                             const BooleanOptions& options = {},
                             std::shared_ptr<const TriangleTree> tree_a = nullptr,
                             std::shared_ptr<const TriangleTree> tree_b = nullptr);

// compute_union's work on valid solids, taken over.
Mesh union_of_valid(std::vector<Mesh> solids, UnionStats* stats = nullptr);

}  // namespace morphex::detail

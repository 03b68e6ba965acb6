// SPDX-License-Identifier: GPL-3.0-or-later
// The check as the Boolean runs it on its operands: the same report, and the box tree the check
// built over the whole mesh, so that the operation does not build it again.
#pragma once

#include <optional>

#include "morphex/check.h"
#include "tree/box_tree.h"

namespace morphex::detail {

// check_mesh(mesh, options); `tree` gets a tree over every triangle of the mesh, along the
// coordinate axes, built from the check's own (its tree, or its two joined when flat patches were
// proved as a whole), and stays empty when the check boxed along a turned part's axes or left
// degenerate faces out of its trees.
MeshReport check_mesh_keeping_tree(const Mesh& mesh, const CheckOptions& options,
                                   std::optional<TriangleTree>& tree);

// The pairs among `candidates` (face indices, i != j) whose closed triangles meet other than in a
// common vertex or a common edge, "common" by position (as the check decides it), in their order.
// For checks that know where to look (rounding.cpp: only near what rounding moved).
std::vector<std::pair<std::uint32_t, std::uint32_t>> improper_pairs(
    const Mesh& mesh, const std::vector<std::pair<std::uint32_t, std::uint32_t>>& candidates);

}  // namespace morphex::detail

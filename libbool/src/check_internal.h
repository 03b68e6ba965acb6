// SPDX-License-Identifier: GPL-3.0-or-later
// The check as the Boolean runs it on its operands: the same report, and the box tree the check
// built over the whole mesh, so that the operation does not build it again.
#pragma once

#include <optional>

#include "morphex/check.h"
#include "spatial.h"

namespace morphex::detail {

// check_mesh(mesh, options); `tree` gets the check's tree when it covers every triangle of the
// mesh (it does not when flat patches were proved as a whole: their triangles are left out of
// it), and stays empty otherwise.
MeshReport check_mesh_keeping_tree(const Mesh& mesh, const CheckOptions& options,
                                   std::optional<TriangleTree>& tree);

}  // namespace morphex::detail

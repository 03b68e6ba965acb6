// SPDX-License-Identifier: GPL-3.0-or-later
// How the morphex libraries make Solids from meshes they have made valid by construction (the
// results of exact operations), without checking them again. Not installed: outside this tree, a
// Solid comes only from check_solid, repair_mesh or solidify and the operations (morphex/solid.h).
#pragma once

#include <memory>
#include <utility>

#include "morphex/solid.h"

namespace morphex::detail {

struct SolidAccess {
  // `mesh` must be a valid solid: the exact operations' results are, and tests check each of them
  // with check_mesh. Debug builds could check here; release builds trust the caller.
  static Solid trust(Mesh mesh) { return Solid(std::make_shared<const Mesh>(std::move(mesh))); }
  static Solid trust(Mesh mesh, std::shared_ptr<const TriangleTree> tree) {
    return Solid(std::make_shared<const Mesh>(std::move(mesh)), std::move(tree));
  }
  static const std::shared_ptr<const TriangleTree>& tree(const Solid& solid) { return solid.tree_; }
};

// Shorthand for the libraries' own results.
inline Solid trusted_solid(Mesh mesh) {
  return SolidAccess::trust(std::move(mesh));
}

}  // namespace morphex::detail

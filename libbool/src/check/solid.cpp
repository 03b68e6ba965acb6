// SPDX-License-Identifier: GPL-3.0-or-later
// Solids (morphex/solid.h): the check once where a mesh enters, keeping the check's box tree for
// the Boolean; exact motions that keep a solid valid.
#include "morphex/solid.h"

#include <tbb/parallel_invoke.h>

#include <optional>

#include "check/check_internal.h"
#include "morphex/check.h"
#include "morphex/internal/solid_access.h"
#include "morphex/shapes.h"

namespace morphex {

Solid::Solid() : mesh_(std::make_shared<const Mesh>()) {}

namespace {

// The checked mesh as a Solid with the tree the check built, or the check's problem thrown.
Solid solid_or_throw(Mesh&& mesh, const MeshReport& report, std::optional<TriangleTree>&& tree,
                     const std::string& where) {
  if (!report.valid_solid()) throw InvalidSolid(where, describe_problems(report));
  std::shared_ptr<const TriangleTree> shared;
  if (tree) shared = std::make_shared<const TriangleTree>(std::move(*tree));
  return detail::SolidAccess::trust(std::move(mesh), std::move(shared));
}

}  // namespace

Solid check_solid(Mesh mesh, const std::string& where) {
  std::optional<TriangleTree> tree;
  const MeshReport report = detail::check_mesh_keeping_tree(mesh, kValidityOnly, tree);
  return solid_or_throw(std::move(mesh), report, std::move(tree), where);
}

std::pair<Solid, Solid> check_solids(Mesh a, const std::string& where_a, Mesh b,
                                     const std::string& where_b) {
  // Both at once: each check is parallel inside, but its sequential parts (edge records, patch
  // proofs) leave threads idle that the other check can use.
  MeshReport reports[2];
  std::optional<TriangleTree> trees[2];
  tbb::parallel_invoke(
      [&] { reports[0] = detail::check_mesh_keeping_tree(a, kValidityOnly, trees[0]); },
      [&] { reports[1] = detail::check_mesh_keeping_tree(b, kValidityOnly, trees[1]); });
  Solid first = solid_or_throw(std::move(a), reports[0], std::move(trees[0]), where_a);
  Solid second = solid_or_throw(std::move(b), reports[1], std::move(trees[1]), where_b);
  return {std::move(first), std::move(second)};
}

Solid transformed(const Solid& solid, const Kernel::Aff_transformation_3& map) {
  // An exact map with a non-zero determinant is a bijection that keeps a valid solid valid;
  // morphex::transformed turns the faces of a reflection so that the result stays outward.
  const CGAL::Sign sign =
      CGAL::sign(map.m(0, 0) * (map.m(1, 1) * map.m(2, 2) - map.m(1, 2) * map.m(2, 1)) -
                 map.m(0, 1) * (map.m(1, 0) * map.m(2, 2) - map.m(1, 2) * map.m(2, 0)) +
                 map.m(0, 2) * (map.m(1, 0) * map.m(2, 1) - map.m(1, 1) * map.m(2, 0)));
  if (sign == CGAL::ZERO) throw InputError("transformed", "the map is singular (determinant 0)");
  Mesh moved = morphex::transformed(solid.mesh(), map);
  make_exact(moved);  // chains of motions would otherwise grow lazy-evaluation graphs
  return detail::trusted_solid(std::move(moved));
}

}  // namespace morphex

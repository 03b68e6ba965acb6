// SPDX-License-Identifier: GPL-3.0-or-later
// A valid solid as a type: a Mesh that has passed the check (morphex/check.h) or was made by an
// exact operation that only makes valid solids.
//
// Valid means closed, consistently and outward oriented, without degenerate faces and without
// self-intersections; touching is allowed where it is separated into distinct vertices
// (morphex/mesh.h). The operations that need a valid operand (compute_boolean, compute_union, the
// morphology, minkowski_sum, describe) take a Solid, so they never check again and never fail on
// an invalid operand: the check happens once, where a mesh enters, and each result comes out as a
// Solid ready for the next operation.
//
// Where Solids come from:
//   check_solid(mesh, where)        any mesh, checked (InvalidSolid names where and the problem)
//   repair_mesh, solidify           meshes that are not valid solids yet (morphex/repair.h,
//                                   morphex/solidify.h)
//   compute_boolean, compute_union, apply_morphology, minkowski_sum, transformed
//                                   the exact operations, whose results are valid by construction
// A Solid is immutable and cheap to copy (its mesh is shared); mesh() reads it, and a Solid is a
// const Mesh& wherever one is asked for (write_mesh, check_mesh, signed_volume...).
#pragma once

#include <memory>
#include <string>
#include <utility>

#include "morphex/mesh.h"

namespace morphex {

class TriangleTree;  // the check's box tree (libbool's own, not part of the API)
namespace detail {
struct SolidAccess;
}  // namespace detail

class Solid {
 public:
  // The empty solid (no faces): what an erosion that removes everything leaves.
  Solid();

  const Mesh& mesh() const { return *mesh_; }
  operator const Mesh&() const { return *mesh_; }  // NOLINT: a Solid is a mesh to every reader
  std::size_t num_triangles() const { return mesh_->num_triangles(); }
  bool empty() const { return mesh_->empty(); }

 private:
  friend struct detail::SolidAccess;
  explicit Solid(std::shared_ptr<const Mesh> mesh,
                 std::shared_ptr<const TriangleTree> tree = nullptr)
      : mesh_(std::move(mesh)), tree_(std::move(tree)) {}

  std::shared_ptr<const Mesh> mesh_;
  // The box tree the check built over every triangle, when it built one: the Boolean's steps 2
  // and 6 reuse it instead of building it again.
  std::shared_ptr<const TriangleTree> tree_;
};

// `mesh` as a Solid after the validity check; throws InvalidSolid "<where>: <problem>" (the first
// problem in words, as describe_problems says it: "mesh is not closed: 4 border edges, first at
// vertex 2"). `where` names the mesh for the message (a file, an operand), "" for none.
Solid check_solid(Mesh mesh, const std::string& where = "");
// Two meshes checked at once (the checks share the threads), for binary operations; throws for
// the first invalid one, naming it by its `where`.
std::pair<Solid, Solid> check_solids(Mesh a, const std::string& where_a, Mesh b,
                                     const std::string& where_b);

// The solid moved by an exact affine map with a non-zero determinant (rotations, translations,
// scalings, reflections: a reflection's faces are turned so that the result stays outward).
// Throws InputError for a singular map.
Solid transformed(const Solid& solid, const Kernel::Aff_transformation_3& map);

}  // namespace morphex

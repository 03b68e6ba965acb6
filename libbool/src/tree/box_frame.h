// SPDX-License-Identifier: GPL-3.0-or-later
// Axes for the boxes of a mesh's triangles.
//
// Why: a box traversal pairs every two triangles whose boxes overlap. A CAD part turned off the
// coordinate axes (a model placed by a rotation) has long thin facets lying diagonally, whose
// axis-aligned boxes are far larger than the facets: a tessellated cylinder's side strips, turned,
// each get a box around most of the cylinder, and the traversal meets a quadratic number of pairs.
// Boxes along the part's own axes, found from its dominant face normals, are as tight as they
// were before the part was turned. Any linear map keeps the boxes sound: a point common to two
// triangles maps into the boxes of both, so no pair that meets is lost.
#pragma once

#include <CGAL/Bbox_3.h>

#include <array>
#include <vector>

#include "exact/point_table.h"
#include "exact/static_filter.h"
#include "morphex/mesh.h"
#include "tree/box_tree.h"

namespace morphex::detail {

struct BoxFrame {
  bool world = true;          // the coordinate axes themselves (the rows below unused)
  std::array<Xyz, 3> axis{};  // orthonormal rows, in doubles (exact constants of the map)
};

// The coordinate axes, unless the axes of the mesh's dominant face normals make the boxes of its
// triangles clearly smaller (measured on a sample of the faces, from `xyz`, the points in doubles:
// a heuristic, which decides the speed of a traversal and never its result). World axes when
// `xyz` is empty.
BoxFrame choose_box_frame(const Mesh& mesh, const std::vector<Xyz>& xyz);
// The same for boxing two meshes together (the Boolean's pairs): the axes of either, whichever
// shrinks the boxes of both the most. xyz_a and xyz_b point at the doubles of each mesh's first
// vertex (null: world axes).
BoxFrame choose_box_frame(const Mesh& a, const Xyz* xyz_a, const Mesh& b, const Xyz* xyz_b);

// An interval point, or the box of an interval point or of a box, in the frame's coordinates: it
// holds the image of every point the argument holds. The caller rounds upward (UpwardRounding).
ApproxPoint point_in_frame(const BoxFrame& frame, const ApproxPoint& p);
FloatBox box_in_frame(const BoxFrame& frame, const ApproxPoint& p);
FloatBox box_in_frame(const BoxFrame& frame, const CGAL::Bbox_3& box);
// The boxes of the points first .. first + count - 1 of `table` along `frame`, in parallel.
std::vector<FloatBox> boxes_in_frame(const BoxFrame& frame, const PointTable& table, PointId first,
                                     std::size_t count);

}  // namespace morphex::detail

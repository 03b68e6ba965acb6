// SPDX-License-Identifier: GPL-3.0-or-later
// Step 1 of the Boolean (docs/boolean-design.md): the input as triangles. A Mesh holds triangles
// only, so step 1 runs where polygons enter, in the readers (mesh/io_*.cpp), once per file,
// rather than at the start of every Boolean.
#pragma once

#include <vector>

#include "morphex/mesh.h"

namespace morphex {

// Triangulates a simple polygon (possibly non-convex, approximately planar) given by vertex
// indices, by ear clipping in the plane of its exact Newell normal. Throws InputError (without a
// location: the reader adds the file and face) when the polygon is degenerate or cannot be
// triangulated.
void triangulate_polygon(const std::vector<Point>& points, const std::vector<VertexIndex>& polygon,
                         std::vector<Triangle>& out);

}  // namespace morphex

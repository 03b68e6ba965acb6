// SPDX-License-Identifier: GPL-3.0-or-later
// Soups welded by position (STL) join what a valid solid keeps apart: where a solid touches
// itself along an edge (four faces on it) or at a vertex (two fans), welding makes one edge or
// one vertex of them, and the mesh reads as non-manifold. separate_touching undoes that as the
// Boolean's assembly does: the faces around an edge used k times each way (k >= 2) are paired
// by the solid wedges between them (exact radial order), and each vertex gets one copy per fan of
// its corners. Edges used unevenly (borders, faces turned the wrong way) are left as they are,
// for the check to report.
#pragma once

#include "morphex/mesh.h"

namespace morphex::detail {

// Returns the number of vertices added (0: nothing was touching).
std::size_t separate_touching(Mesh& mesh);

}  // namespace morphex::detail

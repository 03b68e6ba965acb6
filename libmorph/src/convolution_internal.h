// SPDX-License-Identifier: GPL-3.0-or-later
// The solids the reduced convolution is made of (convolution.cpp chooses them; these build them).
//
// Many small pieces cost far more to unite than a few large ones: two prisms of neighbouring
// facets with the same supporting vertex of B share a wall exactly, and each such contact is a
// coplanar case for the Boolean. So pieces that meet only along shared faces are glued here into
// one solid before the union: a patch of facets with one supporting vertex becomes one sweep, a
// chain of convex edges with the same two supporting vertices becomes one swept triangle. Gluing
// only removes faces shared by two pieces with opposite orientations, so the glued surface's
// winding number is the number of pieces covering a point; where it can exceed one, the glued
// solid is checked and split when it is not valid.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "minkowski_internal.h"

namespace morphex::detail {

// p + q, exactly, as an evaluated leaf.
Point sum_point(const Point& p, const Point& q);

// f + [c, s] for a facet f = (p0, p1, p2) with ids (u0, u1, u2) and n_f . (s - c) > 0: f + c
// reversed, f + s, and one parallelogram per edge split along the diagonal from the smaller id's
// copy at c, so that two prisms sharing a side split it alike.
Mesh prism(const std::array<Point, 3>& p, const Triangle& ids, const Point& s, const Point& c);
// The tetrahedron of four points, outward; empty when they are coplanar.
Mesh tetrahedron(const std::array<Point, 4>& q);

// The facets of `surface` that get a prism (support[f] a single vertex of B, not whole[f]) in
// patches connected through edges whose two facets have the same supporting vertex.
std::vector<std::vector<std::uint32_t>> same_support_patches(
    const Mesh& surface, const DirectedEdges& edges,
    const std::vector<std::vector<VertexIndex>>& support, const std::vector<std::uint8_t>& whole);
// The prisms f + [c, s] of one patch as few valid solids, appended to `out`: the patch's sweep
// when it is a valid solid, else the sweeps of its halves, down to single prisms. Without
// `solids`, the sweep as it is (not checked): its chain is the sum of its prisms' boundaries all
// the same, which is all a winding arrangement of the pieces needs.
void patch_pieces(const Mesh& surface, const DirectedEdges& edges, std::vector<std::uint32_t> patch,
                  const Point& s, const Point& c, bool solids, std::vector<Mesh>& out);

// A convex edge u-v of the surface whose piece is e + T, T = (c, B[s0], B[s1]) with s0 < s1.
struct TriangleEdge {
  VertexIndex u, v, s0, s1;
};
// The pieces e + T of these edges, appended to `out`: edges with the same T are chained where one
// ends and the next starts, each chain monotone along T's normal, and a chain is the triangle T
// swept along it (its prisms lie in disjoint slabs, so the sweep is always a valid solid). An edge
// parallel to T's plane has a flat sum and no piece.
void triangle_edge_pieces(const Mesh& surface, const std::vector<TriangleEdge>& edges,
                          const std::vector<Point>& b, const Point& c, std::vector<Mesh>& out);

// Splits every quadrilateral face that two pieces may share alike in both, so that the two copies
// cancel exactly when the pieces' boundaries are summed into one chain (minkowski.cpp's
// arrangement route): a wall e + [c, s] is a prism's side in one piece and an edge piece's face in
// another, each built (or found by a hull) with its own diagonal. A pair of coplanar triangles of
// one piece that make a strictly convex parallelogram is split along the diagonal through its
// lexicographically smallest corner, unless all four corners lie on A + c: those are facets of
// A moved (prism bottoms), which must keep A's own triangulation to cancel against A + c.
void split_shared_quads_alike(std::vector<Mesh>& pieces, const Mesh& surface, const Point& c);

}  // namespace morphex::detail

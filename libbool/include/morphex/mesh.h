// SPDX-License-Identifier: GPL-3.0-or-later
// The exact mesh model every morphex library shares.
//
// A Mesh is an indexed triangle mesh whose vertex coordinates are exact (CGAL::Epeck: lazy exact
// rationals). Nothing in morphex ever rounds a coordinate of a Mesh; rounding happens only when a
// caller explicitly asks for a DoubleMesh or writes a plain (non-exact) file format.
//
// Two vertices may have the same coordinates: that is how a closed 2-manifold represents a solid
// whose boundary touches itself along an edge or at a vertex (the non-manifold feature is
// separated into distinct vertices).
#pragma once

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>

#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "morphex/error.h"

namespace morphex {

using Kernel = CGAL::Epeck;
using FT = Kernel::FT;
using Point = Kernel::Point_3;
using VertexIndex = std::uint32_t;
using Triangle = std::array<VertexIndex, 3>;  // counter-clockwise seen from outside

struct Mesh {
  std::vector<Point> points;
  std::vector<Triangle> triangles;

  std::size_t num_vertices() const { return points.size(); }
  std::size_t num_triangles() const { return triangles.size(); }
  bool empty() const { return triangles.empty(); }
};

// A mesh with double coordinates, for interchange with floating-point code and plain file formats.
struct DoubleMesh {
  std::vector<std::array<double, 3>> points;
  std::vector<Triangle> triangles;
};

// Every coordinate as a double by CGAL::to_double: exact when it is one; otherwise the midpoint of
// CGAL's interval, which CGAL refines exactly only when it is wider than its relative precision of
// to_double (1e-5 by default), so lazy constructions are rarely evaluated. It is therefore not
// always the nearest double (1/3 may give 0.33333333333333337); the Python module's
// Mesh.vertices rounds to nearest through MPFR where that matters.
DoubleMesh to_double(const Mesh& mesh);
// Exact: every double is a dyadic rational, so the conversion loses nothing.
Mesh from_double(const DoubleMesh& mesh);

// True when the three coordinates are known to be doubles without evaluating anything exactly
// (the point's interval approximation has zero width), as for every point read from a file.
bool has_double_coordinates(const Point& p);

// The point whose coordinates are the given exact values, stored as an evaluated leaf: no
// construction history, tight interval approximations.
Point point_from_exact(Kernel::Exact_kernel::Point_3 exact);

// Replaces each coordinate's construction history by its exact value, so that chains of
// operations do not keep growing lazy-evaluation graphs.
void make_exact(Mesh& mesh);

// An exact rational number in lowest terms, "num/den" or "num" when the denominator is 1.
std::string to_rational_string(const FT& value);
// Parses "num/den", "num" or a decimal/scientific literal (read as the nearest double).
// Throws InputError on malformed text.
FT parse_exact_number(std::string_view text);

// Exact signed volume of a closed mesh (positive when outward oriented), summed pairwise so the
// rational sizes stay balanced.
FT signed_volume(const Mesh& mesh);
// Its sign, exact: an interval sum decides unless the volume is (nearly) zero, then the exact sum.
CGAL::Sign signed_volume_sign(const Mesh& mesh);

}  // namespace morphex

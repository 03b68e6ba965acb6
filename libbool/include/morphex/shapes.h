// SPDX-License-Identifier: GPL-3.0-or-later
// Exact, closed, outward-oriented shapes made in code (boxes, platonic solids, spheres, tori,
// cylinders) and exact rigid motions of meshes. The structuring elements are built from them.
#pragma once

#include "morphex/mesh.h"

namespace morphex {

using Vector = Kernel::Vector_3;
using Transformation = CGAL::Aff_transformation_3<Kernel>;

Mesh make_box(const Point& min, const Point& max);
Mesh make_cube(const FT& half_side, const Point& centre = CGAL::ORIGIN);
Mesh make_tetrahedron();                 // (0,0,0), (1,0,0), (0,1,0), (0,0,1): volume 1/6
Mesh make_octahedron(const FT& radius);  // vertices at +-radius on the axes: volume 4 r^3 / 3
// Icosahedron with vertices (0, +-1, +-g) and cyclic permutations, g = 1618/1000 (a rational
// stand-in for the golden ratio, so the coordinates are exact and the volume is rational).
Mesh make_icosahedron();
// The icosahedron subdivided `level` times, every vertex pushed to the sphere of `radius` in
// double precision then taken exactly: a valid solid with double coordinates.
Mesh make_icosphere(int level, const FT& radius);
Mesh make_torus(int major_segments, int minor_segments, double major_radius, double minor_radius);
Mesh make_cylinder(int segments, double radius, double half_height);

Mesh concatenate(const Mesh& a, const Mesh& b);  // disjoint union of the vertex and face lists
// The rotation of the quaternion (a, b, c, d), not necessarily unit: R(q) / |q|^2 is exactly
// orthogonal in rational arithmetic, so rational quaternions give exact rotations.
Transformation quaternion_rotation(const FT& a, const FT& b, const FT& c, const FT& d);
// The rotation about coordinate axis `axis` (0, 1, 2: x, y, z; counter-clockwise seen from the
// axis' positive end) whose angle has cosine c and sine s; orthogonal when c^2 + s^2 = 1.
Transformation axis_rotation(int axis, const FT& c, const FT& s);
// The same by the angle whose half-angle tangent is t: c = (1 - t^2) / (1 + t^2),
// s = 2t / (1 + t^2), so a rational t gives an exactly orthogonal rotation.
Transformation half_tangent_rotation(int axis, const FT& t);
Mesh transformed(const Mesh& mesh, const Transformation& transformation);  // exact
Mesh translated(const Mesh& mesh, const Vector& offset);                   // exact
Mesh reversed(const Mesh& mesh);                                           // every face flipped

}  // namespace morphex

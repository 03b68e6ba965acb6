// SPDX-License-Identifier: GPL-3.0-or-later
// The input points of a table on one integer grid: every coordinate an integer over one common
// denominator L, for the exact stage of predicates on rational inputs.
//
// Why: a mesh under an exact rotation (a part placed by a rational motion, the second operand of
// most Boolean pairs) has rational coordinates, and exactly coplanar facets of a CAD part then
// reach the exact stage by the thousand. There each point's homogeneous coordinates (mpz, W the
// lcm of its own denominators) went into a 4x4 determinant of numbers near 400 bits. Yet such a
// mesh's denominators are few divisors of the rotation's denominator times powers of two (a
// rotated cheese: 75 distinct, lcm 95 bits), so over their lcm every coordinate is an integer of
// about 100 bits, and an orientation is a 3x3 determinant of differences of two-limb integers,
// without conversions or allocations.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "exact/fixed_integer.h"
#include "exact/wide_integer.h"
#include "morphex/mesh.h"

namespace morphex::detail {

class InputGrid {
 public:
  // Grid coordinates below 2^kBits in magnitude, so that in two's complement their differences
  // fit two limbs, 2x2 minors of differences four and 3x3 determinants six (wide_integer.h).
  static constexpr int kBits = 125;
  using Coordinate = WideInt<2>;
  using GridPoint = std::array<Coordinate, 3>;

  // An input: its point, and its coordinates when the caller knows them to be doubles (null
  // otherwise).
  struct Input {
    const Point* point;
    const std::array<double, 3>* doubles;
  };
  // The grid of `inputs` (each a double point, or a rational point that is not the lazy
  // construction of an earlier operation, which `constructed` tells), or null when the common
  // denominator passes kMaxDenominatorBits, a coordinate passes kBits bits on it, or a point is
  // constructed. Sequential (it may run under a lock held by a parallel task).
  static std::unique_ptr<InputGrid> build(const std::vector<Input>& inputs,
                                          bool (*constructed)(const Point&));

  const GridPoint& operator[](std::size_t i) const { return points_[i]; }

  // CGAL's orientation of p, q, r, s: the sign of det(q - p, r - p, s - p).
  static int orientation(const GridPoint& p, const GridPoint& q, const GridPoint& r,
                         const GridPoint& s);
  // CGAL's orientation of the points projected on coordinates u and v.
  static int orientation_2(int u, int v, const GridPoint& p, const GridPoint& q,
                           const GridPoint& r);
  // The sign of p[axis] - q[axis].
  static int compare(int axis, const GridPoint& p, const GridPoint& q);

  // orientation(a, b, c, s) for many s: the normal (b - a) x (c - a) computed once.
  class Plane {
   public:
    Plane(const GridPoint& a, const GridPoint& b, const GridPoint& c);
    int side(const GridPoint& s) const;

   private:
    const GridPoint* a_;
    std::array<WideInt<4>, 3> normal_;
  };

  static constexpr std::size_t kMaxDenominatorBits = kBits - 1;

 private:
  std::vector<GridPoint> points_;
};

}  // namespace morphex::detail

// SPDX-License-Identifier: GPL-3.0-or-later
// Small pieces of geometry the benchmarks share: the exact power-of-two scale that brings a mesh
// to a common size, and the rational rotation that makes coordinates non-doubles. The command
// line, the medians of timed runs and the JSON output are in bench_harness.h.
#pragma once

#include <cmath>

#include "bench_harness.h"
#include "morphex/mesh.h"
#include "morphex/shapes.h"

namespace morphex::bench {

// Exact rotation about z then x by the rational angle whose half-tangent is near tan(deg/2).
inline Transformation rational_rotation(double degrees) {
  const FT t = FT(std::round(std::tan(degrees * 3.14159265358979 / 360) * 1000)) / 1000;
  return half_tangent_rotation(0, t) * half_tangent_rotation(2, t);
}

// The power of two that brings the mesh's bounding-box diagonal into [1, 2): a scaling by it is
// exact and keeps double coordinates doubles.
inline double unit_diagonal_scale(const Mesh& m) {
  CGAL::Bbox_3 box;
  for (const Point& p : m.points) box += p.bbox();
  const double diagonal =
      std::sqrt(std::pow(box.xmax() - box.xmin(), 2) + std::pow(box.ymax() - box.ymin(), 2) +
                std::pow(box.zmax() - box.zmin(), 2));
  int exponent = 0;
  std::frexp(diagonal, &exponent);  // diagonal = f 2^exponent, f in [1/2, 1)
  return std::ldexp(1.0, 1 - exponent);
}

}  // namespace morphex::bench

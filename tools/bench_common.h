// SPDX-License-Identifier: GPL-3.0-or-later
// Small pieces the benchmarks share: a median of timed runs, the exact power-of-two scale that
// brings a mesh to a common size, and the rational rotation that makes coordinates non-doubles.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "morphex/shapes.h"
#include "morphex/mesh.h"
#include "morphex/internal/stopwatch.h"

namespace morphex::bench {

// The median time of `runs` runs of body, after one untimed warm-up run.
template <class Body>
double median_of_runs(int runs, Body&& body) {
  body();
  std::vector<double> times;
  for (int i = 0; i < runs; ++i) {
    const Stopwatch start;
    body();
    times.push_back(start.seconds());
  }
  std::sort(times.begin(), times.end());
  return times[times.size() / 2];
}

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

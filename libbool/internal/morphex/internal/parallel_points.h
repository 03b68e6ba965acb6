// SPDX-License-Identifier: GPL-3.0-or-later
// Exact points made in parallel.
//
// A default-constructed Epeck point shares one representation per thread. Filling a vector of
// default points from several threads therefore releases that one representation from every
// thread, an atomic on one cache line per point, and the fill stops scaling (the result of a
// Boolean took as long on two threads as on one). parallel_points makes each block of points in
// its own vector and moves them into place: moving a point touches no reference count.
#pragma once

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstddef>
#include <vector>

#include "morphex/mesh.h"

namespace morphex {

// The points make(0), ..., make(n - 1), made in parallel.
template <class Make>
std::vector<Point> parallel_points(std::size_t n, Make&& make) {
  constexpr std::size_t kBlock = 4096;
  std::vector<std::vector<Point>> blocks((n + kBlock - 1) / kBlock);
  tbb::parallel_for(std::size_t(0), blocks.size(), [&](std::size_t b) {
    const std::size_t end = std::min(n, (b + 1) * kBlock);
    blocks[b].reserve(end - b * kBlock);
    for (std::size_t i = b * kBlock; i < end; ++i) blocks[b].push_back(make(i));
  });
  std::vector<Point> points;
  points.reserve(n);
  for (std::vector<Point>& block : blocks)
    for (Point& p : block) points.push_back(std::move(p));
  return points;
}

}  // namespace morphex

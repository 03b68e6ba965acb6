// SPDX-License-Identifier: GPL-3.0-or-later
// Exact identity of points: equal exact coordinates, one id.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <unordered_map>
#include <vector>

#include "morphex/mesh.h"

namespace morphex::detail {

// Maps exact positions to ids 0, 1, 2, ... in order of first insertion and keeps the points.
// Points whose coordinates are doubles (every input vertex, and constructions that land on
// doubles) are found by hashing their coordinates; the others, whose exact value is not three
// doubles, by an exact lexicographic search among themselves. The two sets cannot hold the same
// position, so the identity is exact at hash-table cost for the common case.
class PointIndex {
 public:
  explicit PointIndex(std::vector<Point>& points);
  // Every point already in `points` is indexed (duplicates keep the first id).
  std::uint32_t id(const Point& p);

 private:
  struct Hash {
    std::size_t operator()(const std::array<double, 3>& c) const;
  };
  struct LessXYZ {
    bool operator()(const Point& p, const Point& q) const {
      return CGAL::compare_xyz(p, q) == CGAL::SMALLER;
    }
  };

  std::vector<Point>& points_;
  std::unordered_map<std::array<double, 3>, std::uint32_t, Hash> doubles_;
  std::map<Point, std::uint32_t, LessXYZ> others_;
};

}  // namespace morphex::detail

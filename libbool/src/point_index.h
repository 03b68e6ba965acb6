// SPDX-License-Identifier: GPL-3.0-or-later
// Exact identity of points: equal exact coordinates, one id.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "flat_map.h"
#include "morphex/mesh.h"

namespace morphex::detail {

// Maps exact positions to ids 0, 1, 2, ... in order of first insertion and keeps the points.
// Points whose coordinates are doubles (every point read from a file, and constructions that land
// on doubles) are found by hashing those doubles without any exact evaluation; the others by
// hashing their exact rational coordinates (canonical, so equal values hash alike) and comparing
// exactly on a hash match. A position is in exactly one of the two tables, so the identity is
// exact at hash-table cost.
class PointIndex {
 public:
  // `points` starts empty and receives each new position, in the order of the ids.
  explicit PointIndex(std::vector<Point>& points);
  std::uint32_t id(const Point& p);
  void reserve(std::size_t points) { doubles_.reserve(points); }

 private:
  struct Hash {
    std::size_t operator()(const std::array<double, 3>& c) const;
  };
  std::uint32_t rational_id(const Point& p);

  std::vector<Point>& points_;
  FlatMap<std::array<double, 3>, std::uint32_t, Hash> doubles_;
  // Open addressing over point ids for the rational points; kEmpty marks a free slot.
  static constexpr std::uint32_t kEmpty = 0xffffffffu;
  std::vector<std::uint32_t> rational_slots_;
  std::vector<std::uint64_t> rational_hash_;  // hash of each point in the rational table, by slot
  std::size_t rational_count_ = 0;
};

}  // namespace morphex::detail

// SPDX-License-Identifier: GPL-3.0-or-later
// Exact identity of points: equal exact coordinates, one id.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "flat_map.h"
#include "morphex/mesh.h"

namespace morphex::detail {

// Maps exact positions to ids chosen by the caller. Points whose coordinates are doubles (every
// point read from a file, and constructions that land on doubles) are found by hashing those
// doubles, without any exact evaluation when the interval approximation already says so; the
// others by hashing their exact rational coordinates (canonical, so equal values hash alike) and
// comparing exactly on a hash match. A position is in exactly one of the two tables, so the
// identity is exact at hash-table cost.
class PositionIndex {
 public:
  // The id stored for p's position; `id` is stored when the position is new.
  std::uint32_t find_or_insert(const Point& p, std::uint32_t id);
  void reserve(std::size_t points) { doubles_.reserve(points); }

 private:
  struct Hash {
    std::size_t operator()(const std::array<double, 3>& c) const;
  };
  std::uint32_t rational_find_or_insert(const Point& p, std::uint32_t id);

  FlatMap<std::array<double, 3>, std::uint32_t, Hash> doubles_;
  // Open addressing over entries of the rational table; kEmpty marks a free slot.
  struct Entry {
    Point point;
    std::uint32_t id;
  };
  static constexpr std::uint32_t kEmpty = 0xffffffffu;
  std::vector<Entry> rational_entries_;
  std::vector<std::uint32_t> rational_slots_;  // entry index
  std::vector<std::uint64_t> rational_hash_;   // hash of the entry in each slot
};

// Ids 0, 1, 2, ... in order of first insertion, with the points kept in that order.
class PointIndex {
 public:
  // `points` starts empty and receives each new position, in the order of the ids.
  explicit PointIndex(std::vector<Point>& points);
  std::uint32_t id(const Point& p) {
    const std::uint32_t found = index_.find_or_insert(p, std::uint32_t(points_.size()));
    if (found == points_.size()) points_.push_back(p);
    return found;
  }
  void reserve(std::size_t points) { index_.reserve(points); }

 private:
  std::vector<Point>& points_;
  PositionIndex index_;
};

}  // namespace morphex::detail

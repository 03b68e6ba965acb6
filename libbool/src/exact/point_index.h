// SPDX-License-Identifier: GPL-3.0-or-later
// Exact identity of points: equal exact coordinates, one id.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "containers/flat_map.h"
#include "morphex/mesh.h"

namespace morphex::detail {

// Maps exact positions to ids chosen by the caller, at hash-table cost.
//
// The hash key of a point is canonical without exact arithmetic in nearly every case: each
// coordinate truncated toward zero to 40 significant bits. Truncation is monotone, so when both
// ends of a coordinate's interval approximation truncate alike, so does the exact value between
// them (a double's interval is the double itself); only a coordinate within 2^-40 of a cut needs
// its exact value, truncated by GMP to a double and then to 40 bits, which is the same function.
// Equal points therefore share a key, and points with one key are told apart exactly: by their
// doubles when both are doubles, else by exact comparison.
class PositionIndex {
 public:
  // The id stored for p's position; `id` is stored when the position is new.
  std::uint32_t find_or_insert(const Point& p, std::uint32_t id);
  // The same for the point whose coordinates are exactly these doubles, without reading a Point
  // (a mesh whose coordinates are all doubles, from a contiguous copy of them).
  std::uint32_t find_or_insert(const std::array<double, 3>& xyz, std::uint32_t id);
  void reserve(std::size_t points);

 private:
  using Key = std::array<double, 3>;
  struct Entry {
    Key key;
    Key xyz;  // the coordinates, when they are doubles
    std::uint32_t id;
    std::uint32_t rational;  // index in rationals_, or kDoubles
  };
  static constexpr std::uint32_t kEmpty = 0xffffffffu, kDoubles = 0xffffffffu;
  bool same(const Entry& e, const Point& p, bool doubles, const Key& xyz) const;
  // Finds the entry of key `key` that `is(entry)` says is the point, or stores a new one made by
  // `make()` (which gets `id`).
  template <class Is, class Make>
  std::uint32_t find_or_insert(const Key& key, Is&& is, Make&& make);
  void rebuild(std::size_t capacity);  // slots for `capacity` entries, rehashed

  std::vector<Entry> entries_;
  std::vector<std::uint32_t> slots_;   // entry index, kEmpty when free
  std::vector<std::uint64_t> hashes_;  // the hash of each slot's entry
  std::vector<Point> rationals_;       // the stored points whose coordinates are not doubles
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

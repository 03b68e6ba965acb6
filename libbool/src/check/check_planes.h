// SPDX-License-Identifier: GPL-3.0-or-later
// Each triangle's plane in doubles, computed at most once per check and read by four of its
// passes: the degenerate faces (which faces certainly turn), the coplanar search (which edges
// certainly do not join two faces of one plane), the near-flat search (the faces' rough normals)
// and the self-intersection traversal (pairs settled by one side of a plane).
#pragma once

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <vector>

#include "exact/double_plane.h"
#include "exact/static_filter.h"
#include "morphex/mesh.h"

namespace morphex::detail {

// The planes' side tests are DoublePlane's (double_plane.h).
class FacePlanes {
 public:
  // Without doubles (`xyz` empty: coordinates out of the filters' range) every test declines.
  FacePlanes(const Mesh& mesh, const std::vector<Xyz>& xyz, double error);
  ~FacePlanes();
  FacePlanes(const FacePlanes&) = delete;
  FacePlanes& operator=(const FacePlanes&) = delete;

  bool empty() const { return units_.empty(); }

  // The sign of vertex x's side of triangle g's plane, when the doubles decide it.
  std::optional<int> side(std::uint32_t g, VertexIndex x) const {
    if (units_.empty()) return std::nullopt;
    return side(plane(g), xyz_[x]);
  }

  // All corners of triangle f lie strictly on one side of triangle g's plane (by doubles alone:
  // false when undecided). Then f and g do not meet.
  bool beside(std::uint32_t f, std::uint32_t g) const {
    if (units_.empty()) return false;
    const Plane &plane = this->plane(g), &of_f = this->plane(f);
    int side_of_f = 0;
    for (const Xyz& x : of_f.corner) {
      const std::optional<int> s = side(plane, x);
      if (!s || (side_of_f != 0 && *s != side_of_f)) return false;
      side_of_f = *s;
    }
    return true;
  }

  // The doubles show that triangle f is not degenerate: one of its coordinate projections turns
  // (false when they do not tell).
  bool proper(std::uint32_t f) const { return !proper_.empty() && proper_[f] != 0; }

  // Triangle f's normal of unit length (zero when too small to normalize): a rough quantity, to
  // group faces, never a decision. Not on an empty set of planes.
  const Xyz& unit_normal(std::uint32_t f) const { return units_[f]; }

  // The normals of f and g differ by more than about 5e-5 radians (by their rough unit normals,
  // whose errors stay far below that unless a face is thinner than an angle of about 1e-8). A
  // screen for searches that only look for faces to group (the coplanar search: a pair it skips
  // goes through the pair tests instead), never a decision; false without planes.
  bool bent(std::uint32_t f, std::uint32_t g) const {
    if (units_.empty()) return false;
    const Xyz &a = units_[f], &b = units_[g];
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2] < 1 - 1e-9;
  }

 private:
  // With the triangle's corners beside its plane: the traversal's side tests (millions of pairs
  // of slivers along a tube) then read two records instead of a plane and four scattered points.
  struct alignas(64) Plane {
    DoublePlane plane;
    Xyz corner[3];
  };
  // Face f's record, computed on its first use by whichever thread gets there first (others wait
  // for that one short computation). Most faces of a smooth surface never need one: the traversal
  // meets few pairs that share no proved vertex, and the coplanar search screens by the unit
  // normals; writing every face's record would be a pass over all faces that such a mesh mostly
  // does not need.
  const Plane& plane(std::uint32_t f) const {
    const std::uint32_t slot = slot_[f].load(std::memory_order_acquire);
    if (slot >= kFirstRecord) return record(slot - kFirstRecord);
    return publish(f);
  }
  const Plane& record(std::uint32_t i) const {
    return blocks_[i >> kBlockShift].load(std::memory_order_relaxed)[i & (kBlock - 1)];
  }
  const Plane& publish(std::uint32_t f) const;
  // slot_[f]: kNone, kBusy, or kFirstRecord + the index of f's record (in order of first use).
  static constexpr std::uint32_t kNone = 0, kBusy = 1, kFirstRecord = 2;
  std::optional<int> side(const Plane& plane, const Xyz& v) const {
    return plane.plane.side(plane.corner[0], v, error_);
  }
  const Mesh& mesh_;
  const std::vector<Xyz>& xyz_;
  const double error_;
  // The records, handed out in the order faces are first used, in blocks allocated as they fill:
  // the few faces a smooth mesh needs, indexed by face, would touch a page each, nearly every page
  // of an array over all faces, and each fresh page is a page fault on every call. Each thread
  // fills a block of its own (a cursor per thread of the arena, on a cache line of its own): a
  // counter shared by every first use makes threads wait on each other's writes.
  static constexpr std::uint32_t kBlockShift = 8, kBlock = 1u << kBlockShift;
  struct alignas(64) Cursor {
    std::uint32_t next = 0, end = 0;  // the record to hand out next, the end of its block
  };
  std::uint32_t next_record(std::uint32_t face) const;  // from this thread's cursor
  std::uint32_t new_block(std::uint32_t face) const;    // the first record of a new block
  std::unique_ptr<std::atomic<Plane*>[]> blocks_;       // kBlock records each, or null
  std::size_t num_blocks_ = 0;                          // room in blocks_
  std::unique_ptr<std::atomic<std::uint32_t>[]> slot_;  // by face
  std::unique_ptr<Cursor[]> cursors_;  // by thread of the arena, then one shared (under a lock)
  std::size_t num_cursors_ = 0;
  alignas(64) mutable std::atomic<std::uint32_t> blocks_used_{0};
  mutable std::mutex shared_cursor_;
  alignas(64) std::vector<Xyz> units_;  // unit normals, for every face (empty without doubles)
  std::vector<std::uint8_t> proper_;    // by face: proper()
};

}  // namespace morphex::detail

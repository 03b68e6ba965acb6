// SPDX-License-Identifier: GPL-3.0-or-later
// Whether two triangles meet, exactly, from orientation predicates on their vertices alone.
#pragma once

#include <array>
#include <cstdint>

#include "exact/point_table.h"

namespace morphex::detail {

// Guigue and Devillers' exact test (2003) of two non-coplanar triangles whose vertices are not
// all on one side of the other's plane: with each triangle turned so that its first vertex is
// alone on its side, two more orientations of input points decide whether the chords overlap.
// No point is constructed, so pairs that only come close cost nothing more. Touching counts as
// meeting. s1, s2: the signs of t1's vertices against t2's plane and of t2's against t1's.
class TriangleOverlap {
 public:
  explicit TriangleOverlap(const PointTable& table) : table_(table) {}

  bool operator()(const std::array<PointId, 3>& t1, const std::array<PointId, 3>& t2,
                  const std::int8_t (&s1)[3], const std::int8_t (&s2)[3]) const {
    const PointId p1 = t1[0], q1 = t1[1], r1 = t1[2], p2 = t2[0], q2 = t2[1], r2 = t2[2];
    const int dp1 = s1[0], dq1 = s1[1], dr1 = s1[2], dp2 = s2[0], dq2 = s2[1], dr2 = s2[2];
    if (dp1 > 0) {
      if (dq1 > 0) return canonical(r1, p1, q1, p2, r2, q2, dp2, dr2, dq2);
      if (dr1 > 0) return canonical(q1, r1, p1, p2, r2, q2, dp2, dr2, dq2);
      return canonical(p1, q1, r1, p2, q2, r2, dp2, dq2, dr2);
    }
    if (dp1 < 0) {
      if (dq1 < 0) return canonical(r1, p1, q1, p2, q2, r2, dp2, dq2, dr2);
      if (dr1 < 0) return canonical(q1, r1, p1, p2, q2, r2, dp2, dq2, dr2);
      return canonical(p1, q1, r1, p2, r2, q2, dp2, dr2, dq2);
    }
    if (dq1 < 0) {
      if (dr1 >= 0) return canonical(q1, r1, p1, p2, r2, q2, dp2, dr2, dq2);
      return canonical(p1, q1, r1, p2, q2, r2, dp2, dq2, dr2);
    }
    if (dq1 > 0) {
      if (dr1 > 0) return canonical(p1, q1, r1, p2, r2, q2, dp2, dr2, dq2);
      return canonical(q1, r1, p1, p2, q2, r2, dp2, dq2, dr2);
    }
    if (dr1 > 0) return canonical(r1, p1, q1, p2, q2, r2, dp2, dq2, dr2);
    return canonical(r1, p1, q1, p2, r2, q2, dp2, dr2, dq2);
  }

 private:
  // t1 turned so that p1 is alone on its side of t2's plane; t2's signs against t1's plane.
  bool canonical(PointId p1, PointId q1, PointId r1, PointId p2, PointId q2, PointId r2, int dp2,
                 int dq2, int dr2) const {
    if (dp2 > 0) {
      if (dq2 > 0) return overlap(p1, r1, q1, r2, p2, q2);
      if (dr2 > 0) return overlap(p1, r1, q1, q2, r2, p2);
      return overlap(p1, q1, r1, p2, q2, r2);
    }
    if (dp2 < 0) {
      if (dq2 < 0) return overlap(p1, q1, r1, r2, p2, q2);
      if (dr2 < 0) return overlap(p1, q1, r1, q2, r2, p2);
      return overlap(p1, r1, q1, p2, q2, r2);
    }
    if (dq2 < 0) {
      if (dr2 >= 0) return overlap(p1, r1, q1, q2, r2, p2);
      return overlap(p1, q1, r1, p2, q2, r2);
    }
    if (dq2 > 0) {
      if (dr2 > 0) return overlap(p1, r1, q1, p2, q2, r2);
      return overlap(p1, q1, r1, q2, r2, p2);
    }
    if (dr2 > 0) return overlap(p1, q1, r1, r2, p2, q2);
    return overlap(p1, r1, q1, r2, p2, q2);
  }
  // Both triangles in canonical position: the two chords on the common line overlap.
  bool overlap(PointId p1, PointId q1, PointId r1, PointId p2, PointId q2, PointId r2) const {
    return table_.orientation(q1, p2, p1, q2) != CGAL::POSITIVE &&
           table_.orientation(p1, p2, r1, r2) != CGAL::POSITIVE;
  }

  const PointTable& table_;
};

}  // namespace morphex::detail

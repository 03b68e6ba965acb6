// SPDX-License-Identifier: GPL-3.0-or-later
// 2D triangulation traits over point ids of a PointTable, for points of one plane seen along a
// coordinate axis: the constrained Delaunay triangulations of cut facets and of merged regions.
#pragma once

#include <cstdint>

#include "boolean/facet_lines.h"
#include "exact/point_table.h"

namespace morphex::detail {

// Whether the Delaunay diagonal of the convex quadrilateral a b c d (in order, turning `turn` seen
// along the axis `dropped`) is bd: d strictly inside the circle through a, b and c. On a tie
// either diagonal is Delaunay, and ac is taken.
inline bool delaunay_diagonal_is_bd(const PointTable& table, int dropped, CGAL::Sign turn,
                                    PointId a, PointId b, PointId c, PointId d) {
  const CGAL::Sign in_circle = table.side_of_oriented_circle(dropped, a, b, c, d);
  return (turn == CGAL::NEGATIVE ? -in_circle : in_circle) == CGAL::POSITIVE;
}

// A point of the facet's triangulation: its id and the facet edges it lies on.
struct TablePoint {
  PointId id = 0;
  std::uint8_t edges = 0;
};

// Triangulation traits over table ids, seen along the axis `dropped`.
template <int dropped>
class TableTraits {
 public:
  static constexpr int u = dropped == 0 ? 1 : 0, v = dropped == 2 ? 1 : 2;
  using Point_2 = TablePoint;
  struct Segment_2 {
    TablePoint s, t;
    const TablePoint& source() const { return s; }
    const TablePoint& target() const { return t; }
  };
  struct Triangle_2 {
    TablePoint a, b, c;
  };

  struct Orientation_2 {
    const PointTable* table;
    FacetLines* lines;
    CGAL::Orientation operator()(const TablePoint& p, const TablePoint& q,
                                 const TablePoint& r) const {
      // Three points on one edge of the facet: collinear by construction.
      if ((p.edges & q.edges & r.edges) || p.id == q.id || q.id == r.id || p.id == r.id)
        return CGAL::COLLINEAR;
      return table->orientation_2(dropped, p.id, q.id, r.id, lines);
    }
  };
  struct Side_of_oriented_circle_2 {
    const PointTable* table;
    CGAL::Oriented_side operator()(const TablePoint& p, const TablePoint& q, const TablePoint& r,
                                   const TablePoint& t) const {
      return table->side_of_oriented_circle(dropped, p.id, q.id, r.id, t.id);
    }
  };
  template <int axis>
  struct Compare {
    const PointTable* table;
    CGAL::Comparison_result operator()(const TablePoint& p, const TablePoint& q) const {
      return table->compare(axis, p.id, q.id);
    }
  };
  template <int axis>
  struct Less {
    const PointTable* table;
    bool operator()(const TablePoint& p, const TablePoint& q) const {
      return table->compare(axis, p.id, q.id) == CGAL::SMALLER;
    }
  };
  using Compare_x_2 = Compare<u>;
  using Compare_y_2 = Compare<v>;
  using Less_x_2 = Less<u>;
  using Less_y_2 = Less<v>;
  struct Construct_point_2 {
    const TablePoint& operator()(const TablePoint& p) const { return p; }
  };
  struct Construct_segment_2 {
    Segment_2 operator()(const TablePoint& p, const TablePoint& q) const { return {p, q}; }
  };
  struct Construct_triangle_2 {
    Triangle_2 operator()(const TablePoint& p, const TablePoint& q, const TablePoint& r) const {
      return {p, q, r};
    }
  };

  // `lines`: the input facet every point lies on, if there is one (a cut facet, a region in a
  // facet's plane); it must outlive the traits.
  explicit TableTraits(const PointTable* table = nullptr, FacetLines* lines = nullptr)
      : table_(table), lines_(lines) {}
  Orientation_2 orientation_2_object() const { return {table_, lines_}; }
  Side_of_oriented_circle_2 side_of_oriented_circle_2_object() const { return {table_}; }
  Compare_x_2 compare_x_2_object() const { return {table_}; }
  Compare_y_2 compare_y_2_object() const { return {table_}; }
  Less_x_2 less_x_2_object() const { return {table_}; }
  Less_y_2 less_y_2_object() const { return {table_}; }
  Construct_point_2 construct_point_2_object() const { return {}; }
  Construct_segment_2 construct_segment_2_object() const { return {}; }
  Construct_triangle_2 construct_triangle_2_object() const { return {}; }

 private:
  const PointTable* table_;
  FacetLines* lines_;
};

}  // namespace morphex::detail

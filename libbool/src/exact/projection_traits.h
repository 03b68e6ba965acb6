// SPDX-License-Identifier: GPL-3.0-or-later
// 2D triangulation traits for points of a facet's plane, seen along a coordinate axis.
//
// CGAL's Projection_traits_xy_3<Epeck> answers Orientation_2 and Side_of_oriented_circle_2 by
// building lazy 2D points (one heap node per point per call) before filtering. Here the same
// predicates read the interval approximations of the 3D points directly and fall back to their
// exact coordinates only when the intervals cannot decide: the same exact answers, without the
// allocations that dominated the constrained Delaunay triangulations.
#pragma once

#include <CGAL/Interval_nt.h>
#include <CGAL/Projection_traits_xy_3.h>
#include <CGAL/Projection_traits_xz_3.h>
#include <CGAL/Projection_traits_yz_3.h>
#include <CGAL/predicates/kernel_ftC2.h>

#include "exact/filtered.h"
#include "morphex/mesh.h"

namespace morphex::detail {

// 0, 1 or 2: an axis along which the normal of triangle abc is not zero, so that dropping that
// coordinate projects the triangle's plane without degeneracy (exact: it only selects
// coordinates). Any such axis is exact; the one with the largest certain part of the normal keeps
// the projected predicates well conditioned, and only a normal too small for intervals asks for
// the exact one.
inline int dominant_axis(const Point& a, const Point& b, const Point& c) {
  {
    CGAL::Protect_FPU_rounding<true> rounding;
    const auto &pa = CGAL::approx(a), &pb = CGAL::approx(b), &pc = CGAL::approx(c);
    const auto n = CGAL::cross_product(pb - pa, pc - pa);
    if (const int axis = certain_dominant_axis(n); axis >= 0) return axis;
  }
  const auto &ea = CGAL::exact(a), &eb = CGAL::exact(b), &ec = CGAL::exact(c);
  const auto n = CGAL::cross_product(eb - ea, ec - ea);
  const auto ax = CGAL::abs(n.x()), ay = CGAL::abs(n.y()), az = CGAL::abs(n.z());
  if (ax >= ay && ax >= az) return 0;
  return ay >= az ? 1 : 2;
}

// Dropped axis 0: the plane (y, z); 1: (x, z); 2: (x, y), as in CGAL's Projection_traits_3<K, dim>.
template <int dropped>
struct ProjectedCoordinates {
  static constexpr int u = dropped == 0 ? 1 : 0;
  static constexpr int v = dropped == 2 ? 1 : 2;
  template <class P>
  static const auto& first(const P& p) {
    return p.cartesian(u);
  }
  template <class P>
  static const auto& second(const P& p) {
    return p.cartesian(v);
  }
};

template <int dropped>
struct FilteredProjectedOrientation {
  using result_type = CGAL::Orientation;
  using C = ProjectedCoordinates<dropped>;
  CGAL::Orientation operator()(const Point& p, const Point& q, const Point& r) const {
    {
      CGAL::Protect_FPU_rounding<true> rounding;
      const auto &ap = CGAL::approx(p), &aq = CGAL::approx(q), &ar = CGAL::approx(r);
      const auto s = CGAL::orientationC2(C::first(ap), C::second(ap), C::first(aq), C::second(aq),
                                         C::first(ar), C::second(ar));
      if (CGAL::is_certain(s)) return CGAL::get_certain(s);
    }
    return exact_orientation_2<C::u, C::v>(CGAL::exact(p), CGAL::exact(q), CGAL::exact(r));
  }
};

template <int dropped>
struct FilteredProjectedSideOfOrientedCircle {
  using result_type = CGAL::Oriented_side;
  using C = ProjectedCoordinates<dropped>;
  CGAL::Oriented_side operator()(const Point& p, const Point& q, const Point& r,
                                 const Point& t) const {
    {
      CGAL::Protect_FPU_rounding<true> rounding;
      const auto &ap = CGAL::approx(p), &aq = CGAL::approx(q), &ar = CGAL::approx(r),
                 &at = CGAL::approx(t);
      const auto s =
          CGAL::side_of_oriented_circleC2(C::first(ap), C::second(ap), C::first(aq), C::second(aq),
                                          C::first(ar), C::second(ar), C::first(at), C::second(at));
      if (CGAL::is_certain(s)) return CGAL::get_certain(s);
    }
    const auto &ep = CGAL::exact(p), &eq = CGAL::exact(q), &er = CGAL::exact(r),
               &et = CGAL::exact(t);
    return CGAL::side_of_oriented_circleC2(C::first(ep), C::second(ep), C::first(eq), C::second(eq),
                                           C::first(er), C::second(er), C::first(et),
                                           C::second(et));
  }
};

template <int dropped>
class FilteredProjectionTraits : public CGAL::internal::Projection_traits_3<Kernel, dropped> {
 public:
  using Orientation_2 = FilteredProjectedOrientation<dropped>;
  using Side_of_oriented_circle_2 = FilteredProjectedSideOfOrientedCircle<dropped>;
  Orientation_2 orientation_2_object() const { return {}; }
  Side_of_oriented_circle_2 side_of_oriented_circle_2_object() const { return {}; }
};

}  // namespace morphex::detail

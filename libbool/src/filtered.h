// SPDX-License-Identifier: GPL-3.0-or-later
// Filtered exact evaluation of expressions over points, without lazy construction nodes: first on
// the points' interval approximations, then, only when the intervals cannot decide, on their exact
// coordinates. The expression is generic over the kernel (CGAL's interval and exact kernels both
// provide the vector, triangle and segment types it builds).
#pragma once

#include <CGAL/Interval_nt.h>
#include <CGAL/Uncertain.h>

#include "morphex/mesh.h"

namespace morphex::detail {

template <class Expression, class... Points>
CGAL::Sign filtered_sign(const Expression& expression, const Points&... points) {
  {
    CGAL::Protect_FPU_rounding<true> rounding;
    const CGAL::Uncertain<CGAL::Sign> s = CGAL::sign(expression(CGAL::approx(points)...));
    if (CGAL::is_certain(s)) return CGAL::get_certain(s);
  }
  return CGAL::sign(expression(CGAL::exact(points)...));
}

// For predicates returning a truth value (CGAL's do_intersect and the like).
template <class Predicate, class... Points>
bool filtered_test(const Predicate& predicate, const Points&... points) {
  {
    CGAL::Protect_FPU_rounding<true> rounding;
    try {
      const CGAL::Uncertain<bool> r = predicate(CGAL::approx(points)...);
      if (CGAL::is_certain(r)) return CGAL::get_certain(r);
    } catch (const CGAL::Uncertain_conversion_exception&) {
      // an intermediate comparison was undecided: decide on the exact values
    }
  }
  return predicate(CGAL::exact(points)...);
}

}  // namespace morphex::detail

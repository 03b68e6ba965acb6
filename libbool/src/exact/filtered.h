// SPDX-License-Identifier: GPL-3.0-or-later
// Filtered exact evaluation of expressions over points, without lazy construction nodes: first on
// the points' interval approximations, then, only when the intervals cannot decide, on their exact
// coordinates. The expression is generic over the kernel (CGAL's interval and exact kernels both
// provide the vector, triangle and segment types it builds). It must return a concrete number:
// gmpxx expression templates would refer to temporaries (exact coordinates come by value).
#pragma once

#include <CGAL/Interval_nt.h>
#include <CGAL/Uncertain.h>
#include <gmpxx.h>

#include <array>
#include <utility>

#include "morphex/mesh.h"

namespace morphex::detail {

// The axis of the largest component of an interval normal that is certainly not zero (the
// projection along it is exact and well conditioned), or -1 when no component is certain.
template <class IntervalVector>
int certain_dominant_axis(const IntervalVector& normal) {
  int best = -1;
  double best_bound = 0;
  for (int k = 0; k < 3; ++k) {
    const double bound = CGAL::abs(normal.cartesian(k)).inf();
    if (bound > best_bound) {
      best = k;
      best_bound = bound;
    }
  }
  return best;
}

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

// Exact stages on integers. A rational point (x/dx, y/dy, z/dz) is the homogeneous integer point
// (X, Y, Z, W) with W = lcm(dx, dy, dz) > 0. Determinants of such rows involve no rational
// arithmetic, hence none of the gcd computations that dominate mpq predicates; the positive W
// factors do not change signs.
template <std::size_t N>
std::array<mpz_class, N + 1> homogeneous(const std::array<const mpq_class*, N>& c) {
  mpz_class w = c[0]->get_den();
  for (std::size_t i = 1; i < N; ++i)
    if (c[i]->get_den() != w) mpz_lcm(w.get_mpz_t(), w.get_mpz_t(), c[i]->get_den_mpz_t());
  std::array<mpz_class, N + 1> h;
  for (std::size_t i = 0; i < N; ++i) {
    if (c[i]->get_den() == w) {
      h[i] = c[i]->get_num();
    } else {
      mpz_divexact(h[i].get_mpz_t(), w.get_mpz_t(), c[i]->get_den_mpz_t());
      h[i] *= c[i]->get_num();
    }
  }
  h[N] = std::move(w);
  return h;
}

inline int sign_of_det3(const std::array<mpz_class, 3>& a, const std::array<mpz_class, 3>& b,
                        const std::array<mpz_class, 3>& c) {
  const mpz_class d = a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
                      a[2] * (b[0] * c[1] - b[1] * c[0]);
  return sgn(d);
}

// sign of the 4x4 determinant of the rows, by 2x2 minors of the first and last two rows.
inline int sign_of_det4(const std::array<mpz_class, 4>& r0, const std::array<mpz_class, 4>& r1,
                        const std::array<mpz_class, 4>& r2, const std::array<mpz_class, 4>& r3) {
  auto minor = [](const std::array<mpz_class, 4>& a, const std::array<mpz_class, 4>& b, int i,
                  int j) -> mpz_class { return a[i] * b[j] - a[j] * b[i]; };
  const mpz_class d =
      minor(r0, r1, 0, 1) * minor(r2, r3, 2, 3) - minor(r0, r1, 0, 2) * minor(r2, r3, 1, 3) +
      minor(r0, r1, 0, 3) * minor(r2, r3, 1, 2) + minor(r0, r1, 1, 2) * minor(r2, r3, 0, 3) -
      minor(r0, r1, 1, 3) * minor(r2, r3, 0, 2) + minor(r0, r1, 2, 3) * minor(r2, r3, 0, 1);
  return sgn(d);
}

using ExactPoint = Kernel::Exact_kernel::Point_3;
using Homogeneous = std::array<mpz_class, 4>;

inline Homogeneous homogeneous_point(const ExactPoint& p) {
  return homogeneous<3>({&p.x(), &p.y(), &p.z()});
}

// CGAL::orientation(p, q, r, s) = sign det(q - p, r - p, s - p), exactly.
inline CGAL::Orientation exact_orientation(const ExactPoint& p, const ExactPoint& q,
                                           const ExactPoint& r, const ExactPoint& s) {
  // det [p 1; q 1; r 1; s 1] = -det(q - p, r - p, s - p), and the W factors are positive.
  return CGAL::Orientation(-sign_of_det4(homogeneous_point(p), homogeneous_point(q),
                                         homogeneous_point(r), homogeneous_point(s)));
}

// The same sign as CGAL::orientation on Epeck points: intervals first, integers when undecided.
inline CGAL::Orientation orient3d(const Point& p, const Point& q, const Point& r, const Point& s) {
  {
    CGAL::Protect_FPU_rounding<true> rounding;
    const auto &ap = CGAL::approx(p), &aq = CGAL::approx(q), &ar = CGAL::approx(r),
               &as = CGAL::approx(s);
    const CGAL::Uncertain<CGAL::Sign> o =
        CGAL::orientationC3(ap.x(), ap.y(), ap.z(), aq.x(), aq.y(), aq.z(), ar.x(), ar.y(), ar.z(),
                            as.x(), as.y(), as.z());
    if (CGAL::is_certain(o)) return CGAL::get_certain(o);
  }
  return exact_orientation(CGAL::exact(p), CGAL::exact(q), CGAL::exact(r), CGAL::exact(s));
}

// orientationC2 of the points' coordinates (u, v): sign det(q - p, r - p) in that plane.
template <int u, int v>
CGAL::Orientation exact_orientation_2(const ExactPoint& p, const ExactPoint& q,
                                      const ExactPoint& r) {
  auto h = [](const ExactPoint& a) { return homogeneous<2>({&a.cartesian(u), &a.cartesian(v)}); };
  // det [p 1; q 1; r 1] = det(q - p, r - p), and the W factors are positive.
  return CGAL::Orientation(sign_of_det3(h(p), h(q), h(r)));
}

// CGAL::collinear(p, q, r), with the exact stage on integers: three points are collinear when
// their projections on the three coordinate planes all are. The interval stage decides without
// branching on uncertain comparisons (an exception per undecided case would cost more than the
// exact stage).
inline bool collinear3d(const Point& p, const Point& q, const Point& r) {
  {
    CGAL::Protect_FPU_rounding<true> rounding;
    const auto &ap = CGAL::approx(p), &aq = CGAL::approx(q), &ar = CGAL::approx(r);
    bool all_zero = true;
    for (const auto [u, v] : {std::pair<int, int>{0, 1}, {1, 2}, {0, 2}}) {
      const CGAL::Uncertain<CGAL::Sign> o =
          CGAL::orientationC2(ap.cartesian(u), ap.cartesian(v), aq.cartesian(u), aq.cartesian(v),
                              ar.cartesian(u), ar.cartesian(v));
      if (o.is_certain() && o.make_certain() != CGAL::ZERO) return false;
      all_zero = all_zero && o.is_certain();
    }
    if (all_zero) return true;
  }
  const auto &ep = CGAL::exact(p), &eq = CGAL::exact(q), &er = CGAL::exact(r);
  return exact_orientation_2<0, 1>(ep, eq, er) == CGAL::COLLINEAR &&
         exact_orientation_2<1, 2>(ep, eq, er) == CGAL::COLLINEAR &&
         exact_orientation_2<0, 2>(ep, eq, er) == CGAL::COLLINEAR;
}

}  // namespace morphex::detail

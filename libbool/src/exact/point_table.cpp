// SPDX-License-Identifier: GPL-3.0-or-later
#include "exact/point_table.h"

#include <CGAL/predicates/kernel_ftC2.h>
#include <CGAL/predicates/kernel_ftC3.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>

#include "boolean/facet_lines.h"
#include "exact/filtered.h"
#include "exact/fixed_integer.h"
#include "exact/static_filter.h"
#include "morphex/internal/union_find.h"

namespace morphex::detail {

namespace {

Homogeneous from_doubles(const double (&c)[3]) {
  std::int64_t mantissa[3] = {0, 0, 0};
  int exponent[3] = {0, 0, 0};
  int lowest = 0;
  for (int i = 0; i < 3; ++i) {
    if (c[i] == 0) continue;
    int e = 0;
    const double f = std::frexp(c[i], &e);  // c = f 2^e, 1/2 <= |f| < 1
    mantissa[i] = std::int64_t(std::ldexp(f, 53));
    exponent[i] = e - 53;
    lowest = std::min(lowest, exponent[i]);
  }
  Homogeneous h;
  for (int i = 0; i < 3; ++i) {
    h[i] = static_cast<long>(mantissa[i]);
    if (mantissa[i] != 0)
      mpz_mul_2exp(h[i].get_mpz_t(), h[i].get_mpz_t(), mp_bitcnt_t(exponent[i] - lowest));
  }
  h[3] = 1;
  mpz_mul_2exp(h[3].get_mpz_t(), h[3].get_mpz_t(), mp_bitcnt_t(-lowest));
  return h;
}

// The plane A X + B Y + C Z + D W = 0 through three homogeneous points (the 4D cross product).
std::array<mpz_class, 4> plane_through(const Homogeneous& a, const Homogeneous& b,
                                       const Homogeneous& c) {
  auto det3 = [&](int i, int j, int k) -> mpz_class {
    return a[i] * (b[j] * c[k] - b[k] * c[j]) - a[j] * (b[i] * c[k] - b[k] * c[i]) +
           a[k] * (b[i] * c[j] - b[j] * c[i]);
  };
  return {det3(1, 2, 3), -det3(0, 2, 3), det3(0, 1, 3), -det3(0, 1, 2)};
}

// The plane through the line ab of the coordinate plane that drops axis `dropped`, parallel to
// that axis: the points whose projection lies on the line.
std::array<mpz_class, 4> plane_along_axis(int dropped, const Homogeneous& a, const Homogeneous& b) {
  const int u = dropped == 0 ? 1 : 0, v = dropped == 2 ? 1 : 2;
  std::array<mpz_class, 4> plane;
  plane[dropped] = 0;
  plane[u] = a[v] * b[3] - a[3] * b[v];
  plane[v] = a[3] * b[u] - a[u] * b[3];
  plane[3] = a[u] * b[v] - a[v] * b[u];
  return plane;
}

mpz_class evaluate(const std::array<mpz_class, 4>& plane, const Homogeneous& p) {
  return plane[0] * p[0] + plane[1] * p[1] + plane[2] * p[2] + plane[3] * p[3];
}

Interval hull(const Interval& a, const Interval& b) {
  return Interval(std::min(a.inf(), b.inf()), std::max(a.sup(), b.sup()));
}

// Narrows `x` to `bound`, which is known to contain the exact value.
Interval clamp(const Interval& x, const Interval& bound) {
  const double lo = std::max(x.inf(), bound.inf()), hi = std::min(x.sup(), bound.sup());
  return lo <= hi ? Interval(lo, hi) : bound;
}

// Divides out the common factor of the four coordinates (W stays positive). The result is the
// form homogeneous_of gives the point's rational coordinates (W the least common denominator),
// without them: lcm(W / gcd(X_i, W)) = W / gcd(X, Y, Z, W).
void remove_content(Homogeneous& h) {
  mpz_class g;
  mpz_gcd(g.get_mpz_t(), h[3].get_mpz_t(), h[0].get_mpz_t());
  for (int i = 1; i < 3 && g != 1; ++i) mpz_gcd(g.get_mpz_t(), g.get_mpz_t(), h[i].get_mpz_t());
  if (g == 1) return;
  for (mpz_class& x : h) mpz_divexact(x.get_mpz_t(), x.get_mpz_t(), g.get_mpz_t());
}

// The lazily evaluated output point of a construction: its approximation is the table's; its
// homogeneous coordinates are computed from the parents' (or taken from those already known) on
// first request, after which the parents are released, as CGAL's own lazy constructions do. A
// later operation's table reads them directly (homogeneous_of): a Boolean's result is the next
// one's input in a union tree or a morphology, and the round trip through rational coordinates
// (a gcd per coordinate, then their least common multiple) was a large part of its exact stage.
// The rational coordinates are made only when something asks for them.
using LazyPoint = Point::Rep;
class ConstructedPointRep final : public LazyPoint::Self_rep {
  using Base = LazyPoint::Self_rep;

 public:
  ConstructedPointRep(const ApproxPoint& approx, const Recipe& recipe,
                      const std::array<Point, 5>& parents, const Homogeneous* known)
      : Base(approx), recipe_(recipe), parents_(parents) {
    if (known) known_ = std::make_unique<Homogeneous>(*known);
  }

  const Homogeneous& homogeneous() const {
    std::call_once(homogeneous_once_, [this] {
      if (known_) {
        homogeneous_ = *known_;
      } else {
        std::array<Homogeneous, 5> parents;
        for (int i = 0; i < 5; ++i) parents[i] = homogeneous_of(parents_[i]);
        homogeneous_ = construct_homogeneous(recipe_, parents[0], parents[1], parents[2],
                                             parents[3], parents[4]);
      }
      remove_content(homogeneous_);
      parents_ = {};
      known_.reset();
    });
    return homogeneous_;
  }

  void update_exact() const override {
    auto* exact = new ExactPoint(cartesian(homogeneous()));
    this->set_at(exact);
    this->set_ptr(exact);
  }

 private:
  Recipe recipe_;
  mutable std::array<Point, 5> parents_;
  mutable std::unique_ptr<Homogeneous> known_;
  mutable std::once_flag homogeneous_once_;
  mutable Homogeneous homogeneous_;
};

template <class Number>
Number determinant_3(const Number& a00, const Number& a01, const Number& a02, const Number& a10,
                     const Number& a11, const Number& a12, const Number& a20, const Number& a21,
                     const Number& a22) {
  return a00 * (a11 * a22 - a12 * a21) - a01 * (a10 * a22 - a12 * a20) +
         a02 * (a10 * a21 - a11 * a20);
}

// (q - p) scaled by Wp Wq > 0, on homogeneous integers.
std::array<mpz_class, 3> difference(const Homogeneous& p, const Homogeneous& q) {
  return {q[0] * p[3] - p[0] * q[3], q[1] * p[3] - p[1] * q[3], q[2] * p[3] - p[2] * q[3]};
}

std::array<mpz_class, 3> cross(const std::array<mpz_class, 3>& a,
                               const std::array<mpz_class, 3>& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

}  // namespace

Homogeneous homogeneous_of(const ExactPoint& p) {
  return homogeneous<3>({&p.x(), &p.y(), &p.z()});
}

Homogeneous homogeneous_of(const Point& p) {
  // The handle's representation (public, if meant for CGAL's compact containers).
  const auto* rep = static_cast<const CGAL::Rep*>(p.rep().for_compact_container());
  if (const auto* constructed = dynamic_cast<const ConstructedPointRep*>(rep))
    return constructed->homogeneous();
  if (has_double_coordinates(p)) {
    const auto& a = CGAL::approx(p);
    const double c[3] = {a.x().inf(), a.y().inf(), a.z().inf()};
    return from_doubles(c);
  }
  return homogeneous_of(CGAL::exact(p));
}

Homogeneous construct_homogeneous(const Recipe& recipe, const Homogeneous& p, const Homogeneous& q,
                                  const Homogeneous& a, const Homogeneous& b,
                                  const Homogeneous& c) {
  if (recipe.kind == Recipe::Kind::Centroid) {
    // (P/Wp + Q/Wq + A/Wa) / 3 over the common denominator 3 Wp Wq Wa.
    const mpz_class wqa = q[3] * a[3], wpa = p[3] * a[3], wpq = p[3] * q[3];
    Homogeneous r;
    for (int i = 0; i < 3; ++i) r[i] = p[i] * wqa + q[i] * wpa + a[i] * wpq;
    r[3] = 3 * p[3] * wqa;
    return r;
  }
  const auto plane = recipe.kind == Recipe::Kind::EdgePlane
                         ? plane_through(a, b, c)
                         : plane_along_axis(recipe.dropped, a, b);
  // With d the plane's linear form, the crossing is d(q) p - d(p) q; d(p) and d(q) have strictly
  // opposite signs, so its W is not zero; the sign is fixed so that W > 0.
  const mpz_class dp = evaluate(plane, p), dq = evaluate(plane, q);
  Homogeneous r;
  for (int i = 0; i < 4; ++i) r[i] = dq * p[i] - dp * q[i];
  if (sgn(r[3]) < 0)
    for (auto& x : r) x = -x;
  return r;
}

ExactPoint cartesian(const Homogeneous& h) {
  auto coordinate = [&](int i) {
    mpq_class x(h[i], h[3]);
    x.canonicalize();
    return x;
  };
  return ExactPoint(coordinate(0), coordinate(1), coordinate(2));
}

PointTable::PointTable(const Mesh& a, const Mesh& b, bool same_mesh)
    : same_mesh_(same_mesh),
      num_a_(PointId(a.num_vertices())),
      num_inputs_(PointId(same_mesh ? a.num_vertices() : a.num_vertices() + b.num_vertices())),
      input_exact_(new std::atomic<Homogeneous*>[num_inputs_]()) {
  mesh_[0] = &a;
  mesh_[1] = same_mesh ? &a : &b;
  input_xyz_.resize(num_inputs_);
  input_approx_.resize(num_inputs_);
  // Each coordinate's double is its interval's lower end, within the interval's width of it.
  auto widest_in = [&](PointId begin, PointId end) {
    return tbb::parallel_reduce(
        tbb::blocked_range<PointId>(begin, end, 4096), 0.0,
        [&](const tbb::blocked_range<PointId>& range, double widest) {
          for (PointId i = range.begin(); i != range.end(); ++i) {
            const auto& a = CGAL::approx(input(i));
            input_approx_[i] = a;
            input_xyz_[i] = {a.x().inf(), a.y().inf(), a.z().inf()};
            for (int k = 0; k < 3; ++k)
              widest = std::max(widest, a.cartesian(k).sup() - a.cartesian(k).inf());
          }
          return widest;
        },
        [](double a, double b) { return std::max(a, b); });
  };
  const double widest_a = widest_in(0, num_a_), widest_b = widest_in(num_a_, num_inputs_);
  input_error_ = std::max(widest_a, widest_b);
  doubles_[0] = widest_a == 0;
  doubles_[1] = same_mesh ? doubles_[0] : widest_b == 0;
  // The widths were rounded in the caller's mode: one unit up covers it. A width that is not
  // finite leaves the static filters and the exact stages on doubles out.
  if (input_error_ > 0) input_error_ = std::nextafter(input_error_, HUGE_VAL);
  if (!std::isfinite(input_error_)) {
    input_xyz_ = {};
    doubles_[0] = doubles_[1] = false;
  }
  // A mesh against itself (the input check): its exact questions about rational inputs come by
  // the thousand on a rotated CAD part. A Boolean's two meshes ask far fewer per input (0.2-0.4
  // on rotated CAD pairs), where building the grid cost more than it saved (docs/benchmarks.md).
  if (same_mesh && !doubles_[0]) grid_state_ = std::make_unique<GridState>();
}

namespace {
bool is_constructed_point(const Point& p) {
  const auto* rep = static_cast<const CGAL::Rep*>(p.rep().for_compact_container());
  return dynamic_cast<const ConstructedPointRep*>(rep) != nullptr;
}
}  // namespace

const InputGrid* PointTable::input_grid() const {
  if (!grid_state_) return nullptr;
  GridState& state = *grid_state_;
  if (const InputGrid* ready = state.ready.load(std::memory_order_acquire)) return ready;
  // Building takes 60-90 ns per input. A rotated CAD part's check asks 0.8-5 questions per
  // input (rotor 0.8, couplingdown 0.9, fandisk 1.4, cheese 2.6, cube-meshed 5.5), a rotated
  // pinion's 0.19, where building after an eighth of the inputs' count cost 7%, and a rotated
  // smooth mesh's none.
  const std::uint64_t enough = 32 + num_inputs_ / 4;
  if (state.questions.fetch_add(1, std::memory_order_relaxed) + 1 != enough) return nullptr;
  const ExactStage nearest;
  std::vector<InputGrid::Input> inputs(num_inputs_);
  for (PointId i = 0; i < num_inputs_; ++i)
    inputs[i] = {&input(i), is_double(i) ? &input_xyz_[i] : nullptr};
  state.grid = InputGrid::build(inputs, &is_constructed_point);
  state.ready.store(state.grid.get(), std::memory_order_release);
  return state.grid.get();
}

PointTable::~PointTable() {
  if (input_exact_)
    for (PointId i = 0; i < num_inputs_; ++i) delete input_exact_[i].load();
  for (std::size_t i = 0; i < constructed_exact_.size(); ++i) delete constructed_exact_[i].load();
}

const Homogeneous& PointTable::exact(PointId id) const {
  std::atomic<Homogeneous*>& slot = exact_slot(id);
  if (Homogeneous* known = slot.load(std::memory_order_acquire)) return *known;
  const ExactStage nearest;
  auto fresh = std::make_unique<Homogeneous>(compute_exact(id));
  Homogeneous* expected = nullptr;
  if (slot.compare_exchange_strong(expected, fresh.get(), std::memory_order_acq_rel))
    return *fresh.release();
  return *expected;  // another thread was first
}

Homogeneous PointTable::compute_exact(PointId id) const {
  if (id < num_inputs_) return homogeneous_of(input(id));
  const Recipe& r = recipe(id);
  if (r.kind == Recipe::Kind::Explicit) return homogeneous_of(explicit_[r.p]);
  return construct_homogeneous(r, exact(r.p), exact(r.q), exact(r.a), exact(r.b),
                               exact(r.kind == Recipe::Kind::EdgePlane ? r.c : r.a));
}

Point PointTable::point(PointId id) const {
  if (id < num_inputs_) return input(id);
  const Recipe& r = recipe(id);
  if (r.kind == Recipe::Kind::Explicit) return explicit_[r.p];
  const PointId c = r.kind == Recipe::Kind::EdgePlane ? r.c : r.a;
  const std::array<Point, 5> parents = {point(r.p), point(r.q), point(r.a), point(r.b), point(c)};
  const Homogeneous* known = exact_slot(id).load(std::memory_order_acquire);
  return Point(LazyPoint(new ConstructedPointRep(approx(id), r, parents, known)));
}

ApproxPoint PointTable::approximate(const Recipe& r) const {
  IntervalStage rounding;
  const ApproxPoint &p = approx(r.p), &q = approx(r.q), &a = approx(r.a), &b = approx(r.b);
  if (r.kind == Recipe::Kind::Centroid) {
    Interval c[3];
    for (int i = 0; i < 3; ++i) c[i] = (p.cartesian(i) + q.cartesian(i) + a.cartesian(i)) / 3;
    return ApproxPoint(c[0], c[1], c[2]);
  }
  Interval dp, dq;
  if (r.kind == Recipe::Kind::EdgePlane) {
    const auto n = CGAL::cross_product(b - a, approx(r.c) - a);
    dp = n * (p - a);
    dq = n * (q - a);
  } else {
    const int u = r.dropped == 0 ? 1 : 0, v = r.dropped == 2 ? 1 : 2;
    auto side = [&](const ApproxPoint& x) {
      return (b.cartesian(u) - a.cartesian(u)) * (x.cartesian(v) - a.cartesian(v)) -
             (b.cartesian(v) - a.cartesian(v)) * (x.cartesian(u) - a.cartesian(u));
    };
    dp = side(p);
    dq = side(q);
  }
  // The crossing is p + t (q - p) with t = d(p) / (d(p) - d(q)) in (0, 1), and lies in the box
  // of p and q: both bounds tighten the interval evaluation.
  const Interval t = clamp(dp / (dp - dq), Interval(0, 1));
  Interval c[3];
  for (int i = 0; i < 3; ++i)
    c[i] = clamp(p.cartesian(i) + t * (q.cartesian(i) - p.cartesian(i)),
                 hull(p.cartesian(i), q.cartesian(i)));
  // A plane whose three points share one exact coordinate (a CAD model's face perpendicular to
  // an axis) is that coordinate's plane: its crossings have that coordinate exactly. Without it,
  // the cut points of such a face compare equal along that axis only in exact arithmetic.
  if (r.kind == Recipe::Kind::EdgePlane) {
    const ApproxPoint& pc = approx(r.c);
    for (int i = 0; i < 3; ++i) {
      const Interval& x = a.cartesian(i);
      if (x.is_point() && b.cartesian(i).is_same(x) && pc.cartesian(i).is_same(x)) c[i] = x;
    }
  }
  return ApproxPoint(c[0], c[1], c[2]);
}

PointId PointTable::add(const Recipe& recipe) {
  const PointId id = PointId(size());
  approx_.push_back(approximate(recipe));
  recipes_.push_back(recipe);
  constructed_exact_.emplace_back(nullptr);
  return id;
}

PointId PointTable::add_all(const std::vector<Recipe>& recipes) {
  const PointId first = PointId(size());
  std::vector<ApproxPoint> approximations(recipes.size());
  tbb::parallel_for(std::size_t(0), recipes.size(),
                    [&](std::size_t i) { approximations[i] = approximate(recipes[i]); });
  for (std::size_t i = 0; i < recipes.size(); ++i) {
    approx_.push_back(approximations[i]);
    recipes_.push_back(recipes[i]);
    constructed_exact_.emplace_back(nullptr);
  }
  return first;
}

PointId PointTable::add_explicit(const Point& p) {
  const PointId id = PointId(size());
  Recipe r;
  r.kind = Recipe::Kind::Explicit;
  r.p = PointId(explicit_.size());
  explicit_.push_back(p);
  approx_.push_back(CGAL::approx(p));
  recipes_.push_back(r);
  constructed_exact_.emplace_back(nullptr);
  return id;
}

CGAL::Uncertain<CGAL::Sign> PointTable::orientation_filter(PointId p, PointId q, PointId r,
                                                           PointId s) const {
  if (p == q || p == r || p == s || q == r || q == s || r == s) return CGAL::ZERO;
  if (!input_xyz_.empty() && p < num_inputs_ && q < num_inputs_ && r < num_inputs_ &&
      s < num_inputs_) {
    const Xyz &xp = input_xyz_[p], &xq = input_xyz_[q], &xr = input_xyz_[r], &xs = input_xyz_[s];
    if (const auto o = input_error_ == 0 ? static_orientation(xp, xq, xr, xs)
                                         : static_orientation_near(xp, xq, xr, xs, input_error_))
      return CGAL::Sign(*o);
  }
  IntervalStage rounding;
  const ApproxPoint &ap = approx(p), &aq = approx(q), &ar = approx(r), &as = approx(s);
  return CGAL::orientationC3(ap.x(), ap.y(), ap.z(), aq.x(), aq.y(), aq.z(), ar.x(), ar.y(), ar.z(),
                             as.x(), as.y(), as.z());
}

CGAL::Sign PointTable::orientation_exact(PointId p, PointId q, PointId r, PointId s) const {
  // Inputs that are doubles: most often exactly in doubles (static_filter.h), without the
  // integers' conversions and allocations (nearly coplanar facets of a rounded rotation, exactly
  // coplanar ones of a CAD model, come here by the thousand).
  if (is_double(p) && is_double(q) && is_double(r) && is_double(s)) {
    const Xyz &xp = input_xyz_[p], &xq = input_xyz_[q], &xr = input_xyz_[r], &xs = input_xyz_[s];
    if (on_two_axis_lines(xp, xq, xr, xs)) return CGAL::ZERO;
    // Error-free transformations need round to nearest, whatever scope the caller is in.
    const CGAL::Protect_FPU_rounding<true> nearest(CGAL_FE_TONEAREST);
    if (const auto o = exact_orientation_of_doubles(xp, xq, xr, xs)) return CGAL::Sign(*o);
  }
  if (all_inputs({p, q, r, s}))
    if (const InputGrid* grid = input_grid())
      return CGAL::Sign(InputGrid::orientation((*grid)[p], (*grid)[q], (*grid)[r], (*grid)[s]));
  // det [p 1; q 1; r 1; s 1] = -det(q - p, r - p, s - p), and the W factors are positive.
  const Homogeneous* rows[4] = {&exact(p), &exact(q), &exact(r), &exact(s)};
  if (const auto sign = fixed_sign_of_det4(rows)) return CGAL::Sign(-*sign);
  return CGAL::Sign(-sign_of_det4(*rows[0], *rows[1], *rows[2], *rows[3]));
}

CGAL::Sign PointTable::PlaneSides::operator()(PointId s) const {
  const auto [a, b, c] = plane_;
  const CGAL::Uncertain<CGAL::Sign> o = table_.orientation_filter(a, b, c, s);
  return o.is_certain() ? o.make_certain() : exact(s);
}

CGAL::Sign PointTable::PlaneSides::exact(PointId s) const {
  const auto [a, b, c] = plane_;
  const PointTable& t = table_;
  // Doubles: orientation_exact decides in doubles first, without the integers.
  if (t.is_double(a) && t.is_double(b) && t.is_double(c) && t.is_double(s))
    return t.orientation_exact(a, b, c, s);
  if (!grid_plane_ && t.all_inputs({a, b, c}))
    if ((grid_ = t.input_grid())) grid_plane_.emplace((*grid_)[a], (*grid_)[b], (*grid_)[c]);
  if (grid_plane_ && t.is_input(s)) return CGAL::Sign(grid_plane_->side((*grid_)[s]));
  if (!tried_) {
    tried_ = true;
    const Homogeneous* rows[3] = {&t.exact(a), &t.exact(b), &t.exact(c)};
    form_ = FixedPlaneForm::through(rows);
  }
  // det [a; b; c; s] over homogeneous rows has the opposite sign (see orientation_exact); the
  // GMP equation is its negation already.
  if (form_)
    if (const std::optional<int> sign = form_->sign_at(t.exact(s))) return CGAL::Sign(-*sign);
  if (!equation_) equation_ = plane_through(t.exact(a), t.exact(b), t.exact(c));
  return CGAL::Sign(sgn(evaluate(*equation_, t.exact(s))));
}

CGAL::Sign PointTable::orientation_2(int dropped, PointId p, PointId q, PointId r,
                                     FacetLines* lines) const {
  if (p == q || q == r || p == r) return CGAL::ZERO;
  const int u = dropped == 0 ? 1 : 0, v = dropped == 2 ? 1 : 2;
  if (!input_xyz_.empty() && p < num_inputs_ && q < num_inputs_ && r < num_inputs_) {
    const Xyz &xp = input_xyz_[p], &xq = input_xyz_[q], &xr = input_xyz_[r];
    if (const auto o = input_error_ == 0
                           ? static_orientation_2(u, v, xp, xq, xr)
                           : static_orientation_2_near(u, v, xp, xq, xr, input_error_))
      return CGAL::Sign(*o);
  }
  {
    IntervalStage rounding;
    const ApproxPoint &ap = approx(p), &aq = approx(q), &ar = approx(r);
    const auto o = CGAL::orientationC2(ap.cartesian(u), ap.cartesian(v), aq.cartesian(u),
                                       aq.cartesian(v), ar.cartesian(u), ar.cartesian(v));
    if (CGAL::is_certain(o)) return CGAL::get_certain(o);
  }
  if (is_double(p) && is_double(q) && is_double(r)) {
    const CGAL::Protect_FPU_rounding<true> nearest(CGAL_FE_TONEAREST);
    if (const auto o =
            exact_orientation_2_of_doubles(u, v, input_xyz_[p], input_xyz_[q], input_xyz_[r]))
      return CGAL::Sign(*o);
  }
  // The recipes first, unless a point's exact coordinates are known already: an earlier
  // question left it undecided, and the recipes, when they do not decide, cost about what the
  // exact stage below costs once the coordinates exist. Coarse facets cut into nearly collinear
  // but not collinear rows ask this by the hundred thousand, so asking the recipes every time
  // would pay twice on each of them.
  if (all_inputs({p, q, r}))
    if (const InputGrid* grid = input_grid())
      return CGAL::Sign(InputGrid::orientation_2(u, v, (*grid)[p], (*grid)[q], (*grid)[r]));
  if (lines && !has_exact(p) && !has_exact(q) && !has_exact(r) && lines->collinear(p, q, r))
    return CGAL::ZERO;
  const Homogeneous &hp = exact(p), &hq = exact(q), &hr = exact(r);
  // det [p 1; q 1; r 1] in homogeneous rows, the W factors positive: in fixed-size integers
  // when they fit (no allocation: nearly collinear constructed points in a retriangulation come
  // here by the thousand), else in GMP's.
  const Homogeneous* rows[3] = {&hp, &hq, &hr};
  if (const auto sign = fixed_sign_of_det3(rows, u, v, 3)) return CGAL::Sign(*sign);
  return CGAL::Sign(
      sgn(determinant_3<mpz_class>(hp[u], hp[v], hp[3], hq[u], hq[v], hq[3], hr[u], hr[v], hr[3])));
}

CGAL::Sign PointTable::side_of_oriented_circle(int dropped, PointId p, PointId q, PointId r,
                                               PointId t) const {
  const int u = dropped == 0 ? 1 : 0, v = dropped == 2 ? 1 : 2;
  {
    IntervalStage rounding;
    const ApproxPoint &ap = approx(p), &aq = approx(q), &ar = approx(r), &at = approx(t);
    const auto s = CGAL::side_of_oriented_circleC2(
        ap.cartesian(u), ap.cartesian(v), aq.cartesian(u), aq.cartesian(v), ar.cartesian(u),
        ar.cartesian(v), at.cartesian(u), at.cartesian(v));
    if (CGAL::is_certain(s)) return CGAL::get_certain(s);
  }
  // det [x y x^2+y^2 1] over p, q, r, t is positive when t is inside the circle of the
  // counter-clockwise p, q, r, as CGAL's side_of_oriented_circle; each homogeneous row
  // (U W, V W, U^2 + V^2, W^2) is the Cartesian row times W^2 > 0.
  auto row = [&](PointId id) {
    const Homogeneous& h = exact(id);
    return Homogeneous{h[u] * h[3], h[v] * h[3], h[u] * h[u] + h[v] * h[v], h[3] * h[3]};
  };
  return CGAL::Sign(sign_of_det4(row(p), row(q), row(r), row(t)));
}

CGAL::Comparison_result PointTable::compare(int axis, PointId p, PointId q) const {
  if (p == q) return CGAL::EQUAL;
  {
    IntervalStage rounding;
    const CGAL::Uncertain<CGAL::Comparison_result> c =
        CGAL::compare(approx(p).cartesian(axis), approx(q).cartesian(axis));
    if (CGAL::is_certain(c)) return CGAL::get_certain(c);
  }
  // Points whose coordinate is an input point's by their recipes compare as those inputs do.
  const PointId sp = coordinate_source(axis, p), sq = coordinate_source(axis, q);
  if ((sp != p || sq != q) && is_input(sp) && is_input(sq)) return compare(axis, sp, sq);
  if (all_inputs({p, q}))
    if (const InputGrid* grid = input_grid())
      return CGAL::Comparison_result(InputGrid::compare(axis, (*grid)[p], (*grid)[q]));
  const Homogeneous &hp = exact(p), &hq = exact(q);
  return CGAL::Comparison_result(sgn(hp[axis] * hq[3] - hq[axis] * hp[3]));
}

PointId PointTable::coordinate_source(int axis, PointId id) const {
  if (is_input(id)) return id;
  const Recipe& r = recipe(id);
  if (r.kind != Recipe::Kind::EdgePlane && r.kind != Recipe::Kind::EdgeProjectedLine) return id;
  // On the segment pq: p's coordinate if q has it too. On the plane abc: a's if b and c have it
  // (their plane is then that coordinate's).
  if (compare(axis, r.p, r.q) == CGAL::EQUAL) return r.p;
  if (r.kind == Recipe::Kind::EdgePlane && compare(axis, r.a, r.b) == CGAL::EQUAL &&
      compare(axis, r.a, r.c) == CGAL::EQUAL)
    return r.a;
  return id;
}

bool PointTable::equal(PointId p, PointId q) const {
  for (int axis = 0; axis < 3; ++axis)
    if (compare(axis, p, q) != CGAL::EQUAL) return false;
  return true;
}

CGAL::Sign PointTable::along_line(const ApproxVector& line, const std::array<PointId, 3>& a,
                                  const std::array<PointId, 3>& b, PointId p, PointId q) const {
  {
    IntervalStage rounding;
    const CGAL::Uncertain<CGAL::Sign> s = CGAL::sign(line * (approx(q) - approx(p)));
    if (CGAL::is_certain(s)) return CGAL::get_certain(s);
  }
  return along_line_exact(a, b, p, q);
}

CGAL::Sign PointTable::along_line_exact(const std::array<PointId, 3>& a,
                                        const std::array<PointId, 3>& b, PointId p,
                                        PointId q) const {
  // Every difference is scaled by a product of positive W factors: the sign is unchanged.
  const auto na = cross(difference(exact(a[0]), exact(a[1])), difference(exact(a[0]), exact(a[2])));
  const auto nb = cross(difference(exact(b[0]), exact(b[1])), difference(exact(b[0]), exact(b[2])));
  const auto line = cross(na, nb);
  const auto d = difference(exact(p), exact(q));
  return CGAL::Sign(sgn(line[0] * d[0] + line[1] * d[1] + line[2] * d[2]));
}

CGAL::Sign PointTable::normal_dot(const std::array<PointId, 3>& a,
                                  const std::array<PointId, 3>& b) const {
  {
    IntervalStage rounding;
    const ApproxPoint &a0 = approx(a[0]), &b0 = approx(b[0]);
    const auto na = CGAL::cross_product(approx(a[1]) - a0, approx(a[2]) - a0);
    const auto nb = CGAL::cross_product(approx(b[1]) - b0, approx(b[2]) - b0);
    const CGAL::Uncertain<CGAL::Sign> s = CGAL::sign(na * nb);
    if (CGAL::is_certain(s)) return CGAL::get_certain(s);
  }
  const auto na = cross(difference(exact(a[0]), exact(a[1])), difference(exact(a[0]), exact(a[2])));
  const auto nb = cross(difference(exact(b[0]), exact(b[1])), difference(exact(b[0]), exact(b[2])));
  return CGAL::Sign(sgn(na[0] * nb[0] + na[1] * nb[1] + na[2] * nb[2]));
}

int PointTable::dominant_axis(PointId p, PointId q, PointId r) const {
  // Any axis along which the normal is certainly not zero gives an exact projection; the largest
  // certain component keeps the projected predicates well conditioned.
  {
    IntervalStage rounding;
    const ApproxPoint& ap = approx(p);
    const auto n = CGAL::cross_product(approx(q) - ap, approx(r) - ap);
    if (const int axis = certain_dominant_axis(n); axis >= 0) return axis;
  }
  const auto n = cross(difference(exact(p), exact(q)), difference(exact(p), exact(r)));
  const mpz_class ax = abs(n[0]), ay = abs(n[1]), az = abs(n[2]);
  if (ax >= ay && ax >= az) return 0;
  return ay >= az ? 1 : 2;
}

std::vector<PointId> coincident_representatives(const PointTable& table,
                                                const std::vector<PointId>& ids) {
  std::vector<std::pair<double, std::uint32_t>> by_x(ids.size());  // (lowest x, slot in ids)
  tbb::parallel_for(std::size_t(0), ids.size(), [&](std::size_t i) {
    by_x[i] = {table.approx(ids[i]).x().inf(), std::uint32_t(i)};
  });
  tbb::parallel_sort(by_x.begin(), by_x.end());
  UnionFind same(ids.size());
  for (std::size_t i = 0; i < by_x.size(); ++i) {
    const ApproxPoint& p = table.approx(ids[by_x[i].second]);
    for (std::size_t j = i + 1; j < by_x.size() && by_x[j].first <= p.x().sup(); ++j) {
      const ApproxPoint& q = table.approx(ids[by_x[j].second]);
      if (p.y().inf() <= q.y().sup() && q.y().inf() <= p.y().sup() && p.z().inf() <= q.z().sup() &&
          q.z().inf() <= p.z().sup() && table.equal(ids[by_x[i].second], ids[by_x[j].second]))
        same.join(by_x[i].second, by_x[j].second);
    }
  }
  std::vector<PointId> least(ids.size(), std::numeric_limits<PointId>::max());
  for (std::size_t i = 0; i < ids.size(); ++i) {
    PointId& first = least[same.find(std::uint32_t(i))];
    first = std::min(first, ids[i]);
  }
  std::vector<PointId> out(ids.size());
  for (std::size_t i = 0; i < ids.size(); ++i) out[i] = least[same.find(std::uint32_t(i))];
  return out;
}

}  // namespace morphex::detail

// SPDX-License-Identifier: GPL-3.0-or-later
// The points of one Boolean, by id: A's vertices, then B's, then the points the Boolean constructs.
//
// A constructed point is kept as its recipe (an input edge crossing an input plane, or an input
// line in a coordinate projection) with an interval approximation computed from the inputs'
// approximations. Its exact value is computed only when a predicate cannot be decided on
// intervals, in homogeneous integer coordinates (X, Y, Z, W), W > 0, which need no rational gcds,
// and cached. The output receives each constructed point as a lazily evaluated exact CGAL point:
// exact coordinates in lowest terms are computed when someone asks for them (a predicate, a
// volume, an exact file), as CGAL's own constructions are.
//
// Predicates take ids: intervals first, then the exact homogeneous stage.
#pragma once

#include <CGAL/FPU.h>
#include <CGAL/Interval_nt.h>
#include <gmpxx.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <array>
#include <atomic>
#include <cstdint>
#include <deque>
#include <initializer_list>
#include <memory>
#include <optional>
#include <vector>

#include "exact/fixed_integer.h"
#include "exact/input_grid.h"
#include "exact/stable_vector.h"
#include "morphex/mesh.h"

namespace morphex::detail {

class FacetLines;

// Interval arithmetic needs the FPU rounding toward +infinity, and switching the mode costs about
// as much as a small predicate. A loop that evaluates many predicates holds an UpwardRounding for
// its whole block; the predicates then leave the mode alone (IntervalStage), and their exact
// stages, which may evaluate CGAL lazy values and must not run rounded upward, switch to
// round-to-nearest for their duration (ExactStage).
inline thread_local int upward_rounding_depth = 0;

class UpwardRounding {
 public:
  UpwardRounding() {
    if (upward_rounding_depth++ == 0) saved_ = CGAL::FPU_get_and_set_cw(CGAL_FE_UPWARD);
  }
  ~UpwardRounding() {
    if (--upward_rounding_depth == 0) CGAL::FPU_set_cw(saved_);
  }
  UpwardRounding(const UpwardRounding&) = delete;
  UpwardRounding& operator=(const UpwardRounding&) = delete;

 private:
  CGAL::FPU_CW_t saved_{};
};

// Rounding upward for an interval stage, unless the caller holds it already.
class IntervalStage {
 public:
  IntervalStage() : own_(upward_rounding_depth == 0) {
    if (own_) saved_ = CGAL::FPU_get_and_set_cw(CGAL_FE_UPWARD);
  }
  ~IntervalStage() {
    if (own_) CGAL::FPU_set_cw(saved_);
  }

 private:
  bool own_;
  CGAL::FPU_CW_t saved_{};
};

// Rounding to nearest for an exact stage inside a block held upward.
class ExactStage {
 public:
  ExactStage() : active_(upward_rounding_depth > 0) {
    if (active_) saved_ = CGAL::FPU_get_and_set_cw(CGAL_FE_TONEAREST);
  }
  ~ExactStage() {
    if (active_) CGAL::FPU_set_cw(saved_);
  }

 private:
  bool active_;
  CGAL::FPU_CW_t saved_{};
};

// body(k) for k in [0, n), in parallel blocks that each hold the rounding upward: for loops whose
// bodies are mostly predicates.
template <class Body>
void for_each_upward(std::size_t n, Body&& body) {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      const UpwardRounding upward;
                      for (std::size_t k = range.begin(); k < range.end(); ++k) body(k);
                    });
}

using PointId = std::uint32_t;
using Interval = CGAL::Interval_nt<false>;
using ApproxPoint = Kernel::Approximate_kernel::Point_3;
using ApproxVector = Kernel::Approximate_kernel::Vector_3;
using ExactPoint = Kernel::Exact_kernel::Point_3;
using Homogeneous = std::array<mpz_class, 4>;  // the point (X/W, Y/W, Z/W), W > 0

// How a constructed point is made from input points.
struct Recipe {
  enum class Kind : std::uint8_t {
    EdgePlane,          // the edge pq crossing the plane abc (p, q strictly on both sides)
    EdgeProjectedLine,  // the edge pq crossing the line ab, all seen along the axis `dropped`
                        // (p, q strictly on both sides of the line)
    Explicit,           // an exact point given by the caller
    Centroid,           // the centroid of p, q and a: a sample point inside a sub-triangle, for
                        // the winding numbers of a soup (never an output point)
  };
  Kind kind = Kind::Explicit;
  std::int8_t dropped = -1;
  PointId p = 0, q = 0, a = 0, b = 0, c = 0;
};

// Exact homogeneous coordinates of an exact rational point (W = lcm of the denominators), and of a
// point whose coordinates are doubles (W a power of two, no rational arithmetic at all).
Homogeneous homogeneous_of(const ExactPoint& p);
Homogeneous homogeneous_of(const Point& p);
// The constructed point of `recipe` from its parents' homogeneous coordinates.
Homogeneous construct_homogeneous(const Recipe& recipe, const Homogeneous& p, const Homogeneous& q,
                                  const Homogeneous& a, const Homogeneous& b, const Homogeneous& c);
// Cartesian coordinates in lowest terms.
ExactPoint cartesian(const Homogeneous& h);

class PointTable {
 public:
  PointTable() = default;
  // `same_mesh`: a and b are one mesh (a soup against itself): vertex v has one id on both sides.
  PointTable(const Mesh& a, const Mesh& b, bool same_mesh = false);
  PointTable(const PointTable&) = delete;
  PointTable& operator=(const PointTable&) = delete;
  PointTable(PointTable&&) = default;
  PointTable& operator=(PointTable&&) = default;
  ~PointTable();

  PointId vertex(int side, std::uint32_t v) const {
    return side == 0 || same_mesh_ ? v : PointId(num_a_ + v);
  }
  std::size_t num_inputs() const { return num_inputs_; }
  bool same_mesh() const { return same_mesh_; }
  // 0 for a point of a, 1 for b's (an input id).
  int side_of_input(PointId id) const { return id < num_a_ ? 0 : 1; }
  // The input points as doubles, by id, when every input point is one (else empty): for
  // callers that run the static filters themselves on differences they reuse.
  const std::vector<std::array<double, 3>>& input_doubles() const {
    static const std::vector<std::array<double, 3>> none;
    return input_error_ == 0 ? input_xyz_ : none;
  }
  // The input points as doubles, by id, each coordinate within input_error() of the exact one
  // (0 when input_doubles() is not empty); empty when a coordinate's error is not finite. For the
  // filters of callers that bound that error themselves (static_orientation_near's slack).
  const std::vector<std::array<double, 3>>& input_near_doubles() const { return input_xyz_; }
  double input_error() const { return input_error_; }
  std::size_t size() const { return num_inputs_ + recipes_.size(); }
  bool is_input(PointId id) const { return id < num_inputs_; }
  const Recipe& recipe(PointId id) const { return recipes_[id - num_inputs_]; }

  const ApproxPoint& approx(PointId id) const {
    if (id < num_inputs_) return input_approx_[id];
    return approx_[id - num_inputs_];
  }
  // Exact homogeneous coordinates, computed once (thread-safe).
  const Homogeneous& exact(PointId id) const;
  // Whether exact(id) was computed already.
  bool has_exact(PointId id) const {
    return exact_slot(id).load(std::memory_order_acquire) != nullptr;
  }
  // The exact point: the input point itself, or a lazily evaluated construction.
  Point point(PointId id) const;
  const Point& input(PointId id) const {
    return id < num_a_ ? mesh_[0]->points[id] : mesh_[1]->points[id - num_a_];
  }

  // The interval approximation of a construction from the table's points, as add() stores it.
  ApproxPoint approximate(const Recipe& recipe) const;
  // Appends constructed points (sequential); add_all computes the approximations in parallel.
  PointId add(const Recipe& recipe);
  PointId add_all(const std::vector<Recipe>& recipes);  // the id of the first
  PointId add_explicit(const Point& p);

  // Predicates, exact: intervals first, then homogeneous integers.
  CGAL::Sign orientation(PointId p, PointId q, PointId r, PointId s) const {
    const CGAL::Uncertain<CGAL::Sign> o = orientation_filter(p, q, r, s);
    return o.is_certain() ? o.make_certain() : orientation_exact(p, q, r, s);
  }
  // Its two stages, for callers that gather the undecided cases to evaluate each once.
  CGAL::Uncertain<CGAL::Sign> orientation_filter(PointId p, PointId q, PointId r, PointId s) const;
  CGAL::Sign orientation_exact(PointId p, PointId q, PointId r, PointId s) const;
  // orientation(a, b, c, s) for many points s against one plane (a, b, c): the same filters,
  // then the plane's linear form, computed for the first point they leave undecided: four
  // products per point instead of a 4x4 determinant (the points on a flat face of a rational
  // mesh, step 3's undecided corners grouped by facet). In fixed-size integers, or in GMP's
  // when an entry is too large for them. One per thread.
  class PlaneSides {
   public:
    PlaneSides(const PointTable& table, const std::array<PointId, 3>& plane)
        : table_(table), plane_(plane) {}
    CGAL::Sign operator()(PointId s) const;
    CGAL::Sign exact(PointId s) const;  // the stage after the filters

   private:
    const PointTable& table_;
    const std::array<PointId, 3> plane_;
    mutable bool tried_ = false;  // form_ computed (or too large for the buffers)
    mutable std::optional<FixedPlaneForm> form_;
    mutable std::optional<std::array<mpz_class, 4>> equation_;  // when form_ declines
    mutable const InputGrid* grid_ = nullptr;  // with grid_plane_: the inputs on the grid
    mutable std::optional<InputGrid::Plane> grid_plane_;
  };
  // The interval normal (q - p) x (r - p) (the caller rounds upward), and the interval sign of
  // normal . (s - p): orientation(p, q, r, s) when `normal` is the normal of p, q, r.
  ApproxVector approx_normal(PointId p, PointId q, PointId r) const {
    const ApproxPoint& ap = approx(p);
    return CGAL::cross_product(approx(q) - ap, approx(r) - ap);
  }
  CGAL::Uncertain<CGAL::Sign> side_filter(const ApproxVector& normal, PointId p, PointId s) const {
    return CGAL::sign(normal * (approx(s) - approx(p)));
  }
  // orientation of (p, q, r) seen along the axis `dropped` (coordinates u < v of the other two).
  // `lines`: the points' facet, when the caller knows one; it is asked before the exact stage.
  CGAL::Sign orientation_2(int dropped, PointId p, PointId q, PointId r,
                           FacetLines* lines = nullptr) const;
  // CGAL's side_of_oriented_circle of the projected points.
  CGAL::Sign side_of_oriented_circle(int dropped, PointId p, PointId q, PointId r, PointId t) const;
  CGAL::Comparison_result compare(int axis, PointId p, PointId q) const;
  // An input point whose coordinate `axis` is id's exactly by id's recipe (a crossing of an edge,
  // or of a plane, perpendicular to the axis), or id itself. compare() asks these inputs, which
  // is cheap, before constructing exact coordinates: the cut points of a CAD model's face
  // perpendicular to an axis have equal coordinates and overlapping intervals.
  PointId coordinate_source(int axis, PointId id) const;
  bool equal(PointId p, PointId q) const;
  // sign(((a1 - a0) x (a2 - a0)) x ((b1 - b0) x (b2 - b0)) . (q - p)): the order of p and q along
  // the common line of the planes of triangles a and b. `line` is that direction on intervals
  // (the caller computes it once for the several questions of a pair).
  CGAL::Sign along_line(const ApproxVector& line, const std::array<PointId, 3>& a,
                        const std::array<PointId, 3>& b, PointId p, PointId q) const;
  // The sign of the dot product of the normals of triangles a and b (two triangles of one plane:
  // positive when alike oriented).
  CGAL::Sign normal_dot(const std::array<PointId, 3>& a, const std::array<PointId, 3>& b) const;
  // 0, 1 or 2: the axis of the largest normal coordinate of triangle pqr (ties to the lower axis).
  int dominant_axis(PointId p, PointId q, PointId r) const;

 private:
  Homogeneous compute_exact(PointId id) const;
  // The inputs on one integer grid (input_grid.h) when the exact stage has asked about rational
  // inputs often enough to pay for building it (null before that, and when they do not fit one).
  // The thread that asks the question that reaches the count builds it; the others go on without
  // it meanwhile, so nobody waits.
  const InputGrid* input_grid() const;
  struct GridState {
    std::atomic<std::uint32_t> questions{0};
    std::atomic<const InputGrid*> ready{nullptr};
    std::unique_ptr<InputGrid> grid;
  };
  bool all_inputs(std::initializer_list<PointId> ids) const {
    for (const PointId id : ids)
      if (id >= num_inputs_) return false;
    return true;
  }
  CGAL::Sign along_line_exact(const std::array<PointId, 3>& a, const std::array<PointId, 3>& b,
                              PointId p, PointId q) const;
  std::atomic<Homogeneous*>& exact_slot(PointId id) const {
    return id < num_inputs_ ? input_exact_[id] : constructed_exact_[id - num_inputs_];
  }

  const Mesh* mesh_[2] = {nullptr, nullptr};
  bool same_mesh_ = false;
  PointId num_a_ = 0, num_inputs_ = 0;
  // Constructed points by id - num_inputs_ (their references stay valid as points are added).
  StableVector<Recipe> recipes_;
  StableVector<ApproxPoint> approx_;
  std::deque<Point> explicit_;
  std::unique_ptr<std::atomic<Homogeneous*>[]> input_exact_;
  // The inputs' coordinates side by side as doubles, each within input_error_ of the exact one
  // (0: every one is a double), for the static filters that precede the interval stage
  // (static_filter.h).
  std::vector<std::array<double, 3>> input_xyz_;
  double input_error_ = 0;
  // Whether each side's points are all exactly their doubles in input_xyz_ (the exact stages on
  // doubles apply to a side's points even when the other side's are rational; false for both
  // when input_xyz_ is empty).
  bool doubles_[2] = {false, false};
  bool is_double(PointId id) const { return id < num_inputs_ && doubles_[id < num_a_ ? 0 : 1]; }
  // The inputs' interval approximations side by side: predicates read them without following
  // each lazy point to its representation.
  std::vector<ApproxPoint> input_approx_;
  mutable StableVector<std::atomic<Homogeneous*>> constructed_exact_;
  // Only for one rational mesh against itself (the check): doubles have their own exact stage,
  // and a Boolean's two meshes ask too few questions to pay for a grid.
  std::unique_ptr<GridState> grid_state_;
};

// Exact identity among many points: for each of `ids`, the smallest id of `ids` at its exact
// position. Boxes are swept along x; points are compared exactly only where their interval boxes
// overlap, which for points of distinct positions is rare.
std::vector<PointId> coincident_representatives(const PointTable& table,
                                                const std::vector<PointId>& ids);

}  // namespace morphex::detail

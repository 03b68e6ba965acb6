// SPDX-License-Identifier: GPL-3.0-or-later
// round_mesh (morphex/rounding.h): round, find what rounding broke, resolve it exactly, round the
// new points again.
#include "morphex/rounding.h"

#include <mpfr.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

#include "mesh/rounding_check.h"
#include "morphex/check.h"
#include "morphex/internal/stopwatch.h"
#include "morphex/io.h"
#include "morphex/winding.h"

namespace morphex {
namespace {

using Exact = Kernel::Exact_kernel::FT;

// One coordinate as rounding sees it: its interval, and where its exact value is when the interval
// does not decide. Read from the point itself: a coordinate taken as an FT (p.x()) is a new lazy
// number, and its exact value a copy of the rational (most of the cost of rounding a mesh).
struct Coordinate {
  CGAL::Interval_nt<false> approx;
  const Point* point = nullptr;
  int axis = 0;
  const FT* value = nullptr;
  const Exact& exact() const {
    return value ? CGAL::exact(*value) : CGAL::exact(*point).cartesian(axis);
  }
};

// The exact rational rounded once to `bits` of precision, to nearest (ties to even).
double nearest_with_bits(const Exact& exact, int bits) {
  mpfr_t x;
  mpfr_init2(x, bits);
  mpfr_set_q(x, exact.get_mpq_t(), MPFR_RNDN);
  const double d = mpfr_get_d(x, MPFR_RNDN);  // exact: x has at most 53 bits
  mpfr_clear(x);
  return d;
}

// What lib3mf (1.8) reads back from a float it wrote: it multiplies the float by 10^6 in float
// arithmetic, cuts that to an integer and prints it with six decimals (the float nearest 0.063531,
// 0.0635309964, is written 0.063530; -180.61083984375 is written -180.610832), and its reader
// parses the text as the nearest float.
// The float nearest k / 10^6, as strtof reads the text: the double quotient is correctly rounded,
// and rounding it to a float is right unless it fell exactly between two floats (then the text).
float nearest_float_of_micros(long long k) {
  const double q = double(k) / 1e6;
  const float f = float(q);
  const float other = std::nextafter(f, q > double(f) ? HUGE_VALF : -HUGE_VALF);
  if (double(f) != q && (double(f) + double(other)) / 2 == q) {
    char text[64];
    const unsigned long long units = static_cast<unsigned long long>(k < 0 ? -k : k);
    std::snprintf(text, sizeof text, "%s%llu.%06llu", k < 0 ? "-" : "", units / 1000000,
                  units % 1000000);
    return std::strtof(text, nullptr);
  }
  return f;
}

float three_mf_reread(float f) {
  const volatile float scaled = f * 1e6f;  // in float, as lib3mf does (volatile: no wider math)
  if (!(std::fabs(scaled) < 9e15f)) return NAN;  // beyond what the quotient above keeps exact
  return nearest_float_of_micros(static_cast<long long>(scaled));
}

// The value nearest x that survives lib3mf's round trip unchanged: a float f whose written decimal
// reads back as f. Not every float and not every six-decimal number has one, so the grid is 1e-6
// (or the float's spacing, when coarser) with gaps: a coordinate moves by a few grid steps at
// most. Candidates: the floats nearest the decimals around x, and the floats around x.
double three_mf_value(double x) {
  if (!(std::fabs(x) < 9e9)) return HUGE_VAL;
  constexpr int kReach = 16;
  double best = HUGE_VAL;
  auto consider = [&](float f) {
    if (three_mf_reread(f) == f && std::fabs(double(f) - x) < std::fabs(best - x)) best = f;
  };
  const long long k0 = std::llround(x * 1e6);
  for (long long k = k0 - kReach; k <= k0 + kReach; ++k) consider(nearest_float_of_micros(k));
  float up = float(x), down = up;
  for (int step = 0; step < kReach; ++step) {
    consider(up);
    consider(down);
    up = std::nextafter(up, HUGE_VALF);
    down = std::nextafter(down, -HUGE_VALF);
  }
  return best;
}

}  // namespace

namespace {

// The nearest double. A coordinate's interval is (after make_exact) two neighbouring doubles:
// the exact value against their midpoint decides, a comparison of rationals whose second one is
// a sum of doubles, much cheaper than dividing the exact numerator by its denominator.
double nearest_double(const Coordinate& value) {
  const auto& a = value.approx;
  if (a.is_point()) return a.inf();  // a double already (every coordinate read from a file)
  const double lo = a.inf(), hi = a.sup();
  if (!std::isfinite(lo) || !std::isfinite(hi) || std::nextafter(lo, HUGE_VAL) != hi)
    return nearest_with_bits(value.exact(), 53);
  // Scratch rationals of each thread: their limbs are allocated once, not per coordinate.
  thread_local struct Scratch {
    mpq_t lo, hi;
    Scratch() {
      mpq_init(lo);
      mpq_init(hi);
    }
    ~Scratch() {
      mpq_clear(lo);
      mpq_clear(hi);
    }
  } q;
  mpq_set_d(q.lo, lo);
  mpq_set_d(q.hi, hi);
  mpq_add(q.lo, q.lo, q.hi);
  mpq_div_2exp(q.lo, q.lo, 1);  // the midpoint
  const int side = mpq_cmp(value.exact().get_mpq_t(), q.lo);
  if (side != 0) return side < 0 ? lo : hi;
  std::uint64_t bits;  // a tie: to the even one
  std::memcpy(&bits, &lo, sizeof bits);
  return (bits & 1) == 0 ? lo : hi;
}

// The nearest float: rounding is monotone, so when both ends of the interval round to one float
// every value between them does; otherwise once from the exact value (rounding its nearest double
// again could land a float away at a tie).
double nearest_float(const Coordinate& value) {
  const auto& a = value.approx;
  if (std::fabs(a.inf()) <= FLT_MAX && std::fabs(a.sup()) <= FLT_MAX &&
      float(a.inf()) == float(a.sup()))
    return float(a.inf());
  return nearest_with_bits(value.exact(), 24);
}

double on_grid(const Coordinate& value, RoundingGrid grid) {
  if (grid == RoundingGrid::Double) return nearest_double(value);
  const double d = nearest_float(value);
  if (std::fabs(d) > FLT_MAX) return d > 0 ? HUGE_VAL : -HUGE_VAL;
  const float f = float(d);  // exact unless subnormal
  return grid == RoundingGrid::Float ? double(f) : three_mf_value(d);
}

}  // namespace

double round_coordinate(const FT& value, RoundingGrid grid) {
  Coordinate c;
  c.approx = CGAL::approx(value);
  c.value = &value;
  return on_grid(c, grid);
}

namespace {

// At most 2^6 grid steps for a new point: the bound of the displacement that rounding reports.
constexpr std::size_t kMaxDrop = 6;
// Rounds without a new low of the damage before the grid of new points grows by a bit.
constexpr std::size_t kStalledRounds = 3;

// A new point (off the grid) rounded `drop` bits coarser than the grid: a value of the format
// still, on a sparser grid, so that points that keep meeting near a contact fall onto one point.
double round_coarser(const Coordinate& value, RoundingGrid grid, int drop) {
  if (grid == RoundingGrid::ThreeMf) {  // the decimals' grid, 2^drop steps of 1e-6 apart
    const double step = std::ldexp(1e-6, drop);
    return three_mf_value(std::nearbyint(nearest_double(value) / step) * step);
  }
  const int bits = (grid == RoundingGrid::Double ? 53 : 24) - drop;
  const double d = nearest_with_bits(value.exact(), std::max(bits, 2));
  if (grid == RoundingGrid::Double) return d;
  if (std::fabs(d) > FLT_MAX) return d > 0 ? HUGE_VAL : -HUGE_VAL;
  return d;
}

const char* grid_name(RoundingGrid grid) {
  switch (grid) {
    case RoundingGrid::Double:
      return "doubles (plain OFF, OBJ, PLY)";
    case RoundingGrid::Float:
      return "32-bit floats (STL, glb)";
    case RoundingGrid::ThreeMf:
      return "3MF (floats printed with six decimals by lib3mf)";
  }
  return "";
}

// Every point on the grid, in parallel blocks, the coordinates that are not on it `drop` bits
// coarser; returns how many moved and the largest change of a coordinate. Throws
// LossyOutputError when a coordinate leaves the grid's range.
std::size_t round_points(const Mesh& mesh, RoundingGrid grid, int drop, DoubleMesh& out,
                         std::vector<std::uint8_t>& moved_flags, double& largest) {
  out.points.resize(mesh.points.size());
  moved_flags.assign(mesh.points.size(), 0);
  out.triangles = mesh.triangles;
  std::atomic<std::size_t> moved{0}, overflow{SIZE_MAX};
  std::atomic<double> max_change{0};
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, mesh.points.size(), 4096), [&](auto r) {
    std::size_t block_moved = 0;
    double block_change = 0;
    for (std::size_t v = r.begin(); v != r.end(); ++v) {
      bool changed = false;
      const auto& approx = CGAL::approx(mesh.points[v]);
      for (int c = 0; c < 3; ++c) {
        const Coordinate x{approx.cartesian(c), &mesh.points[v], c};
        const auto& a = x.approx;
        double d = on_grid(x, grid);
        if (drop > 0 && !(a.is_point() && a.inf() == d)) d = round_coarser(x, grid, drop);
        out.points[v][c] = d;
        if (!std::isfinite(d)) {
          std::size_t none = SIZE_MAX;
          overflow.compare_exchange_strong(none, v);
          continue;
        }
        if (a.is_point() && a.inf() == d) continue;
        changed = true;
        block_change =
            std::max(block_change, std::max(std::fabs(a.inf() - d), std::fabs(a.sup() - d)));
      }
      block_moved += changed;
      moved_flags[v] = changed;
    }
    moved += block_moved;
    double seen = max_change.load();
    while (block_change > seen && !max_change.compare_exchange_weak(seen, block_change)) {
    }
  });
  if (overflow != SIZE_MAX)
    throw LossyOutputError("", std::string("the result cannot be written as ") + grid_name(grid) +
                                   ": vertex " + std::to_string(overflow.load()) +
                                   " lies outside the format's range");
  largest = max_change;
  return moved;
}

double to_double_volume(const FT& v) {
  return CGAL::to_double(v);
}

// The solid the rounded chain winds around, intersecting only the broken pairs; if the
// arrangement of those alone is inconsistent (a contact the pair tests did not list, seen on
// 3MF's coarse grid), once more with every pair searched, as repair does.
Mesh resolve(const Mesh& chain, const std::vector<std::pair<std::uint32_t, std::uint32_t>>& pairs,
             RoundingGrid grid) {
  WindingOptions winding;
  winding.pairs = &pairs;
  try {
    return winding_solid(chain, {}, winding);
  } catch (const std::logic_error&) {
  }
  try {
    return winding_solid(chain);
  } catch (const std::logic_error& e) {
    throw LossyOutputError("", std::string("the result cannot be written as ") + grid_name(grid) +
                                   ": the rounded mesh could not be resolved (" + e.what() +
                                   "); write a finer format or the exact OFF");
  }
}

}  // namespace

RoundedMesh round_mesh(const Mesh& mesh, const RoundingOptions& options) {
  RoundedMesh out;
  RoundingReport& r = out.report;
  Mesh resolved;  // the exact solid of the latest round, once one had to be resolved
  const Mesh* current = &mesh;
  Stopwatch clock;
  // When the damage has not reached a new low for a few rounds (points that keep meeting near a
  // contact finer than the grid, in a cycle), new points are rounded a bit coarser (snap
  // rounding's hot pixels grown) so that they land on one point. Coarser points reach further
  // and can break more, so the grid only grows when the rounds stall, one bit at a time.
  int drop = 0;
  std::size_t least_damage = SIZE_MAX, stalled = 0;
  for (;;) {
    double change = 0;
    std::vector<std::uint8_t> moved_flags;
    const std::size_t moved =
        round_points(*current, options.grid, drop, out.mesh, moved_flags, change);
    if (r.rounds == 0) r.moved_vertices = moved;
    r.max_displacement += change;
    r.seconds_round += clock.lap();
    if (moved == 0) break;  // on the grid already: the valid solid itself
    const detail::RoundingDamage damage =
        detail::find_rounding_damage(*current, out.mesh, moved_flags);
    r.seconds_check += clock.lap();
    if (damage.none()) break;
    // Only a valid solid has a solid to keep: anything else (an open surface written from
    // Python, say) is rounded as it is.
    if (r.rounds == 0 && !check_mesh(mesh, kValidityOnly).valid_solid()) {
      r.not_a_solid = true;
      break;
    }
    if (r.rounds == options.max_rounds)
      throw LossyOutputError(
          "", std::string("the result cannot be written as ") + grid_name(options.grid) +
                  ": rounding did not settle in " + std::to_string(options.max_rounds) +
                  " rounds (a contact finer than the format's spacing keeps coming "
                  "back); write a finer format (STL or glb floats, OFF, OBJ or PLY "
                  "doubles) or the exact OFF");
    const std::size_t size = damage.pairs.size() + damage.flattened_faces + damage.turned_shells;
    stalled = size < least_damage ? 0 : stalled + 1;
    least_damage = std::min(least_damage, size);
    if (stalled == kStalledRounds && drop < int(kMaxDrop)) {
      ++drop;
      stalled = 0;
    }
    ++r.rounds;
    r.broken_pairs += damage.pairs.size();
    r.flattened_faces += damage.flattened_faces;
    // The rounded mesh is a closed chain (rounding merges vertices, never opens an edge): the
    // solid it winds around, with only the broken pairs intersected.
    resolved = resolve(from_double(out.mesh), damage.pairs, options.grid);
    make_exact(resolved);
    current = &resolved;
    r.seconds_resolve += clock.lap();
  }
  r.collapsed = out.mesh.triangles.empty() && !mesh.triangles.empty();
  if (options.measure_volume) {
    r.volume_measured = true;
    if (r.moved_vertices == 0) return out;  // the same solid: no change to measure
    const FT before = signed_volume(mesh);
    const FT change = signed_volume(from_double(out.mesh)) - before;
    // + 0.0: an exact zero is reported as 0, not -0.
    r.volume_change = to_double_volume(change) + 0.0;
    r.relative_volume_change = CGAL::is_zero(before) ? 0 : to_double_volume(change / before) + 0.0;
  }
  return out;
}

}  // namespace morphex

// SPDX-License-Identifier: GPL-3.0-or-later
// Manifold (github.com/elalish/manifold, floating point) as an optional benchmark peer of the
// exact Booleans and morphology: bench_bool and bench_morph compile manifold_peer.cpp only when
// CMake finds a Manifold built by tools/peers/build-manifold, and define MORPHEX_HAVE_MANIFOLD.
// Without it these functions report that Manifold is absent, and the Manifold columns say "n/a".
#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "morphex/boolean.h"
#include "morphex/mesh.h"

namespace morphex::peers {

struct ManifoldResult {
  double seconds = 0;  // the operation alone, with its lazy evaluation forced; no conversions
  double volume = 0;   // floating point: compare it to an exact volume with a tolerance
  std::size_t triangles = 0;  // the result's
};

// One step of a chain of Manifold's Minkowski operations by `b`: MinkowskiSum, a + b, or
// (`difference`) MinkowskiDifference, a less the sweep of b over a's surface: a - (dA + b). That
// is morphex's erosion by -b (morphex/morphology.h): pass the reflected structuring element.
struct MinkowskiStep {
  const Mesh* b = nullptr;
  bool difference = false;
};

// Times one operation: called with a function that runs it once and returns its seconds, returns
// the seconds to report (bench_bool's median over repeated runs). The default runs it once.
using Timing = std::function<double(const std::function<double()>& once)>;

#ifdef MORPHEX_HAVE_MANIFOLD
inline constexpr bool kHaveManifold = true;
// Manifold's version, as its headers state it ("3.5.1").
std::string manifold_version();
// a op b: both inputs are converted to MeshGL64 (every coordinate rounded to a double) and to
// Manifolds off the clock. Empty when Manifold refuses an input or fails on the result; `why`
// then says so (Manifold's Status).
std::optional<ManifoldResult> manifold_boolean(const Mesh& a, const Mesh& b, BooleanOp op,
                                               const Timing& timing = {},
                                               std::string* why = nullptr);
// a + b or (`difference`) a - (dA + b), as manifold_boolean times the Boolean: the conversions
// off the clock, the operation (eager in Manifold) and its result's status on it.
std::optional<ManifoldResult> manifold_minkowski(const Mesh& a, const Mesh& b, bool difference,
                                                 const Timing& timing = {},
                                                 std::string* why = nullptr);
// The steps applied in order, each to the previous result (an opening: the difference, then the
// sum), all of them timed together; the intermediate results stay Manifold's floating point.
std::optional<ManifoldResult> manifold_minkowski_chain(const Mesh& a,
                                                       const std::vector<MinkowskiStep>& steps,
                                                       const Timing& timing = {},
                                                       std::string* why = nullptr);
#else
inline constexpr bool kHaveManifold = false;
inline std::string manifold_version() {
  return "n/a";
}
inline std::optional<ManifoldResult> manifold_boolean(const Mesh&, const Mesh&, BooleanOp,
                                                      const Timing& = {},
                                                      std::string* why = nullptr) {
  if (why) *why = "not built with Manifold";
  return std::nullopt;
}
inline std::optional<ManifoldResult> manifold_minkowski(const Mesh&, const Mesh&, bool,
                                                        const Timing& = {},
                                                        std::string* why = nullptr) {
  if (why) *why = "not built with Manifold";
  return std::nullopt;
}
inline std::optional<ManifoldResult> manifold_minkowski_chain(const Mesh&,
                                                              const std::vector<MinkowskiStep>&,
                                                              const Timing& = {},
                                                              std::string* why = nullptr) {
  if (why) *why = "not built with Manifold";
  return std::nullopt;
}
#endif

}  // namespace morphex::peers

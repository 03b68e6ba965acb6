// SPDX-License-Identifier: GPL-3.0-or-later
// Manifold (github.com/elalish/manifold, floating point) as an optional benchmark peer of the
// exact Booleans: bench_bool compiles manifold_peer.cpp only when CMake finds a Manifold built by
// tools/peers/build-manifold, and defines MORPHEX_HAVE_MANIFOLD. Without it these functions
// report that Manifold is absent, and the benchmark's Manifold columns say "n/a".
#pragma once

#include <functional>
#include <optional>
#include <string>

#include "morphex/boolean.h"
#include "morphex/mesh.h"

namespace morphex::peers {

struct ManifoldResult {
  double seconds = 0;  // the Boolean alone, with its lazy evaluation forced; no conversions
  double volume = 0;   // floating point: compare it to an exact volume with a tolerance
};

// Times one Boolean: called with a function that runs it once and returns its seconds, returns
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
#endif

}  // namespace morphex::peers

// SPDX-License-Identifier: GPL-3.0-or-later
// Can a plain format hold this mesh? Plain formats round every coordinate (to doubles, to floats,
// or to lib3mf's six decimals); a result whose vertices are closer than that rounding re-reads as
// another mesh, usually an invalid one (a cube dilated by 1e300 loses its unit-sized features).
// Writing such a file silently would hand the user a broken result: it is refused instead.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <cmath>
#include <cstring>
#include <unordered_map>

#include "io_text.h"

namespace morphex {
namespace detail {
namespace {

[[noreturn]] void refuse(const std::string& name, const std::string& format,
                         const std::string& problem) {
  throw LossyOutputError(name + ": the result cannot be written as " + format + ": " + problem +
                         "; write the exact format instead (--exact with a .off output)");
}

}  // namespace

void check_rounded(const Mesh& exact, const DoubleMesh& rounded, const std::string& name,
                   const std::string& format) {
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  std::unordered_map<std::array<double, 3>, std::size_t, DoublePointHash> seen;
  seen.reserve(rounded.points.size());
  for (std::size_t v = 0; v < rounded.points.size(); ++v) {
    const auto& p = rounded.points[v];
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
      refuse(name, format, "vertex " + std::to_string(v) + " overflows its range");
    const auto [it, inserted] = seen.emplace(std::array<double, 3>{p[0], p[1], p[2]}, v);
    // Vertices that were one exact point already are the input's business, not the format's.
    if (!inserted && exact.points[it->second] != exact.points[v])
      refuse(name, format,
             "rounding makes vertices " + std::to_string(it->second) + " and " + std::to_string(v) +
                 " one point");
  }
  for (std::size_t f = 0; f < rounded.triangles.size(); ++f) {
    const Triangle& t = rounded.triangles[f];
    K::Point_3 q[3];
    for (int k = 0; k < 3; ++k) {
      const auto& p = rounded.points[t[k]];
      q[k] = K::Point_3(p[0], p[1], p[2]);
    }
    const Triangle& e = exact.triangles[f];
    if (CGAL::collinear(q[0], q[1], q[2]) &&
        !CGAL::collinear(exact.points[e[0]], exact.points[e[1]], exact.points[e[2]]))
      refuse(name, format, "rounding flattens face " + std::to_string(f) + " to a line");
  }
}

}  // namespace detail

void check_representable(const Mesh& mesh, bool to_float, const std::string& name) {
  DoubleMesh rounded = to_double(mesh);
  if (to_float)
    for (auto& p : rounded.points)
      for (double& c : p) {
        // Through memory: GCC at -O3 with -frounding-math was seen to drop the float round trip.
        volatile float f = float(c);
        c = f;
      }
  detail::check_rounded(mesh, rounded, name,
                        to_float ? "32-bit floats (STL, glb)" : "doubles (plain OFF, OBJ, PLY)");
}

}  // namespace morphex

// SPDX-License-Identifier: GPL-3.0-or-later
// Manifold as a benchmark peer (see manifold_peer.h). Compiled only with MORPHEX_HAVE_MANIFOLD.
#include "manifold_peer.h"

#include <manifold/manifold.h>
#include <manifold/version.h>

#include <vector>

#include "morphex/internal/stopwatch.h"

namespace morphex::peers {

namespace {

// Manifold names its errors only in debug builds (ToString needs MANIFOLD_DEBUG).
std::string error_name(manifold::Manifold::Error error) {
  using E = manifold::Manifold::Error;
  switch (error) {
    case E::NoError:
      return "no error";
    case E::NonFiniteVertex:
      return "non-finite vertex";
    case E::NotManifold:
      return "not manifold";
    case E::VertexOutOfBounds:
      return "vertex out of bounds";
    case E::InvalidConstruction:
      return "invalid construction";
    case E::ResultTooLarge:
      return "result too large";
    default:
      return "error " + std::to_string(int(error));
  }
}

// Every coordinate rounded to a double (CGAL's interval midpoint, see morphex::to_double), the
// triangles as they are: a morphex solid is a closed 2-manifold by its indices, as Manifold asks.
manifold::MeshGL64 to_meshgl(const Mesh& mesh) {
  const DoubleMesh rounded = to_double(mesh);
  manifold::MeshGL64 out;
  out.numProp = 3;
  out.vertProperties.reserve(3 * rounded.points.size());
  for (const auto& p : rounded.points)
    out.vertProperties.insert(out.vertProperties.end(), p.begin(), p.end());
  out.triVerts.reserve(3 * rounded.triangles.size());
  for (const Triangle& t : rounded.triangles)
    out.triVerts.insert(out.triVerts.end(), t.begin(), t.end());
  return out;
}

manifold::OpType to_op_type(BooleanOp op) {
  switch (op) {
    case BooleanOp::Union:
      return manifold::OpType::Add;
    case BooleanOp::Intersection:
      return manifold::OpType::Intersect;
    case BooleanOp::Difference:
      return manifold::OpType::Subtract;
  }
  return manifold::OpType::Add;
}

// Whether Manifold took the input; `why` says otherwise ("input A: not manifold").
bool accepted(const manifold::Manifold& input, const std::string& name, std::string* why) {
  if (input.Status() == manifold::Manifold::Error::NoError) return true;
  if (why) *why = "input " + name + ": " + error_name(input.Status());
  return false;
}

// The timed result as reported: empty when Manifold failed on it (`why` says how).
std::optional<ManifoldResult> reported(const manifold::Manifold& result, double seconds,
                                       std::string* why) {
  if (result.Status() != manifold::Manifold::Error::NoError) {
    if (why) *why = "result: " + error_name(result.Status());
    return std::nullopt;
  }
  return ManifoldResult{seconds, result.Volume(), result.NumTri()};
}

}  // namespace

std::string manifold_version() {
  return std::to_string(MANIFOLD_VERSION_MAJOR) + "." + std::to_string(MANIFOLD_VERSION_MINOR) +
         "." + std::to_string(MANIFOLD_VERSION_PATCH);
}

std::optional<ManifoldResult> manifold_boolean(const Mesh& a, const Mesh& b, BooleanOp op,
                                               const Timing& timing, std::string* why) {
  const manifold::Manifold ma(to_meshgl(a)), mb(to_meshgl(b));
  if (!accepted(ma, "A", why) || !accepted(mb, "B", why)) return std::nullopt;
  manifold::Manifold result;
  auto once = [&] {
    result = manifold::Manifold();  // the previous result is freed off the clock
    const Stopwatch start;
    result = ma.Boolean(mb, to_op_type(op));
    // Manifold builds a CSG tree and evaluates it on demand: Status() forces the Boolean, so the
    // time is the whole operation, as morphex's. Exporting the result (GetMeshGL) is not timed,
    // as the conversions of the inputs are not.
    result.Status();
    return start.seconds();
  };
  const double seconds = timing ? timing(once) : once();
  return reported(result, seconds, why);
}

std::optional<ManifoldResult> manifold_minkowski(const Mesh& a, const Mesh& b, bool difference,
                                                 const Timing& timing, std::string* why) {
  return manifold_minkowski_chain(a, {MinkowskiStep{&b, difference}}, timing, why);
}

std::optional<ManifoldResult> manifold_minkowski_chain(const Mesh& a,
                                                       const std::vector<MinkowskiStep>& steps,
                                                       const Timing& timing, std::string* why) {
  const manifold::Manifold ma(to_meshgl(a));
  if (!accepted(ma, "A", why)) return std::nullopt;
  std::vector<manifold::Manifold> bs;
  for (const MinkowskiStep& step : steps) {
    bs.emplace_back(to_meshgl(*step.b));
    if (!accepted(bs.back(), "B", why)) return std::nullopt;
  }
  manifold::Manifold result;
  auto once = [&] {
    result = manifold::Manifold();  // the previous result is freed off the clock
    const Stopwatch start;
    result = ma;
    // MinkowskiSum and MinkowskiDifference are eager (their pieces' Booleans are evaluated
    // inside); Status() forces whatever remains, as in manifold_boolean.
    for (std::size_t i = 0; i < steps.size(); ++i)
      result = steps[i].difference ? result.MinkowskiDifference(bs[i]) : result.MinkowskiSum(bs[i]);
    result.Status();
    return start.seconds();
  };
  const double seconds = timing ? timing(once) : once();
  return reported(result, seconds, why);
}

}  // namespace morphex::peers

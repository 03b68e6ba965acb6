// SPDX-License-Identifier: GPL-3.0-or-later
// Manifold as a benchmark peer (see manifold_peer.h). Compiled only with MORPHEX_HAVE_MANIFOLD.
#include "manifold_peer.h"

#include <manifold/manifold.h>
#include <manifold/version.h>

#include <utility>

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

}  // namespace

std::string manifold_version() {
  return std::to_string(MANIFOLD_VERSION_MAJOR) + "." + std::to_string(MANIFOLD_VERSION_MINOR) +
         "." + std::to_string(MANIFOLD_VERSION_PATCH);
}

std::optional<ManifoldResult> manifold_boolean(const Mesh& a, const Mesh& b, BooleanOp op,
                                               const Timing& timing, std::string* why) {
  const manifold::Manifold ma(to_meshgl(a)), mb(to_meshgl(b));
  for (const auto& [input, name] : {std::pair{&ma, "A"}, std::pair{&mb, "B"}})
    if (input->Status() != manifold::Manifold::Error::NoError) {
      if (why) *why = std::string("input ") + name + ": " + error_name(input->Status());
      return std::nullopt;
    }
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
  ManifoldResult out;
  out.seconds = timing ? timing(once) : once();
  if (result.Status() != manifold::Manifold::Error::NoError) {
    if (why) *why = "result: " + error_name(result.Status());
    return std::nullopt;
  }
  out.volume = result.Volume();
  return out;
}

}  // namespace morphex::peers

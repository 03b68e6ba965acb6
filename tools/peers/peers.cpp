// SPDX-License-Identifier: GPL-3.0-or-later
#include "peers.h"
#include "morphex/stopwatch.h"

#include "nef.h"  // before minkowski_sum_3.h, which needs the Nef headers first

#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/minkowski_sum_3.h>

#include <chrono>
#include <exception>

#include "surface_mesh.h"

namespace morphex::peers {
namespace {

namespace PMP = CGAL::Polygon_mesh_processing;

}  // namespace

PeerResult nef_boolean(const Mesh& a, const Mesh& b, BooleanOp op) {
  const Stopwatch start;
  const NefPolyhedron na = to_nef(a), nb = to_nef(b);
  const NefPolyhedron r = op == BooleanOp::Union          ? na + nb
                          : op == BooleanOp::Intersection ? na * nb
                                                          : na - nb;
  const double seconds = start.seconds();
  return {signed_volume(from_nef(r)), seconds};
}

std::optional<PeerResult> corefinement_boolean(const Mesh& a, const Mesh& b, BooleanOp op) {
  SurfaceMesh sa = to_surface_mesh(a), sb = to_surface_mesh(b), out;
  bool ok = false;
  const Stopwatch start;
  try {
    ok = op == BooleanOp::Union          ? PMP::corefine_and_compute_union(sa, sb, out)
         : op == BooleanOp::Intersection ? PMP::corefine_and_compute_intersection(sa, sb, out)
                                         : PMP::corefine_and_compute_difference(sa, sb, out);
  } catch (const std::exception&) {
    ok = false;
  }
  const double seconds = start.seconds();
  if (!ok) return std::nullopt;
  return PeerResult{PMP::volume(out), seconds};
}

PeerResult nef_minkowski_sum(const Mesh& a, const Mesh& b) {
  NefPolyhedron na = to_nef(a), nb = to_nef(b);
  const Stopwatch start;
  const NefPolyhedron sum = CGAL::minkowski_sum_3(na, nb);
  const double seconds = start.seconds();
  return {signed_volume(from_nef(sum)), seconds};
}

bool cgal_does_self_intersect(const Mesh& mesh) {
  return PMP::does_self_intersect(to_surface_mesh(mesh));
}

}  // namespace morphex::peers

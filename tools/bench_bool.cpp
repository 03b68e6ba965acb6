// SPDX-License-Identifier: GPL-3.0-or-later
// bench_bool A B [--rotate DEG] [--translate X Y Z] [--op union|intersection|difference]
// Times morphex against CGAL corefinement (Epeck) on the same input in the same process, and
// checks that both give the same exact volume. B is moved by an exact rational rotation about
// the axis (1, 1, 1)-ish built from a Pythagorean-like tangent, then translated.
#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Surface_mesh.h>

#include <chrono>
#include <cmath>
#include <iostream>
#include <string>

#include "morphex/boolean.h"
#include "morphex/check.h"
#include "morphex/generators.h"
#include "morphex/io.h"
#include "morphex/surface_mesh.h"

using namespace morphex;
namespace PMP = CGAL::Polygon_mesh_processing;

namespace {
double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Exact rotation about z then x by the rational angle whose half-tangent is t: cos =
// (1-t^2)/(1+t^2).
Transformation rational_rotation(double degrees) {
  const FT t = FT(std::round(std::tan(degrees * 3.14159265358979 / 360) * 1000)) / 1000;
  const FT c = (1 - t * t) / (1 + t * t), s = 2 * t / (1 + t * t);
  const Transformation rz(c, -s, 0, s, c, 0, 0, 0, 1);
  const Transformation rx(1, 0, 0, 0, c, -s, 0, s, c);
  return rx * rz;
}
}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::cerr << "usage: bench_bool A B [--rotate DEG] [--translate X Y Z] [--op OP]\n";
    return 2;
  }
  Mesh a = read_mesh(argv[1]), b = read_mesh(argv[2]);
  double degrees = 0;
  Vector offset(0, 0, 0);
  BooleanOp op = BooleanOp::Union;
  for (int i = 3; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--rotate" && i + 1 < argc)
      degrees = std::stod(argv[++i]);
    else if (arg == "--translate" && i + 3 < argc) {
      offset = Vector(std::stod(argv[i + 1]), std::stod(argv[i + 2]), std::stod(argv[i + 3]));
      i += 3;
    } else if (arg == "--op" && i + 1 < argc)
      op = parse_boolean_op(argv[++i]);
  }
  if (degrees != 0) b = transformed(b, rational_rotation(degrees));
  b = translated(b, offset);
  make_exact(b);

  auto start = std::chrono::steady_clock::now();
  const BooleanResult r = compute_boolean(a, b, op);
  const double ours = seconds_since(start);
  if (!r.ok()) {
    std::cerr << r.message << '\n';
    return 1;
  }
  const FT our_volume = signed_volume(r.mesh);

  SurfaceMesh sa = to_surface_mesh(a), sb = to_surface_mesh(b), out;
  start = std::chrono::steady_clock::now();
  const bool ok = op == BooleanOp::Union ? PMP::corefine_and_compute_union(sa, sb, out)
                  : op == BooleanOp::Intersection
                      ? PMP::corefine_and_compute_intersection(sa, sb, out)
                      : PMP::corefine_and_compute_difference(sa, sb, out);
  const double theirs = seconds_since(start);
  const bool agree = ok && PMP::volume(out) == our_volume;
  const auto& s = r.stats.seconds;
  std::cout << "input triangles " << a.num_triangles() << " + " << b.num_triangles() << ", "
            << to_string(op) << ", cut facets " << r.stats.cut_facets_a + r.stats.cut_facets_b
            << ", patches " << r.stats.patches << " (" << r.stats.patches_by_orientation_rule
            << " by the orientation rule, " << r.stats.patches_by_ray_cast << " by ray cast)"
            << "\nmorphex      " << ours << " s (validate " << s.validate << ", pairs " << s.pairs
            << ", segments " << s.segments << ", retriangulate " << s.retriangulate << ", classify "
            << s.classify << ", assemble " << s.assemble << ")"
            << "\ncorefinement " << theirs << " s" << (ok ? "" : " (failed)")
            << "\nratio (corefinement / morphex) " << theirs / ours
            << "\nexact volumes agree: " << (agree ? "yes" : "NO") << " ("
            << CGAL::to_double(our_volume) << ")\n";
  return agree ? 0 : 1;
}

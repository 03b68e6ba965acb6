// SPDX-License-Identifier: GPL-3.0-or-later
// Multi-scale granulometries by exact openings and closings with cubes, where their residues lie,
// and the D2 shape distribution (descriptors.h has the definitions).
#include "morphex/descriptors.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>
#include <sstream>
#include <stdexcept>

#include "descriptor_internal.h"
#include "morphex/check.h"
#include "morphex/descriptor_settings.h"
#include "morphex/internal/union_find.h"
#include "morphex/morphology.h"
#include "morphex/progress.h"
#include "morphex/shapes.h"
#include "morphex/simplify.h"
#include "morphology_internal.h"

namespace morphex {
namespace {

// Volume, first and second moments of a solid: integrals of 1, x_i and x_i^2 over it.
struct Moments {
  double volume = 0;
  Eigen::Vector3d first = Eigen::Vector3d::Zero(), second = Eigen::Vector3d::Zero();

  Moments operator-(const Moments& o) const {
    return {volume - o.volume, first - o.first, second - o.second};
  }
};

// By the signed tetrahedra (0, a, b, c) of the faces: volume det/6, integral of x = volume
// (a + b + c) / 4, integral of x_i^2 = volume / 20 (a_i^2 + b_i^2 + c_i^2 + (a_i + b_i + c_i)^2).
// The Booleans may list the same faces in another order from one run to the next (parallel
// assembly), so each face starts at its least corner and the terms are summed in sorted order:
// the same solid always gets the same bits, and a copy of an indexed mesh is at distance 0.
Moments moments_of(const Mesh& solid) {
  const DoubleMesh m = to_double(solid);
  std::vector<std::array<double, 7>> terms;
  terms.reserve(m.triangles.size());
  for (const Triangle& t : m.triangles) {
    int first = 0;
    for (int k = 1; k < 3; ++k)
      if (m.points[t[k]] < m.points[t[first]]) first = k;
    Eigen::Vector3d p[3];
    for (int k = 0; k < 3; ++k) {
      const auto& q = m.points[t[(first + k) % 3]];
      p[k] = Eigen::Vector3d(q[0], q[1], q[2]);
    }
    const double v = p[0].dot(p[1].cross(p[2])) / 6.0;
    const Eigen::Vector3d sum = p[0] + p[1] + p[2];
    const Eigen::Vector3d first_moment = v * sum / 4.0;
    const Eigen::Vector3d second_moment =
        v / 20.0 * (p[0].cwiseAbs2() + p[1].cwiseAbs2() + p[2].cwiseAbs2() + sum.cwiseAbs2());
    terms.push_back({v, first_moment[0], first_moment[1], first_moment[2], second_moment[0],
                     second_moment[1], second_moment[2]});
  }
  std::sort(terms.begin(), terms.end());
  Moments out;
  for (const auto& x : terms) {
    out.volume += x[0];
    out.first += Eigen::Vector3d(x[1], x[2], x[3]);
    out.second += Eigen::Vector3d(x[4], x[5], x[6]);
  }
  return out;
}

std::size_t component_count(const Mesh& m) {
  UnionFind sets(m.points.size());
  for (const Triangle& t : m.triangles) {
    sets.join(t[0], t[1]);
    sets.join(t[0], t[2]);
  }
  std::vector<bool> root(m.points.size(), false);
  std::size_t count = 0;
  for (const Triangle& t : m.triangles) {
    const auto r = sets.find(t[0]);
    if (!root[r]) ++count;
    root[r] = true;
  }
  return count;
}

// The 6 numbers saying where a part (residue or filled gap) of moments `part` lies, relative to
// the solid of moments `whole` (volume 1 and L = 1 in the descriptor's frame): its second moments
// about the solid's centroid along each axis, and |offset of its centroid| times its volume.
void append_placement(std::vector<double>& out, const Moments& part, const Moments& whole) {
  const Eigen::Vector3d c = whole.first / whole.volume;
  for (int k = 0; k < 3; ++k)
    out.push_back(
        std::max(0.0, part.second[k] - 2 * c[k] * part.first[k] + c[k] * c[k] * part.volume) /
        whole.volume);
  for (int k = 0; k < 3; ++k)
    out.push_back(std::abs(part.first[k] - c[k] * part.volume) / whole.volume);
}

std::vector<double> geometric(double from, double to, int n) {
  std::vector<double> out;
  for (int k = 0; k < n; ++k)
    out.push_back(n == 1 ? from : from * std::pow(to / from, double(k) / double(n - 1)));
  return out;
}

StructuringElement cube_of(const FT& half_side) {
  StructuringElement se;
  se.shape = "cube";
  se.mesh = make_cube(half_side);
  se.convex = true;
  return se;
}

// The copy that is filtered: posed and scaled to unit volume in double precision, simplified to
// the budget; the exact rotation of the full mesh when the rounded copy is not a valid solid.
// The filtered copy's coordinates and the cube radii are multiples of this (the copy has unit
// volume): exact arithmetic then works with short dyadic numbers, at a relative precision far
// below what the descriptor resolves.
constexpr double kGrid = 1.0 / (1 << 20);

double on_grid(double r) {
  return std::max(kGrid, std::round(r / kGrid) * kGrid);
}

Mesh filtered_copy(const Mesh& solid, const DoubleMesh& dm, double scale,
                   const DescriptorSettings& s, Descriptors& d) {
  detail::PrincipalFrame frame;
  if (s.normalise_pose) frame = detail::principal_frame(dm);
  const DoubleMesh posed = detail::posed_copy(dm, frame, scale);
  const std::size_t budget = s.facet_budget ? s.facet_budget : posed.triangles.size();
  try {
    SimplifyReport report;
    Mesh copy = simplified_solid(posed, budget, &report, kGrid);
    d.simplified = report.simplified;
    return copy;
  } catch (const InvalidSolid&) {
    // Rounding the turned coordinates made the surface touch itself: turn it exactly instead.
    Mesh exact = s.normalise_pose ? normalise_pose(solid) : solid;
    Mesh out = transformed(exact, Transformation(CGAL::SCALING, FT(1) / FT(scale)));
    make_exact(out);
    return out;
  }
}

// Every opening and closing is computed from the copy itself, not chained from the previous
// radius (A - (r + s)B = (A - rB) - sB would be exact for the convex cube too): an erosion by a
// cube has about three times the facets of a smooth input, and rational intersection points instead
// of doubles, so each chained step would cost several times a step from the copy (profiled on
// SHREC 2007 meshes; the figures are in docs/benchmarks.md).
void filter_by_cubes(const Mesh& a, const DescriptorSettings& s, Descriptors& d) {
  // The filters are most of a description; D2 is counted as one more step.
  const double steps = double(d.open_radii.size() + (s.closings ? d.close_radii.size() : 0) + 1);
  double finished = 0;
  const auto advanced = [&] {
    if (s.on_progress) s.on_progress(++finished / steps);
  };
  const Moments whole = moments_of(a);
  double g_previous = 1;
  bool vanished = false;  // a larger cube cannot fit where a smaller one did not
  for (double r : d.open_radii) {
    const StructuringElement cube = cube_of(FT(r));
    const ProgressPhase phase(finished / steps, (finished + 1) / steps, "opening");
    Mesh opened;
    if (!vanished) {
      opened = detail::morphology_of_valid(MorphologyOp::Open, a, cube);
      vanished = opened.empty();  // the erosion was empty
    }
    const Moments m = opened.empty() ? Moments{} : moments_of(opened);
    const double g = std::clamp(m.volume / whole.volume, 0.0, 1.0);
    d.granulometry.push_back(g);
    d.pattern_spectrum.push_back(std::max(0.0, g_previous - g));
    g_previous = g;
    append_placement(d.opening_residue, whole - m, whole);
    d.components.push_back(std::log2(1.0 + double(opened.empty() ? 0 : component_count(opened))));
    advanced();
  }
  if (!s.closings) return;
  for (double r : d.close_radii) {
    const StructuringElement cube = cube_of(FT(r));
    const ProgressPhase phase(finished / steps, (finished + 1) / steps, "closing");
    const Moments m = moments_of(detail::morphology_of_valid(MorphologyOp::Close, a, cube));
    d.anti_granulometry.push_back(std::max(0.0, m.volume / whole.volume - 1));
    append_placement(d.closing_residue, m - whole, whole);
    advanced();
  }
}

}  // namespace

std::string DescriptorSettings::to_string() const {
  std::ostringstream out;
  out << "scales=" << scales << ";open=" << open_from << ".." << open_to << ";close=" << close_from
      << ".." << close_to << ";closings=" << closings << ";pose=" << normalise_pose
      << ";facet_budget=" << facet_budget << ";d2_samples=" << d2_samples << ";d2_bins=" << d2_bins
      << ";seed=" << seed;
  return out.str();
}

Descriptors describe(const Solid& input, const DescriptorSettings& settings) {
  const Mesh& solid = input.mesh();
  check_descriptor_settings(settings);  // InputError naming the setting
  // The volume only sets the scale (the descriptor is computed in double precision around the
  // exact filtering): its sign exactly, its value in double precision.
  if (signed_volume_sign(solid) != CGAL::POSITIVE)
    throw InvalidSolid("cannot describe", "the mesh has no volume");
  const DoubleMesh dm = to_double(solid);
  double volume = 0;
  for (const Triangle& t : dm.triangles) {
    const auto &a = dm.points[t[0]], &b = dm.points[t[1]], &c = dm.points[t[2]];
    volume += (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
               a[2] * (b[0] * c[1] - b[1] * c[0])) /
              6;
  }
  const auto start = std::chrono::steady_clock::now();
  Descriptors d;
  d.scale_length = std::cbrt(volume);
  const Mesh a = filtered_copy(solid, dm, d.scale_length, settings, d);
  d.facets = a.triangles.size();
  // Unit volume: L = 1, and T = 3 / area.
  d.thickness = 3.0 * CGAL::to_double(signed_volume(a)) / detail::surface_area(to_double(a));
  for (double f : geometric(settings.open_from, settings.open_to, settings.scales))
    d.open_radii.push_back(on_grid(f * d.thickness));
  if (settings.closings)
    for (double f : geometric(settings.close_from, settings.close_to, settings.scales))
      d.close_radii.push_back(on_grid(f));
  filter_by_cubes(a, settings, d);
  d.seconds_morphology =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  d.d2 = detail::d2_histogram(dm, settings.d2_samples, settings.d2_bins, settings.seed);
  return d;
}

}  // namespace morphex

// SPDX-License-Identifier: GPL-3.0-or-later
// Dilation and erosion by one segment S = [-h, h] (h a vector, e its direction), as one
// winding_solid: the step of morphology by a zonotope (a box among them), which is the sum of its
// centre and its segments, so that A + B = ((A + centre) + S1) + ... + Sk, and the erosion is the
// erosion by each segment in turn (erosion by a sum is the composition of the erosions;
// zonotope.cpp).
//
// Dilation by a segment. Write S = -h + [0, 2h]. For a solid A and a direction d,
//   A + [0, d] = A  u  U { f + [0, d] : facets f with n_f . d > 0 }
// (almost every point x of A + [0, d] outside A has a first point a = x - t d of A along -d
// inside a facet f that d leaves through, so n_f . d > 0 and x lies in f's prism; both sides are
// closed and the left one is the closure of its interior). As a chain, the prisms' bottoms cancel
// the facets of A - h e they stand on, and the walls of neighbouring prisms cancel in pairs: what
// is left is every front facet (n_f . e > 0) moved by +h, every other facet by -h, and over
// each edge between a moved-up and a moved-down facet, the wall the edge sweeps. {w >= 1} of that
// chain is A + S.
// Erosion by a segment: A - S is the complement of A's complement dilated by -S = S. The same
// construction on the reversed surface moves the back facets (n_f . e < 0) up and every other facet
// down: {w >= 1} of that chain is A - S.
//
// Unlike the reduced convolution's prisms, which overlap wherever the supporting vertex changes,
// the sheets of a sweep overlap only where the solid folds back along e within 2|h|.
#include <tbb/parallel_for.h>

#include <array>
#include <numeric>
#include <unordered_map>

#include "minkowski_internal.h"
#include "morphex/internal/parallel_points.h"
#include "morphex/shapes.h"
#include "morphex/winding.h"

namespace morphex::detail {
namespace {

using ExactVector = Kernel::Exact_kernel::Vector_3;

// The sign of n_f . d for the facet pqr's normal n_f = (q - p) x (r - p): intervals first, then
// the exact coordinates.
CGAL::Sign normal_direction_sign(const Point& p, const Point& q, const Point& r, const Vector& d) {
  {
    CGAL::Protect_FPU_rounding<true> rounding;
    const auto& ap = CGAL::approx(p);
    const CGAL::Uncertain<CGAL::Sign> s =
        CGAL::sign(CGAL::determinant(CGAL::approx(q) - ap, CGAL::approx(r) - ap, CGAL::approx(d)));
    if (CGAL::is_certain(s)) return CGAL::get_certain(s);
  }
  const auto& ep = CGAL::exact(p);
  return CGAL::sign(CGAL::determinant(CGAL::exact(q) - ep, CGAL::exact(r) - ep, CGAL::exact(d)));
}

// The chain of one sweep, with its plane labels and its groups: the facets moved up are a
// translate of part of a valid surface, and so are those moved down, so neither meets itself
// other than at common corners and edges (WindingOptions::groups): the arrangement searches only
// the pairs that can cross, those with a wall, a stretched facet or a facet moved the other way.
struct SweepChain {
  Mesh chain;
  std::vector<std::uint32_t> planes;
  std::vector<std::uint32_t> groups;
};

SweepChain sweep_chain(const LabelledSolid& in, const Vector& half, bool erode) {
  const Mesh& a = in.mesh;
  const std::size_t nv = a.points.size(), nf = a.triangles.size();
  // Lazy coordinates are evaluated once here (CGAL's lazy evaluation of a shared point is not safe
  // from several threads).
  for (const Point& p : a.points) CGAL::exact(p);
  const ExactVector& h = CGAL::exact(half);
  const ExactVector minus_h = -h;
  Mesh chain;
  // Vertex v at -h is 2 v, at +h is 2 v + 1.
  chain.points = parallel_points(2 * nv, [&](std::size_t i) {
    return point_from_exact(CGAL::exact(a.points[i / 2]) + (i % 2 ? h : minus_h));
  });
  // Which copy each corner takes: a facet with n_f . e > 0 (< 0 for an erosion) moves up, one
  // with the opposite sign down. A facet parallel to e (often a wall of an earlier sweep along
  // e) may take either copy at each corner: the chains differ by pieces parallel to e, whose
  // winding number is zero. Its corners take the copy of the facets around the vertex when
  // those all agree, so that it stretches with them instead of meeting a coplanar wall.
  std::vector<std::int8_t> side(nf);
  tbb::parallel_for(std::size_t(0), nf, [&](std::size_t f) {
    const Triangle& t = a.triangles[f];
    const CGAL::Sign s =
        normal_direction_sign(a.points[t[0]], a.points[t[1]], a.points[t[2]], half);
    side[f] = std::int8_t(erode ? -s : s);  // +1 up, -1 down, 0 parallel
  });
  std::vector<std::uint8_t> around(nv, 0);  // bit 0: an up facet at the vertex, bit 1: a down one
  for (std::uint32_t f = 0; f < nf; ++f)
    if (side[f] != 0)
      for (VertexIndex v : a.triangles[f]) around[v] |= side[f] > 0 ? 1 : 2;
  auto copy = [&](std::uint32_t f, VertexIndex v) {  // the chain vertex of corner v of facet f
    const bool up = side[f] > 0 || (side[f] == 0 && around[v] == 1);
    return 2 * v + (up ? 1 : 0);
  };
  // Plane labels: a facet parallel to e stays in its plane; coplanar facets moved alike stay
  // coplanar; the two triangles of a wall share one.
  std::vector<std::uint32_t> planes, groups;
  planes.reserve(nf + nf / 2);
  groups.reserve(nf + nf / 2);
  std::unordered_map<std::uint64_t, std::uint32_t> moved_plane;  // (label, side) -> label
  auto moved = [&](std::uint32_t f) {
    const std::uint64_t key = (std::uint64_t(in.plane[f]) << 2) | std::uint64_t(side[f] + 1);
    return moved_plane.emplace(key, std::uint32_t(moved_plane.size())).first->second;
  };
  auto wall_plane = std::uint32_t(nf);  // above every moved label (at most one per facet)
  const DirectedEdges edges(a);
  chain.triangles.reserve(nf + nf / 2);
  for (std::uint32_t f = 0; f < nf; ++f) {
    const Triangle& t = a.triangles[f];
    chain.triangles.push_back({copy(f, t[0]), copy(f, t[1]), copy(f, t[2])});
    planes.push_back(moved(f));
    groups.push_back(side[f] > 0 ? 0 : side[f] < 0 ? 1 : WindingOptions::kNoGroup);
    // Where the facet across an edge u -> v (u < v: each edge once) takes other copies, the wall
    // the edge sweeps between them: (v', u', u'', v''), primes for this facet's copies.
    for (int i = 0; i < 3; ++i) {
      const VertexIndex u = t[i], v = t[(i + 1) % 3];
      if (u > v) continue;
      const std::uint32_t g = edges.facet(v, u);
      if (g == DirectedEdges::kNone) continue;
      const VertexIndex fu = copy(f, u), fv = copy(f, v), gu = copy(g, u), gv = copy(g, v);
      if (fu == gu && fv == gv) continue;
      if (fu != gu) {
        chain.triangles.push_back({fv, fu, gu});
        planes.push_back(wall_plane);
        groups.push_back(WindingOptions::kNoGroup);
      }
      if (fv != gv) {
        chain.triangles.push_back({fv, gu, gv});
        planes.push_back(wall_plane);
        groups.push_back(WindingOptions::kNoGroup);
      }
      ++wall_plane;
    }
  }
  return {std::move(chain), std::move(planes), std::move(groups)};
}

// A sweep whose sheets fold back within 2|h| many layers deep (a thin part wound along e, a
// coil) costs far more than its facets: its arrangement holds every crossing of those layers.
// Since S_h = S_{h/2} + S_{h/2}, the same sum is two half sweeps, and the second sweeps a solid
// whose folds narrower than h are already filled: on a SHREC 2007 mesh, one sweep of 65 candidate
// pairs per triangle took 33 s, its steps h/8, h/8, h/4 and h/2 about 6 s in all. Beyond
// `max_pairs` per triangle a sweep is halved, at most kMaxHalvings deep, while halving thins its
// pairs: a half with more than three quarters of its whole's pairs (long thin facets overlap at
// any length) and the half after it run without further halving. Two such halves were still
// faster than the whole sweep on the SHREC meshes where it happens (up to 15% per description).
constexpr int kMaxHalvings = 6;

// `halvings`: how many more times the sweep may be halved; `parent_pairs`: the candidate pairs of
// the sweep this one halves (0 for none). Sets `thinned` to whether halving thinned the pairs.
LabelledSolid sweep_in_steps(const LabelledSolid& in, const Vector& half, bool erode,
                             double max_pairs, int halvings, std::size_t parent_pairs,
                             bool& thinned, std::size_t* arrangements) {
  thinned = true;
  if (in.mesh.empty()) return {};
  if (arrangements) ++*arrangements;
  const SweepChain sweep = sweep_chain(in, half, erode);
  LabelledSolid out;
  WindingOptions options;
  options.planes = &sweep.planes;
  options.groups = &sweep.groups;
  options.result_planes = &out.plane;
  WindingStats stats;
  if (auto solid =
          winding_solid_within(halvings > 0 ? max_pairs : 0, sweep.chain, {}, options, &stats)) {
    out.mesh = std::move(*solid);
    return out;
  }
  if (parent_pairs > 0 && 4 * stats.candidate_pairs > 3 * parent_pairs) {
    thinned = false;  // not folds: this half whole, and the next one without halving
    out.mesh = winding_solid(sweep.chain, {}, options);
    return out;
  }
  const Vector quarter = half / 2;
  const LabelledSolid first = sweep_in_steps(in, quarter, erode, max_pairs, halvings - 1,
                                             stats.candidate_pairs, thinned, arrangements);
  return sweep_in_steps(first, quarter, erode, max_pairs, thinned ? halvings - 1 : 0, 0, thinned,
                        arrangements);
}

}  // namespace

LabelledSolid segment_sweep(const LabelledSolid& in, const Vector& half, bool erode,
                            double max_pairs_per_triangle, std::size_t* arrangements) {
  bool thinned = true;
  return sweep_in_steps(in, half, erode, max_pairs_per_triangle,
                        max_pairs_per_triangle > 0 ? kMaxHalvings : 0, 0, thinned, arrangements);
}

}  // namespace morphex::detail

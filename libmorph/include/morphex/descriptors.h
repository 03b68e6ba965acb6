// SPDX-License-Identifier: GPL-3.0-or-later
// Morphological shape descriptors for retrieval, and the D2 baseline.
//
// What is measured. A is turned to its principal axes and scaled to unit volume (pose, below),
// optionally replaced by a coarser valid copy of at most `facet_budget` facets (simplify.h), and
// then filtered exactly by cubes of growing half side r_1 < ... < r_n, chosen per mesh:
//
//   thickness          T = 3 vol(A) / area(A)    (the radius of a ball has T = R; a slab of
//                                                 thickness h has T = 1.5 h)
//   opening radii      r_k = T * geometric(open_from, open_to, n)     (openings empty near 0.6 T)
//   closing radii      s_k = L * geometric(close_from, close_to, n)   (L = cbrt(vol A) = 1 here)
//
//   granulometry       g_k = vol(open(A, r_k)) / vol(A)             (decreasing, <= 1)
//   pattern spectrum   p_k = g_{k-1} - g_k, g_0 = 1                  (volume removed per size)
//   anti-granulometry  c_k = vol(close(A, s_k)) / vol(A) - 1         (increasing, >= 0)
//   residue moments    for the residue A \ open(A, r_k) (and the filled part close(A, s_k) \ A):
//                      its second moments about A's centroid along the three principal axes,
//                      divided by vol(A) L^2, and the distance of its centroid from A's
//                      centroid along each axis, times its volume fraction, divided by L. They say
//                      where the thin parts (and the gaps) lie: in the ends of a long shape, around
//                      its waist, far from or near its middle. Both come from moments that are
//                      linear in the solid, so the residue's are the difference of two solids'.
//   components         the number of solid components of each opening, per unit (log2(1 + n)).
//   shape ratio        T / L, the compactness (a ball 0.806, thin shapes near 0).
//   D2                 histogram of distances between random surface point pairs (Osada et al.
//                      2002) of the full-resolution surface, divided by their mean, over [0, 3)
//                      in `d2_bins` bins, fixed seed.
//
// Exactness: the openings and closings of the copy are exact; the pose, the optional simplification
// and the statistics of the results are in double precision. Invariance: translation, uniform scale
// and rotation (up to the ambiguity of nearly equal principal moments) leave the descriptor
// unchanged up to rounding; tests check it on exact copies.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "morphex/mesh.h"
#include "morphex/solid.h"

namespace morphex {

struct DescriptorSettings {
  int scales = 8;                             // n, at least 1
  double open_from = 0.05, open_to = 0.6;     // opening radii, in units of T
  double close_from = 0.02, close_to = 0.35;  // closing radii, in units of L
  bool closings = true;                       // also the anti-granulometry
  bool normalise_pose = true;
  std::size_t facet_budget = 300;  // simplify larger meshes to about this many facets; 0: never
  int d2_samples = 200000;         // point pairs
  int d2_bins = 64;
  std::uint64_t seed = 1;
  // Called with the finished share of the work (0 to 1) after each filter, for progress displays;
  // not a setting of the descriptor (to_string leaves it out).
  std::function<void(double share)> on_progress;
  std::string to_string() const;  // canonical text, stored with indexed descriptors
};

struct Descriptors {
  double scale_length = 0;  // L of the input, in its own units
  double thickness = 0;     // T / L
  std::size_t facets = 0;   // facets of the copy that was filtered
  bool simplified = false;
  std::vector<double> open_radii, close_radii;  // in units of L
  std::vector<double> granulometry, pattern_spectrum, anti_granulometry;
  std::vector<double> opening_residue, closing_residue;  // 6 per scale: 3 moments, 3 offsets
  std::vector<double> components;                        // log2(1 + components) per opening
  std::vector<double> d2;
  double seconds_morphology = 0;
};

// The descriptors of a solid with positive volume (InvalidSolid "cannot describe: the mesh has no
// volume" otherwise; InputError for settings out of range).
Descriptors describe(const Solid& solid, const DescriptorSettings& settings = {});

// The names under which descriptor vectors are stored and compared, and the vector for each:
//   "morphology"        every morphological block, weighted (the best purely morphological one)
//   "granulometry"      g_k followed by c_k
//   "pattern_spectrum"  p_k
//   "spatial"           the residue moments and offsets of openings and closings
//   "d2"                the D2 histogram
//   "combined"          morphology and D2 (the default for queries), weights in descriptors.cpp
std::vector<std::string> descriptor_kinds();
std::vector<double> descriptor_vector(const Descriptors& d, const std::string& kind);
const char* default_descriptor_kind();  // "combined"
// The version of what describe computes, stored with indexed descriptors: an index built by
// another version is described again, never compared with vectors of another definition.
const char* descriptor_version();

enum class Metric { L1, L2, ChiSquare };
// "l1", "l2", "chi2"; throws InputError otherwise.
Metric parse_metric(const std::string& name);
const char* to_string(Metric metric);
// chi2 is sum (a - b)^2 / (|a| + |b|), terms with a = b = 0 omitted. Throws InputError
// for vectors of different lengths (computed with other settings).
double distance(const std::vector<double>& a, const std::vector<double>& b, Metric metric);
double l1_distance(const std::vector<double>& a, const std::vector<double>& b);

// A to its principal axes by an exactly orthogonal rational rotation (the surface's covariance
// eigenvectors, largest first, signs fixed by the third moment; equal moments keep the mesh's
// own axes). The exact route, used when the double-precision copy is not a valid solid.
Mesh normalise_pose(const Mesh& solid);

}  // namespace morphex

// SPDX-License-Identifier: GPL-3.0-or-later
// Morphological shape descriptors for retrieval, and the D2 baseline.
//
// Scale: every size is relative to L = cbrt(vol(A)), the edge of the cube of the same volume, so a
// scaled copy of a mesh gets the same descriptor (up to the rounding of the SE size to a double).
// Pose: the cube SE is not rotation invariant, so A is first turned to its principal axes (the
// eigenvectors of the covariance of its surface, area weighted, largest first, signs fixed by the
// third moment) by an exactly orthogonal rational rotation; the descriptor is then invariant to
// rotations up to the ambiguity of nearly equal principal moments. Translation never matters.
//
//   granulometry       g_k = vol(open(A, cube(r_k L))) / vol(A)      for r_1 < r_2 < ...  (<= 1)
//   pattern spectrum   p_k = g_{k-1} - g_k   with g_0 = 1             (the volume removed per size)
//   anti-granulometry  c_k = vol(close(A, cube(r_k L))) / vol(A)     (>= 1)
//   D2                 histogram of distances between random surface point pairs (Osada et al.
//                      2002), divided by their mean, over [0, 3) in `d2_bins` bins, fixed seed.
// Distances between descriptors are L1 (sum of absolute differences).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "morphex/mesh.h"

namespace morphex {

struct DescriptorSettings {
  std::vector<double> radii = {0.1, 0.2, 0.35};  // cube half sides, in units of L
  bool closings = true;                          // also the anti-granulometry
  bool normalise_pose = true;
  int d2_samples = 4096;  // point pairs
  int d2_bins = 32;
  std::uint64_t seed = 1;
  std::string to_string() const;  // canonical text, stored with indexed descriptors
};

struct Descriptors {
  double scale_length = 0;  // L
  std::vector<double> granulometry, pattern_spectrum, anti_granulometry, d2;
};

// Precondition: a valid solid with positive volume (throws std::invalid_argument otherwise).
Descriptors describe(const Mesh& solid, const DescriptorSettings& settings = {});

// The names under which descriptor vectors are stored and compared, and the vector for each:
// "granulometry" (openings followed by closings when computed), "pattern_spectrum", "d2".
std::vector<std::string> descriptor_kinds();
std::vector<double> descriptor_vector(const Descriptors& d, const std::string& kind);

double l1_distance(const std::vector<double>& a, const std::vector<double>& b);

// A to its principal axes by an exactly orthogonal rational rotation (see above).
Mesh normalise_pose(const Mesh& solid);

}  // namespace morphex

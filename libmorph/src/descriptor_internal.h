// SPDX-License-Identifier: GPL-3.0-or-later
// What the descriptor code shares between its files: the double-precision pose and D2.
#pragma once

#include <Eigen/Dense>

#include <cstdint>
#include <vector>

#include "morphex/mesh.h"

namespace morphex::detail {

// The principal axes of a surface as the rows of a rotation matrix (largest moment first), and
// the area centroid. See descriptors.h for the rules on signs and equal moments.
struct PrincipalFrame {
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
};
PrincipalFrame principal_frame(const DoubleMesh& m);

// R (p - centre) / scale for every point, in double precision (the faces are kept).
DoubleMesh posed_copy(const DoubleMesh& m, const PrincipalFrame& frame, double scale);

// Total area of the triangles.
double surface_area(const DoubleMesh& m);

// The D2 histogram of the surface (normalised by the mean distance, over [0, 3)).
std::vector<double> d2_histogram(const DoubleMesh& m, int samples, int bins, std::uint64_t seed);

}  // namespace morphex::detail

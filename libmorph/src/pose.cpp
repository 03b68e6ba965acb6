// SPDX-License-Identifier: GPL-3.0-or-later
// Pose normalisation: the principal axes of the surface, applied in double precision (the
// descriptor's copy) or as an exactly orthogonal rational rotation (normalise_pose).
#include <cmath>

#include "descriptor_internal.h"
#include "morphex/descriptors.h"
#include "morphex/shapes.h"

namespace morphex {
namespace detail {
namespace {

Eigen::Vector3d point_of(const DoubleMesh& m, VertexIndex v) {
  return Eigen::Vector3d(m.points[v][0], m.points[v][1], m.points[v][2]);
}

// Equal moments leave the axes free within their eigenspace (a cube, a square bar): there, keep
// the mesh's own axes, so that symmetric shapes are not turned at random.
void settle_equal_moments(Eigen::Matrix3d& axes, const Eigen::Vector3d& moments) {
  const auto same = [&](int i, int j) {
    return std::abs(moments[i] - moments[j]) <= 1e-6 * std::abs(moments[0]);
  };
  if (same(0, 1) && same(1, 2)) {
    axes.setIdentity();
  } else if (same(0, 1) || same(1, 2)) {
    const int single = same(0, 1) ? 2 : 0;  // the axis whose moment differs
    const Eigen::Vector3d u = axes.row(single).transpose();
    int least = 0;  // the coordinate axis least aligned with u spans the free plane best
    for (int k = 1; k < 3; ++k)
      if (std::abs(u[k]) < std::abs(u[least])) least = k;
    const Eigen::Vector3d v = (Eigen::Vector3d::Unit(least) - u[least] * u).normalized();
    const Eigen::Vector3d w = u.cross(v);
    const int first = single == 0 ? 1 : 0;
    axes.row(first) = v.transpose();
    axes.row(first == 0 ? 1 : 2) = w.transpose();
  }
}

}  // namespace

PrincipalFrame principal_frame(const DoubleMesh& m) {
  // Covariance of the surface as a uniform area density: over a triangle abc of area A,
  // integral of x x^T = A/12 (a a^T + b b^T + c c^T + (a+b+c)(a+b+c)^T).
  double total = 0;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
  std::vector<std::pair<Eigen::Vector3d, double>> centroids;
  centroids.reserve(m.triangles.size());
  for (const Triangle& t : m.triangles) {
    const Eigen::Vector3d p[3] = {point_of(m, t[0]), point_of(m, t[1]), point_of(m, t[2])};
    const double area = 0.5 * (p[1] - p[0]).cross(p[2] - p[0]).norm();
    const Eigen::Vector3d sum = p[0] + p[1] + p[2];
    centroids.push_back({sum / 3.0, area});
    mean += area * sum / 3.0;
    second += area / 12.0 *
              (p[0] * p[0].transpose() + p[1] * p[1].transpose() + p[2] * p[2].transpose() +
               sum * sum.transpose());
    total += area;
  }
  PrincipalFrame frame;
  if (total <= 0) return frame;
  mean /= total;
  frame.centre = mean;
  const Eigen::Matrix3d covariance = second / total - mean * mean.transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance);
  Eigen::Matrix3d axes;  // rows: principal axes, largest moment first
  for (int k = 0; k < 3; ++k) axes.row(k) = solver.eigenvectors().col(2 - k).transpose();
  const Eigen::Vector3d moments(solver.eigenvalues()[2], solver.eigenvalues()[1],
                                solver.eigenvalues()[0]);
  settle_equal_moments(axes, moments);
  for (int k = 0; k < 2; ++k) {  // sign: the side with the heavier third moment is positive
    double skew = 0;
    for (const auto& [c, w] : centroids) skew += w * std::pow(axes.row(k).dot(c - mean), 3);
    if (skew < -1e-9 * std::pow(moments[0], 1.5)) axes.row(k) = -axes.row(k);
  }
  if (axes.determinant() < 0) axes.row(2) = -axes.row(2);  // a rotation, not a reflection
  frame.axes = axes;
  return frame;
}

DoubleMesh posed_copy(const DoubleMesh& m, const PrincipalFrame& frame, double scale) {
  DoubleMesh out;
  out.triangles = m.triangles;
  out.points.reserve(m.points.size());
  for (std::size_t v = 0; v < m.points.size(); ++v) {
    const Eigen::Vector3d q = frame.axes * (point_of(m, VertexIndex(v)) - frame.centre) / scale;
    out.points.push_back({q[0], q[1], q[2]});
  }
  return out;
}

}  // namespace detail

namespace {

// An exactly orthogonal rational matrix near the rotation `r`: from its quaternion rounded to a
// 2^-20 grid, R(q) / |q|^2 is orthogonal in exact arithmetic.
Transformation rational_rotation(const Eigen::Matrix3d& r) {
  const Eigen::Quaterniond q(r);
  const auto grid = [](double v) { return FT(std::round(v * 1048576.0)) / 1048576; };
  const FT a = grid(q.w()), b = grid(q.x()), c = grid(q.y()), d = grid(q.z());
  return quaternion_rotation(a, b, c, d);
}

}  // namespace

Mesh normalise_pose(const Mesh& solid) {
  const detail::PrincipalFrame frame = detail::principal_frame(to_double(solid));
  Mesh turned = transformed(solid, rational_rotation(frame.axes));
  make_exact(turned);
  return turned;
}

}  // namespace morphex

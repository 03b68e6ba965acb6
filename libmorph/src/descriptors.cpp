// SPDX-License-Identifier: GPL-3.0-or-later
// Granulometries by exact openings and closings with cubes, and the D2 shape distribution.
#include "morphex/descriptors.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>
#include <stdexcept>

#include "morphex/check.h"
#include "morphex/generators.h"
#include "morphex/morphology.h"

namespace morphex {
namespace {

struct SurfaceSample {
  std::vector<std::array<double, 3>> a, b, c;  // triangle corners
  std::vector<double> cumulative_area;
};

SurfaceSample surface_of(const DoubleMesh& m) {
  SurfaceSample s;
  double total = 0;
  for (const Triangle& t : m.triangles) {
    const auto &p = m.points[t[0]], &q = m.points[t[1]], &r = m.points[t[2]];
    const Eigen::Vector3d u(q[0] - p[0], q[1] - p[1], q[2] - p[2]);
    const Eigen::Vector3d v(r[0] - p[0], r[1] - p[1], r[2] - p[2]);
    total += 0.5 * u.cross(v).norm();
    s.a.push_back(p);
    s.b.push_back(q);
    s.c.push_back(r);
    s.cumulative_area.push_back(total);
  }
  return s;
}

Eigen::Vector3d random_point(const SurfaceSample& s, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double pick = unit(rng) * s.cumulative_area.back();
  const std::size_t t = std::min<std::size_t>(
      std::lower_bound(s.cumulative_area.begin(), s.cumulative_area.end(), pick) -
          s.cumulative_area.begin(),
      s.a.size() - 1);
  double x = unit(rng), y = unit(rng);
  if (x + y > 1) {
    x = 1 - x;
    y = 1 - y;
  }
  Eigen::Vector3d out;
  for (int k = 0; k < 3; ++k)
    out[k] = s.a[t][k] + x * (s.b[t][k] - s.a[t][k]) + y * (s.c[t][k] - s.a[t][k]);
  return out;
}

// An exactly orthogonal rational matrix near the rotation `r`: from its quaternion rounded to a
// 2^-20 grid, R(q) / |q|^2 is orthogonal in exact arithmetic.
Transformation rational_rotation(const Eigen::Matrix3d& r) {
  const Eigen::Quaterniond q(r);
  const auto grid = [](double v) { return FT(std::round(v * 1048576.0)) / 1048576; };
  const FT a = grid(q.w()), b = grid(q.x()), c = grid(q.y()), d = grid(q.z());
  return quaternion_rotation(a, b, c, d);
}

}  // namespace

std::string DescriptorSettings::to_string() const {
  std::ostringstream out;
  out << "radii=";
  for (std::size_t i = 0; i < radii.size(); ++i) out << (i ? "," : "") << radii[i];
  out << ";closings=" << closings << ";pose=" << normalise_pose << ";d2_samples=" << d2_samples
      << ";d2_bins=" << d2_bins << ";seed=" << seed;
  return out.str();
}

Mesh normalise_pose(const Mesh& solid) {
  const DoubleMesh m = to_double(solid);
  // Covariance of the surface as a uniform area density: over a triangle abc of area A,
  // integral of x x^T = A/12 (a a^T + b b^T + c c^T + (a+b+c)(a+b+c)^T).
  double total = 0;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
  std::vector<std::pair<Eigen::Vector3d, double>> centroids;
  for (const Triangle& t : m.triangles) {
    Eigen::Vector3d p[3];
    for (int k = 0; k < 3; ++k)
      p[k] = Eigen::Vector3d(m.points[t[k]][0], m.points[t[k]][1], m.points[t[k]][2]);
    const double area = 0.5 * (p[1] - p[0]).cross(p[2] - p[0]).norm();
    const Eigen::Vector3d sum = p[0] + p[1] + p[2];
    centroids.push_back({sum / 3.0, area});
    mean += area * sum / 3.0;
    second += area / 12.0 *
              (p[0] * p[0].transpose() + p[1] * p[1].transpose() + p[2] * p[2].transpose() +
               sum * sum.transpose());
    total += area;
  }
  if (total <= 0) return solid;
  mean /= total;
  const Eigen::Matrix3d covariance = second / total - mean * mean.transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance);
  Eigen::Matrix3d axes;  // rows: principal axes, largest moment first
  for (int k = 0; k < 3; ++k) axes.row(k) = solver.eigenvectors().col(2 - k).transpose();
  // Equal moments leave the axes free within their eigenspace (a cube, a square bar): there, keep
  // the mesh's own axes, so that symmetric shapes are not turned at random.
  const Eigen::Vector3d moments(solver.eigenvalues()[2], solver.eigenvalues()[1],
                                solver.eigenvalues()[0]);
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
  for (int k = 0; k < 2; ++k) {  // sign: the side with the heavier third moment is positive
    double skew = 0;
    for (const auto& [c, w] : centroids) skew += w * std::pow(axes.row(k).dot(c - mean), 3);
    if (skew < -1e-9 * std::pow(moments[0], 1.5)) axes.row(k) = -axes.row(k);
  }
  if (axes.determinant() < 0) axes.row(2) = -axes.row(2);  // a rotation, not a reflection
  Mesh turned = transformed(solid, rational_rotation(axes));
  make_exact(turned);
  return turned;
}

Descriptors describe(const Mesh& solid, const DescriptorSettings& settings) {
  const MeshReport report = check_mesh(solid);
  if (!report.valid_solid() || report.volume <= 0)
    throw std::invalid_argument("cannot describe: " + (report.valid_solid()
                                                           ? std::string("the mesh has no volume")
                                                           : describe_problems(report)));
  Descriptors d;
  const double volume = CGAL::to_double(report.volume);
  d.scale_length = std::cbrt(volume);
  const Mesh posed = settings.normalise_pose ? normalise_pose(solid) : solid;
  const FT exact_volume = report.volume;
  auto fraction = [&](const Mesh& m) { return CGAL::to_double(signed_volume(m) / exact_volume); };
  double previous = 1;
  for (double r : settings.radii) {
    StructuringElement se;
    se.shape = "cube";
    se.mesh = make_cube(FT(r * d.scale_length));
    const double g = fraction(opening(posed, se));
    d.granulometry.push_back(g);
    d.pattern_spectrum.push_back(previous - g);
    previous = g;
    if (settings.closings) d.anti_granulometry.push_back(fraction(closing(posed, se)));
  }

  const SurfaceSample surface = surface_of(to_double(solid));
  std::mt19937_64 rng(settings.seed);
  std::vector<double> distances(std::size_t(std::max(1, settings.d2_samples)));
  for (double& x : distances) x = (random_point(surface, rng) - random_point(surface, rng)).norm();
  double mean = 0;
  for (double x : distances) mean += x;
  mean /= double(distances.size());
  d.d2.assign(std::size_t(std::max(1, settings.d2_bins)), 0.0);
  for (double x : distances) {
    const double scaled = mean > 0 ? x / mean : 0;
    const auto bin = std::size_t(std::min(scaled / 3.0, 0.999999) * double(d.d2.size()));
    d.d2[bin] += 1.0 / double(distances.size());
  }
  return d;
}

std::vector<std::string> descriptor_kinds() {
  return {"granulometry", "pattern_spectrum", "d2"};
}

std::vector<double> descriptor_vector(const Descriptors& d, const std::string& kind) {
  if (kind == "granulometry") {
    std::vector<double> v = d.granulometry;
    v.insert(v.end(), d.anti_granulometry.begin(), d.anti_granulometry.end());
    return v;
  }
  if (kind == "pattern_spectrum") return d.pattern_spectrum;
  if (kind == "d2") return d.d2;
  throw std::invalid_argument("unknown descriptor '" + kind +
                              "' (expected granulometry, pattern_spectrum or d2)");
}

double l1_distance(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size())
    throw std::invalid_argument("descriptors of different lengths: computed with other settings");
  double sum = 0;
  for (std::size_t i = 0; i < a.size(); ++i) sum += std::abs(a[i] - b[i]);
  return sum;
}

}  // namespace morphex

// SPDX-License-Identifier: GPL-3.0-or-later
// The D2 shape distribution (Osada, Funkhouser, Chazelle and Dobkin 2002): distances between
// random pairs of points drawn uniformly on the surface.
#include <algorithm>
#include <random>

#include "descriptor_internal.h"

namespace morphex::detail {
namespace {

struct SurfaceSample {
  std::vector<std::array<double, 3>> a, b, c;  // triangle corners
  std::vector<double> cumulative_area;
};

double triangle_area(const std::array<double, 3>& p, const std::array<double, 3>& q,
                     const std::array<double, 3>& r) {
  const Eigen::Vector3d u(q[0] - p[0], q[1] - p[1], q[2] - p[2]);
  const Eigen::Vector3d v(r[0] - p[0], r[1] - p[1], r[2] - p[2]);
  return 0.5 * u.cross(v).norm();
}

SurfaceSample surface_of(const DoubleMesh& m) {
  SurfaceSample s;
  double total = 0;
  for (const Triangle& t : m.triangles) {
    const auto &p = m.points[t[0]], &q = m.points[t[1]], &r = m.points[t[2]];
    total += triangle_area(p, q, r);
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

}  // namespace

double surface_area(const DoubleMesh& m) {
  double area = 0;
  for (const Triangle& t : m.triangles)
    area += triangle_area(m.points[t[0]], m.points[t[1]], m.points[t[2]]);
  return area;
}

std::vector<double> d2_histogram(const DoubleMesh& m, int samples, int bins, std::uint64_t seed) {
  const SurfaceSample surface = surface_of(m);
  std::mt19937_64 rng(seed);
  std::vector<double> distances(std::size_t(std::max(1, samples)));
  for (double& x : distances) x = (random_point(surface, rng) - random_point(surface, rng)).norm();
  double mean = 0;
  for (double x : distances) mean += x;
  mean /= double(distances.size());
  std::vector<double> histogram(std::size_t(std::max(1, bins)), 0.0);
  for (double x : distances) {
    const double scaled = mean > 0 ? x / mean : 0;
    const auto bin = std::size_t(std::min(scaled / 3.0, 0.999999) * double(histogram.size()));
    histogram[bin] += 1.0 / double(distances.size());
  }
  return histogram;
}

}  // namespace morphex::detail

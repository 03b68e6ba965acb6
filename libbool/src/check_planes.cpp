// SPDX-License-Identifier: GPL-3.0-or-later
// Each triangle's plane in doubles (check_planes.h).
#include "check_planes.h"

#include <tbb/parallel_for.h>

namespace morphex::detail {

FacePlanes::FacePlanes(const Mesh& mesh, const std::vector<Xyz>& xyz, double error)
    : xyz_(xyz), error_(error) {
  if (xyz.empty()) return;
  planes_.resize(mesh.num_triangles());
  units_.resize(mesh.num_triangles());
  tbb::parallel_for(std::size_t(0), mesh.num_triangles(), [&](std::size_t t) {
    const Triangle& f = mesh.triangles[t];
    const Xyz &p = xyz[f[0]], &q = xyz[f[1]], &r = xyz[f[2]];
    const double a[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]};
    const double b[3] = {r[0] - p[0], r[1] - p[1], r[2] - p[2]};
    Plane& plane = planes_[t];
    plane.reach = 0;
    plane.corner[0] = p, plane.corner[1] = q, plane.corner[2] = r;
    for (int k = 0; k < 3; ++k) {
      const int i = (k + 1) % 3, j = (k + 2) % 3;
      plane.normal[k] = a[i] * b[j] - a[j] * b[i];
      plane.magnitude[k] = std::fabs(a[i] * b[j]) + std::fabs(a[j] * b[i]);
      plane.reach = std::max({plane.reach, std::fabs(a[k]), std::fabs(b[k])});
    }
    const double* n = plane.normal;
    const double length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    units_[t] = length > 0 && std::isfinite(length)
                    ? Xyz{n[0] / length, n[1] / length, n[2] / length}
                    : Xyz{0, 0, 0};
  });
}

}  // namespace morphex::detail

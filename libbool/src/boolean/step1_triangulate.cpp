// SPDX-License-Identifier: GPL-3.0-or-later
// Step 1: triangulation of the polygons that mesh files list (ear clipping in the plane of the
// exact Newell normal), done as files are read (step1_triangulate.h says why).
#include <algorithm>
#include <stdexcept>
#include <string>

#include "boolean/step1_triangulate.h"

namespace morphex {

void triangulate_polygon(const std::vector<Point>& points, const std::vector<VertexIndex>& polygon,
                         std::vector<Triangle>& out) {
  const std::size_t n = polygon.size();
  if (n < 3) throw InputError("", "polygon with fewer than 3 vertices");
  for (std::size_t i = 0; i < n; ++i)
    if (polygon[i] == polygon[(i + 1) % n])
      throw InputError("", "polygon repeats vertex " + std::to_string(polygon[i]));
  if (n == 3) {
    out.push_back({polygon[0], polygon[1], polygon[2]});
    return;
  }
  // Newell normal, exact: its dominant axis gives a projection that keeps the polygon simple.
  FT nx = 0, ny = 0, nz = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const Point& p = points[polygon[i]];
    const Point& q = points[polygon[(i + 1) % n]];
    nx += (p.y() - q.y()) * (p.z() + q.z());
    ny += (p.z() - q.z()) * (p.x() + q.x());
    nz += (p.x() - q.x()) * (p.y() + q.y());
  }
  const FT ax = CGAL::abs(nx), ay = CGAL::abs(ny), az = CGAL::abs(nz);
  const int axis = (ax >= ay && ax >= az) ? 0 : (ay >= az ? 1 : 2);
  const FT& dominant = axis == 0 ? nx : axis == 1 ? ny : nz;
  if (CGAL::is_zero(dominant)) throw InputError("", "degenerate polygon (zero area)");
  std::vector<Kernel::Point_2> flat;
  for (VertexIndex v : polygon) {
    const Point& p = points[v];
    if (axis == 0)
      flat.emplace_back(p.y(), p.z());
    else if (axis == 1)
      flat.emplace_back(p.z(), p.x());
    else
      flat.emplace_back(p.x(), p.y());
  }
  const CGAL::Orientation ccw =
      CGAL::sign(dominant) == CGAL::POSITIVE ? CGAL::LEFT_TURN : CGAL::RIGHT_TURN;
  std::vector<std::size_t> ring(n);
  for (std::size_t i = 0; i < n; ++i) ring[i] = i;
  while (ring.size() > 3) {
    bool clipped = false;
    for (std::size_t k = 0; k < ring.size() && !clipped; ++k) {
      const std::size_t a = ring[(k + ring.size() - 1) % ring.size()], b = ring[k],
                        c = ring[(k + 1) % ring.size()];
      if (CGAL::orientation(flat[a], flat[b], flat[c]) != ccw) continue;
      bool empty = true;
      for (std::size_t other : ring) {
        if (other == a || other == b || other == c) continue;
        const auto s0 = CGAL::orientation(flat[a], flat[b], flat[other]);
        const auto s1 = CGAL::orientation(flat[b], flat[c], flat[other]);
        const auto s2 = CGAL::orientation(flat[c], flat[a], flat[other]);
        if (s0 != -ccw && s1 != -ccw && s2 != -ccw) {
          empty = false;
          break;
        }
      }
      if (!empty) continue;
      out.push_back({polygon[a], polygon[b], polygon[c]});
      ring.erase(ring.begin() + std::ptrdiff_t(k));
      clipped = true;
    }
    if (!clipped)
      throw InputError("", "polygon cannot be triangulated (self-intersecting or degenerate)");
  }
  if (CGAL::orientation(flat[ring[0]], flat[ring[1]], flat[ring[2]]) != ccw)
    throw InputError("", "polygon cannot be triangulated (degenerate)");
  out.push_back({polygon[ring[0]], polygon[ring[1]], polygon[ring[2]]});
}

}  // namespace morphex

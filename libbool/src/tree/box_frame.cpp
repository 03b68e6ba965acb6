// SPDX-License-Identifier: GPL-3.0-or-later
// Axes for the boxes of a mesh's triangles (box_frame.h).
#include "tree/box_frame.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace morphex::detail {
namespace {

using I = CGAL::Interval_nt<false>;

// About this many faces are looked at: the frame is a heuristic, and must cost little next to
// the traversal it speeds up.
constexpr std::size_t kSampleFaces = 1024;
// The frame is taken when it shrinks the sampled boxes' spread by at least this factor (boxing
// in a frame costs a small matrix product per vertex).
constexpr double kGain = 0.6;
// Normals whose cosine with the first axis is below this (within about 6 degrees of a right
// angle) count as perpendicular to it.
constexpr double kPerpendicular = 0.1;

Xyz minus(const Xyz& a, const Xyz& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
Xyz cross(const Xyz& a, const Xyz& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double dot(const Xyz& a, const Xyz& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
Xyz scaled(const Xyz& a, double s) {
  return {a[0] * s, a[1] * s, a[2] * s};
}
Xyz unit(const Xyz& a) {
  return scaled(a, 1 / std::sqrt(dot(a, a)));
}

// A sampled face's unit normal up to sign (its largest coordinate made positive), its area, and
// the cell of directions it falls in (about 1/32 radian wide).
struct Facing {
  std::uint64_t cell;
  double area;
  Xyz normal;
  bool operator<(const Facing& o) const { return cell < o.cell; }
};

Facing facing(const Xyz& n, double area) {
  int largest = 0;
  for (int k = 1; k < 3; ++k)
    if (std::fabs(n[k]) > std::fabs(n[largest])) largest = k;
  const Xyz u = scaled(n, (n[largest] < 0 ? -1 : 1) / area);
  std::uint64_t cell = 0;
  for (int k = 0; k < 3; ++k) cell = cell * 1024 + std::uint64_t(std::lround(u[k] * 32) + 512);
  return {cell, area, u};
}

// Directions of equal cell, merged: their total area and area-weighted mean normal.
struct Cluster {
  double area = 0;
  Xyz sum{0, 0, 0};
};

std::vector<Cluster> clusters_of(std::vector<Facing> facings) {
  std::stable_sort(facings.begin(), facings.end());
  std::vector<Cluster> out;
  for (std::size_t i = 0; i < facings.size(); ++i) {
    if (i == 0 || facings[i].cell != facings[i - 1].cell) out.emplace_back();
    out.back().area += facings[i].area;
    for (int k = 0; k < 3; ++k) out.back().sum[k] += facings[i].area * facings[i].normal[k];
  }
  return out;
}

// The largest cluster's direction, then the largest one about perpendicular to it (or the
// coordinate axis least aligned with it), made orthogonal, and their cross product.
std::array<Xyz, 3> dominant_axes(const std::vector<Cluster>& clusters) {
  auto largest = [&](auto&& eligible) {
    const Cluster* best = nullptr;
    for (const Cluster& c : clusters)
      if (eligible(c) && (!best || c.area > best->area)) best = &c;
    return best;
  };
  const Xyz first = unit(largest([](const Cluster&) { return true; })->sum);
  const Cluster* across = largest(
      [&](const Cluster& c) { return std::fabs(dot(unit(c.sum), first)) < kPerpendicular; });
  Xyz second{0, 0, 0};
  if (across) {
    second = unit(across->sum);
  } else {
    int least = 0;
    for (int k = 1; k < 3; ++k)
      if (std::fabs(first[k]) < std::fabs(first[least])) least = k;
    second[least] = 1;
  }
  second = unit(minus(second, scaled(first, dot(second, first))));
  return {first, second, cross(first, second)};
}

// A mesh's sampled faces (every stride-th with a finite nonzero normal) and their facings.
struct Sample {
  const Mesh* mesh = nullptr;
  const Xyz* xyz = nullptr;
  std::vector<std::uint32_t> faces;
  std::vector<Facing> facings;
};

Sample sample_of(const Mesh& mesh, const Xyz* xyz, std::size_t faces) {
  Sample s{&mesh, xyz, {}, {}};
  const std::size_t nf = mesh.num_triangles();
  if (!xyz || nf == 0) return s;
  const std::size_t stride = std::max<std::size_t>(1, nf / faces);
  for (std::size_t t = 0; t < nf; t += stride) {
    const Triangle& f = mesh.triangles[t];
    const Xyz n = cross(minus(xyz[f[1]], xyz[f[0]]), minus(xyz[f[2]], xyz[f[0]]));
    const double area = std::sqrt(dot(n, n));
    if (!(area > 0 && std::isfinite(area))) continue;
    s.faces.push_back(std::uint32_t(t));
    s.facings.push_back(facing(n, area));
  }
  return s;
}

// How much the boxes of the sampled faces spread, along given axes: the sum of their boxes'
// pairwise products of extents (about the area they present to one another).
double spread(const Sample& s, const std::array<Xyz, 3>& axes) {
  double total = 0;
  for (const std::uint32_t t : s.faces) {
    double e[3];
    for (int k = 0; k < 3; ++k) {
      double lo = INFINITY, hi = -INFINITY;
      for (const VertexIndex v : s.mesh->triangles[t]) {
        const double c = dot(axes[k], s.xyz[v]);
        lo = std::min(lo, c), hi = std::max(hi, c);
      }
      e[k] = hi - lo;
    }
    total += e[0] * e[1] + e[1] * e[2] + e[2] * e[0];
  }
  return total;
}

// The axes of a sample's dominant normals that shrink the boxes of all samples the most, when
// by at least kGain; else the coordinate axes.
BoxFrame best_frame(const std::vector<Sample>& samples) {
  auto spread_along = [&](const std::array<Xyz, 3>& axes) {
    double total = 0;
    for (const Sample& s : samples) total += spread(s, axes);
    return total;
  };
  BoxFrame best;
  double least = kGain * spread_along({Xyz{1, 0, 0}, Xyz{0, 1, 0}, Xyz{0, 0, 1}});
  for (const Sample& s : samples) {
    if (s.facings.empty()) continue;
    const std::array<Xyz, 3> axes = dominant_axes(clusters_of(s.facings));
    const double along = spread_along(axes);
    if (along < least) least = along, best.world = false, best.axis = axes;  // false for NaN
  }
  return best;
}

}  // namespace

BoxFrame choose_box_frame(const Mesh& mesh, const std::vector<Xyz>& xyz) {
  return best_frame({sample_of(mesh, xyz.empty() ? nullptr : xyz.data(), kSampleFaces)});
}

BoxFrame choose_box_frame(const Mesh& a, const Xyz* xyz_a, const Mesh& b, const Xyz* xyz_b) {
  return best_frame({sample_of(a, xyz_a, kSampleFaces / 2), sample_of(b, xyz_b, kSampleFaces / 2)});
}

ApproxPoint point_in_frame(const BoxFrame& frame, const ApproxPoint& p) {
  if (frame.world) return p;
  I c[3];
  for (int k = 0; k < 3; ++k) {
    const Xyz& a = frame.axis[k];
    c[k] = a[0] * p.x() + a[1] * p.y() + a[2] * p.z();
  }
  return {c[0], c[1], c[2]};
}

FloatBox box_in_frame(const BoxFrame& frame, const ApproxPoint& p) {
  return FloatBox::of(point_in_frame(frame, p));
}

FloatBox box_in_frame(const BoxFrame& frame, const CGAL::Bbox_3& box) {
  if (frame.world) return FloatBox::of(box);
  return FloatBox::of(point_in_frame(
      frame, {I(box.xmin(), box.xmax()), I(box.ymin(), box.ymax()), I(box.zmin(), box.zmax())}));
}

std::vector<FloatBox> boxes_in_frame(const BoxFrame& frame, const PointTable& table, PointId first,
                                     std::size_t count) {
  std::vector<FloatBox> boxes(count);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, 4096),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      const UpwardRounding rounding;
                      for (std::size_t i = range.begin(); i != range.end(); ++i)
                        boxes[i] = box_in_frame(frame, table.approx(first + PointId(i)));
                    });
  return boxes;
}

}  // namespace morphex::detail

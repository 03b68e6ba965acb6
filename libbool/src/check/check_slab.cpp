// SPDX-License-Identifier: GPL-3.0-or-later
// The boxes and the projection test that the nearly flat patches of the self-intersection check
// rely on (check_planar.h): a triangle's part in a patch's slab, a thin triangle's slices, and
// whether a triangle and a box are apart along the patch's axis. All in interval arithmetic, the
// caller rounding upward, so that every box holds what it claims.
#include <algorithm>
#include <cmath>

#include "check/check_planar.h"

namespace morphex::detail {
namespace {
using I = CGAL::Interval_nt<false>;
}  // namespace

ApproxCorners corners_in(const PointTable& table, const BoxFrame& frame,
                         const std::array<PointId, 3>& t) {
  return {point_in_frame(frame, table.approx(t[0])), point_in_frame(frame, table.approx(t[1])),
          point_in_frame(frame, table.approx(t[2]))};
}

int dropped_in(const BoxFrame& frame, const PlanarPatch& patch) {
  if (frame.world) return patch.dropped;
  int best = 0;
  double along[3];
  for (int k = 0; k < 3; ++k) {
    const Xyz& a = frame.axis[k];
    along[k] = std::fabs(a[0] * patch.normal[0] + a[1] * patch.normal[1] + a[2] * patch.normal[2]);
    if (along[k] > along[best]) best = k;
  }
  return best;
}

EdgeLines edge_lines(const ApproxCorners& t, int dropped) {
  EdgeLines out;
  out.u = dropped == 0 ? 1 : 0, out.v = dropped == 2 ? 1 : 2;
  I x[3], y[3];
  for (int k = 0; k < 3; ++k) {
    x[k] = t[k].cartesian(out.u);
    y[k] = t[k].cartesian(out.v);
  }
  for (int k = 0; k < 3; ++k) {
    const int j = (k + 1) % 3, o = (k + 2) % 3;
    // side(p) = (b - a) x (p - a) for the edge a b; the triangle's third corner fixes the inside.
    EdgeLines::Line l;
    l.ex = x[j] - x[k], l.ey = y[j] - y[k], l.x = x[k], l.y = y[k];
    const I inner = l.ex * (y[o] - l.y) - l.ey * (x[o] - l.x);
    l.positive = inner.inf() > 0;
    if (!l.positive && !(inner.sup() < 0)) continue;
    // The box is outside when its corner most to the inside is: the one the gradient of the
    // inside's side (-ey, ex) points to, or both along an axis where its sign is uncertain.
    const I gu = l.positive ? -l.ey : l.ey, gv = l.positive ? l.ex : -l.ex;
    // (A gradient component that is exactly zero takes either corner.)
    l.u_first = gu.inf() >= 0 ? 1 : 0, l.u_last = gu.sup() <= 0 ? 0 : 1;
    l.v_first = gv.inf() >= 0 ? 1 : 0, l.v_last = gv.sup() <= 0 ? 0 : 1;
    if (l.u_first > l.u_last) l.u_first = l.u_last = 0;
    if (l.v_first > l.v_last) l.v_first = l.v_last = 0;
    out.line[out.count++] = l;
  }
  return out;
}

bool apart_along_axis(const EdgeLines& lines, const CGAL::Bbox_3& part) {
  const double bx[2] = {part.min(lines.u), part.max(lines.u)},
               by[2] = {part.min(lines.v), part.max(lines.v)};
  for (int k = 0; k < lines.count; ++k) {
    const EdgeLines::Line& l = lines.line[k];
    bool all_out = true;
    for (int cu = l.u_first; cu <= l.u_last && all_out; ++cu)
      for (int cv = l.v_first; cv <= l.v_last && all_out; ++cv) {
        const I s = l.ex * (I(by[cv]) - l.y) - l.ey * (I(bx[cu]) - l.x);
        all_out = l.positive ? s.sup() < 0 : s.inf() > 0;
      }
    if (all_out) return true;
  }
  return false;
}

namespace {

// The box of the part of triangle t where the affine function h (its values at the corners
// given) lies in [low, high]: the hull of the corners in that range and of the points where the
// edges cross h = low and h = high, each taken with its interval. Empty when no part is.
CGAL::Bbox_3 part_between(const ApproxCorners& t, const I (&h)[3], double low, double high) {
  CGAL::Bbox_3 part;
  for (int k = 0; k < 3; ++k) {
    const ApproxPoint& x = t[k];
    if (h[k].inf() <= high && h[k].sup() >= low) part += x.bbox();
    const int j = (k + 1) % 3;
    const ApproxPoint& y = t[j];
    for (const double c : {low, high}) {
      const bool k_over = h[k].inf() > c, k_under = h[k].sup() < c;
      const bool j_over = h[j].inf() > c, j_under = h[j].sup() < c;
      if ((k_over && j_over) || (k_under && j_under)) continue;  // the edge stays on one side
      const I rise = h[j] - h[k];
      if (rise.inf() <= 0 && rise.sup() >= 0) {  // too flat to place the crossing: the edge
        part += x.bbox();
        part += y.bbox();
        continue;
      }
      const I s = (c - h[k]) / rise;
      part += (x + s * (y - x)).bbox();
    }
  }
  return part;
}

CGAL::Bbox_3 common_box(const CGAL::Bbox_3& a, const CGAL::Bbox_3& b) {
  return {std::max(a.xmin(), b.xmin()), std::max(a.ymin(), b.ymin()), std::max(a.zmin(), b.zmin()),
          std::min(a.xmax(), b.xmax()), std::min(a.ymax(), b.ymax()), std::min(a.zmax(), b.zmax())};
}

}  // namespace

std::optional<CGAL::Bbox_3> part_in_slab(const PointTable& table, const PlanarPatch& patch,
                                         const std::array<PointId, 3>& t, const BoxFrame& frame) {
  const auto& n = patch.normal;
  I h[3];
  bool above = true, below = true;
  for (int k = 0; k < 3; ++k) {
    const ApproxPoint& x = table.approx(t[k]);  // the slab is along the coordinate axes
    h[k] = n[0] * x.x() + n[1] * x.y() + n[2] * x.z();
    above &= h[k].inf() > patch.high;
    below &= h[k].sup() < patch.low;
  }
  if (above || below) return std::nullopt;
  // The part's corners and crossings in the frame: the crossings' parameters along the edges are
  // the same in any coordinates. Both boxes hold the part; their intersection does too.
  const ApproxCorners c = corners_in(table, frame, t);
  CGAL::Bbox_3 whole;
  for (const ApproxPoint& x : c) whole += x.bbox();
  return common_box(part_between(c, h, patch.low, patch.high), whole);
}

namespace {

std::array<double, 3> rough_cross(const ApproxCorners& t) {
  double p[3][3];
  for (int k = 0; k < 3; ++k)
    for (int a = 0; a < 3; ++a) p[k][a] = t[k].cartesian(a).inf();
  const double u[3] = {p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2]};
  const double v[3] = {p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2]};
  return {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
}

}  // namespace

std::array<double, 3> rough_cross(const PointTable& table, const std::array<PointId, 3>& t) {
  return rough_cross(ApproxCorners{table.approx(t[0]), table.approx(t[1]), table.approx(t[2])});
}

int pieces_for(const ApproxCorners& t) {
  constexpr int kMaxPieces = 16;
  // The box's two largest extents against the triangle's area (in doubles: any count is sound).
  // A thin triangle lying diagonally has a box face about its length squared, one along an
  // axis about its own area; slicing a diagonal one into k pieces shrinks each box k-fold.
  CGAL::Bbox_3 box;
  for (const ApproxPoint& x : t) box += x.bbox();
  double extent[3] = {box.xmax() - box.xmin(), box.ymax() - box.ymin(), box.zmax() - box.zmin()};
  std::sort(extent, extent + 3);
  const std::array<double, 3> c = rough_cross(t);
  const double twice_area = std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
  const double pieces = std::sqrt(extent[2] * extent[1] / (2 * twice_area));
  if (!(pieces < kMaxPieces)) return twice_area > 0 ? kMaxPieces : 1;  // too thin to tell: one
  return std::max(1, int(pieces));
}

void add_pieces(const ApproxCorners& t, int pieces, std::vector<CGAL::Bbox_3>& out) {
  CGAL::Bbox_3 whole;
  for (const ApproxPoint& x : t) whole += x.bbox();
  if (pieces <= 1) {
    out.push_back(whole);
    return;
  }
  int axis = 0;
  for (int a = 1; a < 3; ++a)
    if (whole.max(a) - whole.min(a) > whole.max(axis) - whole.min(axis)) axis = a;
  const I h[3] = {t[0].cartesian(axis), t[1].cartesian(axis), t[2].cartesian(axis)};
  const double lo = whole.min(axis), step = (whole.max(axis) - lo) / pieces;
  for (int i = 0; i < pieces; ++i) {
    // The last piece ends at the box's end, whatever the rounding of the steps.
    const double a = i == 0 ? lo : lo + i * step,
                 b = i + 1 == pieces ? whole.max(axis) : lo + (i + 1) * step;
    const CGAL::Bbox_3 piece = common_box(part_between(t, h, a, b), whole);
    if (piece.xmin() <= piece.xmax() && piece.ymin() <= piece.ymax() &&
        piece.zmin() <= piece.zmax())
      out.push_back(piece);
  }
}

}  // namespace morphex::detail

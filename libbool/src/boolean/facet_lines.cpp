// SPDX-License-Identifier: GPL-3.0-or-later
#include "boolean/facet_lines.h"

#include <algorithm>

namespace morphex::detail {

namespace {
constexpr std::size_t kKept = 64;  // points kept on the plane: lookups stay a short scan
}

std::vector<PointId> FacetLines::span(PointId p, PointId q, PointId r) const {
  const PointTable& t = table_;
  const PointId corner = facet_[0];
  if (!t.is_input(corner) || t.same_mesh()) return {};
  const int side = t.side_of_input(corner);
  auto other = [&](PointId id) { return t.is_input(id) && t.side_of_input(id) != side; };
  std::vector<PointId> out;
  for (const PointId x : {p, q, r}) {
    if (t.is_input(x)) {
      out.push_back(x);
      continue;
    }
    const Recipe& recipe = t.recipe(x);
    if (recipe.kind != Recipe::Kind::EdgePlane && recipe.kind != Recipe::Kind::EdgeProjectedLine)
      return {};
    if (other(recipe.p)) {
      out.insert(out.end(), {recipe.p, recipe.q});
    } else if (recipe.kind == Recipe::Kind::EdgePlane && other(recipe.a)) {
      out.insert(out.end(), {recipe.a, recipe.b, recipe.c});
    } else {
      return {};
    }
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

bool FacetLines::on_kept_plane(const std::vector<PointId>& span) {
  if (!plane_) return false;
  for (const PointId x : span) {
    if (std::find(on_.begin(), on_.end(), x) != on_.end()) continue;
    if ((*plane_)(x) != CGAL::ZERO) return false;
    if (on_.size() < kKept) on_.push_back(x);
  }
  return true;
}

bool FacetLines::collinear(PointId p, PointId q, PointId r) {
  const std::vector<PointId> s = span(p, q, r);
  if (s.empty()) return false;
  if (on_kept_plane(s)) return true;
  const PointTable& t = table_;
  // Three of them not on one line, a, b and c; if there are none, the three points are on the
  // line of them all.
  auto on_line = [&](PointId a, PointId b, PointId c) {
    for (int axis = 0; axis < 3; ++axis)
      if (t.orientation_2(axis, a, b, c) != CGAL::ZERO) return false;
    return true;
  };
  const std::size_t n = s.size();
  std::size_t i = 1;
  while (i < n && t.equal(s[0], s[i])) ++i;
  if (i == n) return true;
  std::size_t j = i + 1;
  while (j < n && on_line(s[0], s[i], s[j])) ++j;
  if (j == n) return true;
  const std::array<PointId, 3> abc = {s[0], s[i], s[j]};
  const PointTable::PlaneSides plane(t, abc);
  for (std::size_t k = i + 1; k < n; ++k)
    if (k != j && plane(s[k]) != CGAL::ZERO) return false;
  // Their plane is not the facet's: it meets the facet's plane in a line.
  for (const PointId x : abc)
    if (t.orientation(facet_[0], facet_[1], facet_[2], x) != CGAL::ZERO) {
      plane_.emplace(t, abc);
      on_.assign(s.begin(), s.begin() + std::ptrdiff_t(std::min(s.size(), kKept)));
      return true;
    }
  return false;
}

}  // namespace morphex::detail

// SPDX-License-Identifier: GPL-3.0-or-later
#include "point_index.h"

#include <cmath>
#include <cstring>
#include <type_traits>
#include <optional>

namespace morphex::detail {

namespace {

// The three coordinates as doubles when each one is exactly a double, without exact evaluation
// whenever the interval approximation already says so. (+0.0 stands for -0.0: equal values.)
std::optional<std::array<double, 3>> double_coordinates(const Point& p) {
  const auto& a = CGAL::approx(p);
  if (a.x().is_point() && a.y().is_point() && a.z().is_point())
    return std::array<double, 3>{a.x().inf() + 0.0, a.y().inf() + 0.0, a.z().inf() + 0.0};
  const auto& e = CGAL::exact(p);
  std::array<double, 3> c{};
  using Exact = std::decay_t<decltype(e.x())>;
  const Exact* exact[3] = {&e.x(), &e.y(), &e.z()};
  for (int i = 0; i < 3; ++i) {
    c[i] = CGAL::to_double(*exact[i]) + 0.0;
    if (!std::isfinite(c[i]) || Exact(c[i]) != *exact[i]) return std::nullopt;
  }
  return c;
}

}  // namespace

std::size_t PointIndex::Hash::operator()(const std::array<double, 3>& c) const {
  std::uint64_t h = 0x9e3779b97f4a7c15ull;
  for (double d : c) {
    std::uint64_t bits;
    std::memcpy(&bits, &d, sizeof bits);
    h ^= bits + 0x9e3779b97f4a7c15ull + (h << 6) + (h >> 2);
  }
  return std::size_t(h);
}

PointIndex::PointIndex(std::vector<Point>& points) : points_(points) {
  doubles_.reserve(points.size() * 2);
  const std::size_t n = points.size();
  for (std::size_t i = 0; i < n; ++i) {
    if (const auto key = double_coordinates(points[i]))
      doubles_.emplace(*key, std::uint32_t(i));
    else
      others_.emplace(points[i], std::uint32_t(i));
  }
}

std::uint32_t PointIndex::id(const Point& p) {
  if (const auto key = double_coordinates(p)) {
    const auto [it, inserted] = doubles_.emplace(*key, std::uint32_t(points_.size()));
    if (inserted) points_.push_back(p);
    return it->second;
  }
  const auto [it, inserted] = others_.emplace(p, std::uint32_t(points_.size()));
  if (inserted) points_.push_back(p);
  return it->second;
}

}  // namespace morphex::detail

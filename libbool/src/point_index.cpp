// SPDX-License-Identifier: GPL-3.0-or-later
#include "point_index.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <optional>
#include <stdexcept>
#include <type_traits>

namespace morphex::detail {

namespace {

// The three coordinates as doubles when each one is exactly a double, without exact evaluation
// whenever the interval approximation already says so. (+0.0 stands for -0.0: equal values.)
std::optional<std::array<double, 3>> double_coordinates(const Point& p) {
  if (has_double_coordinates(p)) {
    const auto& a = CGAL::approx(p);
    return std::array<double, 3>{a.x().inf() + 0.0, a.y().inf() + 0.0, a.z().inf() + 0.0};
  }
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

std::uint64_t hash_integer(mpz_srcptr z, std::uint64_t h) {
  h = mix64(h ^ std::uint64_t(std::int64_t(mpz_sgn(z))));
  for (std::size_t i = 0, n = mpz_size(z); i < n; ++i)
    h = mix64(h ^ std::uint64_t(mpz_getlimbn(z, i)));
  return h;
}

// Exact rationals are kept in lowest terms, so equal values have equal numerators and
// denominators, limb for limb.
std::uint64_t hash_exact(const Point& p) {
  const auto& e = CGAL::exact(p);
  std::uint64_t h = 0x243f6a8885a308d3ull;
  for (int i = 0; i < 3; ++i) {
    const auto& c = e.cartesian(i);
    h = hash_integer(c.get_num_mpz_t(), h);
    h = hash_integer(c.get_den_mpz_t(), h);
  }
  return h;
}

}  // namespace

std::uint32_t PositionIndex::rational_find_or_insert(const Point& p, std::uint32_t id) {
  if (2 * (rational_entries_.size() + 1) > rational_slots_.size()) {
    // Grow and re-insert by the stored hashes.
    std::vector<std::uint32_t> old_slots = std::move(rational_slots_);
    std::vector<std::uint64_t> old_hash = std::move(rational_hash_);
    const std::size_t capacity = std::max<std::size_t>(64, 2 * old_slots.size());
    rational_slots_.assign(capacity, kEmpty);
    rational_hash_.assign(capacity, 0);
    for (std::size_t s = 0; s < old_slots.size(); ++s) {
      if (old_slots[s] == kEmpty) continue;
      std::size_t i = old_hash[s] & (capacity - 1);
      while (rational_slots_[i] != kEmpty) i = (i + 1) & (capacity - 1);
      rational_slots_[i] = old_slots[s];
      rational_hash_[i] = old_hash[s];
    }
  }
  const std::uint64_t h = hash_exact(p);
  const std::size_t mask = rational_slots_.size() - 1;
  for (std::size_t i = h & mask;; i = (i + 1) & mask) {
    const std::uint32_t entry = rational_slots_[i];
    if (entry == kEmpty) {
      rational_slots_[i] = std::uint32_t(rational_entries_.size());
      rational_hash_[i] = h;
      rational_entries_.push_back({p, id});
      return id;
    }
    if (rational_hash_[i] == h && CGAL::exact(rational_entries_[entry].point) == CGAL::exact(p))
      return rational_entries_[entry].id;
  }
}

std::size_t PositionIndex::Hash::operator()(const std::array<double, 3>& c) const {
  std::uint64_t h = 0;
  for (double d : c) {
    std::uint64_t bits;
    std::memcpy(&bits, &d, sizeof bits);
    h = mix64(h ^ bits);
  }
  return std::size_t(h);
}

std::uint32_t PositionIndex::find_or_insert(const Point& p, std::uint32_t id) {
  if (const auto key = double_coordinates(p)) return doubles_.emplace(*key, id).first;
  return rational_find_or_insert(p, id);
}

PointIndex::PointIndex(std::vector<Point>& points) : points_(points) {
  if (!points.empty()) throw std::logic_error("PointIndex: the point vector must start empty");
}

}  // namespace morphex::detail

// SPDX-License-Identifier: GPL-3.0-or-later
#include "exact/point_index.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <optional>
#include <stdexcept>
#include <type_traits>

namespace morphex::detail {

namespace {

// x truncated toward zero to 40 significant bits (the low 13 bits of the significand cleared),
// with magnitudes below 2^-1000 taken as 0 and above 2^1000 as 2^1000: a monotone function of x,
// the same for a double and for any real that GMP truncates to that double first.
double truncated(double x) {
  if (std::fabs(x) < 0x1p-1000) return 0.0;
  if (std::fabs(x) > 0x1p1000) return std::copysign(0x1p1000, x);
  std::uint64_t bits;
  std::memcpy(&bits, &x, sizeof bits);
  bits &= ~std::uint64_t(0x1fff);
  std::memcpy(&x, &bits, sizeof bits);
  return x;
}

std::uint64_t hash_key(const std::array<double, 3>& key) {
  std::uint64_t h = 0x243f6a8885a308d3ull;
  for (const double d : key) {
    std::uint64_t bits;
    std::memcpy(&bits, &d, sizeof bits);
    h = mix64(h ^ bits);
  }
  return h;
}

}  // namespace

void PositionIndex::reserve(std::size_t points) {
  entries_.reserve(points);
  std::size_t capacity = 64;
  while (capacity < 2 * points + 2) capacity *= 2;
  if (capacity > slots_.size()) rebuild(capacity);
}

void PositionIndex::rebuild(std::size_t capacity) {
  slots_.assign(capacity, kEmpty);
  hashes_.assign(capacity, 0);
  for (std::uint32_t e = 0; e < entries_.size(); ++e) {
    const std::uint64_t h = hash_key(entries_[e].key);
    std::size_t i = h & (capacity - 1);
    while (slots_[i] != kEmpty) i = (i + 1) & (capacity - 1);
    slots_[i] = e;
    hashes_[i] = h;
  }
}

bool PositionIndex::same(const Entry& e, const Point& p, bool doubles, const Key& xyz) const {
  if (e.rational == kDoubles && doubles) return e.xyz == xyz;
  if (e.rational == kDoubles) return p == Point(e.xyz[0], e.xyz[1], e.xyz[2]);
  return rationals_[e.rational] == p;
}

template <class Is, class Make>
std::uint32_t PositionIndex::find_or_insert(const Key& key, Is&& is, Make&& make) {
  if (2 * (entries_.size() + 1) > slots_.size())
    rebuild(std::max<std::size_t>(64, 2 * slots_.size()));
  const std::uint64_t h = hash_key(key);
  const std::size_t mask = slots_.size() - 1;
  for (std::size_t i = h & mask;; i = (i + 1) & mask) {
    const std::uint32_t e = slots_[i];
    if (e == kEmpty) {
      slots_[i] = std::uint32_t(entries_.size());
      hashes_[i] = h;
      entries_.push_back(make());
      return entries_.back().id;
    }
    if (hashes_[i] == h && entries_[e].key == key && is(entries_[e])) return entries_[e].id;
  }
}

std::uint32_t PositionIndex::find_or_insert(const Point& p, std::uint32_t id) {
  const auto& a = CGAL::approx(p);
  const bool doubles = has_double_coordinates(p);
  Key key, xyz{};
  for (int k = 0; k < 3; ++k) {
    const auto& c = a.cartesian(k);
    xyz[k] = c.inf() + 0.0;  // +0.0 stands for -0.0: equal values
    const double lo = truncated(c.inf()), hi = truncated(c.sup());
    key[k] =
        lo == hi ? lo + 0.0 : truncated(mpq_get_d(CGAL::exact(p.cartesian(k)).get_mpq_t())) + 0.0;
  }
  return find_or_insert(
      key, [&](const Entry& e) { return same(e, p, doubles, xyz); },
      [&] {
        std::uint32_t rational = kDoubles;
        if (!doubles) {
          rational = std::uint32_t(rationals_.size());
          rationals_.push_back(p);
        }
        return Entry{key, xyz, id, rational};
      });
}

std::uint32_t PositionIndex::find_or_insert(const std::array<double, 3>& point, std::uint32_t id) {
  // A double's interval is the double itself: the key and coordinates of find_or_insert(Point).
  Key key, xyz;
  for (int k = 0; k < 3; ++k) {
    xyz[k] = point[k] + 0.0;
    key[k] = truncated(point[k]) + 0.0;
  }
  return find_or_insert(
      key,
      [&](const Entry& e) {
        return e.rational == kDoubles ? e.xyz == xyz
                                      : rationals_[e.rational] == Point(xyz[0], xyz[1], xyz[2]);
      },
      [&] {
        return Entry{key, xyz, id, kDoubles};
      });
}

PointIndex::PointIndex(std::vector<Point>& points) : points_(points) {
  if (!points.empty()) throw std::logic_error("PointIndex: the point vector must start empty");
}

}  // namespace morphex::detail

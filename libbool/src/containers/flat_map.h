// SPDX-License-Identifier: GPL-3.0-or-later
// An insert-only hash map with open addressing, for the large integer-keyed tables of the Boolean
// (edges to faces, coordinates to point ids): one allocation for the whole table instead of one
// node per entry.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

namespace morphex::detail {

template <class Key, class Value, class Hash>
class FlatMap {
 public:
  explicit FlatMap(std::size_t expected = 0) { rehash(expected); }

  // The value stored for `key`, inserting `value` first when the key is new; true when inserted.
  std::pair<Value, bool> emplace(const Key& key, Value value) {
    if (2 * (size_ + 1) > slots_.size()) rehash(slots_.size());
    std::size_t i = Hash()(key) & mask_;
    for (;; i = (i + 1) & mask_) {
      Slot& s = slots_[i];
      if (!s.used) {
        s = {key, value, true};
        ++size_;
        return {value, true};
      }
      if (s.key == key) return {s.value, false};
    }
  }

  const Value* find(const Key& key) const {
    for (std::size_t i = Hash()(key) & mask_;; i = (i + 1) & mask_) {
      const Slot& s = slots_[i];
      if (!s.used) return nullptr;
      if (s.key == key) return &s.value;
    }
  }

  std::size_t size() const { return size_; }
  void reserve(std::size_t expected) {
    if (2 * expected + 2 > slots_.size()) rehash(expected);
  }

 private:
  struct Slot {
    Key key{};
    Value value{};
    bool used = false;
  };

  // Capacity: a power of two at least twice the expected number of entries.
  void rehash(std::size_t expected) {
    std::size_t capacity = 16;
    while (capacity < 2 * expected + 2) capacity *= 2;
    std::vector<Slot> old = std::move(slots_);
    slots_.assign(capacity, Slot{});
    mask_ = capacity - 1;
    size_ = 0;
    for (const Slot& s : old)
      if (s.used) emplace(s.key, s.value);
  }

  std::vector<Slot> slots_;
  std::size_t mask_ = 0, size_ = 0;
};

// A 64-bit mix (splitmix64's finaliser), so that packed keys with structure spread over the table.
inline std::uint64_t mix64(std::uint64_t x) {
  x ^= x >> 30;
  x *= 0xbf58476d1ce4e5b9ull;
  x ^= x >> 27;
  x *= 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

struct Hash64 {
  std::size_t operator()(std::uint64_t key) const { return std::size_t(mix64(key)); }
};

}  // namespace morphex::detail

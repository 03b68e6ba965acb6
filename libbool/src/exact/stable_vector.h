// SPDX-License-Identifier: GPL-3.0-or-later
// A growing array whose elements never move, indexed in one step. The point table hands out
// references to its points while it grows (constructed points are added during the phases that
// read them); std::deque keeps them in place too, but its blocks of 512 bytes hold ten interval
// points and each index divides by ten and follows a pointer per block. Here blocks hold
// 2^kShift elements: an index is a shift, a mask and one pointer.
// Private to libbool.
#pragma once

#include <cstddef>
#include <memory>
#include <new>
#include <utility>
#include <vector>

namespace morphex::detail {

template <class T, unsigned kShift = 10>
class StableVector {
 public:
  StableVector() = default;
  StableVector(const StableVector&) = delete;
  StableVector& operator=(const StableVector&) = delete;
  StableVector(StableVector&& o) noexcept
      : blocks_(std::move(o.blocks_)), size_(std::exchange(o.size_, 0)) {}
  StableVector& operator=(StableVector&& o) noexcept {
    if (this != &o) {
      clear();
      blocks_ = std::move(o.blocks_);
      size_ = std::exchange(o.size_, 0);
    }
    return *this;
  }
  ~StableVector() { clear(); }

  std::size_t size() const { return size_; }
  T& operator[](std::size_t i) { return blocks_[i >> kShift][i & kMask]; }
  const T& operator[](std::size_t i) const { return blocks_[i >> kShift][i & kMask]; }

  template <class... Args>
  T& emplace_back(Args&&... args) {
    if ((size_ >> kShift) == blocks_.size())
      blocks_.push_back(static_cast<T*>(::operator new(sizeof(T) << kShift, kAlign)));
    T* slot = &blocks_[size_ >> kShift][size_ & kMask];
    new (slot) T(std::forward<Args>(args)...);
    ++size_;
    return *slot;
  }
  void push_back(const T& value) { emplace_back(value); }

 private:
  static constexpr std::size_t kMask = (std::size_t(1) << kShift) - 1;
  static constexpr std::align_val_t kAlign{alignof(T)};

  void clear() {
    for (std::size_t i = 0; i < size_; ++i) (*this)[i].~T();
    for (T* block : blocks_) ::operator delete(block, kAlign);
    blocks_.clear();
    size_ = 0;
  }

  std::vector<T*> blocks_;
  std::size_t size_ = 0;
};

}  // namespace morphex::detail

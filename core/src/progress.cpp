// SPDX-License-Identifier: GPL-3.0-or-later
// Progress reports: a thread-local pointer to the current frame, and one lock per displayed
// operation so that the sink sees shares in order from whichever thread finished the work.
#include "morphex/progress.h"

#include <algorithm>
#include <mutex>

namespace morphex {
namespace detail {

struct ProgressShared {
  ProgressSink sink;
  std::mutex mutex;
  double last = -1;
  std::string last_phase;

  void emit(double share, const std::string& phase) {
    std::lock_guard<std::mutex> lock(mutex);
    share = std::clamp(share, 0.0, 1.0);
    // Monotone, and at most every 1/1000 unless the phase changes: a counter of millions of units
    // must not call the sink millions of times.
    if (share < last + 1e-3 && phase == last_phase && share < 1) return;
    if (share < last) share = last;
    last = share;
    last_phase = phase;
    try {
      sink(share, phase);
    } catch (...) {
    }
  }
};

void ProgressFrame::report(double share) const {
  if (shared) shared->emit(lo + (hi - lo) * std::clamp(share, 0.0, 1.0), phase);
}

namespace {
// The frame operations on this thread report into; null when nobody listens (or a counter owns
// the work being done here).
thread_local const ProgressFrame* current = nullptr;

// A nested step without a name keeps its caller's; a named one is shown after its caller's last
// name ("erosion: uniting pieces"), two levels at most so that the line stays short.
std::string nested_phase(const std::string& parent, const std::string& child) {
  if (child.empty()) return parent;
  if (parent.empty()) return child;
  const std::size_t colon = parent.rfind(": ");
  return (colon == std::string::npos ? parent : parent.substr(colon + 2)) + ": " + child;
}
}  // namespace

}  // namespace detail

ProgressScope::ProgressScope(ProgressSink sink) : previous_(detail::current) {
  frame_.shared = std::make_shared<detail::ProgressShared>();
  frame_.shared->sink = std::move(sink);
  detail::current = &frame_;
}

ProgressScope::~ProgressScope() {
  detail::current = previous_;
}

using detail::nested_phase;

ProgressPhase::ProgressPhase(double begin, double end, std::string phase)
    : previous_(detail::current), active_(previous_ != nullptr) {
  if (!active_) return;
  const detail::ProgressFrame& parent = *previous_;
  const double width = parent.hi - parent.lo;
  frame_.shared = parent.shared;
  frame_.lo = parent.lo + width * begin;
  frame_.hi = parent.lo + width * end;
  frame_.phase = nested_phase(parent.phase, phase);
  detail::current = &frame_;
  frame_.report(0);
}

ProgressPhase::~ProgressPhase() {
  if (!active_) return;
  frame_.report(1);
  detail::current = previous_;
}

ProgressCounter::ProgressCounter(double total) : previous_(detail::current), total_(total) {
  if (previous_) frame_ = std::make_unique<detail::ProgressFrame>(*previous_);
  detail::current = nullptr;
}

ProgressCounter::~ProgressCounter() {
  detail::current = previous_;
}

void ProgressCounter::add(double units) {
  if (!frame_ || total_ <= 0) return;
  double done = done_.load(std::memory_order_relaxed);
  while (!done_.compare_exchange_weak(done, done + units, std::memory_order_relaxed)) {
  }
  frame_->report((done + units) / total_);
}

}  // namespace morphex

// SPDX-License-Identifier: GPL-3.0-or-later
// Progress of long operations, for displays: the finished share (0 to 1) of the outermost
// operation a caller runs, and the phase it is in.
//
// A caller that wants progress installs a sink on its thread (ProgressScope) and calls any
// operation there. Operations report in their own terms: a phase boundary (ProgressPhase) or
// units of work finished (ProgressCounter, from any thread: a counter binds to the range that was
// current on the thread that made it). An operation nested inside another reports within the
// range its caller gave it, so a Boolean inside a union tree inside an opening moves the one bar
// of the opening. Without a scope every report is a no-op costing one thread-local read.
//
// The sink is called from whichever thread finished the work, under a lock, with shares that never
// decrease; it should be quick (draw, do not compute). Exceptions from the sink are swallowed:
// a display must not fail the operation it displays.
#pragma once

#include <atomic>
#include <functional>
#include <memory>
#include <optional>
#include <string>

namespace morphex {

using ProgressSink = std::function<void(double share, const std::string& phase)>;

namespace detail {
struct ProgressShared;
// The range of the outermost operation's [0, 1] that the current step covers; phase names the
// step for the display.
struct ProgressFrame {
  std::shared_ptr<ProgressShared> shared;
  double lo = 0, hi = 1;
  std::string phase;
  void report(double share) const;  // share of this frame's range
};
}  // namespace detail

// Installs `sink` for operations run on this thread until destruction (then restores the previous
// one). Not copyable; make one per displayed operation.
class ProgressScope {
 public:
  explicit ProgressScope(ProgressSink sink);
  ~ProgressScope();
  ProgressScope(const ProgressScope&) = delete;
  ProgressScope& operator=(const ProgressScope&) = delete;

 private:
  const detail::ProgressFrame* previous_;
  detail::ProgressFrame frame_;
};

// A step of the current operation covering [begin, end] of its range (shares of that range),
// named `phase`: reports `begin` now and `end` when the step ends, and nested reports on this
// thread land inside. With no scope installed it does nothing.
class ProgressPhase {
 public:
  ProgressPhase(double begin, double end, std::string phase = {});
  ~ProgressPhase();
  ProgressPhase(const ProgressPhase&) = delete;
  ProgressPhase& operator=(const ProgressPhase&) = delete;

 private:
  const detail::ProgressFrame* previous_;
  detail::ProgressFrame frame_;
  bool active_;
};

// Consecutive steps of one operation: next(end, phase) ends the current step (if any) and starts
// one that runs to `end` (a share of the current range), from where the last one ended.
class ProgressSteps {
 public:
  void next(double end, std::string phase) {
    current_.reset();
    current_.emplace(begin_, end, std::move(phase));
    begin_ = end;
  }

 private:
  std::optional<ProgressPhase> current_;
  double begin_ = 0;
};

// Counts finished units of `total` from any thread, reported as a share of the range current on
// the thread that constructed it. While it lives, operations the constructing thread runs report
// nothing of their own (their work is what the counter counts); work on other threads never
// inherits a scope.
class ProgressCounter {
 public:
  explicit ProgressCounter(double total);
  ~ProgressCounter();
  ProgressCounter(const ProgressCounter&) = delete;
  ProgressCounter& operator=(const ProgressCounter&) = delete;
  void add(double units);

 private:
  const detail::ProgressFrame* previous_;
  std::unique_ptr<detail::ProgressFrame> frame_;  // null without a scope
  double total_;
  std::atomic<double> done_{0};
};

}  // namespace morphex

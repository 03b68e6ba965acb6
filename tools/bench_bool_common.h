// SPDX-License-Identifier: GPL-3.0-or-later
// What bench_bool's two case sets share (bench_bool.cpp: generated cases against CGAL's exact
// Booleans; bench_bool_real.cpp: pairs of real meshes against Manifold): the timing of one
// operation (median_seconds) and the forked child each engine runs in (in_child).
#pragma once

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "bench_common.h"
#include "morphex/boolean.h"
#include "morphex/mesh.h"
#include "morphex/shapes.h"

namespace morphex::bench {

struct Case {
  std::string name;
  Mesh a, b;
};

struct Run {
  bool ok = false;
  double seconds = 0, peak_mib = 0;
  std::string volume;  // exact, as a rational string
  std::string note;    // what the engine reported besides (morphex's phases)
};

// Resident memory of this process now (MiB), from /proc/self/statm.
inline double resident_mib() {
  std::ifstream statm("/proc/self/statm");
  double total_pages = 0, resident_pages = 0;
  statm >> total_pages >> resident_pages;
  return resident_pages * double(sysconf(_SC_PAGESIZE)) / (1024.0 * 1024.0);
}

// Set by an engine in the child: sent back after the volume.
inline std::string child_note;

// Times an operation in the steady state of its process: `once` runs it and returns its seconds.
// An operation that takes over half a second runs once; a shorter one runs at least three times
// and until a second has been spent (at most 31 runs), because a median of three millisecond runs
// on a busy two-core machine still moves by a third between invocations. The median is reported.
// Every engine gets the same treatment.
template <class Once>
double median_seconds(Once&& once) {
  std::vector<double> runs{once()};
  double spent = runs[0];
  while (runs[0] < 0.5 && (runs.size() < 3 || (spent < 1.0 && runs.size() < 31))) {
    runs.push_back(once());
    spent += runs.back();
  }
  return median_of(std::move(runs));
}

// Runs `engine` in a child process. The engine times the operation itself (not the volume it
// then computes for the check); time, exact volume and the child's peak memory come back.
template <class Engine>
Run in_child(Engine&& engine) {
  int fds[2];
  if (pipe(fds) != 0) return {};
  const pid_t pid = fork();
  if (pid == 0) {
    close(fds[0]);
    const double inherited_mib = resident_mib();
    std::string message;
    try {
      const std::optional<std::pair<double, FT>> result = engine();
      // A failure carries the engine's reason (its note), if it gave one.
      message = result ? std::to_string(result->first) + " " + to_rational_string(result->second)
                       : "failed" + (child_note.empty() ? "" : " " + child_note);
      if (result) {
        // Peak memory above what the child inherited from the benchmark (the input meshes of
        // every case): the engine's own.
        rusage self{};
        getrusage(RUSAGE_SELF, &self);
        message = std::to_string(std::max(0.0, double(self.ru_maxrss) / 1024.0 - inherited_mib)) +
                  " " + message;
        if (!child_note.empty()) message += " " + child_note;
      }
    } catch (const std::exception& e) {
      message = std::string("failed ") + e.what();
    }
    [[maybe_unused]] auto w = write(fds[1], message.data(), message.size());
    close(fds[1]);
    _exit(0);
  }
  close(fds[1]);
  std::string message;
  char buffer[4096];
  for (ssize_t n; (n = read(fds[0], buffer, sizeof buffer)) > 0;)
    message.append(buffer, std::size_t(n));
  close(fds[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  Run run;
  if (message.empty()) return run;
  if (message.rfind("failed", 0) == 0) {
    run.note = message.size() > 7 ? message.substr(7) : "";
    return run;
  }
  const auto first = message.find(' ');
  run.peak_mib = std::stod(message.substr(0, first));
  message.erase(0, first + 1);
  const auto space = message.find(' ');
  run.ok = true;
  run.seconds = std::stod(message.substr(0, space));
  run.volume = message.substr(space + 1);
  if (const auto note = run.volume.find(' '); note != std::string::npos) {
    run.note = run.volume.substr(note + 1);
    run.volume.resize(note);
  }
  return run;
}

// Each child first runs its engine once on two small crossing cubes, untimed: one-time costs
// (thread pool start, first allocations) are not part of the time per operation that a chain of
// Booleans sees.
struct Warmup {
  Mesh a, b;
};

using Result = std::optional<std::pair<double, FT>>;

// A forked child shares the parent's pages until it writes them, and copying a point handle
// writes its reference count. Each child makes its inputs its own before any clock starts, as a
// process that read them would have them (corefinement's input conversion does it anyway).
inline void own_inputs(const Case& c) {
  const Mesh a = c.a, b = c.b;
}

// The real-mesh pairs set (bench_bool --set real, bench_bool_real.cpp).
struct RealSetOptions {
  BooleanOp op = BooleanOp::Union;
  // "tuning": the pairs the work was measured and tuned on; "held-out": pairs never used to tune
  // anything; "all": both.
  std::string pairs = "tuning";
  std::string only, demo_dir, prusa_dir;
  // Manifold's EMBER cases (ember-benchmark-cases.json and the meshes, ID.stl), as
  // tools/peers/extract-ember-meshes leaves them; the EMBER pairs are skipped without it.
  std::string ember_dir;
  // A pair run while the rest of the machine kept over a quarter of a core busy runs again, up to
  // this many times, and the least disturbed attempt is reported.
  int busy_retries = 2;
  // When set, each selected pair's two meshes are written there as placed (exact OFF,
  // "<A> x <B>.a.off" and ".b.off"), so that one pair can be profiled alone with `bench_bool A B`.
  std::string write_cases;
};
// Runs the set, prints its table and summary, writes the JSON (output.write_json); the exit
// status (0: every pair that ran agreed).
int run_real_set(const RealSetOptions& options, const Harness& output);

}  // namespace morphex::bench

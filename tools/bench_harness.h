// SPDX-License-Identifier: GPL-3.0-or-later
// What every benchmark (and the stress test) shares besides its own cases and table: one CLI11
// command line with the options they have in common (--json, --runs, --threads), the median of
// timed runs, and the JSON output with a record of the run (machine, date, command) under "run",
// written atomically. Argument parsing and plumbing only: no algorithm lives here.
#pragma once

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstddef>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "morphex/internal/stopwatch.h"

namespace morphex::bench {

// The median of measured values: the upper middle one of an even count (a value that was
// measured, not an average of two); 0 without values.
inline double median_of(std::vector<double> values) {
  if (values.empty()) return 0;
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

// The median time of `runs` runs of body, after one untimed warm-up run (first allocations, the
// thread pool's start and cold caches stay out of the figure).
template <class Body>
double median_of_runs(int runs, Body&& body) {
  body();
  std::vector<double> times;
  for (int i = 0; i < runs; ++i) {
    const Stopwatch start;
    body();
    times.push_back(start.seconds());
  }
  return median_of(std::move(times));
}

// Where and how a benchmark ran, for its JSON output: host name, CPU model (/proc/cpuinfo),
// hardware threads, the UTC date in ISO 8601 and the command line (argv, shell-quoted).
nlohmann::json run_record(int argc, const char* const* argv);

// One benchmark's command line and JSON output.
class Harness {
 public:
  explicit Harness(const std::string& description);

  // The benchmark's own options go here.
  CLI::App& app() { return app_; }

  // The shared options, each spelled as every benchmark spells it.
  // --json FILE: the results as JSON (write_json).
  CLI::Option* add_json(const std::string& what = "Write the results as JSON to FILE");
  // --runs N: timed runs per measurement (positive), the median reported.
  CLI::Option* add_runs(int& runs, const std::string& what = "Timed runs per measurement (median)");
  // --threads N: one thread limit (positive; the default is the benchmark's).
  CLI::Option* add_threads(unsigned& threads, const std::string& what);
  // --threads N,M,...: the thread counts to measure, comma-separated.
  CLI::Option* add_thread_counts(std::vector<unsigned>& threads, const std::string& what);

  // Parses the command line. Returns the exit status when the program should stop at once: 0
  // after --help, 2 after a usage error or a --json path in no folder (reported on standard
  // error).
  std::optional<int> parse(int argc, char** argv);

  const std::string& json_path() const { return json_path_; }

  // Without --json, nothing. Otherwise writes `results` (an object, or an array that becomes
  // {"rows": results}) with the run record added under "run", through a temporary file renamed
  // into place: a reader never sees half a file. False (the reason on standard error) when the
  // file could not be written.
  [[nodiscard]] bool write_json(nlohmann::json results) const;

 private:
  CLI::App app_;
  std::string json_path_;
  nlohmann::json run_;
};

}  // namespace morphex::bench

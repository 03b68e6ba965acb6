// SPDX-License-Identifier: GPL-3.0-or-later
// The benchmarks' shared command line and JSON output (bench_harness.h).
#include "bench_harness.h"

#include <unistd.h>

#include <ctime>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <ostream>
#include <thread>

#include "morphex/internal/files.h"

namespace morphex::bench {

namespace {

// The "model name" line of /proc/cpuinfo (the first core's), or "unknown".
std::string cpu_model() {
  std::ifstream cpuinfo("/proc/cpuinfo");
  for (std::string line; std::getline(cpuinfo, line);)
    if (line.rfind("model name", 0) == 0) {
      const auto colon = line.find(':');
      if (colon != std::string::npos) return line.substr(line.find_first_not_of(" \t", colon + 1));
    }
  return "unknown";
}

std::string host_name() {
  char name[256] = {};
  if (gethostname(name, sizeof name - 1) != 0) return "unknown";
  return name;
}

std::string utc_date() {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text;
}

// An argument as a shell reads it back: quoted when it holds anything but plain characters (the
// recorded command can be pasted to run again).
std::string shell_quoted(const std::string& arg) {
  if (!arg.empty() && arg.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                            "0123456789-_=+./,:@%") == std::string::npos)
    return arg;
  std::string out = "'";
  for (const char c : arg) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

// A positive integer (thread counts and runs), with a message that says so.
CLI::Validator positive() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        std::size_t end = 0;
        try {
          if (std::stol(text, &end) > 0 && end == text.size()) return "";
        } catch (const std::exception&) {
        }
        return "a positive integer is needed, not '" + text + "'";
      },
      "POSITIVE");
}

// Why the JSON output cannot be written where --json asks, or "": checked before any work, so
// that a long run does not end without its results.
std::string json_path_problem(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code error;
  if (fs::is_directory(path, error)) return "--json: " + path + " is a folder";
  const fs::path folder = fs::path(path).parent_path();
  if (!folder.empty() && !fs::is_directory(folder, error))
    return "--json: no folder " + folder.string();
  return "";
}

}  // namespace

nlohmann::json run_record(int argc, const char* const* argv) {
  std::string command;
  for (int i = 0; i < argc; ++i) command += (i ? " " : "") + shell_quoted(argv[i]);
  return {{"host", host_name()},
          {"cpu", cpu_model()},
          {"hardware_threads", std::thread::hardware_concurrency()},
          {"date", utc_date()},
          {"command", command}};
}

Harness::Harness(const std::string& description) : app_(description) {}

CLI::Option* Harness::add_json(const std::string& what) {
  return app_.add_option("--json", json_path_, what)->type_name("FILE");
}

CLI::Option* Harness::add_runs(int& runs, const std::string& what) {
  return app_.add_option("--runs", runs, what)->check(positive())->capture_default_str();
}

CLI::Option* Harness::add_threads(unsigned& threads, const std::string& what) {
  return app_.add_option("--threads", threads, what)->check(positive());
}

CLI::Option* Harness::add_thread_counts(std::vector<unsigned>& threads, const std::string& what) {
  return app_.add_option("--threads", threads, what)
      ->delimiter(',')
      ->allow_extra_args(false)  // `--threads 1 mesh.off`: mesh.off is an input
      ->check(positive())
      ->capture_default_str();
}

std::optional<int> Harness::parse(int argc, char** argv) {
  run_ = run_record(argc, argv);
  try {
    app_.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help (and --help-all) exit with 0; a usage error with 2, as the benchmarks did before.
    const int status = app_.exit(e);
    return status == 0 ? 0 : 2;
  }
  if (const std::string problem = json_path_problem(json_path_); !problem.empty()) {
    std::cerr << problem << '\n';
    return 2;
  }
  return std::nullopt;
}

bool Harness::write_json(nlohmann::json results) const {
  if (json_path_.empty()) return true;
  if (!results.is_object()) results = nlohmann::json{{"rows", std::move(results)}};
  results["run"] = run_;
  try {
    write_file_atomically(json_path_, [&](std::ostream& out) { out << results.dump(2) << '\n'; });
  } catch (const std::exception& e) {
    std::cerr << e.what() << '\n';
    return false;
  }
  return true;
}

}  // namespace morphex::bench

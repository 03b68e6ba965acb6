// SPDX-License-Identifier: GPL-3.0-or-later
#include "cli_common.h"

#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "morphex/check.h"
#include "morphex/internal/files.h"
#include "morphex/io.h"
#include "morphex/json.h"

namespace morphex::cli {

void print_error(const std::string& message) {
  std::cerr << "morphex: " << message << '\n';
}

nlohmann::json result_stats(const Mesh& mesh, double seconds) {
  const MeshReport report = check_mesh(mesh);
  nlohmann::json j;
  j["faces"] = mesh.num_triangles();
  j["vertices"] = mesh.num_vertices();
  // A decimal by default: the exact rational can run to thousands of digits (volume_exact, kept
  // by write_result under --exact only).
  j["volume"] = CGAL::to_double(report.volume);
  j["volume_approx"] = CGAL::to_double(report.volume);  // the name scripts used before "volume"
  j["volume_exact"] = to_rational_string(report.volume);
  j["closed"] = report.closed();
  j["self_intersecting"] = report.self_intersections > 0;
  j["valid"] = report.valid_solid();
  j["seconds"] = seconds;
  return j;
}

nlohmann::json rounding_json(const RoundingReport& r) {
  nlohmann::json j = r;
  j.erase("not_a_solid");  // the command line rounds valid solids only
  return j;
}

std::string shown_output(const std::string& path) {
  return path == kStandardStream ? "<stdout>" : path;
}

std::string shown_path(const std::string& path) {
  return path == kStandardStream ? "<stdin>" : path;
}

std::string solid_problem(const std::string& file, const std::string& problem) {
  std::string text = shown_path(file) + ": " + problem;
  for (const char* repairable : {"self-intersects", "non-manifold", "degenerate", "inward"})
    if (problem.find(repairable) != std::string::npos &&
        problem.find("not closed") == std::string::npos)
      return text + " (`morphex repair " + (file == kStandardStream ? "-" : file) +
             " -o repaired.off` makes the valid solid it bounds)";
  return text;
}

std::optional<Solid> read_solid(const std::string& path) {
  try {
    Mesh mesh = read_mesh(path);
    try {
      const OperationProgress progress("check");
      return check_solid(std::move(mesh), path);
    } catch (const InvalidSolid& e) {
      print_error(solid_problem(path, e.problem()));
      return std::nullopt;
    }
  } catch (const std::bad_alloc&) {
    throw;  // reported once, by main, as out of memory
  } catch (const std::exception& e) {
    print_error(e.what());
    return std::nullopt;
  }
}

bool output_overwrites_input(const std::string& output, const std::vector<std::string>& inputs) {
  if (std::count(inputs.begin(), inputs.end(), kStandardStream) > 1) {
    print_error("-: standard input can be read only once: give the other operands as files");
    return true;
  }
  for (const std::string& input : inputs)
    if (input != kStandardStream && output != kStandardStream && same_file(input, output)) {
      print_error(output + ": refusing to overwrite an input");
      return true;
    }
  return false;
}

std::string output_folder_problem(const std::string& path) {
  if (path == kStandardStream) return "";
  namespace fs = std::filesystem;
  std::error_code error;
  fs::path folder = fs::path(path).parent_path();
  if (folder.empty()) folder = ".";
  if (!fs::exists(folder, error))
    return "cannot write in the folder " + folder.string() + ": it does not exist";
  if (!fs::is_directory(folder, error))
    return "cannot write in the folder " + folder.string() + ": it is not a folder";
  if (access(folder.c_str(), W_OK | X_OK) != 0)
    return "cannot write in the folder " + folder.string() + ": no permission";
  return "";
}

bool writes_safe(const std::vector<NamedFile>& writes, const std::vector<NamedFile>& reads) {
  bool safe = true;
  for (std::size_t i = 0; i < writes.size(); ++i) {
    const NamedFile& w = writes[i];
    if (w.path.empty() || w.path == kStandardStream) continue;
    const auto refuse = [&](const std::string& problem) {
      print_error(w.path + ": " + problem);
      safe = false;
    };
    if (const std::string problem = output_folder_problem(w.path); !problem.empty())
      refuse(problem);
    for (const NamedFile& r : reads)
      if (!r.path.empty() && r.path != kStandardStream && same_file(r.path, w.path))
        refuse("refusing to overwrite " + r.role + " " + r.path + " (" + w.role + ")");
    for (std::size_t j = 0; j < i; ++j)
      if (writes[j].path != kStandardStream && same_file(writes[j].path, w.path))
        refuse(w.role + " and " + writes[j].role + " name the same file");
  }
  return safe;
}

std::string se_file(const std::string& spec) {
  if (spec.rfind("mesh:", 0) != 0) return "";
  const std::size_t start = spec.find("path=");
  if (start == std::string::npos) return "";
  const std::size_t end = spec.find(',', start);
  return spec.substr(start + 5, end == std::string::npos ? std::string::npos : end - start - 5);
}

void add_output_options(CLI::App* cmd, OutputArgs& args) {
  // An unknown extension is bad usage, reported before any work (exit 2).
  cmd->add_option("-o,--output", args.out,
                  "Output mesh (format from the extension), or '-' for standard output")
      ->required()
      ->check(CLI::Validator(
          [](std::string& path) -> std::string {
            try {
              if (path != kStandardStream) format_from_path(path);
              return "";
            } catch (const InputError& e) {
              return e.problem();
            }
          },
          "MESH"));
  cmd->add_option("--format", args.format,
                  "Format written to standard output (-o -): off (default), obj, stl, ply, 3mf "
                  "or glb")
      ->check(CLI::Validator(
          [](std::string& name) -> std::string {
            try {
              if (!format_available(format_from_name(name))) format_from_path("x." + name);
              return "";
            } catch (const InputError& e) {
              return e.problem();
            }
          },
          "FORMAT"));
  cmd->add_flag(
      "--exact", args.exact,
      "Write the lossless exact OFF format, and the exact volume (volume_exact) in --stats");
  cmd->add_option("--stats", args.stats, "Write statistics as JSON to FILE, or '-' for stdout");
}

bool output_usable(const OutputArgs& args, const std::vector<std::string>& inputs,
                   const std::vector<NamedFile>& other_reads) {
  const bool to_stdout = args.out == kStandardStream;
  if (to_stdout && args.stats == kStandardStream) {
    print_error(
        "--stats -: standard output carries the mesh (-o -); write the statistics to a file");
    return false;
  }
  if (!to_stdout && !args.format.empty()) {
    print_error("--format " + args.format + ": only for -o - (a file's format is its extension)");
    return false;
  }
  const MeshFormat format =
      to_stdout ? (args.format.empty() ? MeshFormat::Off : format_from_name(args.format))
                : format_from_path(args.out);
  if (args.exact && format != MeshFormat::Off) {
    print_error(shown_path(args.out) + ": the exact format is OFF: use a .off output with --exact");
    return false;
  }
  if (output_overwrites_input(args.out, inputs)) return false;
  std::vector<NamedFile> reads = other_reads;
  for (const std::string& input : inputs) reads.push_back({input, "the input"});
  return writes_safe({{args.out, "--output"}, {args.stats, "--stats"}}, reads);
}

CLI::Validator positive_integer() {
  return CLI::Validator(
      [](std::string& value) -> std::string {
        return !value.empty() && value.size() < 19 &&
                       value.find_first_not_of("0123456789") == std::string::npos &&
                       value.find_first_not_of('0') != std::string::npos
                   ? ""
                   : "expected a positive whole number, got '" + value + "'";
      },
      "POSITIVE");
}

std::string& command_line() {
  static std::string line;
  return line;
}

void write_result(const Mesh& mesh, const OutputArgs& args,
                  const std::function<nlohmann::json()>& stats) {
  WriteOptions options;
  options.exact = args.exact;
  options.provenance = command_line();
  if (!args.format.empty()) options.stream_format = format_from_name(args.format);
  options.measure_rounding = !args.stats.empty();
  const RoundingReport rounding = write_mesh(mesh, args.out, options);
  if (rounding.collapsed)
    print_error("warning: " + shown_output(args.out) +
                ": the result is thinner than the format's resolution everywhere and collapsed "
                "to an empty solid when rounded (--exact with a .off output keeps it)");
  if (args.stats.empty()) return;
  nlohmann::json j = stats();
  if (!args.exact) {
    j.erase("volume_exact");
    j["rounding"] = rounding_json(rounding);
  }
  emit_json(j, args.stats);
}

void emit_json(const nlohmann::json& value, const std::string& target) {
  if (target == "-") {
    std::cout << value.dump() << std::endl;
    return;
  }
  write_file_atomically(target, [&](std::ostream& out) { out << value.dump(2) << '\n'; });
}

ProgressDisplay::ProgressDisplay(std::string verb, std::string units, bool in_logs)
    : verb_(std::move(verb)),
      units_(std::move(units)),
      tty_(isatty(STDERR_FILENO) != 0),
      in_logs_(in_logs) {}

void ProgressDisplay::update(std::size_t done, std::size_t total, std::size_t failed,
                             const std::string& note, double running) {
  if (total == 0 || (!tty_ && !in_logs_)) return;
  const double elapsed = clock_.seconds();
  if (!tty_ && done != total && last_line_ >= 0 && elapsed - last_line_ < 5) return;
  last_line_ = elapsed;
  const double eta = done > 0 ? elapsed / double(done) * double(total - done) : 0;
  std::ostringstream eta_text;
  eta_text << int(eta) / 60 << "m" << std::setw(2) << std::setfill('0') << int(eta) % 60 << "s";
  if (!tty_) {
    std::cerr << verb_ << " " << done << "/" << total << " " << units_ << ", " << failed
              << " failed, ETA " << eta_text.str() << std::endl;
    return;
  }
  const int width = 30;
  const int filled = std::min(width, int(width * (double(done) + running) / double(total)));
  std::cerr << "\r\033[K[" << std::string(filled, '=') << std::string(width - filled, ' ') << "] "
            << done << "/" << total << " " << units_ << ", " << failed << " failed, ETA "
            << eta_text.str() << (note.empty() ? "" : "  " + note) << (done == total ? "\n" : "")
            << std::flush;
}

namespace {
double progress_delay() {
  const char* text = std::getenv("MORPHEX_PROGRESS_AFTER");
  if (!text || !*text) return 2;
  char* end = nullptr;
  const double value = std::strtod(text, &end);
  return end && *end == 0 && value >= 0 ? value : 2;
}
}  // namespace

OperationProgress::OperationProgress(std::string verb)
    : verb_(std::move(verb)),
      tty_(isatty(STDERR_FILENO) != 0),
      after_(progress_delay()),
      scope_([this](double share, const std::string& phase) { draw(share, phase); }) {}

OperationProgress::~OperationProgress() {
  if (drawn_) std::cerr << "\r\033[K" << std::flush;
}

// Called under the progress lock, from whichever thread reported.
void OperationProgress::draw(double share, const std::string& phase) {
  if (!tty_) return;
  const double elapsed = clock_.seconds();
  // Redrawn at most ten times a second: a terminal line is cheap, but not free over ssh.
  if (elapsed < after_ || (last_draw_ >= 0 && elapsed - last_draw_ < 0.1 && share < 1)) return;
  last_draw_ = elapsed;
  drawn_ = true;
  const int width = 30;
  const int filled = std::clamp(int(width * share), 0, width);
  std::ostringstream line;
  line << "\r\033[K" << verb_ << " [" << std::string(filled, '=')
       << std::string(width - filled, ' ') << "] " << std::setw(3) << int(share * 100) << "%  "
       << int(elapsed) / 60 << "m" << std::setw(2) << std::setfill('0') << int(elapsed) % 60 << "s";
  if (!phase.empty()) line << "  " << phase;
  std::cerr << line.str() << std::flush;
}

}  // namespace morphex::cli

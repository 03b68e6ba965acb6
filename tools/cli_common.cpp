// SPDX-License-Identifier: GPL-3.0-or-later
#include "cli_common.h"

#include <unistd.h>

#include <algorithm>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "morphex/check.h"
#include "morphex/io.h"

namespace morphex::cli {

void print_error(const std::string& message) {
  std::cerr << "morphex: " << message << '\n';
}

nlohmann::json result_stats(const Mesh& mesh, double seconds) {
  const MeshReport report = check_mesh(mesh);
  nlohmann::json j;
  j["faces"] = mesh.num_triangles();
  j["vertices"] = mesh.num_vertices();
  j["volume"] = to_rational_string(report.volume);
  j["volume_approx"] = CGAL::to_double(report.volume);
  j["closed"] = report.closed();
  j["self_intersecting"] = report.self_intersections > 0;
  j["valid"] = report.valid_solid();
  j["seconds"] = seconds;
  return j;
}

nlohmann::json rounding_json(const RoundingReport& r) {
  nlohmann::json j = {
      {"moved_vertices", r.moved_vertices},
      {"rounds", r.rounds},
      {"resolved_pairs", r.broken_pairs},
      {"flattened_faces", r.flattened_faces},
      {"max_displacement", r.max_displacement},
      {"collapsed", r.collapsed},
      {"phases",
       {{"round", r.seconds_round}, {"check", r.seconds_check}, {"resolve", r.seconds_resolve}}}};
  if (r.volume_measured) {
    j["volume_change"] = r.volume_change;
    j["relative_volume_change"] = r.relative_volume_change;
  }
  return j;
}

std::string shown_output(const std::string& path) {
  return path == kStandardStream ? "<stdout>" : path;
}

std::string shown_path(const std::string& path) {
  return path == kStandardStream ? "<stdin>" : path;
}

std::optional<Mesh> read_solid(const std::string& path) {
  try {
    Mesh mesh = read_mesh(path);
    const MeshReport report = check_mesh(mesh, kValidityOnly);
    if (!report.valid_solid()) {
      print_error(shown_path(path) + ": " + describe_problems(report));
      return std::nullopt;
    }
    return mesh;
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
  cmd->add_flag("--exact", args.exact, "Write the lossless exact OFF format");
  cmd->add_option("--stats", args.stats, "Write statistics as JSON to FILE, or '-' for stdout");
}

bool output_usable(const OutputArgs& args, const std::vector<std::string>& inputs) {
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
  return !output_overwrites_input(args.out, inputs);
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
  if (!args.exact) j["rounding"] = rounding_json(rounding);
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

}  // namespace morphex::cli

// SPDX-License-Identifier: GPL-3.0-or-later
#include "cli_common.h"

#include <unistd.h>

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

std::optional<Mesh> read_solid(const std::string& path) {
  try {
    Mesh mesh = read_mesh(path);
    const MeshReport report = check_mesh(mesh, kValidityOnly);
    if (!report.valid_solid()) {
      print_error(path + ": " + describe_problems(report));
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
  for (const std::string& input : inputs)
    if (same_file(input, output)) {
      print_error(output + ": refusing to overwrite an input");
      return true;
    }
  return false;
}

void add_output_options(CLI::App* cmd, OutputArgs& args) {
  // An unknown extension is bad usage, reported before any work (exit 2).
  cmd->add_option("-o,--output", args.out, "Output mesh (format from the extension)")
      ->required()
      ->check(CLI::Validator(
          [](std::string& path) -> std::string {
            try {
              format_from_path(path);
              return "";
            } catch (const InputError& e) {
              return e.problem();
            }
          },
          "MESH"));
  cmd->add_flag("--exact", args.exact, "Write the lossless exact OFF format");
  cmd->add_option("--stats", args.stats, "Write statistics as JSON to FILE, or '-' for stdout");
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
  write_mesh(mesh, args.out, options);
  if (!args.stats.empty()) emit_json(stats(), args.stats);
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

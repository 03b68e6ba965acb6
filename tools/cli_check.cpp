// SPDX-License-Identifier: GPL-3.0-or-later
// `morphex check MESH [--json]`: is this file a valid closed solid, and what is its exact volume?
#include <algorithm>
#include <charconv>
#include <chrono>
#include <iostream>

#include "cli_common.h"
#include "morphex/check.h"
#include "morphex/internal/stopwatch.h"
#include "morphex/io.h"
#include "morphex/json.h"

namespace morphex::cli {

namespace {

// A volume as users read it: the shortest decimal that reads back as the same double.
std::string decimal(const FT& value) {
  char text[32];
  const auto end = std::to_chars(text, text + sizeof text, CGAL::to_double(value)).ptr;
  return std::string(text, end);
}

// The library's report, with the file and the time around it; the exact volume only under --exact
// (it can run to thousands of digits).
nlohmann::json report_json(const std::string& path, const MeshReport& r, double seconds,
                           bool exact) {
  nlohmann::json j = r;
  j["file"] = path;
  if (!exact) j.erase("volume_exact");
  j["seconds"] = seconds;
  return j;
}

void print_text(const std::string& path, const MeshReport& r, bool exact) {
  std::cout << path << ": " << (r.valid_solid() ? "valid closed solid" : "NOT a valid solid")
            << '\n'
            << "  triangles " << r.triangles << ", vertices " << r.vertices << ", components "
            << r.components << ", genus "
            << (r.closed() ? std::to_string(r.genus) : "undefined (not closed)") << '\n'
            << "  border edges " << r.border_edges << ", non-manifold edges "
            << r.non_manifold_edges << ", non-manifold vertices " << r.non_manifold_vertices
            << ", degenerate faces " << r.degenerate_faces << '\n'
            << "  consistently oriented " << (r.consistently_oriented ? "yes" : "no")
            << ", outward " << (r.outward ? "yes" : "no") << ", self-intersections "
            << r.self_intersections << '\n'
            << "  volume "
            << (!r.closed() ? "undefined (not closed)"
                : exact     ? to_rational_string(r.volume) + " (~" + decimal(r.volume) + ")"
                            : decimal(r.volume))
            << '\n';
  if (!r.valid_solid()) std::cout << "  problem: " << describe_problems(r) << '\n';
}

// One file: its report on stdout (text, or one JSON line), its problem on stderr. Returns the
// file's exit code.
int check_one(const std::string& file, bool json, bool exact) {
  const std::string path = shown_path(file);
  Mesh mesh;
  try {
    mesh = read_mesh(file);
  } catch (const std::bad_alloc&) {
    throw;
  } catch (const std::exception& e) {
    print_error(e.what());
    // With --json, stdout still carries one object per file, so a script reading it sees why.
    if (json) emit_json({{"file", path}, {"valid", false}, {"error", e.what()}}, "-");
    return kBadInput;
  }
  const Stopwatch start;
  MeshReport report;
  {
    const OperationProgress progress("check");
    report = check_mesh(mesh);
  }
  const double seconds = start.seconds();
  if (json)
    emit_json(report_json(path, report, seconds, exact), "-");
  else
    print_text(path, report, exact);
  if (!report.valid_solid()) {
    print_error(solid_problem(file, describe_problems(report)));
    return kFailed;
  }
  return kSuccess;
}

}  // namespace

Command add_check_command(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "check",
      "Validity report of meshes (exit 0 all valid solids, 1 some not, 2 some unreadable)");
  auto paths = std::make_shared<std::vector<std::string>>();
  auto json = std::make_shared<bool>(false);
  cmd->add_option("MESH", *paths, "Mesh files (OFF, OBJ, STL, PLY, 3MF), '-' for standard input")
      ->required();
  cmd->add_flag("--json", *json, "Print one JSON object per file (one line each) instead of text");
  auto exact = std::make_shared<bool>(false);
  cmd->add_flag("--exact", *exact,
                "Also print the exact volume, a rational (volume_exact in JSON; it can run to "
                "thousands of digits)");
  return {cmd, [=]() -> int {
            if (std::count(paths->begin(), paths->end(), kStandardStream) > 1) {
              print_error("-: standard input can be read only once");
              return kBadInput;
            }
            int worst = kSuccess;  // bad input (2) outranks an invalid solid (1)
            for (const std::string& path : *paths)
              worst = std::max(worst, check_one(path, *json, *exact));
            return worst;
          }};
}

}  // namespace morphex::cli

// SPDX-License-Identifier: GPL-3.0-or-later
// bench_rounding: what writing an exact result to a float format costs and gives (issue 42).
// For every result (Booleans of the real pairs, dilations of meshes by small cubes, octahedra and
// balls), in one run and on one thread: the operation's time, the time of round_mesh to floats
// and to doubles beside it (the ratio is the target: at most 10%), then the result written as
// STL, OBJ, PLY, 3MF and glb, each file read back and checked (a valid solid, and its volume
// against the exact result's).
//
//   bench_rounding [--cases DIR] [--ops union,intersection,difference] [--morph MESH...]
//                  [--se 'cube;octahedron;ball'] [--radii 1/400,1/100,1/20] [--runs N]
//                  [--json FILE]
// --cases: the placed pairs that `bench_bool --set real --write-cases DIR` writes (NAME.a.off,
// NAME.b.off, exact). --morph: meshes scaled by a power of two to a bounding-box diagonal in
// [1, 2), so that the radii are fractions of their size.
#include <tbb/global_control.h>

#include <CLI/CLI.hpp>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "bench_common.h"
#include "bench_harness.h"
#include "morphex/boolean.h"
#include "morphex/check.h"
#include "morphex/internal/huge_pages.h"
#include "morphex/internal/solid_access.h"
#include "morphex/io.h"
#include "morphex/morphology.h"
#include "morphex/rounding.h"
#include "morphex/structuring_element.h"

using namespace morphex;
namespace fs = std::filesystem;

namespace {

struct Options {
  std::string cases;
  std::vector<std::string> ops = {"union", "intersection", "difference"};
  std::vector<std::string> morph, shapes = {"cube", "octahedron", "ball"};
  std::vector<std::string> radii = {"1/400", "1/100", "1/20"};
  int runs = 3;
};

// One result written in every format and read back.
struct Written {
  int files = 0, valid = 0;
  double worst_relative_volume = 0;
  std::map<std::string, double> relative_volume;  // by format
  std::vector<std::string> failures;
};

Written write_everywhere(const Mesh& result, const fs::path& dir) {
  Written w;
  const FT exact = signed_volume(result);
  for (const char* ext : {"stl", "obj", "ply", "3mf", "glb"}) {
    const std::string path = (dir / (std::string("result.") + ext)).string();
    if (!format_available(format_from_path(path))) continue;
    ++w.files;
    try {
      write_mesh(result, path);
      if (std::string(ext) == "glb") {  // written for viewers only: its size is what can be seen
        w.valid += fs::file_size(path) > 0;
        continue;
      }
      const MeshReport r = check_mesh(read_mesh(path));
      if (!r.valid_solid()) {
        w.failures.push_back(std::string(ext) + ": " + describe_problems(r));
        continue;
      }
      ++w.valid;
      const double change =
          CGAL::is_zero(exact) ? 0 : std::fabs(CGAL::to_double((r.volume - exact) / exact));
      w.relative_volume[ext] = change;
      w.worst_relative_volume = std::max(w.worst_relative_volume, change);
    } catch (const std::exception& e) {
      w.failures.push_back(std::string(ext) + ": " + e.what());
    }
  }
  return w;
}

// Where the exact results that failed are kept for a closer look (MORPHEX_ROUNDING_FAILURES).
std::string failures_dir() {
  const char* dir = std::getenv("MORPHEX_ROUNDING_FAILURES");
  return dir ? dir : "";
}

struct Row {
  std::string name, op;
  std::size_t facets = 0;
  double op_seconds = 0, float_seconds = 0, double_seconds = 0;
  RoundingReport report;  // of the float rounding
  RoundingReport double_report;
  Written written;
};

Row measure(const std::string& name, const std::string& op, int runs,
            const std::function<Mesh()>& operation, const fs::path& dir) {
  Row row{name, op};
  Mesh result;
  row.op_seconds = bench::median_of_runs(runs, [&] { result = operation(); });
  row.facets = result.num_triangles();
  make_exact(result);  // as the library's results are: no construction history left to evaluate
  try {
    row.float_seconds = bench::median_of_runs(runs, [&] {
      row.report = round_mesh(result, {RoundingGrid::Float, false}).report;
    });
    row.double_seconds = bench::median_of_runs(runs, [&] {
      row.double_report = round_mesh(result, {RoundingGrid::Double, false}).report;
    });
    row.report.relative_volume_change =
        round_mesh(result, {RoundingGrid::Float, true}).report.relative_volume_change;
  } catch (const std::exception& e) {
    row.float_seconds = row.double_seconds = NAN;
    row.written.failures.push_back(std::string("rounding: ") + e.what());
  }
  const Written written = write_everywhere(result, dir);
  row.written.files = written.files;
  row.written.valid = written.valid;
  row.written.worst_relative_volume = written.worst_relative_volume;
  row.written.relative_volume = written.relative_volume;
  for (const std::string& f : written.failures) row.written.failures.push_back(f);
  if (!row.written.failures.empty() && !failures_dir().empty()) {
    static int count = 0;
    write_mesh(result, failures_dir() + "/failure-" + std::to_string(++count) + ".off", {true});
  }
  return row;
}

void print(const Row& r) {
  std::cout << std::left << std::setw(44) << (r.name + " " + r.op) << std::right << std::setw(8)
            << r.facets << std::setw(10) << std::setprecision(3) << r.op_seconds << std::setw(10)
            << r.float_seconds << std::setw(8) << std::fixed << std::setprecision(1)
            << 100 * r.float_seconds / r.op_seconds << "%" << std::setw(8)
            << 100 * r.double_seconds / r.op_seconds << "%" << std::defaultfloat << std::setw(4)
            << r.report.rounds << std::setw(6) << r.report.broken_pairs << std::setw(11)
            << std::setprecision(2) << r.report.max_displacement << std::setw(11)
            << r.written.worst_relative_volume << std::setw(4) << r.written.valid << "/"
            << r.written.files << '\n';
  for (const std::string& f : r.written.failures) std::cout << "    failed: " << f << '\n';
}

nlohmann::json to_json(const Row& r) {
  return {{"case", r.name},
          {"operation", r.op},
          {"result_facets", r.facets},
          {"operation_seconds", r.op_seconds},
          {"round_float_seconds", r.float_seconds},
          {"round_double_seconds", r.double_seconds},
          {"float_cost_ratio", r.float_seconds / r.op_seconds},
          {"double_cost_ratio", r.double_seconds / r.op_seconds},
          {"rounds", r.report.rounds},
          {"resolved_pairs", r.report.broken_pairs},
          {"flattened_faces", r.report.flattened_faces},
          {"float_phases",
           {{"round", r.report.seconds_round},
            {"check", r.report.seconds_check},
            {"resolve", r.report.seconds_resolve}}},
          {"double_phases",
           {{"round", r.double_report.seconds_round},
            {"check", r.double_report.seconds_check},
            {"resolve", r.double_report.seconds_resolve}}},
          {"double_rounds", r.double_report.rounds},
          {"max_displacement", r.report.max_displacement},
          {"float_relative_volume_change", r.report.relative_volume_change},
          {"files_written", r.written.files},
          {"files_valid", r.written.valid},
          {"worst_relative_volume_error", r.written.worst_relative_volume},
          {"relative_volume_error_by_format", r.written.relative_volume},
          {"failures", r.written.failures}};
}

std::vector<Row> boolean_rows(const Options& o, const fs::path& dir) {
  std::vector<Row> rows;
  if (o.cases.empty()) return rows;
  std::vector<fs::path> firsts;
  for (const auto& e : fs::directory_iterator(o.cases))
    if (e.path().string().size() > 6 &&
        e.path().string().compare(e.path().string().size() - 6, 6, ".a.off") == 0)
      firsts.push_back(e.path());
  std::sort(firsts.begin(), firsts.end());
  for (const fs::path& a_path : firsts) {
    const std::string stem = a_path.string().substr(0, a_path.string().size() - 6);
    // The cases are results of bench_bool's valid pairs: taken as valid, the operation alone,
    // as bench_bool's "m" column.
    const Solid a = detail::trusted_solid(read_mesh(a_path.string())),
                b = detail::trusted_solid(read_mesh(stem + ".b.off"));
    for (const std::string& op : o.ops) {
      const Row row = measure(
          fs::path(stem).filename().string(), op, o.runs,
          [&] { return compute_boolean(a, b, parse_boolean_op(op)).solid.mesh(); }, dir);
      print(row);
      rows.push_back(row);
    }
  }
  return rows;
}

std::vector<Row> morphology_rows(const Options& o, const fs::path& dir) {
  std::vector<Row> rows;
  for (const std::string& path : o.morph) {
    Mesh read = read_mesh(path);
    const double scale = bench::unit_diagonal_scale(read);
    for (Point& p : read.points) p = Point(p.x() * scale, p.y() * scale, p.z() * scale);
    const Solid m = check_solid(std::move(read), path);
    for (const std::string& shape : o.shapes)
      for (const std::string& radius : o.radii) {
        // "ball:level=1" takes its extra parameters after the radius.
        const std::size_t colon = shape.find(':');
        const std::string spec = shape.substr(0, colon) + ":r=" + radius +
                                 (colon == std::string::npos ? "" : "," + shape.substr(colon + 1));
        const StructuringElement se = parse_structuring_element(spec);
        const Row row = measure(
            fs::path(path).stem().string(), "dilate " + spec, 1,
            [&] { return apply_morphology(MorphologyOp::Dilate, m, se).mesh(); }, dir);
        print(row);
        rows.push_back(row);
      }
  }
  return rows;
}

}  // namespace

int main(int argc, char** argv) {
  morphex::use_huge_page_malloc(argv);  // first: it may restart the process
  bench::Harness harness(
      "bench_rounding: the cost and the validity of rounding exact results to floats");
  CLI::App& app = harness.app();
  Options o;
  app.add_option("--cases", o.cases, "Folder of placed pairs written by bench_bool --write-cases");
  app.add_option("--ops", o.ops, "Boolean operations")->delimiter(',');
  app.add_option("--morph", o.morph, "Meshes to dilate");
  app.add_option("--se", o.shapes,
                 "Structuring element shapes, extra parameters after a colon (ball:level=1)")
      ->delimiter(';');
  app.add_option("--radii", o.radii, "Radii, fractions of the bounding-box diagonal")
      ->delimiter(',');
  harness.add_runs(o.runs, "Timed runs per Boolean after a warm-up (median)");
  harness.add_json("Write the rows and the summary as JSON");
  if (const std::optional<int> stop = harness.parse(argc, argv)) return *stop;
  tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
  const fs::path dir =
      fs::temp_directory_path() / ("morphex-bench-rounding-" + std::to_string(getpid()));
  fs::create_directories(dir);
  std::cout << "one thread; seconds are medians; cost: rounding time over the operation's\n"
            << std::left << std::setw(44) << "case" << std::right << std::setw(8) << "facets"
            << std::setw(10) << "op s" << std::setw(10) << "float s" << std::setw(9) << "float"
            << std::setw(9) << "double" << std::setw(4) << "rd" << std::setw(6) << "pairs"
            << std::setw(11) << "max disp" << std::setw(11) << "worst dV" << std::setw(6)
            << "files\n";
  std::vector<Row> rows = boolean_rows(o, dir);
  for (Row& r : morphology_rows(o, dir)) rows.push_back(std::move(r));
  fs::remove_all(dir);
  std::vector<double> ratios;
  int files = 0, valid = 0, resolved = 0;
  double worst = 0;
  std::map<std::string, double> worst_by_format;
  for (const Row& r : rows) {
    for (const auto& [format, change] : r.written.relative_volume)
      worst_by_format[format] = std::max(worst_by_format[format], change);
    if (std::isfinite(r.float_seconds)) ratios.push_back(r.float_seconds / r.op_seconds);
    files += r.written.files;
    valid += r.written.valid;
    resolved += r.report.rounds > 0;
    worst = std::max(worst, r.written.worst_relative_volume);
  }
  std::sort(ratios.begin(), ratios.end());
  const nlohmann::json summary = {{"results", rows.size()},
                                  {"results_resolved", resolved},
                                  {"files_written", files},
                                  {"files_valid", valid},
                                  {"median_float_cost_ratio", bench::median_of(ratios)},
                                  {"max_float_cost_ratio", ratios.empty() ? 0 : ratios.back()},
                                  {"worst_relative_volume_error", worst},
                                  {"worst_relative_volume_error_by_format", worst_by_format}};
  std::cout << "\n" << summary.dump(2) << '\n';
  nlohmann::json all = nlohmann::json::array();
  for (const Row& r : rows) all.push_back(to_json(r));
  if (!harness.write_json({{"rows", all}, {"summary", summary}})) return 2;
  return valid == files ? 0 : 1;
}

// SPDX-License-Identifier: GPL-3.0-or-later
// bench_repair: the exact repair against the validity check on the same meshes, in one run.
//
//   bench_repair [--threads N] [--runs K] [--json FILE] MESH...
// For each mesh: the time of check_mesh (what `morphex check` and every command's input check
// run; CGAL's does_self_intersect beside it as a peer), the time of repair_mesh, their ratio, and
// whether the result is a valid solid whose volume stays near the input's signed volume. Times are
// medians of K runs (default 3) after a warm-up.
#include <tbb/global_control.h>

#include <algorithm>
#include <chrono>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "bench_common.h"
#include "bench_harness.h"
#include "morphex/check.h"
#include "morphex/internal/huge_pages.h"
#include "morphex/internal/stopwatch.h"
#include "morphex/io.h"
#include "morphex/repair.h"
#include "peers.h"

using namespace morphex;

namespace {

using bench::median_of_runs;

}  // namespace

int main(int argc, char** argv) {
  morphex::use_huge_page_malloc(argv);  // first: it may restart the process
  bench::Harness harness("bench_repair: the exact repair against the validity check");
  CLI::App& app = harness.app();
  int runs = 3;
  unsigned threads = std::max(1u, std::thread::hardware_concurrency());
  std::vector<std::string> inputs;
  harness.add_threads(threads, "Thread limit (default: all cores)")->capture_default_str();
  harness.add_runs(runs, "Timed runs per measurement after a warm-up (median)");
  harness.add_json();
  app.add_option("MESH", inputs, "Mesh files")->required();
  if (const std::optional<int> stop = harness.parse(argc, argv)) return *stop;
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  nlohmann::json rows = nlohmann::json::array();
  bool all_valid = true;
  std::cout << std::left << std::setw(34) << "mesh" << std::right << std::setw(8) << "faces"
            << std::setw(7) << "pairs" << std::setw(10) << "check s" << std::setw(10) << "CGAL s"
            << std::setw(10) << "repair s" << std::setw(8) << "ratio" << std::setw(11) << "volume"
            << "  result\n";
  for (const std::string& input : inputs) {
    Mesh mesh;
    try {
      mesh = read_mesh(input);
    } catch (const std::exception& e) {
      std::cerr << e.what() << '\n';
      return 2;
    }
    MeshReport report;
    const double check_seconds =
        median_of_runs(runs, [&] { report = check_mesh(mesh, kValidityOnly); });
    bool cgal_says = false;
    const double cgal_seconds =
        median_of_runs(runs, [&] { cgal_says = peers::cgal_does_self_intersect(mesh); });
    RepairResult repaired;
    std::string outcome;
    double repair_seconds = 0;
    try {
      repair_seconds = median_of_runs(runs, [&] { repaired = repair_mesh(mesh); });
      outcome = check_mesh(repaired.solid, kValidityOnly).valid_solid() ? "valid" : "INVALID";
    } catch (const InputError& e) {
      outcome = std::string("refused: ") + e.what();
    }
    all_valid = all_valid && outcome != "INVALID";
    const double v_in = CGAL::to_double(signed_volume(mesh));
    const double v_out =
        repaired.solid.empty() ? 0 : CGAL::to_double(signed_volume(repaired.solid));
    const double change = v_in != 0 ? (v_out - std::abs(v_in)) / std::abs(v_in) : 0;
    std::cout << std::left << std::setw(33)
              << input.substr(input.size() > 33 ? input.size() - 33 : 0) << ' ' << std::right
              << std::setw(8) << mesh.num_triangles() << std::setw(7) << report.self_intersections
              << std::setw(10) << std::setprecision(3) << check_seconds << std::setw(10)
              << cgal_seconds << std::setw(10) << repair_seconds << std::setw(8)
              << std::setprecision(3) << repair_seconds / check_seconds << std::setw(10)
              << std::setprecision(2) << 100 * change << "%  " << outcome
              << (report.valid_solid() ? " (was valid)" : "") << std::endl;
    rows.push_back({{"mesh", input},
                    {"faces", mesh.num_triangles()},
                    {"self_intersections", report.self_intersections},
                    {"cgal_self_intersects", cgal_says},
                    {"check_seconds", check_seconds},
                    {"cgal_does_self_intersect_seconds", cgal_seconds},
                    {"repair_seconds", repair_seconds},
                    {"ratio", repair_seconds / check_seconds},
                    {"volume_change", change},
                    {"result", outcome},
                    {"threads", threads}});
  }
  if (!harness.write_json(rows)) return 2;
  return all_valid ? 0 : 1;
}

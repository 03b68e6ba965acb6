// SPDX-License-Identifier: GPL-3.0-or-later
// bench_check: the validity check per million facets, on real meshes and on generated inputs with
// long thin facets, at several thread counts, beside CGAL's self-intersection test.
//
//   bench_check [--threads 1,2,4] [--runs K] [--no-peer] [--json FILE] INPUT...
// INPUT is a mesh file or a generated shape:
//   fan-prism:N   a prism over a regular N-gon whose caps are fans from one vertex (CAD-style
//                 flat faces of long thin facets all meeting at one vertex)
//   cylinder:N    a prism whose caps are fans from their centres
//   cone:N        a cone whose side triangles all meet at its apex, its base a fan from one vertex
//   icosphere:L   the icosphere of level L (20 4^L facets)
//   segment-shells:N  N thin tetrahedra around one segment: N shells that all touch there, every
//                 pair of faces boxed together (a crafted file's worst case for the check)
//   rotated:INPUT INPUT under a rational rotation (coordinates that are not doubles, as in the
//                 second operand of bench_bool's real pairs and in every Boolean's output)
// Columns: `morphex check` as the command runs it (exact volume included) on one thread; the
// check the Boolean runs on its inputs (validity only) at each thread count, with the speed-up
// over one thread; CGAL's does_self_intersect (one thread, Epeck) as a peer, and whether the two
// agree that the mesh self-intersects. Times are medians of
// K runs (default 3) after a warm-up; seconds per million facets beside them.
#include <tbb/global_control.h>

#include <algorithm>
#include <iomanip>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "bench_common.h"
#include "bench_harness.h"
#include "morphex/check.h"
#include "morphex/internal/fixtures.h"
#include "morphex/internal/huge_pages.h"
#include "morphex/internal/stopwatch.h"
#include "morphex/io.h"
#include "peers.h"

using namespace morphex;

namespace {

using bench::median_of_runs;
using bench::rational_rotation;

Mesh input_mesh(const std::string& spec) {
  // rotated:SPEC: the mesh under bench_bool's rational rotation (coordinates no longer doubles,
  // as the second operand of its real pairs and every output of a Boolean).
  if (spec.rfind("rotated:", 0) == 0)
    return transformed(input_mesh(spec.substr(8)), rational_rotation(20));
  const auto colon = spec.find(':');
  const std::string kind = spec.substr(0, colon);
  const int n = colon == std::string::npos ? 0 : std::stoi(spec.substr(colon + 1));
  if (kind == "fan-prism") return make_fan_prism(n, 10.0, 5.0);
  if (kind == "cylinder") return make_cylinder(n, 10.0, 2.5);
  if (kind == "cone") return make_fan_cone(n, 10.0, 5.0);
  if (kind == "icosphere") return make_icosphere(n, FT(1));
  if (kind == "segment-shells") return make_tetrahedra_on_segment(n);
  return read_mesh(spec);
}

}  // namespace

int main(int argc, char** argv) {
  morphex::use_huge_page_malloc(argv);  // first: it may restart the process
  bench::Harness harness(
      "bench_check: the validity check per million facets at several thread counts, beside "
      "CGAL's self-intersection test");
  CLI::App& app = harness.app();
  int runs = 3;
  bool peer = true;
  std::vector<unsigned> threads{1, 2, 4};
  std::vector<std::string> inputs;
  harness.add_thread_counts(threads, "Thread counts of the validity check (comma-separated)");
  harness.add_runs(runs, "Timed runs per measurement after a warm-up (median)");
  app.add_flag_callback(
      "--no-peer", [&peer] { peer = false; }, "Without CGAL's does_self_intersect");
  harness.add_json();
  app.add_option("INPUT", inputs,
                 "Mesh files or generated shapes: fan-prism:N, cylinder:N, cone:N, icosphere:L, "
                 "segment-shells:N, rotated:INPUT (default: fan-prism:7000 cone:7000 cylinder:7000 "
                 "icosphere:7)");
  if (const std::optional<int> stop = harness.parse(argc, argv)) return *stop;
  if (inputs.empty()) inputs = {"fan-prism:7000", "cone:7000", "cylinder:7000", "icosphere:7"};
  nlohmann::json rows = nlohmann::json::array();
  std::cout << std::left << std::setw(26) << "input" << std::right << std::setw(9) << "facets"
            << std::setw(10) << "check" << std::setw(8) << "s/M";
  for (const unsigned t : threads)
    std::cout << std::setw(9) << ("valid " + std::to_string(t) + "t");
  std::cout << std::setw(9) << "s/M 1t" << std::setw(9) << "x 2t" << std::setw(10) << "CGAL"
            << std::setw(7) << "valid" << std::setw(7) << "agree\n";
  for (const std::string& spec : inputs) {
    Mesh mesh;
    try {
      mesh = input_mesh(spec);
    } catch (const std::exception& e) {
      std::cerr << "bench_check: skipping " << spec << ": " << e.what() << '\n';
      continue;
    }
    const double facets = double(mesh.num_triangles()), per_million = 1e6 / facets;
    nlohmann::json row{{"input", spec}, {"facets", mesh.num_triangles()}};
    bool valid = false;
    double full = 0;
    {
      const tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
      full = median_of_runs(runs, [&] { valid = check_mesh(mesh).valid_solid(); });
    }
    row["check_seconds"] = full;
    row["valid"] = valid;
    std::map<unsigned, double> validity;
    for (const unsigned t : threads) {
      const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, t);
      validity[t] = median_of_runs(runs, [&] { check_mesh(mesh, kValidityOnly); });
      row["validity_seconds"][std::to_string(t)] = validity[t];
    }
    double cgal = 0;
    std::string agree = "-";
    if (peer) {
      const tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
      bool cgal_says = false;
      cgal = median_of_runs(1, [&] { cgal_says = peers::cgal_does_self_intersect(mesh); });
      // CGAL tells contacts apart by vertex index, morphex by position: they may differ (by
      // design) only on meshes with coincident distinct vertices.
      const bool ours = check_mesh(mesh, kValidityOnly).self_intersections > 0;
      agree = ours == cgal_says ? "yes" : "NO";
      row["cgal_self_intersection_seconds"] = cgal;
      row["self_intersecting"] = ours;
      row["cgal_self_intersecting"] = cgal_says;
    }
    // The file's name without its directory, any prefix such as rotated: kept.
    const std::size_t slash = spec.find_last_of('/'), colon = spec.find(':');
    const std::string name =
        slash == std::string::npos
            ? spec
            : (colon < slash ? spec.substr(0, colon + 1) : std::string()) + spec.substr(slash + 1);
    std::cout << std::left << std::setw(26) << name.substr(0, 25) << std::right << std::setw(9)
              << mesh.num_triangles() << std::fixed << std::setprecision(3) << std::setw(10) << full
              << std::setprecision(2) << std::setw(8) << full * per_million << std::setprecision(3);
    for (const unsigned t : threads) std::cout << std::setw(9) << validity[t];
    const double first = validity[threads.front()];
    std::cout << std::setprecision(2) << std::setw(9) << first * per_million << std::setw(9)
              << (validity.count(2) ? first / validity[2] : 0.0) << std::setprecision(3)
              << std::setw(10) << (peer ? cgal : 0.0) << std::setw(7) << (valid ? "yes" : "NO")
              << std::setw(7) << agree << '\n';
    rows.push_back(row);
  }
  if (!harness.write_json(rows)) return 2;
  return 0;
}

// SPDX-License-Identifier: GPL-3.0-or-later
// bench_morph: morphex morphology against CGAL's minkowski_sum_3 (Nef polyhedra, exact) and
// Manifold's MinkowskiSum/MinkowskiDifference (floating point) on the same input in the same run,
// with volumes compared, wall time and peak memory.
//
//   bench_morph [--se SPEC] [--ops dilate,erode,open,close] [--peer] [--manifold]
//               [--manifold-timeout S] [--nary] [--chain N] [--threads N] [--normalize]
//               [--repair] [--json FILE] INPUT...
// INPUT is a mesh file or a generated mesh: torus:U,V (U*V*2 facets, non-convex), l-shape,
// icosphere:L. --normalize scales each input by a power of two so that its bounding-box
// diagonal lies in [1, 2) (one SE size for every input, coordinates still doubles); --repair
// makes inputs that are not valid solids valid first (morphex repair). --peer runs
// minkowski_sum_3 on every dilation; --manifold runs Manifold (when bench_morph was built with it:
// tools/peers/build-manifold) on every operation, under the same --threads, in a process of its
// own that is stopped after --manifold-timeout seconds (default 900; its row then records the
// limit and the ratio it bounds); --nary also times
// the dilation with the pieces united by one winding arrangement instead of the binary-union tree
// (the default); --chain N dilates N times in a row and reports the first and the last step.
#include <poll.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <tbb/global_control.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "bench_common.h"
#include "bench_harness.h"
#include "manifold_peer.h"
#include "morphex/boolean.h"
#include "morphex/check.h"
#include "morphex/internal/huge_pages.h"
#include "morphex/internal/solid_access.h"
#include "morphex/internal/stopwatch.h"
#include "morphex/io.h"
#include "morphex/minkowski.h"
#include "morphex/morphology.h"
#include "morphex/repair.h"
#include "morphex/shapes.h"
#include "peers.h"

using namespace morphex;

namespace {

// Peak resident memory of the process so far (Linux reports KiB).
double peak_mib() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss / 1024.0;
}

Mesh load(const std::string& input) {
  if (input.rfind("torus:", 0) == 0) {
    int u = 16, v = 10;
    char comma;
    std::istringstream(input.substr(6)) >> u >> comma >> v;
    return make_torus(u, v, 1.0, 0.4);
  }
  if (input.rfind("icosphere:", 0) == 0) return make_icosphere(std::stoi(input.substr(10)), FT(1));
  if (input == "l-shape")
    return compute_boolean(check_solid(make_box(Point(0, 0, 0), Point(2, 1, 1))),
                           check_solid(make_box(Point(0, 0, 0), Point(1, 2, 1))), BooleanOp::Union)
        .solid.mesh();
  return read_mesh(input);
}

// Scaled by the power of two that brings its bounding-box diagonal into [1, 2): an exact
// scaling that keeps double coordinates doubles, so that one SE size fits every input.
Mesh scaled_to_unit_diagonal(const Mesh& m) {
  Mesh out = transformed(m, Transformation(CGAL::SCALING, FT(bench::unit_diagonal_scale(m))));
  make_exact(out);
  return out;
}

// The command line's settings, with their defaults.
struct Options {
  std::string se_spec = "cube:r=1/20";
  std::vector<std::string> ops = {"dilate"}, inputs;
  bool peer = false, nary = false, normalize = false, repair = false, manifold = false;
  bool manifold_child = false;  // this process is the Manifold run of another (see below)
  double manifold_timeout = 900;
  int chain = 0;
  unsigned threads = 0;  // 0: all cores
};

// The input as the benchmark runs it: read or generated, repaired and scaled as asked.
Mesh prepared(const std::string& input, const Options& o) {
  Mesh a = load(input);
  if (o.repair) a = repair_mesh(a).solid.mesh();
  if (o.normalize) a = scaled_to_unit_diagonal(a);
  return a;
}

// The command line (see the top of this file) into `o`.
void add_options(bench::Harness& harness, Options& o) {
  CLI::App& app = harness.app();
  app.add_option("--se", o.se_spec, "Structuring element")->capture_default_str();
  // One comma-separated argument: `--ops open,close mesh.off` leaves mesh.off an input.
  app.add_option("--ops", o.ops, "Operations: dilate, erode, open, close (comma-separated)")
      ->delimiter(',')
      ->allow_extra_args(false)
      ->capture_default_str();
  app.add_flag("--peer", o.peer, "Run CGAL's minkowski_sum_3 on every dilation");
  app.add_flag("--manifold", o.manifold,
               "Run Manifold's MinkowskiSum/MinkowskiDifference on every operation");
  app.add_flag("--nary", o.nary,
               "Also time the dilation with the pieces united by one winding arrangement");
  app.add_option("--manifold-timeout", o.manifold_timeout,
                 "Stop a Manifold run after this many seconds (its row records the limit)")
      ->check(CLI::Range(0.001, 1e6))
      ->capture_default_str();
  app.add_flag("--manifold-child", o.manifold_child)->group("");  // internal: see manifold_run
  app.add_option("--chain", o.chain, "Dilate N times in a row, report the first and the last step");
  app.add_flag("--normalize", o.normalize,
               "Scale each input by a power of two to a bounding-box diagonal in [1, 2)");
  app.add_flag("--repair", o.repair, "Make inputs that are not valid solids valid first");
  harness.add_threads(o.threads, "Limit morphex's threads (default: all cores)");
  harness.add_json();
  app.add_option("INPUT", o.inputs, "Mesh files or torus:U,V, l-shape, icosphere:L")->required();
}

// Manifold's run of one operation on the same input and structuring element, or why there is none.
struct ManifoldRun {
  std::optional<peers::ManifoldResult> result;
  std::string note;
  double stopped_after = 0;  // seconds, when the run was stopped (manifold_in_child)
};

// MinkowskiSum by B for a dilation; MinkowskiDifference by -B for an erosion (Manifold removes
// dA + B'; morphex's erosion removes dA + (-B) for a B that holds the origin, as the SEs do, see
// morphex/morphology.h); the two chained for an opening (erode, dilate) and a closing (dilate,
// erode). Manifold's intermediate result of a chain is its own floating-point one.
ManifoldRun run_manifold(const Mesh& a, MorphologyOp op, const StructuringElement& se) {
  const Mesh minus_b = reflected(se.mesh);
  const peers::MinkowskiStep dilate{&se.mesh, false}, erode{&minus_b, true};
  ManifoldRun run;
  switch (op) {
    case MorphologyOp::Dilate:
      run.result = peers::manifold_minkowski(a, se.mesh, false, {}, &run.note);
      break;
    case MorphologyOp::Erode:
      run.result = peers::manifold_minkowski(a, minus_b, true, {}, &run.note);
      break;
    case MorphologyOp::Open:
      run.result = peers::manifold_minkowski_chain(a, {erode, dilate}, {}, &run.note);
      break;
    case MorphologyOp::Close:
      run.result = peers::manifold_minkowski_chain(a, {dilate, erode}, {}, &run.note);
      break;
  }
  return run;
}

// Manifold in a process of its own: this program again with --manifold-child, the same settings
// and one input and operation, which prints "ok SECONDS VOLUME TRIANGLES" or "failed WHY" (main).
// A run past --manifold-timeout is killed, so that one slow case of the peer cannot hold the whole
// benchmark (Manifold 3.5.1's closing of CGAL's man by an octahedron was still in its ear clipping
// after several minutes; its opening took 50 s). The child reads, repairs and scales its own copy
// of the input before its clock starts. It is exec'd, not only forked as bench_bool's engines
// are (bench_bool_common.h, in_child): by then this process has run morphex, and a forked child
// would inherit a TBB pool whose worker threads it does not have.
ManifoldRun manifold_in_child(const std::string& input, const std::string& op, const Options& o) {
  std::vector<std::string> args = {
      "bench_morph", "--manifold-child", "--se", o.se_spec, "--ops", op};
  if (o.threads > 0) args.insert(args.end(), {"--threads", std::to_string(o.threads)});
  if (o.normalize) args.push_back("--normalize");
  if (o.repair) args.push_back("--repair");
  args.push_back(input);
  std::vector<char*> argv;
  for (std::string& arg : args) argv.push_back(arg.data());
  argv.push_back(nullptr);
  ManifoldRun run;
  int fds[2];
  if (pipe(fds) != 0) {
    run.note = "no pipe for the Manifold process";
    return run;
  }
  const pid_t pid = fork();
  if (pid == 0) {  // only async-signal-safe calls until exec
    dup2(fds[1], STDOUT_FILENO);
    close(fds[0]);
    close(fds[1]);
    execv("/proc/self/exe", argv.data());
    _exit(127);
  }
  close(fds[1]);
  using Clock = std::chrono::steady_clock;
  const Clock::time_point deadline =
      Clock::now() + std::chrono::duration_cast<Clock::duration>(
                         std::chrono::duration<double>(o.manifold_timeout));
  std::string message;
  for (;;) {
    const double left = std::chrono::duration<double>(deadline - Clock::now()).count();
    if (left <= 0) {
      kill(pid, SIGKILL);
      run.stopped_after = o.manifold_timeout;
      break;
    }
    pollfd ready{fds[0], POLLIN, 0};
    if (poll(&ready, 1, int(std::min(left, 60.0) * 1000) + 1) <= 0) continue;
    char buffer[4096];
    const ssize_t n = read(fds[0], buffer, sizeof buffer);
    if (n <= 0) break;
    message.append(buffer, std::size_t(n));
  }
  close(fds[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  if (run.stopped_after > 0) {
    std::ostringstream words;
    words << "stopped after " << o.manifold_timeout << " s";
    run.note = words.str();
    return run;
  }
  std::istringstream words(message);
  std::string first;
  words >> first;
  peers::ManifoldResult result;
  if (first == "ok" && words >> result.seconds >> result.volume >> result.triangles) {
    run.result = result;
  } else {
    std::getline(words >> std::ws, run.note);
    if (run.note.empty())
      run.note = "the Manifold process ended with status " + std::to_string(status);
  }
  return run;
}

// The other side of manifold_in_child: one input, one operation, one line on standard output.
// Manifold first runs once on a small cube, untimed, as morphex's first operation follows others
// in the parent: a fresh process's one-time costs (thread pool, first allocations) are not the
// operation's.
int manifold_child(const Mesh& a, const Options& o) {
  const StructuringElement se = parse_structuring_element(o.se_spec);
  run_manifold(make_box(Point(0, 0, 0), Point(1, 1, 1)), MorphologyOp::Dilate, se);
  const ManifoldRun run = run_manifold(a, parse_morphology_op(o.ops.at(0)), se);
  if (run.result)
    std::cout << "ok " << std::setprecision(17) << run.result->seconds << ' ' << run.result->volume
              << ' ' << run.result->triangles << std::endl;
  else
    std::cout << "failed " << run.note << std::endl;
  return 0;
}

// |Manifold's volume - morphex's exact volume| / |morphex's| (the absolute difference when
// morphex's result is empty).
double relative_volume_difference(const FT& exact, double floating) {
  const FT difference = CGAL::abs(FT(floating) - exact);
  return CGAL::to_double(exact == 0 ? difference : difference / CGAL::abs(exact));
}

// Manifold's figures in the JSON row, and the words the table's last column says about them.
std::string record_manifold(const ManifoldRun& run, const FT& exact_volume, double our_seconds,
                            nlohmann::json& row) {
  if (!peers::kHaveManifold) return "";
  if (run.stopped_after > 0) {
    // Manifold took longer than the limit: the limit bounds its time, and its ratio, from below.
    row["manifold_stopped_after_seconds"] = run.stopped_after;
    row["manifold_ratio_at_least"] = run.stopped_after / our_seconds;
    return ", Manifold " + run.note;
  }
  if (!run.result) {
    row["manifold_error"] = run.note;
    return ", Manifold FAILED (" + run.note + ")";
  }
  const peers::ManifoldResult& r = *run.result;
  const double relative = relative_volume_difference(exact_volume, r.volume);
  row["manifold_seconds"] = r.seconds;
  row["manifold_ratio"] = r.seconds / our_seconds;
  row["manifold_volume"] = r.volume;
  row["manifold_volume_relative_difference"] = relative;
  row["manifold_result_facets"] = r.triangles;
  std::ostringstream words;
  words << ", Manifold volume rel. diff " << std::setprecision(2) << relative;
  return words.str();
}

// Manifold's cells of a table row: seconds, ms per input facet, its time over morphex's.
std::string manifold_cells(const ManifoldRun& run, double our_seconds, std::size_t facets) {
  std::ostringstream cells;
  cells << std::setprecision(3);
  if (!peers::kHaveManifold || !run.result) {
    const char* word = !peers::kHaveManifold ? "n/a" : run.stopped_after > 0 ? "stopped" : "FAIL";
    cells << std::setw(10) << word << std::setw(9) << word << std::setw(8) << word;
  } else {
    const double seconds = run.result->seconds;
    cells << std::setw(10) << seconds << std::setw(9) << 1000 * seconds / double(facets)
          << std::setw(8) << seconds / our_seconds;
  }
  return cells.str();
}

void print_header(bool manifold) {
  std::cout << std::left << std::setw(28) << "input" << std::setw(8) << "op" << std::right
            << std::setw(8) << "facets" << std::setw(10) << "morphex s" << std::setw(9)
            << "ms/facet" << std::setw(10) << "CGAL s" << std::setw(9) << "ratio";
  if (manifold)
    std::cout << std::setw(10) << "Mf s" << std::setw(9) << "Mf ms/f" << std::setw(8) << "Mf/m";
  std::cout << std::setw(9) << "result" << std::setw(10) << "peak MiB"
            << "  exact volumes\n";
}

// What --manifold compares, said once above the table.
void print_manifold_note() {
  if (!peers::kHaveManifold) {
    std::cout << "--manifold: bench_morph was built without Manifold (configure with "
                 "-DMORPHEX_MANIFOLD_DIR=$(tools/peers/build-manifold SRC)); its columns say "
                 "n/a\n";
    return;
  }
  std::cout << "Mf = Manifold " << peers::manifold_version()
            << " (floating point): MinkowskiSum (dilate), MinkowskiDifference by -B (erode), "
               "chained for open/close; its time excludes the mesh conversions. Mf/m: "
               "Manifold's time over morphex's (above 1: morphex is faster). Manifold runs in a "
               "process of its own, stopped after --manifold-timeout seconds; peak MiB is "
               "morphex's high-water mark\n";
}

}  // namespace

int main(int argc, char** argv) {
  morphex::use_huge_page_malloc(argv);  // first: it may restart the process
  bench::Harness harness(
      "bench_morph: morphex morphology against CGAL's minkowski_sum_3 on the same input");
  Options o;
  add_options(harness, o);
  // The settings under the names the measuring code below has always used.
  auto& [se_spec, ops, inputs, peer, nary, normalize, repair, manifold, manifold_child_run,
         manifold_timeout, chain, threads] = o;
  if (const std::optional<int> stop = harness.parse(argc, argv)) return *stop;
  std::optional<tbb::global_control> limit;
  if (threads > 0) limit.emplace(tbb::global_control::max_allowed_parallelism, threads);
  if (manifold_child_run) return manifold_child(prepared(inputs.at(0), o), o);
  const StructuringElement se = parse_structuring_element(se_spec);
  nlohmann::json rows = nlohmann::json::array();
  bool all_agree = true;
  if (manifold) print_manifold_note();
  print_header(manifold);
  for (const std::string& input : inputs) {
    const Mesh a = prepared(input, o);
    for (const std::string& op_name : ops) {
      const MorphologyOp op = parse_morphology_op(op_name);
      MorphologyStats stats;
      Stopwatch start;
      // The input check is timed with the operation, as the command line runs them.
      const Solid ours = apply_morphology(op, check_solid(a, input), se, &stats);
      const double our_seconds = start.seconds();
      const MeshReport report = check_mesh(ours);
      nlohmann::json row = {{"input", input},
                            {"op", op_name},
                            {"se", se.spec},
                            {"facets", a.num_triangles()},
                            {"seconds", our_seconds},
                            {"ms_per_facet", 1000 * our_seconds / double(a.num_triangles())},
                            {"result_facets", ours.num_triangles()},
                            {"pieces", stats.pieces},
                            {"valid", report.valid_solid()},
                            {"peak_mib", peak_mib()}};
      std::string agreement = report.valid_solid() ? "valid" : "INVALID";
      double their_seconds = 0;
      if (peer && op == MorphologyOp::Dilate) {
        const peers::PeerResult theirs = peers::nef_minkowski_sum(a, se.mesh);
        their_seconds = theirs.seconds;
        const bool agree = theirs.volume == report.volume;
        all_agree = all_agree && agree;
        agreement += agree ? ", agree with minkowski_sum_3" : ", DIFFER from minkowski_sum_3";
        row["cgal_minkowski_sum_3_seconds"] = their_seconds;
        row["ratio"] = their_seconds / our_seconds;
        row["agree"] = agree;
      }
      if (nary && op == MorphologyOp::Dilate && se.convex) {
        start.restart();
        Mesh shell = boundary_sum(a, se.mesh, true, nullptr, PieceUnion::Arrangement);
        // The SEs hold the origin; the shell is a valid solid by construction.
        const Solid by_nary =
            compute_union({detail::trusted_solid(std::move(shell)), detail::trusted_solid(a)});
        const double nary_seconds = start.seconds();
        const bool agree = signed_volume(by_nary) == report.volume;
        all_agree = all_agree && agree;
        agreement += agree ? ", n-ary agrees" : ", N-ARY DIFFERS";
        row["nary_union_seconds"] = nary_seconds;
        std::cout << "  n-ary union of the pieces: " << nary_seconds << " s ("
                  << nary_seconds / our_seconds << "x the tree's time)\n";
      }
      ManifoldRun mf;
      if (manifold) {
        // Under the same thread limit as morphex: Manifold's parallel backend is the same TBB.
        mf = manifold_in_child(input, op_name, o);
        agreement += record_manifold(mf, report.volume, our_seconds, row);
      }
      all_agree = all_agree && report.valid_solid();
      // Rows are flushed as they come: a large input's opening can take minutes.
      std::cout << std::left << std::setw(27) << input << ' ' << std::setw(8) << op_name
                << std::right << std::setw(8) << a.num_triangles() << std::setw(10)
                << std::setprecision(3) << our_seconds << std::setw(9)
                << 1000 * our_seconds / double(a.num_triangles()) << std::setw(10)
                << (their_seconds > 0 ? std::to_string(their_seconds).substr(0, 6) : "-")
                << std::setw(9)
                << (their_seconds > 0 ? std::to_string(their_seconds / our_seconds).substr(0, 6)
                                      : "-")
                << (manifold ? manifold_cells(mf, our_seconds, a.num_triangles()) : "")
                << std::setw(9) << ours.num_triangles() << std::setw(10) << int(peak_mib()) << "  "
                << agreement << std::endl;
      rows.push_back(row);
    }
    if (chain > 0) {
      Solid current = check_solid(a, input);
      std::vector<double> steps;
      std::vector<std::size_t> facets;
      for (int i = 0; i < chain; ++i) {
        facets.push_back(current.num_triangles());
        const Stopwatch start;
        current = dilation(current, se);
        steps.push_back(start.seconds());
      }
      std::cout << "chain of " << chain << " dilations of " << input << " (step: input facets, s):";
      for (int i = 0; i < chain; ++i)
        std::cout << ' ' << i + 1 << ": " << facets[i] << ", " << std::setprecision(3) << steps[i];
      std::cout << "; result " << current.num_triangles() << " facets, valid "
                << check_mesh(current).valid_solid() << '\n';
      rows.push_back({{"input", input},
                      {"chain", chain},
                      {"step_seconds", steps},
                      {"step_input_facets", facets}});
    }
  }
  if (!harness.write_json(rows)) return 2;
  return all_agree ? 0 : 1;
}

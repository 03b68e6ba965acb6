// SPDX-License-Identifier: GPL-3.0-or-later
// bench_bool: morphex Booleans against CGAL corefinement and CGAL Nef polyhedra (all exact, Epeck)
// on the same input in the same run.
//
//   bench_bool [--op union|intersection|difference] [--max-level L] [--nef-max-faces N]
//              [--json FILE] [--demo-dir DIR] [--only SUBSTRING] [--phases]
//              [--no-peers]   (morphex alone, for profiling) [--threads N]
//   bench_bool A B [--rotate DEG] [--translate X Y Z] [--op OP]      (one pair from files)
//   bench_bool --set real [--pairs tuning|held-out|all] [--op OP] [--demo-dir DIR]
//              [--prusa-dir DIR] [--ember-dir DIR] [--only SUBSTRING] [--json FILE] [--busy-retries
//              N] [--write-cases DIR] (pairs of real meshes against Manifold: bench_bool_real.cpp)
//
// Cases: icosphere pairs crossing each other from level 2 up to --max-level (a scaling curve),
// dense intersections (a sphere against a slightly rotated copy), coplanar contacts (a box grid
// against a shifted grid, a mesh against itself), a coarse box against a fine sphere, and CGAL's
// demo meshes against rotated copies. Each engine runs in a forked child, and the reported peak
// memory is that child's peak resident size above what it inherited at the fork (the engine's
// own); exact volumes must agree. --phases adds
// morphex's time per phase in the timed run (the profile that guides the speed work) to the table
// and the JSON.
#include <tbb/global_control.h>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <thread>

#include "bench_bool_common.h"
#include "bench_harness.h"
#include "morphex/boolean.h"
#include "morphex/check.h"
#include "morphex/internal/solid_access.h"
#include "morphex/internal/stopwatch.h"
#include "morphex/io.h"
#include "morphex/shapes.h"
#include "peers.h"

using namespace morphex;
using namespace morphex::bench;

namespace {

std::vector<Case> generated_cases(int max_level, const std::string& demo_dir) {
  std::vector<Case> cases;
  const Vector shift(FT(1) / 3, FT(1) / 5, FT(1) / 7);
  // Every input is made exact, as if read from an exact file: neither engine should pay for
  // evaluating the generator's lazy constructions.
  for (int level = 2; level <= max_level; ++level) {
    Mesh moved = translated(make_icosphere(level, FT(1)), shift);
    make_exact(moved);
    cases.push_back({"icospheres L" + std::to_string(level), make_icosphere(level, FT(1)), moved});
  }
  {
    const Mesh s = make_icosphere(std::min(max_level, 4), FT(1));
    Mesh turned = transformed(s, rational_rotation(1));
    make_exact(turned);
    cases.push_back({"dense: sphere vs 1-degree turn", s, turned});
  }
  {
    Mesh grid, other;
    for (int i = 0; i < 6; ++i)
      for (int j = 0; j < 6; ++j) {
        grid = concatenate(grid, make_box(Point(2 * i, 2 * j, 0), Point(2 * i + 1, 2 * j + 1, 1)));
        other = concatenate(other, make_box(Point(2 * i + FT(1) / 2, 2 * j, 0),
                                            Point(2 * i + FT(3) / 2, 2 * j + 1, 1)));
      }
    cases.push_back({"coplanar: box grid vs shifted grid", grid, other});
    const Mesh s = make_icosphere(std::min(max_level, 4), FT(1));
    cases.push_back({"coplanar: sphere vs itself", s, s});
  }
  cases.push_back({"coarse box vs fine sphere",
                   make_box(Point(-2, -2, -FT(1) / 3), Point(2, 2, FT(1) / 3)),
                   make_icosphere(std::min(max_level, 5), FT(1))});
  for (const char* name : {"elephant", "eight", "blobby"}) {
    const std::string path = demo_dir + "/" + name + ".off";
    if (!std::filesystem::exists(path)) continue;
    const Mesh m = read_mesh(path);
    Mesh turned =
        translated(transformed(m, rational_rotation(10)), Vector(FT(1) / 100, FT(1) / 50, 0));
    make_exact(turned);
    cases.push_back({std::string(name) + " vs rotated copy", m, turned});
  }
  return cases;
}

// The command line's settings, with their defaults.
struct Options {
  BooleanOp op = BooleanOp::Union;
  int max_level = 5;
  std::size_t nef_max_faces = 3000;
  std::string only, a_path, b_path;
  std::string set = "generated";  // or "real"
  std::string pairs = "tuning";   // --set real only: tuning, held-out or all
  int busy_retries = 2;           // --set real only
  bool phases = false, peers_too = true;
  unsigned threads = 0;  // 0: all cores
  std::string demo_dir, prusa_dir, ember_dir, write_cases;
  double degrees = 0;
  Vector offset = Vector(0, 0, 0);
};

// A Boolean operation's name as parse_boolean_op takes it, or why not.
std::string check_boolean_op(const std::string& name) {
  try {
    parse_boolean_op(name);
    return "";
  } catch (const std::exception& e) {
    return e.what();
  }
}

// The options of the generated set and of one pair from files (see the top of this file).
void add_generated_options(CLI::App& app, Options& o, std::vector<double>& translate) {
  app.add_option("A", o.a_path, "One pair from files: A (against itself without B)");
  app.add_option("B", o.b_path, "One pair from files: B, moved by --rotate and --translate");
  app.add_option("--max-level", o.max_level, "Largest icosphere level of the scaling curve")
      ->capture_default_str();
  app.add_option("--nef-max-faces", o.nef_max_faces,
                 "Nef polyhedra run on cases of at most this many input faces")
      ->capture_default_str();
  app.add_flag("--phases", o.phases, "Add morphex's time per phase to the table and the JSON");
  app.add_flag_callback(
      "--no-peers", [&o] { o.peers_too = false; }, "morphex alone (for profiling)");
  app.add_option("--rotate", o.degrees, "Turn B by this many degrees (rational rotation)");
  app.add_option("--translate", translate, "Move B by X Y Z")->expected(3)->type_name("FLOAT");
}

// The options of --set real (bench_bool_real.cpp).
void add_real_options(CLI::App& app, Options& o) {
  app.add_option("--set", o.set,
                 "generated: icospheres, contacts, demo meshes against CGAL; "
                 "real: pairs of real meshes against Manifold")
      ->check(CLI::IsMember({"generated", "real"}))
      ->capture_default_str();
  app.add_option("--pairs", o.pairs,
                 "tuning: the pairs the Boolean was tuned on; held-out: pairs never used to "
                 "tune anything; all (--set real)")
      ->check(CLI::IsMember({"tuning", "held-out", "all"}))
      ->capture_default_str();
  app.add_option("--prusa-dir", o.prusa_dir, "PrusaSlicer's sample shapes (--set real)")
      ->capture_default_str();
  app.add_option("--ember-dir", o.ember_dir, "The EMBER cases and meshes (--set real)")
      ->capture_default_str();
  app.add_option("--busy-retries", o.busy_retries,
                 "Runs again a pair disturbed by other load, up to this many times (--set real)")
      ->capture_default_str();
  app.add_option("--write-cases", o.write_cases,
                 "Write each selected pair as placed, exact OFF, into DIR (--set real)");
}

// The command line (see the top of this file) into `o`; the exit status when the program should
// stop at once (--help, a usage error).
std::optional<int> parse_arguments(Harness& harness, Options& o, int argc, char** argv) {
  const char* home = std::getenv("HOME");
  o.demo_dir = std::string(home ? home : ".") + "/.cache/morphex/cgal-demo";
  o.prusa_dir = std::string(home ? home : ".") + "/.cache/morphex/prusa-shapes";
  o.ember_dir = std::string(home ? home : ".") + "/.cache/morphex/ember";
  CLI::App& app = harness.app();
  std::string op = "union";
  std::vector<double> translate;
  app.add_option("--op", op, "union, intersection or difference")
      ->check(check_boolean_op)
      ->capture_default_str();
  app.add_option("--demo-dir", o.demo_dir, "CGAL's demo meshes (scripts/fetch-cgal-demo-meshes)")
      ->capture_default_str();
  app.add_option("--only", o.only, "Only the cases whose name contains this");
  harness.add_json();
  harness.add_threads(o.threads, "Limit morphex's threads (default: all cores)");
  add_generated_options(app, o, translate);
  add_real_options(app, o);
  if (const std::optional<int> stop = harness.parse(argc, argv)) return stop;
  o.op = parse_boolean_op(op);
  if (!translate.empty()) o.offset = Vector(translate[0], translate[1], translate[2]);
  return std::nullopt;
}

// The cases to run: the pair of files given (B moved as asked, A against itself without B), or
// the generated cases.
std::vector<Case> make_cases(const Options& o) {
  if (o.a_path.empty()) return generated_cases(o.max_level, o.demo_dir);
  const std::string b_path = o.b_path.empty() ? o.a_path : o.b_path;
  Mesh b = read_mesh(b_path);
  if (o.degrees != 0) b = transformed(b, rational_rotation(o.degrees));
  b = translated(b, o.offset);
  make_exact(b);
  std::vector<Case> cases;
  cases.push_back({o.a_path + " vs " + b_path, read_mesh(o.a_path), b});
  return cases;
}

// morphex's phase times and counts, as the child sends them back in its note.
std::string phase_note(const PhaseSeconds& p, const BooleanStats& s) {
  std::ostringstream note;
  note << p.pairs << ' ' << p.segments << ' ' << p.retriangulate << ' ' << p.classify << ' '
       << p.assemble << " pairs " << s.candidate_pairs << " intersecting " << s.intersecting_pairs
       << " cut " << s.cut_facets_a << "+" << s.cut_facets_b << " points " << s.intersection_points
       << " patches " << s.patches << " (ray cast " << s.patches_by_ray_cast << ")";
  return note.str();
}

// The operation is timed on inputs taken as valid, as corefinement takes them (Solids made
// without the check, so without the check's trees); the validity check is timed on its own
// (run_check).
Run run_morphex(const Case& c, BooleanOp op, const Warmup& warm) {
  return in_child([&]() -> Result {
    compute_boolean(detail::trusted_solid(warm.a), detail::trusted_solid(warm.b), op);
    own_inputs(c);
    const Solid a = detail::trusted_solid(c.a), b = detail::trusted_solid(c.b);
    BooleanResult r;
    std::vector<std::pair<double, PhaseSeconds>> runs;
    const double seconds = median_seconds([&] {
      r = BooleanResult{};  // the previous run's result is freed off the clock, as the peers'
      const Stopwatch start;
      r = compute_boolean(a, b, op);
      runs.emplace_back(start.seconds(), r.stats.seconds);
      return runs.back().first;
    });
    // Phases are measured in the timed runs themselves (the median one): a parent that ran TBB
    // would hand its children a thread pool whose workers were not forked with them.
    std::sort(runs.begin(), runs.end(),
              [](const auto& x, const auto& y) { return x.first < y.first; });
    child_note = phase_note(runs[runs.size() / 2].second, r.stats);
    return std::make_pair(seconds, signed_volume(r.solid));
  });
}

// morphex's validity check of both inputs (fails when either is not a valid solid).
Run run_check(const Case& c, const Warmup& warm) {
  return in_child([&]() -> Result {
    check_mesh(warm.a, kValidityOnly);
    own_inputs(c);
    bool valid = false;
    const double seconds = median_seconds([&] {
      const Stopwatch start;
      valid = check_mesh(c.a, kValidityOnly).valid_solid() &&
              check_mesh(c.b, kValidityOnly).valid_solid();
      return start.seconds();
    });
    if (!valid) return std::nullopt;
    return std::make_pair(seconds, FT(0));
  });
}

// CGAL's corefinement; without peers the child still runs, and reports nothing.
Run run_corefinement(const Case& c, BooleanOp op, bool peers_too, const Warmup& warm) {
  return in_child([&]() -> Result {
    if (!peers_too) return std::nullopt;
    peers::corefinement_boolean(warm.a, warm.b, op);
    own_inputs(c);
    std::optional<peers::PeerResult> r;
    const double seconds = median_seconds([&] {
      r = peers::corefinement_boolean(c.a, c.b, op);
      return r ? r->seconds : 0.0;
    });
    if (r) return std::make_pair(seconds, r->volume);
    return std::nullopt;
  });
}

// CGAL's Nef polyhedra, timed with the conversions in.
Run run_nef(const Case& c, BooleanOp op, const Warmup& warm) {
  return in_child([&]() -> Result {
    peers::nef_boolean(warm.a, warm.b, op);
    own_inputs(c);
    peers::PeerResult r;
    const double seconds = median_seconds([&] {
      r = peers::nef_boolean(c.a, c.b, op);  // conversions in
      return r.seconds;
    });
    return std::make_pair(seconds, r.volume);
  });
}

// One case's run of each engine (a run that did not happen has ok false, and prints "-").
struct Runs {
  Run ours, check, coref, nef;
};

// All engines on one case, each in its own child. Nef, far slower than the others, runs only on
// cases of at most --nef-max-faces input faces (and only with the peers).
Runs run_case(const Case& c, const Options& o, std::size_t faces, const Warmup& warm) {
  Runs runs;
  runs.ours = run_morphex(c, o.op, warm);
  runs.check = run_check(c, warm);
  runs.coref = run_corefinement(c, o.op, o.peers_too, warm);
  if (o.peers_too && faces <= o.nef_max_faces) runs.nef = run_nef(c, o.op, warm);
  return runs;
}

// The last column of a row: failures and whether the exact volumes agree.
std::string volume_agreement(const Runs& r, bool peers_too) {
  std::string out = r.ours.ok ? "" : "morphex FAILED";
  if (!r.check.ok) out += "INVALID INPUT ";
  if (r.ours.ok && r.coref.ok)
    out += r.ours.volume == r.coref.volume ? "=coref " : "DIFFER(coref) ";
  if (r.ours.ok && r.nef.ok) out += r.ours.volume == r.nef.volume ? "=Nef" : "DIFFER(Nef)";
  if (!r.coref.ok && peers_too) out += " (coref failed)";
  return out;
}

// Whether a case passed: morphex and the check succeeded, and every peer that succeeded computed
// the same exact volume.
bool agrees(const Runs& r) {
  return r.ours.ok && r.check.ok && (!r.coref.ok || r.ours.volume == r.coref.volume) &&
         (!r.nef.ok || r.ours.volume == r.nef.volume);
}

// The table's column titles; the widths match print_row's.
void print_header() {
  std::cout << std::left << std::setw(36) << "case" << std::right << std::setw(9) << "faces"
            << std::setw(10) << "morphex" << std::setw(9) << "check" << std::setw(10) << "coref"
            << std::setw(9) << "ratio" << std::setw(10) << "Nef" << std::setw(9) << "ratio"
            << std::setw(12) << "tri/s" << std::setw(14) << "MiB m/c/N"
            << "  volumes\n";
}

// One row of the table: a failed run's cells show "-".
void print_row(const Case& c, std::size_t faces, const Runs& runs, const std::string& agreement) {
  const Run &ours = runs.ours, &check = runs.check, &coref = runs.coref, &nef = runs.nef;
  auto cell = [](const Run& r, double value) {
    std::ostringstream out;
    if (r.ok)
      out << std::setprecision(3) << value;
    else
      out << "-";
    return out.str();
  };
  std::cout << std::left << std::setw(36) << c.name.substr(0, 35) << std::right << std::setw(9)
            << faces << std::setw(10) << cell(ours, ours.seconds) << std::setw(9)
            << cell(check, check.seconds) << std::setw(10) << cell(coref, coref.seconds)
            << std::setw(9) << cell(coref, coref.seconds / ours.seconds) << std::setw(10)
            << cell(nef, nef.seconds) << std::setw(9) << cell(nef, nef.seconds / ours.seconds)
            << std::setw(12) << cell(ours, double(faces) / ours.seconds) << ' ' << std::setw(15)
            << (cell(ours, ours.peak_mib) + "/" + cell(coref, coref.peak_mib) + "/" +
                cell(nef, nef.peak_mib))
            << "  " << agreement << '\n';
}

// One case's JSON row; `all_agree` is whether this and every earlier case passed.
nlohmann::json json_row(const Case& c, const Options& o, std::size_t faces, const Runs& r,
                        bool all_agree) {
  nlohmann::json row = {
      {"case", c.name},
      {"op", to_string(o.op)},
      {"faces", faces},
      {"morphex_seconds", r.ours.seconds},
      {"morphex_peak_mib", r.ours.peak_mib},
      {"morphex_check_seconds", r.check.seconds},
      {"threads", o.threads > 0 ? o.threads : std::thread::hardware_concurrency()},
      {"agree", all_agree}};
  if (r.coref.ok) {
    row["corefinement_seconds"] = r.coref.seconds;
    row["corefinement_peak_mib"] = r.coref.peak_mib;
    row["ratio_corefinement"] = r.coref.seconds / r.ours.seconds;
  }
  if (r.nef.ok) {
    row["nef_seconds"] = r.nef.seconds;
    row["nef_peak_mib"] = r.nef.peak_mib;
    row["ratio_nef"] = r.nef.seconds / r.ours.seconds;
  }
  return row;
}

// --phases: morphex's time per phase (from the note run_morphex sent back) under the row, and
// into the JSON row.
void print_phases(const std::string& note, nlohmann::json& row) {
  std::istringstream in(note);
  std::cout << "    phases:";
  for (const char* name : {"pairs", "segments", "retriangulate", "classify", "assemble"}) {
    double seconds = 0;
    in >> seconds;
    std::cout << ' ' << name << ' ' << std::setprecision(3) << seconds;
    row["morphex_phase_seconds"][name] = seconds;
  }
  std::string counts;
  std::getline(in, counts);
  std::cout << " |" << counts << "\n";
}

// What the columns mean, under the table, so that a saved log explains itself.
void print_legend() {
  std::cout
      << "ratio = peer time / morphex time (above 1: morphex is faster); tri/s = input "
         "triangles per second of morphex; MiB = peak memory above the inputs, morphex / "
         "corefinement / Nef.\n"
         "morphex times the operation on trusted inputs, as corefinement does; check = "
         "morphex's validity check of both inputs, which makes the Solids the Boolean takes "
         "(check_solids). Both "
         "return exact output points that are evaluated lazily (as CGAL's Epeck constructions "
         "are); the volumes compared are exact.\n";
}

}  // namespace

int main(int argc, char** argv) {
  Harness harness(
      "bench_bool: morphex Booleans against CGAL corefinement and Nef polyhedra (or, "
      "--set real, against Manifold on pairs of real meshes)");
  Options o;
  if (const std::optional<int> stop = parse_arguments(harness, o, argc, argv)) return *stop;
  // The real set runs each engine at the thread counts it compares (1, 2, 4), set in each child.
  if (o.set == "real")
    return run_real_set({o.op, o.pairs, o.only, o.demo_dir, o.prusa_dir, o.ember_dir,
                         o.busy_retries, o.write_cases},
                        harness);
  const std::vector<Case> cases = make_cases(o);

  // Limits morphex's TBB phases; CGAL's corefinement and Nef run sequentially anyway.
  std::optional<tbb::global_control> thread_limit;
  if (o.threads > 0) thread_limit.emplace(tbb::global_control::max_allowed_parallelism, o.threads);
  nlohmann::json rows = nlohmann::json::array();
  bool all_agree = true;
  print_header();
  const Warmup warm{make_box(Point(0, 0, 0), Point(1, 1, 1)),
                    make_box(Point(FT(1) / 3, FT(1) / 5, FT(1) / 7), Point(2, 2, 2))};
  for (const Case& c : cases) {
    if (!o.only.empty() && c.name.find(o.only) == std::string::npos) continue;
    const std::size_t faces = c.a.num_triangles() + c.b.num_triangles();
    const Runs runs = run_case(c, o, faces, warm);
    all_agree = all_agree && agrees(runs);
    print_row(c, faces, runs, volume_agreement(runs, o.peers_too));
    nlohmann::json row = json_row(c, o, faces, runs, all_agree);
    if (o.phases && runs.ours.ok) print_phases(runs.ours.note, row);
    rows.push_back(row);
  }
  if (!harness.write_json(rows)) return 2;
  print_legend();
  return all_agree ? 0 : 1;
}

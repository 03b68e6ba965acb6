// SPDX-License-Identifier: GPL-3.0-or-later
// bench_bool --set real: Booleans on pairs of real meshes (CGAL's demo meshes, PrusaSlicer's
// sample shapes), morphex against Manifold (floating point, when bench_bool was built with it:
// tools/peers/build-manifold) in the same run.
//
// Each input is read, checked, repaired when it is not a valid solid (morphex repair; the output
// says which), scaled by a power of two to a bounding-box diagonal in [1, 2) and centred on a
// dyadic point, all exactly. B then turns by a rational rotation and moves by a rational fraction
// of its box, so A and B overlap substantially. The EMBER pairs (Thingi10K meshes from Manifold's
// benchmark of the EMBER paper's cases) are placed by their cases' affine maps instead, in doubles
// as Manifold applies them, and both engines get the same double meshes. Per pair, each in its own
// forked child with its own thread limit: morphex's operation on inputs taken as valid and morphex
// as `morphex bool` runs it (input check + operation), Manifold, at one thread; morphex at 2 and 4
// threads and Manifold at 2 for the scaling. Per input, check_mesh on the file as read (what
// `morphex check` does; an EMBER mesh as placed, what `morphex bool` checks) at one thread.
#include <tbb/global_control.h>

#include <array>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <functional>
#include <iomanip>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "bench_bool_common.h"
#include "bench_common.h"
#include "manifold_peer.h"
#include "morphex/check.h"
#include "morphex/internal/solid_access.h"
#include "morphex/internal/stopwatch.h"
#include "morphex/io.h"
#include "morphex/repair.h"

namespace morphex::bench {

namespace {

// A pair of inputs named "demo:NAME" (DEMO_DIR/NAME.off), "prusa:NAME" (PRUSA_DIR/NAME.stl),
// "ember:ID@CASE" (EMBER_DIR/ID.stl placed as case CASE of ember-benchmark-cases.json places it)
// or "thingi:ID" (the Thingi10K mesh EMBER_DIR/ID.stl, placed like the demo meshes); B turns by
// `degrees` (rational_rotation) before it moves, except in EMBER pairs.
struct PairSpec {
  std::string a, b;
  double degrees;
};

bool is_ember(const std::string& source) {
  return source.rfind("ember:", 0) == 0;
}

// Large against large (over 100,000 facets together: the thread scaling), organic and CAD
// meshes of a few thousand facets, a mesh against a rotated copy of itself, and coarse against
// fine (12 and 44 facets against tens of thousands). ChineseDragon-10kv, lion and blade are open
// (repair refuses them), hence not here.
const std::vector<PairSpec> kPairs = {
    {"demo:bunny00", "demo:armadillo", 10},
    {"demo:refined_elephant", "demo:bunny00", 20},
    {"demo:bunny00", "demo:bunny00", 10},
    {"demo:armadillo", "demo:man", 15},
    {"demo:fandisk_large", "demo:bear", 25},
    {"demo:homer", "demo:triceratops", 30},
    {"demo:camel", "demo:bull", 10},
    {"demo:turbine", "demo:femur", 20},
    {"demo:cheese", "demo:fandisk", 15},
    {"demo:knot1", "demo:knot2", 10},
    {"demo:elephant", "demo:cow", 20},
    {"demo:anchor", "demo:couplingdown", 30},
    {"prusa:box", "demo:bunny00", 20},
    {"demo:tripod", "demo:armadillo", 20},
    {"prusa:M3x10_screw", "prusa:M3_hex_nut", 5},
    {"prusa:torus", "prusa:sphere", 15},
    // The EMBER cases whose two meshes Manifold's source carries (the six the issue measured):
    // coarse against fine among them (1,660 facets against 68,548; 3,632 against 71,974; 1,466
    // against 14,740 long thin ones).
    {"ember:88566@16", "ember:58011@16", 0},
    {"ember:1706459@84", "ember:1514499@84", 0},
    {"ember:908460@260", "ember:73416@260", 0},
    {"ember:1063852@406", "ember:72214@406", 0},
    {"ember:79741@582", "ember:65004@582", 0},
    {"ember:472042@667", "ember:99865@667", 0},
};

// The held-out pairs (--pairs held-out): chosen after the work above was tuned on kPairs, and
// never used to tune anything. They widen what kPairs covers: other CGAL and Thingi10K meshes,
// meshes against copies of themselves turned by small angles (gears and rotors: many nearly
// parallel facets) or only moved (a translated copy), small pairs of a few hundred facets where
// fixed costs (thread start-up, trees) dominate, and coarse against fine.
const std::vector<PairSpec> kHeldOutPairs = {
    {"demo:bear_bis", "demo:dino", 15},
    {"demo:retinal", "demo:blobby", 20},
    {"demo:anchor_dense", "demo:rotor_small", 10},
    {"demo:knot", "demo:hand", 25},
    {"thingi:112932", "thingi:520644", 10},
    {"thingi:520644", "thingi:99865", 20},
    {"thingi:1514499", "demo:retinal", 30},
    // copies of one mesh: turned by a few degrees, or only moved (0)
    {"demo:pinion", "demo:pinion", 3},
    {"demo:rotor", "demo:rotor", 7},
    {"demo:spool", "demo:spool", 45},
    {"thingi:112932", "thingi:112932", 5},
    {"thingi:65004", "thingi:65004", 2},
    {"demo:couplingdown", "demo:couplingdown", 0},
    {"demo:cube-meshed", "demo:cube-meshed", 0},
    // small: a few hundred facets together
    {"demo:star", "demo:cross", 10},
    {"demo:P", "demo:3torus", 20},
    {"demo:joint", "demo:part", 15},
    {"demo:dragknob", "demo:eight", 30},
    {"demo:mpi", "demo:u", 5},
    {"prusa:bunny", "prusa:cone", 12},
    // coarse against fine
    {"demo:cube", "demo:bear_bis", 20},
    {"prusa:helper_disk", "demo:dino", 10},
};

// One input as the pairs use it.
struct Input {
  std::string path;
  bool ok = false;
  std::string status;  // "valid", "repaired ...", or why it is skipped
  Mesh mesh;           // valid, scaled and centred
  std::size_t file_facets = 0;
  Run check;  // check_mesh on the file as read, one thread
};

// The NAME or ID of a source.
std::string source_name(const std::string& source) {
  const auto colon = source.find(':');
  return source.substr(colon + 1, source.find('@') - colon - 1);
}

// "bunny00 x armadillo", "79741 x 65004 (ember)": the row's name, which --only matches.
std::string pair_name(const PairSpec& p) {
  return source_name(p.a) + " x " + source_name(p.b) + (is_ember(p.a) ? " (ember)" : "");
}

std::string input_path(const std::string& source, const RealSetOptions& o) {
  const std::string kind = source.substr(0, source.find(':')), name = source_name(source);
  if (kind == "ember" || kind == "thingi") return o.ember_dir + "/" + name + ".stl";
  return kind == "prusa" ? o.prusa_dir + "/" + name + ".stl" : o.demo_dir + "/" + name + ".off";
}

// An EMBER case's affine map of one of its meshes: columns (x, y, z, translation), in doubles.
using AffineColumns = std::array<std::array<double, 3>, 4>;

// The map of "ember:ID@CASE" from EMBER_DIR/ember-benchmark-cases.json (transform_a when ID is
// the case's id_a), or nullopt (with `why`) when the file or the case is not there.
std::optional<AffineColumns> ember_placement(const std::string& source, const RealSetOptions& o,
                                             std::string& why) {
  const std::string cases_path = o.ember_dir + "/ember-benchmark-cases.json";
  std::ifstream in(cases_path);
  if (!in) {
    why = "missing file " + cases_path;
    return std::nullopt;
  }
  const nlohmann::json cases = nlohmann::json::parse(in);
  const std::size_t at = std::stoul(source.substr(source.find('@') + 1));
  const long id = std::stol(source_name(source));
  if (at >= cases.size() || (cases[at]["id_a"] != id && cases[at]["id_b"] != id)) {
    why = "no EMBER case " + std::to_string(at) + " with mesh " + std::to_string(id);
    return std::nullopt;
  }
  const nlohmann::json& t = cases[at][cases[at]["id_a"] == id ? "transform_a" : "transform_b"];
  AffineColumns columns;
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 3; ++r)
      columns[c][r] = t["col" + std::to_string(c)][std::string(1, "xyz"[r])].get<double>();
  return columns;
}

// The mesh under the map, each coordinate x*c0 + y*c1 + z*c2 + c3 rounded in doubles in that
// order (as Manifold's Transform computes it): the same double mesh goes to both engines.
Mesh placed(const Mesh& m, const AffineColumns& t) {
  Mesh out = m;
  for (Point& p : out.points) {
    const double x = CGAL::to_double(p.x()), y = CGAL::to_double(p.y()), z = CGAL::to_double(p.z());
    double q[3];
    for (int r = 0; r < 3; ++r) q[r] = x * t[0][r] + y * t[1][r] + z * t[2][r] + t[3][r];
    p = Point(q[0], q[1], q[2]);
  }
  return out;
}

// Scaled by the power of two that brings its bounding-box diagonal into [1, 2), then moved so
// that its box centre, rounded to a multiple of 2^-10, is the origin: both exact, and a double
// coordinate stays a double unless the translation needs more bits.
Mesh normalized(const Mesh& m) {
  CGAL::Bbox_3 box;
  for (const Point& p : m.points) box += p.bbox();
  const double scale = bench::unit_diagonal_scale(m);
  auto centre = [&](double lo, double hi) {
    return -std::round((lo + hi) / 2 * scale * 1024) / 1024;
  };
  Mesh out = translated(transformed(m, Transformation(CGAL::SCALING, FT(scale))),
                        Vector(centre(box.xmin(), box.xmax()), centre(box.ymin(), box.ymax()),
                               centre(box.zmin(), box.zmax())));
  make_exact(out);
  return out;
}

// Reads, checks, repairs and places one input (`place`: normalized, or an EMBER case's map) in a
// child (the check and the repair run TBB, which the parent must not start before it forks),
// which writes the result as an exact OFF file for the parent and sends back what it did. The
// placed mesh is checked again: rounding an EMBER map could break it.
Input prepare_input(const std::string& path, const std::string& prepared_path,
                    const std::function<Mesh(const Mesh&)>& place) {
  Input in;
  in.path = path;
  if (!std::filesystem::exists(path)) {
    in.status = "missing file " + path;
    return in;
  }
  const Run run = in_child([&]() -> Result {
    const Mesh read = read_mesh(path);
    const MeshReport report = check_mesh(read, kValidityOnly);
    Mesh valid = read;
    child_note = "valid";
    if (!report.valid_solid()) {
      try {
        const RepairResult repaired = repair_mesh(read);
        valid = repaired.solid;
        child_note = "repaired (" + describe_problems(report) + ") to " +
                     std::to_string(valid.num_triangles()) + " facets";
      } catch (const std::exception& e) {
        child_note = "not a valid solid (" + describe_problems(report) +
                     ") and repair refused it: " + e.what();
        return std::nullopt;
      }
    }
    const Mesh out = place(valid);
    const MeshReport placed_report = check_mesh(out, kValidityOnly);
    if (!placed_report.valid_solid()) {
      child_note = "not a valid solid once placed (" + describe_problems(placed_report) + ")";
      return std::nullopt;
    }
    WriteOptions exact;
    exact.exact = true;
    write_mesh(out, prepared_path, exact);
    return std::make_pair(0.0, FT(int(read.num_triangles())));
  });
  in.status = run.note;
  if (!run.ok) return in;
  in.file_facets = std::stoul(run.volume);
  in.mesh = read_mesh(prepared_path);
  in.ok = true;
  return in;
}

// check_mesh with its default options (the exact volume included), as `morphex check` runs it
// on the file, at one thread.
Run time_check(const std::string& path, const Mesh& warm) {
  return in_child([&]() -> Result {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    const Mesh m = read_mesh(path);
    check_mesh(warm);
    const double seconds = median_seconds([&] {
      const Stopwatch start;
      check_mesh(m);
      return start.seconds();
    });
    return std::make_pair(seconds, FT(int(m.num_triangles())));
  });
}

// morphex at `threads` threads: the operation alone on inputs taken as valid, or (`as_cli`) as
// `morphex bool` runs it, the input check included in the time.
Run run_morphex_at(const Case& c, BooleanOp op, std::size_t threads, bool as_cli,
                   const Warmup& warm) {
  return in_child([&]() -> Result {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    // As the command line: both inputs checked (check_solids), then the operation; otherwise the
    // inputs are taken as valid, as the peers take them.
    const auto run = [&](const Mesh& a, const Mesh& b) {
      if (!as_cli) return compute_boolean(detail::trusted_solid(a), detail::trusted_solid(b), op);
      const auto [sa, sb] = check_solids(a, "A", b, "B");
      return compute_boolean(sa, sb, op);
    };
    run(warm.a, warm.b);
    own_inputs(c);
    BooleanResult r;
    try {
      const double seconds = median_seconds([&] {
        r = BooleanResult{};  // the previous run's result is freed off the clock
        const Stopwatch start;
        r = run(c.a, c.b);
        return start.seconds();
      });
      return std::make_pair(seconds, signed_volume(r.solid));
    } catch (const InvalidSolid& e) {
      child_note = e.what();
      return std::nullopt;
    }
  });
}

// Manifold at `threads` threads (the same TBB limit: Manifold runs on Debian's TBB as morphex).
// Its floating-point volume comes back as the exact value of the double.
Run run_manifold_at(const Case& c, BooleanOp op, std::size_t threads, const Warmup& warm) {
  if (!peers::kHaveManifold) return {};
  return in_child([&]() -> Result {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    peers::manifold_boolean(warm.a, warm.b, op);
    own_inputs(c);
    std::string why;
    const auto r = peers::manifold_boolean(
        c.a, c.b, op, [](const std::function<double()>& once) { return median_seconds(once); },
        &why);
    if (!r) {
      child_note = why;
      return std::nullopt;
    }
    return std::make_pair(r->seconds, FT(r->volume));
  });
}

// One pair's runs: morphex alone (m), as the command line (cli), Manifold (mf), by threads.
struct PairRuns {
  Run m1, cli1, mf1, m2, m4, mf2;
  double other_cores = 0;  // CPU the rest of the machine used meanwhile (see CpuSample)
  int attempts = 1;        // runs of the pair (--busy-retries), the least disturbed reported
};

// The machine's busy CPU time (/proc/stat, every process of every user) and this process's with
// its children's, at one moment. Between two samples, their difference over the wall time is how
// many cores something else kept busy: on a shared machine that is what makes a 2-thread run no
// faster than a 1-thread one, so each row reports it.
struct CpuSample {
  double machine = 0, ours = 0, wall = 0;  // seconds
};

CpuSample cpu_sample() {
  CpuSample s;
  std::ifstream stat("/proc/stat");
  std::string cpu;
  double user = 0, nice = 0, system = 0, idle = 0, iowait = 0, irq = 0, softirq = 0, steal = 0;
  stat >> cpu >> user >> nice >> system >> idle >> iowait >> irq >> softirq >> steal;
  s.machine = (user + nice + system + irq + softirq + steal) / double(sysconf(_SC_CLK_TCK));
  for (const int who : {RUSAGE_SELF, RUSAGE_CHILDREN}) {
    rusage r{};
    getrusage(who, &r);
    s.ours += double(r.ru_utime.tv_sec + r.ru_stime.tv_sec) +
              double(r.ru_utime.tv_usec + r.ru_stime.tv_usec) / 1e6;
  }
  s.wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
  return s;
}

double other_cores(const CpuSample& before, const CpuSample& after) {
  const double wall = after.wall - before.wall;
  if (wall <= 0) return 0;
  return std::max(0.0, (after.machine - before.machine) - (after.ours - before.ours)) / wall;
}

PairRuns run_pair(const Case& c, BooleanOp op, const Warmup& warm) {
  PairRuns r;
  const CpuSample before = cpu_sample();
  r.m1 = run_morphex_at(c, op, 1, false, warm);
  r.cli1 = run_morphex_at(c, op, 1, true, warm);
  r.mf1 = run_manifold_at(c, op, 1, warm);
  r.m2 = run_morphex_at(c, op, 2, false, warm);
  r.m4 = run_morphex_at(c, op, 4, false, warm);
  r.mf2 = run_manifold_at(c, op, 2, warm);
  r.other_cores = other_cores(before, cpu_sample());
  return r;
}

// The pair: A as prepared, B turned and moved by (1/5, 1/7, 1/11) of its box's extents.
Case make_pair_case(const std::string& name, const Input& a, const Input& b, double degrees) {
  CGAL::Bbox_3 box;
  for (const Point& p : b.mesh.points) box += p.bbox();
  const Vector offset(FT(box.xmax() - box.xmin()) / 5, FT(box.ymax() - box.ymin()) / 7,
                      FT(box.zmax() - box.zmin()) / 11);
  Mesh moved = translated(transformed(b.mesh, rational_rotation(degrees)), offset);
  make_exact(moved);
  return {name, a.mesh, moved};
}

// |Manifold's volume - morphex's exact volume| / |morphex's|, from the rational strings.
double relative_volume_difference(const Run& exact, const Run& floating) {
  const FT v = parse_exact_number(exact.volume), w = parse_exact_number(floating.volume);
  if (v == 0) return CGAL::to_double(CGAL::abs(w));
  return CGAL::to_double(CGAL::abs(w - v) / CGAL::abs(v));
}

std::string cell(const Run& r, double value, bool manifold_column = false) {
  if (manifold_column && !peers::kHaveManifold) return "n/a";
  if (!r.ok) return manifold_column ? "FAIL" : "-";
  std::ostringstream out;
  out << std::setprecision(3) << value;
  return out.str();
}

std::string ratio_cell(const Run& peer, const Run& ours) {
  if (!peers::kHaveManifold) return "n/a";
  if (!peer.ok || !ours.ok) return "-";
  return cell(peer, peer.seconds / ours.seconds);
}

void print_header() {
  std::cout << std::left << std::setw(34) << "pair" << std::right << std::setw(15) << "facets A+B"
            << std::setw(9) << "m 1t" << std::setw(9) << "cli 1t" << std::setw(9) << "Mf 1t"
            << std::setw(8) << "Mf/m" << std::setw(8) << "Mf/cli" << std::setw(9) << "m 2t"
            << std::setw(9) << "m 4t" << std::setw(9) << "Mf 2t" << std::setw(7) << "m 1>2"
            << std::setw(10) << "vol rel" << std::setw(7) << "other"
            << "  agree\n";
}

// Whether morphex's four runs computed the same exact volume (and all succeeded).
bool morphex_agrees(const PairRuns& r) {
  return r.m1.ok && r.cli1.ok && r.m2.ok && r.m4.ok && r.m1.volume == r.cli1.volume &&
         r.m1.volume == r.m2.volume && r.m1.volume == r.m4.volume;
}

void print_row(const Case& c, const PairRuns& r) {
  std::ostringstream facets;
  facets << c.a.num_triangles() << "+" << c.b.num_triangles();
  const bool volumes = r.m1.ok && r.mf1.ok;
  std::string agreement = morphex_agrees(r) ? "exact" : "MORPHEX RUNS DIFFER OR FAILED";
  std::ostringstream other;
  other << std::fixed << std::setprecision(2) << r.other_cores;
  if (r.attempts > 1) agreement += " (" + std::to_string(r.attempts) + " attempts)";
  for (const Run* mf : {&r.mf1, &r.mf2})
    if (peers::kHaveManifold && !mf->ok) agreement += " (Manifold: " + mf->note + ")";
  std::cout << std::left << std::setw(34) << c.name.substr(0, 33) << std::right << std::setw(15)
            << facets.str() << std::setw(9) << cell(r.m1, r.m1.seconds) << std::setw(9)
            << cell(r.cli1, r.cli1.seconds) << std::setw(9) << cell(r.mf1, r.mf1.seconds, true)
            << std::setw(8) << ratio_cell(r.mf1, r.m1) << std::setw(8) << ratio_cell(r.mf1, r.cli1)
            << std::setw(9) << cell(r.m2, r.m2.seconds) << std::setw(9) << cell(r.m4, r.m4.seconds)
            << std::setw(9) << cell(r.mf2, r.mf2.seconds, true) << std::setw(7)
            << (r.m1.ok && r.m2.ok ? cell(r.m2, r.m1.seconds / r.m2.seconds) : "-") << std::setw(10)
            << (volumes ? cell(r.mf1, relative_volume_difference(r.m1, r.mf1)) : "n/a")
            << std::setw(7) << other.str() << "  " << agreement << '\n';
}

nlohmann::json json_row(const Case& c, const RealSetOptions& o, const PairRuns& r, const Input& a,
                        const Input& b) {
  nlohmann::json row = {{"pair", c.name},
                        {"op", to_string(o.op)},
                        {"facets_a", c.a.num_triangles()},
                        {"facets_b", c.b.num_triangles()},
                        {"input_a", a.status},
                        {"input_b", b.status},
                        {"morphex_exact_volumes_agree", morphex_agrees(r)},
                        {"other_load_cores", r.other_cores},
                        {"attempts", r.attempts}};
  auto put = [&](const char* key, const Run& run) {
    if (run.ok) {
      row[key] = run.seconds;
      row[std::string(key) + "_peak_mib"] = run.peak_mib;
    } else if (!run.note.empty())
      row[std::string(key) + "_failed"] = run.note;
  };
  put("morphex_seconds_1t", r.m1);
  put("morphex_cli_seconds_1t", r.cli1);
  put("morphex_seconds_2t", r.m2);
  put("morphex_seconds_4t", r.m4);
  put("manifold_seconds_1t", r.mf1);
  put("manifold_seconds_2t", r.mf2);
  // The exact volume has thousands of digits after the rational rotation: its double is shown.
  if (r.m1.ok) row["morphex_volume"] = CGAL::to_double(parse_exact_number(r.m1.volume));
  if (r.mf1.ok) row["manifold_volume"] = CGAL::to_double(parse_exact_number(r.mf1.volume));
  if (r.m1.ok && r.mf1.ok) {
    row["ratio_manifold_morphex"] = r.mf1.seconds / r.m1.seconds;
    row["manifold_volume_relative_difference"] = relative_volume_difference(r.m1, r.mf1);
  }
  if (r.cli1.ok && r.mf1.ok) row["ratio_manifold_morphex_cli"] = r.mf1.seconds / r.cli1.seconds;
  if (r.m1.ok && r.m2.ok) row["morphex_speedup_1_to_2"] = r.m1.seconds / r.m2.seconds;
  return row;
}

// The pair's meshes as the engines get them, in exact OFF (the placed coordinates are rational).
void write_case(const Case& c, const std::filesystem::path& dir) {
  std::filesystem::create_directories(dir);
  std::string stem = c.name;
  for (char& ch : stem)
    if (ch == '/' || ch == ':' || ch == '@') ch = '_';
  WriteOptions exact;
  exact.exact = true;
  write_mesh(c.a, (dir / (stem + ".a.off")).string(), exact);
  write_mesh(c.b, (dir / (stem + ".b.off")).string(), exact);
}

double median(std::vector<double> values) {
  if (values.empty()) return std::nan("");
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : (values[n / 2 - 1] + values[n / 2]) / 2;
}

double minimum(const std::vector<double>& values) {
  return values.empty() ? std::nan("") : *std::min_element(values.begin(), values.end());
}

}  // namespace

namespace {

// Every input the selected pairs use, each prepared once, its preparation reported.
std::map<std::string, Input> prepare_inputs(const std::vector<PairSpec>& pairs,
                                            const RealSetOptions& o,
                                            const std::filesystem::path& scratch) {
  std::map<std::string, Input> inputs;
  const Mesh warm = make_box(Point(0, 0, 0), Point(1, 1, 1));
  for (const PairSpec& p : pairs)
    for (const std::string& source : {p.a, p.b}) {
      if (inputs.count(source)) continue;
      const std::string prepared = (scratch / (std::to_string(inputs.size()) + ".off")).string();
      std::function<Mesh(const Mesh&)> place = normalized;
      std::string why;
      if (is_ember(source)) {
        const std::optional<AffineColumns> map = ember_placement(source, o, why);
        if (!map) {
          Input missing;
          missing.status = why;
          inputs.emplace(source, std::move(missing));
          std::cout << "input " << source << ": " << why << std::endl;
          continue;
        }
        place = [map](const Mesh& m) { return placed(m, *map); };
      }
      Input in = prepare_input(input_path(source, o), prepared, place);
      // An EMBER mesh is checked as placed: the mesh `morphex bool` gets and checks.
      if (in.ok) in.check = time_check(is_ember(source) ? prepared : in.path, warm);
      std::cout << "input " << std::left << std::setw(26) << source << std::right << std::setw(8)
                << in.file_facets << " facets: " << in.status << std::endl;  // progress, as it goes
      inputs.emplace(source, std::move(in));
    }
  return inputs;
}

// The `morphex check` speed per input, one thread.
void print_check_speeds(const std::map<std::string, Input>& inputs, nlohmann::json& summary) {
  std::cout << "\ncheck_mesh on each file as read, the EMBER meshes as placed (default options, "
               "one thread):\n";
  for (const auto& [source, in] : inputs) {
    if (!in.ok || !in.check.ok) continue;
    const double per_million = in.check.seconds / double(in.file_facets) * 1e6;
    std::cout << "  " << std::left << std::setw(26) << source << std::right << std::setw(8)
              << in.file_facets << " facets " << std::setw(9) << std::setprecision(3)
              << in.check.seconds << " s " << std::setw(8) << per_million << " s per million facets"
              << (in.status == "valid" ? "" : "  (not a valid solid as read)") << '\n';
    summary["check"][source] = {{"facets", in.file_facets},
                                {"seconds", in.check.seconds},
                                {"seconds_per_million_facets", per_million},
                                {"valid_as_read", in.status == "valid"}};
  }
}

void print_legend() {
  std::cout
      << "m = morphex's operation on inputs taken as valid; cli = as `morphex bool` runs it "
         "(input check + operation); Mf = Manifold "
      << peers::manifold_version()
      << " (floating point; \"n/a\": bench_bool built without it, see "
         "tools/peers/build-manifold); Nt = N threads (this machine has "
      << std::thread::hardware_concurrency()
      << " cores). Mf/m, Mf/cli: Manifold's time over morphex's (above 1: morphex is "
         "faster). m 1>2: morphex's 1- over 2-thread time. vol rel: |Manifold volume - exact "
         "volume| / exact volume. other: cores the rest of the machine kept busy during the pair "
         "(above 0.2 the thread scaling is not trustworthy; such a pair runs again, "
         "--busy-retries, "
         "and the least disturbed attempt is shown). agree: morphex's four runs give one "
         "exact volume. Seconds "
         "are medians of repeated runs under half a second; no conversion is timed.\n";
}

}  // namespace

int run_real_set(const RealSetOptions& o, const Harness& output) {
  std::vector<PairSpec> pairs;
  std::vector<const char*> set_of;  // of each pair: "tuning" or "held-out"
  for (const auto* set : {&kPairs, &kHeldOutPairs}) {
    const bool held_out = set == &kHeldOutPairs;
    if (held_out ? o.pairs == "tuning" : o.pairs == "held-out") continue;
    for (const PairSpec& p : *set)
      if (o.only.empty() || pair_name(p).find(o.only) != std::string::npos) {
        pairs.push_back(p);
        set_of.push_back(held_out ? "held-out" : "tuning");
      }
  }
  const std::filesystem::path scratch =
      std::filesystem::temp_directory_path() / ("morphex-bench-real-" + std::to_string(getpid()));
  std::filesystem::create_directories(scratch);
  std::cout << "Booleans (" << to_string(o.op) << ") on real pairs (" << o.pairs
            << "); Manifold: " << (peers::kHaveManifold ? peers::manifold_version() : "n/a")
            << "\n";
  const std::map<std::string, Input> inputs = prepare_inputs(pairs, o, scratch);
  std::filesystem::remove_all(scratch);

  const Warmup warm{make_box(Point(0, 0, 0), Point(1, 1, 1)),
                    make_box(Point(FT(1) / 3, FT(1) / 5, FT(1) / 7), Point(2, 2, 2))};
  nlohmann::json rows = nlohmann::json::array();
  std::vector<double> ratios, cli_ratios, speedups;
  bool all_agree = true;
  std::cout << '\n';
  print_header();
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const PairSpec& p = pairs[i];
    const Input &a = inputs.at(p.a), &b = inputs.at(p.b);
    const std::string name = pair_name(p);
    if (!a.ok || !b.ok) {
      std::cout << name << ": skipped (" << (a.ok ? b.status : a.status) << ")\n";
      continue;
    }
    const Case c =
        is_ember(p.a) ? Case{name, a.mesh, b.mesh} : make_pair_case(name, a, b, p.degrees);
    if (!o.write_cases.empty()) write_case(c, o.write_cases);
    PairRuns r = run_pair(c, o.op, warm);
    for (int retry = 0; retry < o.busy_retries && r.other_cores > 0.25; ++retry) {
      PairRuns again = run_pair(c, o.op, warm);
      again.attempts = r.attempts + 1;
      if (again.other_cores < r.other_cores) r = again;
      r.attempts = again.attempts;
    }
    print_row(c, r);
    std::cout << std::flush;  // a long run shows its rows as they come
    all_agree = all_agree && morphex_agrees(r);
    if (r.m1.ok && r.mf1.ok) ratios.push_back(r.mf1.seconds / r.m1.seconds);
    if (r.cli1.ok && r.mf1.ok) cli_ratios.push_back(r.mf1.seconds / r.cli1.seconds);
    if (r.m1.ok && r.m2.ok && c.a.num_triangles() + c.b.num_triangles() >= 100000)
      speedups.push_back(r.m1.seconds / r.m2.seconds);
    rows.push_back(json_row(c, o, r, a, b));
    rows.back()["set"] = set_of[i];
  }
  nlohmann::json summary = {{"manifold", peers::manifold_version()},
                            {"pairs", o.pairs},
                            {"operation", to_string(o.op)},
                            {"median_ratio_manifold_morphex", median(ratios)},
                            {"median_ratio_manifold_morphex_cli", median(cli_ratios)},
                            {"min_ratio_manifold_morphex", minimum(ratios)},
                            {"min_ratio_manifold_morphex_cli", minimum(cli_ratios)},
                            {"median_speedup_1_to_2_over_100k", median(speedups)},
                            {"pairs_over_100k", speedups.size()}};
  std::cout << std::setprecision(3) << "\nmedian Mf/m " << median(ratios) << " (worst "
            << minimum(ratios) << "), median Mf/cli " << median(cli_ratios) << " (worst "
            << minimum(cli_ratios) << ") (over " << ratios.size()
            << " pairs); median morphex 1->2 thread speed-up " << median(speedups) << " (over "
            << speedups.size() << " pairs of at least 100,000 facets)\n";
  print_check_speeds(inputs, summary);
  print_legend();
  if (!output.write_json({{"pairs", rows}, {"summary", summary}})) return 2;
  return all_agree ? 0 : 1;
}

}  // namespace morphex::bench

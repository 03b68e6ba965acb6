// SPDX-License-Identifier: GPL-3.0-or-later
// Descriptors and retrieval: `morphex describe`, `generate`, `index`, `query` and `evaluate`.
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "cli_common.h"
#include "index_db.h"
#include "morphex/collection.h"
#include "morphex/descriptors.h"
#include "morphex/io.h"
#include "morphex/pipeline.h"
#include "morphex/retrieval.h"
#include "morphex/stopwatch.h"

namespace morphex::cli {
namespace {

namespace mp = morphex::pipeline;
namespace fs = std::filesystem;

const char* kDefaultPipeline =
    R"({"pipeline": [{"type": "read", "path": "${input}"}, {"type": "describe"}]})";

// The document with a repair stage after every read: the repair takes the read's tag (the read
// gets "<tag>.as-read"), so that every stage that took the read's mesh takes the repaired one.
nlohmann::json with_repairs(const nlohmann::json& document) {
  nlohmann::json out = document;
  nlohmann::json& stages = out.is_array() ? out : out["pipeline"];
  nlohmann::json rewritten = nlohmann::json::array();
  for (const nlohmann::json& stage : stages) {
    if (!stage.is_object() || stage.value("type", "") != "read") {
      rewritten.push_back(stage);
      continue;
    }
    nlohmann::json read = stage, repair = {{"type", "repair"}};
    if (stage.contains("tag") && stage["tag"].is_string()) {
      const std::string tag = stage["tag"].get<std::string>();
      read["tag"] = tag + ".as-read";
      repair["tag"] = tag;
      repair["inputs"] = read["tag"];
    }
    rewritten.push_back(read);
    rewritten.push_back(repair);
  }
  stages = rewritten;
  return out;
}

// What the repair stage of a finished input changed, as JSON text (empty when nothing).
std::string repair_of(const mp::InputReport& input) {
  for (const mp::StageReport& s : input.stages)
    if (s.type == "repair" && s.extra.contains("repair") &&
        s.extra["repair"].value("changed", false))
      return s.extra["repair"].dump();
  return "";
}

// The descriptors of the last describe stage of a finished input, by kind.
std::map<std::string, std::vector<double>> descriptors_of(const mp::InputReport& input) {
  std::map<std::string, std::vector<double>> out;
  for (const mp::StageReport& s : input.stages)
    if (s.type == "describe")
      for (const auto& [kind, v] : s.extra["descriptors"].items())
        out[kind] = v.get<std::vector<double>>();
  return out;
}

nlohmann::json descriptors_json(const Descriptors& d) {
  nlohmann::json j = {{"scale_length", d.scale_length},
                      {"thickness", d.thickness},
                      {"filtered_facets", d.facets},
                      {"simplified", d.simplified},
                      {"open_radii", d.open_radii},
                      {"close_radii", d.close_radii},
                      {"granulometry", d.granulometry},
                      {"pattern_spectrum", d.pattern_spectrum},
                      {"anti_granulometry", d.anti_granulometry},
                      {"opening_residue", d.opening_residue},
                      {"closing_residue", d.closing_residue},
                      {"components", d.components},
                      {"d2", d.d2},
                      {"seconds_morphology", d.seconds_morphology}};
  for (const std::string& kind : descriptor_kinds())
    j["vectors"][kind] = descriptor_vector(d, kind);
  return j;
}

Command add_describe_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("describe", "Morphological descriptors and D2 of a closed mesh");
  struct Args {
    std::string mesh;
    bool json = false, repair = false;
    DescriptorSettings settings;
  };
  auto args = std::make_shared<Args>();
  auto& s = args->settings;
  cmd->add_option("MESH", args->mesh, "Closed mesh")->required();
  cmd->add_flag("--json", args->json, "One JSON object on stdout");
  cmd->add_flag("--repair", args->repair,
                "Repair the mesh first when it is not a valid solid (morphex repair)");
  cmd->add_option("--scales", s.scales, "Number of opening and closing radii")
      ->capture_default_str()
      ->check(CLI::Range(1, 64));
  const auto positive = CLI::PositiveNumber;
  cmd->add_option("--open-from", s.open_from,
                  "Smallest opening cube half side, in units of the thickness 3 volume / area")
      ->capture_default_str()
      ->check(positive);
  cmd->add_option("--open-to", s.open_to, "Largest opening cube half side, in units of it")
      ->capture_default_str()
      ->check(positive);
  cmd->add_option("--close-from", s.close_from,
                  "Smallest closing cube half side, in units of cbrt(volume)")
      ->capture_default_str()
      ->check(positive);
  cmd->add_option("--close-to", s.close_to, "Largest closing cube half side, in units of it")
      ->capture_default_str()
      ->check(positive);
  cmd->add_flag("!--no-closings", s.closings, "Skip the anti-granulometry");
  cmd->add_option("--facet-budget", s.facet_budget,
                  "Filter a simplified valid copy of about this many facets (0: the mesh itself)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--d2-samples", s.d2_samples, "D2 point pairs")
      ->capture_default_str()
      ->check(CLI::Range(16, 10000000));
  cmd->add_option("--d2-bins", s.d2_bins, "D2 histogram bins")
      ->capture_default_str()
      ->check(CLI::Range(4, 4096));
  cmd->add_option("--seed", s.seed, "D2 random seed");
  return {cmd, [args]() -> int {
            const auto& s = args->settings;
            if (s.open_from > s.open_to || s.close_from > s.close_to) {
              print_error("--open-from/--close-from must not exceed --open-to/--close-to");
              return kBadInput;
            }
            std::optional<Mesh> mesh;
            std::optional<RepairReport> repaired;
            if (args->repair) {
              try {
                RepairResult r = repair_mesh(read_mesh(args->mesh));
                mesh = std::move(r.mesh);
                repaired = r.report;
              } catch (const InputError& e) {
                // A reader's error names the file; the repair's says what it cannot repair.
                print_error(e.where().empty() ? args->mesh + ": cannot repair: " + e.what()
                                              : std::string(e.what()));
                return kBadInput;
              }
            } else {
              mesh = read_solid(args->mesh);
            }
            if (!mesh) return kBadInput;
            const Stopwatch start;
            const Descriptors d = describe_valid(*mesh, s);  // read_solid or repair checked it
            nlohmann::json j = descriptors_json(d);
            if (repaired) j["repair"] = mp::to_json(*repaired);
            j["name"] = fs::path(args->mesh).stem().string();
            j["path"] = args->mesh;
            j["settings"] = s.to_string();
            j["seconds"] = start.seconds();
            if (args->json) {
              std::cout << j.dump() << std::endl;
              return kSuccess;
            }
            std::cout << args->mesh << "  (L = cbrt(volume) = " << d.scale_length
                      << ", thickness T/L = " << d.thickness << ", " << d.facets
                      << " facets filtered" << (d.simplified ? ", simplified" : "") << ")\n";
            for (const char* key : {"open_radii", "granulometry", "pattern_spectrum", "close_radii",
                                    "anti_granulometry", "components", "d2"}) {
              std::cout << std::left << std::setw(19) << key;
              for (double v : j[key].get<std::vector<double>>())
                std::cout << ' ' << std::setprecision(4) << v;
              std::cout << '\n';
            }
            return kSuccess;
          }};
}

Command add_generate_command(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "generate", "Write the procedural labelled collection (exact OFF files and labels.cla)");
  struct Args {
    std::string dir;
    int per_family = 4;
    std::uint64_t seed = 1;
  };
  auto args = std::make_shared<Args>();
  cmd->add_option("DIR", args->dir, "Output directory (created)")->required();
  cmd->add_option("--per-class", args->per_family, "Meshes per family")->check(CLI::Range(1, 1000));
  cmd->add_option("--seed", args->seed, "Random seed");
  return {cmd, [args]() -> int {
            fs::create_directories(args->dir);
            const auto meshes = make_collection(args->per_family, args->seed);
            WriteOptions exact;
            exact.exact = true;
            for (const LabelledMesh& m : meshes)
              write_mesh(m.mesh, (fs::path(args->dir) / (m.name + ".off")).string(), exact);
            const std::string labels = (fs::path(args->dir) / "labels.cla").string();
            write_file_atomically(labels, [&](std::ostream& out) { out << to_cla(meshes); });
            std::cout << "wrote " << meshes.size() << " meshes in " << collection_families().size()
                      << " classes and " << labels << '\n';
            return kSuccess;
          }};
}

// Progress of an index run on stderr: a bar redrawn in place on a terminal; in a log (stderr not
// a terminal), a plain line at most every five seconds and one at the end.
class ProgressBar {
 public:
  explicit ProgressBar(std::size_t total) : total_(total), tty_(isatty(STDERR_FILENO) != 0) {}
  void update(std::size_t done, std::size_t failed) {
    if (total_ == 0) return;
    const double elapsed = start_.seconds();
    if (!tty_ && done != total_ && elapsed - last_line_ < 5) return;
    last_line_ = elapsed;
    const double eta = done > 0 ? elapsed / double(done) * double(total_ - done) : 0;
    std::ostringstream eta_text;
    eta_text << int(eta) / 60 << "m" << std::setw(2) << std::setfill('0') << int(eta) % 60 << "s";
    if (!tty_) {
      std::cerr << "indexed " << done << "/" << total_ << ", " << failed << " failed, ETA "
                << eta_text.str() << std::endl;
      return;
    }
    const int width = 30, filled = int(width * done / total_);
    std::cerr << "\r\033[K[" << std::string(filled, '=') << std::string(width - filled, ' ') << "] "
              << done << "/" << total_ << " meshes, " << failed << " failed, ETA " << eta_text.str()
              << (done == total_ ? "\n" : "") << std::flush;
  }

 private:
  std::size_t total_;
  bool tty_;
  double last_line_ = 0;
  Stopwatch start_;
};

Command add_index_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("index", "Describe meshes into a SQLite retrieval index");
  struct Args {
    std::vector<std::string> inputs, sets;
    std::string db, pipeline;
    bool repair = true;
  };
  auto args = std::make_shared<Args>();
  cmd->add_option("INPUT", args->inputs, "Meshes or quoted globs")->required();
  cmd->add_flag("--repair,!--no-repair", args->repair,
                "Repair meshes that are not valid solids (self-intersecting, touching, repeated or "
                "degenerate faces) before describing them; on by default, recorded per mesh");
  cmd->add_option("--db", args->db, "Index file (SQLite), created if missing")->required();
  cmd->add_option("--pipeline", args->pipeline,
                  "Descriptor pipeline run on each ${input}; its last describe stage is stored "
                  "(default: read, then describe with default settings)");
  cmd->add_option("--set", args->sets, "Pipeline variable name=value (repeatable)");
  return {cmd, [args]() -> int {
            nlohmann::json document;
            try {
              document = args->pipeline.empty() ? mp::parse_document(kDefaultPipeline, "default")
                                                : mp::load_document(args->pipeline);
              if (args->repair) document = with_repairs(document);
              const auto p = mp::validate(document, args->pipeline, {}, {"input", "stem"});
              if (std::none_of(p.stages.begin(), p.stages.end(),
                               [](const mp::Stage& s) { return s.type == "describe"; }))
                throw mp::PipelineError(std::vector<mp::Problem>{
                    {"pipeline", "an index pipeline needs a describe stage"}});
            } catch (const mp::PipelineError& e) {
              for (const auto& p : e.problems()) print_error(args->pipeline + ": " + p.text());
              return kBadInput;
            }
            mp::RunOptions options;
            try {
              options.variables = mp::parse_assignments(args->sets);
            } catch (const mp::PipelineError& e) {
              for (const auto& p : e.problems()) print_error(p.text());
              return kBadInput;
            }
            std::string sets;
            for (const std::string& s : args->sets) sets += s + ";";
            const std::string settings =
                document.dump() + "|" + sets + "|descriptors " + descriptor_version();
            IndexDb db(args->db);
            db.set_meta("pipeline", document.dump());
            db.set_meta("sets", nlohmann::json(options.variables).dump());

            const Stopwatch start;
            std::size_t skipped = 0, failed = 0, done = 0, indexed = 0;
            std::map<std::string, std::string> hashes;
            for (const std::string& input : expand_inputs(args->inputs)) {
              std::string hash;
              try {
                hash = content_hash(input);
              } catch (const std::exception& e) {
                ++failed;
                print_error(input + ": cannot read the file");
                db.store({0,
                          fs::path(input).stem().string(),
                          input,
                          "",
                          settings,
                          "failed",
                          "cannot read the file",
                          {}},
                         0, "", 0);
                continue;
              }
              if (db.up_to_date(input, hash, settings)) {
                ++skipped;
                continue;
              }
              hashes[input] = hash;
              options.inputs.push_back(input);
            }
            ProgressBar bar(options.inputs.size());
            options.on_input_done = [&](const mp::InputReport& r) {
              IndexedMesh m;
              m.name = fs::path(r.input).stem().string();
              m.path = r.input;
              m.hash = hashes[r.input];
              m.settings = settings;
              m.status = r.ok ? "ok" : "failed";
              m.error = r.error;
              if (r.ok) m.descriptors = descriptors_of(r);
              m.repair = repair_of(r);
              const std::size_t faces = r.stages.empty() ? 0 : r.stages.front().faces;
              const std::string volume = r.stages.empty() ? "" : r.stages.front().volume;
              db.store(m, faces, volume, r.seconds);
              ++done;
              if (r.ok) ++indexed;
              if (!r.ok) {
                ++failed;
                print_error(r.input + ": " + r.error);
              }
              bar.update(done, failed);
            };
            if (!options.inputs.empty()) {
              try {
                mp::run(document, args->pipeline, options);
              } catch (const mp::PipelineError& e) {
                for (const auto& p : e.problems()) print_error(args->pipeline + ": " + p.text());
                return kBadInput;
              }
            }
            const double seconds = start.seconds();
            std::cout << args->db << ": indexed " << indexed << " meshes (" << skipped
                      << " already up to date, " << failed << " failed) in " << std::setprecision(3)
                      << seconds << " s";
            if (done > 0)
              std::cout << ", " << std::setprecision(3) << 60.0 * double(done) / seconds
                        << " meshes/min";
            std::cout << '\n';
            return failed == 0 ? kSuccess : kFailed;
          }};
}

Command add_query_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("query", "Nearest neighbours of a mesh in a retrieval index");
  struct Args {
    std::string db, mesh, descriptor = default_descriptor_kind(), metric = "l1";
    std::size_t k = 10;
    bool json = false;
  };
  auto args = std::make_shared<Args>();
  cmd->add_option("--db", args->db, "Index file")->required()->check(CLI::ExistingFile);
  cmd->add_option("MESH", args->mesh, "A mesh file, or the name (stem) or path of an indexed mesh")
      ->required();
  cmd->add_option("-k", args->k, "Number of neighbours")->check(CLI::PositiveNumber);
  cmd->add_option("--descriptor", args->descriptor, "Descriptor kind")
      ->capture_default_str()
      ->check(CLI::IsMember(descriptor_kinds()));
  cmd->add_option("--metric", args->metric, "Distance: l1, l2 or chi2")
      ->capture_default_str()
      ->check(CLI::IsMember({"l1", "l2", "chi2"}));
  cmd->add_flag("--json", args->json, "One JSON object on stdout");
  return {cmd, [args]() -> int {
            IndexDb db(args->db);
            const std::vector<IndexedMesh> meshes = db.load();
            std::vector<double> query;
            long long exclude = -1;
            const auto by_id = std::find_if(
                meshes.begin(), meshes.end(),
                [&](const IndexedMesh& m) { return m.name == args->mesh || m.path == args->mesh; });
            if (!fs::exists(args->mesh) && by_id != meshes.end()) {
              if (!by_id->descriptors.count(args->descriptor)) {
                print_error(args->db + ": " + by_id->name + " has no '" + args->descriptor +
                            "' descriptor (indexed by another version of morphex: run morphex "
                            "index again)");
                return kBadInput;
              }
              query = by_id->descriptors.at(args->descriptor);
              exclude = by_id->id;
            } else {
              mp::RunOptions options;
              options.inputs = {args->mesh};
              const auto sets = db.meta("sets");
              if (sets) options.variables = nlohmann::json::parse(*sets).get<mp::Variables>();
              const std::string pipeline = db.meta("pipeline").value_or(kDefaultPipeline);
              const mp::RunReport r = mp::run(nlohmann::json::parse(pipeline), args->db, options);
              if (!r.ok()) {
                print_error(args->mesh + ": " + r.inputs.front().error);
                return kBadInput;
              }
              query = descriptors_of(r.inputs.front()).at(args->descriptor);
            }
            std::vector<std::pair<double, const IndexedMesh*>> ranked;
            for (const IndexedMesh& m : meshes)
              if (m.id != exclude && m.descriptors.count(args->descriptor))
                ranked.emplace_back(
                    distance(query, m.descriptors.at(args->descriptor), parse_metric(args->metric)),
                    &m);
            std::sort(ranked.begin(), ranked.end(), [](const auto& a, const auto& b) {
              return a.first != b.first ? a.first < b.first : a.second->name < b.second->name;
            });
            ranked.resize(std::min(ranked.size(), args->k));
            nlohmann::json j = {{"query", args->mesh},
                                {"descriptor", args->descriptor},
                                {"distance", args->metric},
                                {"neighbours", nlohmann::json::array()}};
            for (const auto& [d, m] : ranked)
              j["neighbours"].push_back({{"name", m->name}, {"path", m->path}, {"distance", d}});
            if (args->json) {
              std::cout << j.dump() << std::endl;
            } else {
              for (std::size_t i = 0; i < ranked.size(); ++i)
                std::cout << std::setw(3) << i + 1 << "  " << std::left << std::setw(24)
                          << ranked[i].second->name << std::right << std::setw(12)
                          << std::setprecision(5) << ranked[i].first << "  "
                          << ranked[i].second->path << '\n';
            }
            return kSuccess;
          }};
}

Command add_evaluate_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("evaluate", "Retrieval scores of every stored descriptor");
  struct Args {
    std::string db, labels, metric = "l1";
    bool json = false;
  };
  auto args = std::make_shared<Args>();
  cmd->add_option("--db", args->db, "Index file")->required()->check(CLI::ExistingFile);
  cmd->add_option("--labels", args->labels, "Princeton .cla labels (model names = file stems)")
      ->required();
  cmd->add_option("--metric", args->metric, "Distance: l1, l2 or chi2")
      ->capture_default_str()
      ->check(CLI::IsMember({"l1", "l2", "chi2"}));
  cmd->add_flag("--json", args->json, "One JSON object on stdout");
  return {cmd, [args]() -> int {
            std::map<std::string, std::string> labels;
            try {
              labels = read_cla(args->labels);
            } catch (const std::exception& e) {
              print_error(e.what());
              return kBadInput;
            }
            IndexDb db(args->db);
            std::vector<IndexedMesh> meshes;
            std::size_t unlabelled = 0;
            for (IndexedMesh& m : db.load())
              if (labels.count(m.name))
                meshes.push_back(std::move(m));
              else
                ++unlabelled;
            std::vector<std::string> names, classes;
            for (const IndexedMesh& m : meshes) {
              names.push_back(m.name);
              classes.push_back(labels[m.name]);
            }
            const Metric metric = parse_metric(args->metric);
            nlohmann::json j = {{"models", meshes.size()},
                                {"metric", args->metric},
                                {"unlabelled", unlabelled},
                                {"descriptors", nlohmann::json::object()}};
            if (!args->json)
              std::cout << std::left << std::setw(18) << "descriptor" << std::right << std::setw(18)
                        << "Nearest Neighbor" << std::setw(12) << "First Tier" << std::setw(13)
                        << "Second Tier" << std::setw(11) << "E-measure" << std::setw(8) << "DCG"
                        << '\n';
            for (const std::string& kind : descriptor_kinds()) {
              if (std::any_of(meshes.begin(), meshes.end(),
                              [&](const IndexedMesh& m) { return !m.descriptors.count(kind); }))
                continue;
              std::vector<std::vector<double>> distance(meshes.size(),
                                                        std::vector<double>(meshes.size()));
              for (std::size_t a = 0; a < meshes.size(); ++a)
                for (std::size_t b = 0; b < meshes.size(); ++b)
                  distance[a][b] = morphex::distance(meshes[a].descriptors.at(kind),
                                                     meshes[b].descriptors.at(kind), metric);
              const RetrievalScores s = evaluate_retrieval(names, classes, distance);
              j["descriptors"][kind] = {{"nearest_neighbor", s.nearest_neighbor},
                                        {"first_tier", s.first_tier},
                                        {"second_tier", s.second_tier},
                                        {"e_measure", s.e_measure},
                                        {"dcg", s.dcg},
                                        {"queries", s.queries}};
              if (!args->json)
                std::cout << std::left << std::setw(18) << kind << std::right << std::fixed
                          << std::setprecision(3) << std::setw(18) << s.nearest_neighbor
                          << std::setw(12) << s.first_tier << std::setw(13) << s.second_tier
                          << std::setw(11) << s.e_measure << std::setw(8) << s.dcg << '\n'
                          << std::defaultfloat;
            }
            if (args->json)
              std::cout << j.dump() << std::endl;
            else
              std::cout << meshes.size() << " labelled models"
                        << (unlabelled ? ", " + std::to_string(unlabelled) +
                                             " indexed models without a label skipped"
                                       : "")
                        << '\n';
            return kSuccess;
          }};
}

}  // namespace

std::vector<Command> add_retrieval_commands(CLI::App& app) {
  return {add_describe_command(app), add_generate_command(app), add_index_command(app),
          add_query_command(app), add_evaluate_command(app)};
}

}  // namespace morphex::cli

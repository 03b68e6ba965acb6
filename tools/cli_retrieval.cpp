// SPDX-License-Identifier: GPL-3.0-or-later
// Descriptors and retrieval: `morphex describe`, `generate`, `query` and `evaluate` (`index`, `ls`
// and `rm`, the collection manager, are in cli_index.cpp).
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <set>
#include <sstream>
#include <variant>

#include "cli_common.h"
#include "morphex/collection.h"
#include "morphex/descriptor_settings.h"
#include "morphex/descriptors.h"
#include "morphex/index.h"
#include "morphex/internal/files.h"
#include "morphex/io.h"
#include "morphex/json.h"
#include "morphex/morph_json.h"
#include "morphex/pipeline.h"
#include "morphex/plot.h"
#include "morphex/retrieval.h"
#include "morphex/retrieval_json.h"

namespace morphex::cli {
namespace {

namespace mp = morphex::pipeline;
namespace fs = std::filesystem;

// --plot FILE: an SVG file, written atomically; "-" writes it on stdout in place of the usual
// output (which is why it cannot go with --json).
void add_plot_option(CLI::App* cmd, std::string& plot, const std::string& what) {
  cmd->add_option("--plot", plot,
                  "Write " + what + " as an SVG file (- : on stdout, in place of the table)")
      ->type_name("FILE");
}

bool plot_usable(const std::string& plot, bool json, const std::vector<NamedFile>& reads) {
  if (plot == "-" && json) {
    print_error("--plot - and --json both write to stdout: give --plot a file name");
    return false;
  }
  return writes_safe({{plot, "--plot"}}, reads);
}

void write_plot(const std::string& plot, const Figure& figure) {
  if (plot == "-")
    std::cout << to_svg(figure);
  else
    write_svg(plot, figure);
}

// The command line's name of a descriptor setting: open_from is --open-from.
std::string option_name(const std::string& setting) {
  std::string out = "--" + setting;
  std::replace(out.begin(), out.end(), '_', '-');
  return out;
}

// One option per descriptor setting, from the library's table (morphex/descriptor_settings.h):
// --name VALUE for a number, --no-name for a setting that is on by default. Their ranges are
// checked by the library (settings_usable), with the one message every front end gives.
void add_descriptor_setting_options(CLI::App* cmd, DescriptorSettings& s) {
  for (const DescriptorSettingInfo& setting : descriptor_settings_table()) {
    std::string doc = setting.doc;
    std::visit(
        [&](auto member) {
          using T = std::remove_reference_t<decltype(s.*member)>;
          if constexpr (std::is_same_v<T, bool>) {
            cmd->add_flag("!--no-" + option_name(setting.name).substr(2), s.*member,
                          "Do not " + doc);
          } else {
            doc[0] = char(std::toupper(static_cast<unsigned char>(doc[0])));
            cmd->add_option(option_name(setting.name), s.*member, doc)->capture_default_str();
          }
        },
        setting.field);
  }
}

// The library's check of the settings, its message under the option's name.
bool settings_usable(const DescriptorSettings& s) {
  try {
    check_descriptor_settings(s);
    return true;
  } catch (const InputError& e) {
    print_error(option_name(e.where()) + ": " + e.problem());
    return false;
  }
}

struct DescribeArgs {
  std::string mesh, plot;
  bool json = false, repair = true;
  DescriptorSettings settings;
};

// What `morphex describe` runs: the pipeline read, solidify (unless --no-repair), describe with the
// options' settings. The mesh is bound as ${input}, so no character of its path reads as a
// variable.
nlohmann::json describe_pipeline(const DescribeArgs& args) {
  nlohmann::json stages = {{{"type", "read"}, {"path", "${input}"}}};
  if (args.repair) stages.push_back({{"type", "solidify"}});
  nlohmann::json describe = args.settings;  // the describe stage's options are the settings
  describe["type"] = "describe";
  stages.push_back(describe);
  return {{"pipeline", stages}};
}

// A failed run in the words of a command that runs a pipeline the user never wrote: the reader's
// error names the file, solidify's says why there is no solid, and the read's refusal of a mesh
// that is not a valid solid is the command line's (solid_problem: `morphex repair` for what it
// repairs) rather than the pipeline's advice to add a repair stage.
std::string describe_error(const DescribeArgs& args, const mp::InputReport& r) {
  const std::string& error = r.stage_error;
  if (r.failed_stage == 0) {
    const std::string prefix = args.mesh + ": ";
    const std::string stage_hint = " (a repair stage after the read repairs it)";
    if (error.rfind(prefix, 0) == 0 && error.size() > prefix.size() + stage_hint.size() &&
        error.compare(error.size() - stage_hint.size(), stage_hint.size(), stage_hint) == 0)
      return solid_problem(
          args.mesh, error.substr(prefix.size(), error.size() - prefix.size() - stage_hint.size()));
    return error;
  }
  if (args.repair && r.failed_stage == 1) return args.mesh + ": cannot solidify: " + error;
  return args.mesh + ": " + error;
}

// Runs the describe pipeline on the mesh; its description as `describe --json` prints it (the
// describe stage's report, with what solidify changed, the name, path, settings and seconds), or
// nullopt after printing why there is none.
std::optional<nlohmann::json> run_describe(const DescribeArgs& args) {
  mp::RunOptions options;
  options.inputs = {args.mesh};
  ProgressDisplay display("described", "stages", false);  // on a terminal only
  options.on_progress = [&](double done, std::size_t total, const std::string&,
                            const std::string& stage) {
    display.update(std::size_t(done), total, 0, stage, done - std::floor(done));
  };
  mp::RunReport report;
  try {
    report = mp::run(describe_pipeline(args), "describe", options);
  } catch (const mp::PipelineError& e) {
    for (const mp::Problem& p : e.problems()) print_error(p.text());
    return std::nullopt;
  }
  const mp::InputReport& r = report.inputs.at(0);
  if (!r.ok) {
    print_error(describe_error(args, r));
    return std::nullopt;
  }
  const mp::StageReport& described = r.stages.back();
  nlohmann::json j = described.extra;  // the library's JSON of the description
  j["vectors"] = std::move(j["descriptors"]);
  j.erase("descriptors");
  j["settings"] = std::move(j["descriptor_settings"]);
  j.erase("descriptor_settings");
  if (args.repair && r.stages.at(1).extra.at("solidify").at("changed").get<bool>())
    j["solidify"] = r.stages[1].extra["solidify"];
  j["name"] = fs::path(args.mesh).stem().string();
  j["path"] = args.mesh;
  j["seconds"] = described.seconds;
  return j;
}

void print_description(const std::string& mesh, const nlohmann::json& j) {
  const Descriptors d = j.get<Descriptors>();
  std::cout << mesh << "  (L = cbrt(volume) = " << d.scale_length
            << ", thickness T/L = " << d.thickness << ", " << d.facets << " facets filtered"
            << (d.simplified ? ", simplified" : "") << ")\n";
  for (const char* key : {"open_radii", "granulometry", "pattern_spectrum", "close_radii",
                          "anti_granulometry", "components", "d2"}) {
    std::cout << std::left << std::setw(19) << key;
    for (double v : j[key].get<std::vector<double>>())
      std::cout << ' ' << std::setprecision(4) << v;
    std::cout << '\n';
  }
}

Command add_describe_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("describe", "Morphological descriptors and D2 of a mesh");
  auto args = std::make_shared<DescribeArgs>();
  cmd->add_option("MESH", args->mesh, "Mesh (a valid solid, or anything solidify takes)")
      ->required();
  cmd->add_flag("--json", args->json, "One JSON object on stdout");
  add_plot_option(cmd, args->plot,
                  "the granulometry, anti-granulometry, pattern spectrum and D2 curves");
  cmd->add_flag("--repair,!--no-repair", args->repair,
                "Make a mesh that is not a valid solid into one first (morphex solidify; on by "
                "default, what was done reported); --no-repair refuses it instead");
  add_descriptor_setting_options(cmd, args->settings);
  return {cmd, [args]() -> int {
            if (!settings_usable(args->settings)) return kBadInput;
            if (!plot_usable(args->plot, args->json, {{args->mesh, "the input"}})) return kBadInput;
            std::optional<nlohmann::json> j = run_describe(*args);
            if (!j) return kBadInput;
            if (!args->plot.empty()) {
              write_plot(args->plot,
                         descriptor_figure(j->get<Descriptors>(), (*j)["name"].get<std::string>()));
              if (args->plot == "-") return kSuccess;
              (*j)["plot"] = args->plot;
            }
            if (args->json) {
              std::cout << j->dump() << std::endl;
              return kSuccess;
            }
            print_description(args->mesh, *j);
            if (!args->plot.empty()) std::cout << "wrote " << args->plot << '\n';
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
  cmd->add_option("-k", args->k, "Number of neighbours")->check(positive_integer());
  cmd->add_option("--descriptor", args->descriptor, "Descriptor kind")
      ->capture_default_str()
      ->check(CLI::IsMember(descriptor_kinds()));
  cmd->add_option("--metric", args->metric, "Distance: l1, l2 or chi2")
      ->capture_default_str()
      ->check(CLI::IsMember({"l1", "l2", "chi2"}));
  cmd->add_flag("--json", args->json, "One JSON object on stdout");
  return {cmd, [args]() -> int {
            IndexDb db(args->db, IndexAccess::ReadOnly);
            std::vector<Neighbour> ranked;
            try {
              const OperationProgress progress("query");  // a query mesh file is described first
              ranked = query_index(db, args->mesh, args->k, args->descriptor,
                                   parse_metric(args->metric));
            } catch (const InputError& e) {
              print_error(e.what());
              return kBadInput;
            }
            nlohmann::json j = {{"query", args->mesh},
                                {"descriptor", args->descriptor},
                                {"distance", args->metric},
                                {"neighbours", nlohmann::json::array()}};
            for (const Neighbour& n : ranked) {
              nlohmann::json neighbour = n;
              neighbour.erase("id");  // the row number means nothing outside the index file
              j["neighbours"].push_back(neighbour);
            }
            if (args->json) {
              std::cout << j.dump() << std::endl;
              return kSuccess;
            }
            for (std::size_t i = 0; i < ranked.size(); ++i)
              std::cout << std::setw(3) << i + 1 << "  " << std::left << std::setw(24)
                        << ranked[i].name << std::right << std::setw(12) << std::setprecision(5)
                        << ranked[i].distance << "  " << ranked[i].path << '\n';
            return kSuccess;
          }};
}

// The table's header and rows: a first column `first` wide, then the five measures.
void print_scores_header(const std::string& first, int width) {
  std::cout << std::left << std::setw(width) << first << std::right << std::setw(18)
            << "Nearest Neighbor" << std::setw(12) << "First Tier" << std::setw(13) << "Second Tier"
            << std::setw(11) << "E-measure" << std::setw(8) << "DCG" << '\n';
}
void print_scores_row(const std::string& first, int width, const RetrievalScores& s) {
  std::cout << std::left << std::setw(width) << first << std::right << std::fixed
            << std::setprecision(3) << std::setw(18) << s.nearest_neighbor << std::setw(12)
            << s.first_tier << std::setw(13) << s.second_tier << std::setw(11) << s.e_measure
            << std::setw(8) << s.dcg << '\n'
            << std::defaultfloat;
}

// Per descriptor kind, a table of its classes: size, queries and the means of their queries.
void print_per_class(const IndexEvaluation& e) {
  for (const auto& [kind, classes] : e.per_class) {
    std::size_t width = 18;
    for (const ClassScores& c : classes) width = std::max(width, c.name.size() + 2);
    std::cout << "\nper class, " << kind << ":\n";
    print_scores_header("class (models)", int(width));
    for (const ClassScores& c : classes) {
      const std::string first = c.name + " (" + std::to_string(c.models) + ")";
      if (c.scores.queries == 0)
        std::cout << std::left << std::setw(int(width)) << first << std::right << std::setw(18)
                  << "-"
                  << "  (no other member to find)\n";
      else
        print_scores_row(first, int(width), c.scores);
    }
  }
}

Command add_evaluate_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("evaluate", "Retrieval scores of every stored descriptor");
  struct Args {
    std::string db, labels, metric = "l1", plot;
    bool json = false, per_class = false;
  };
  auto args = std::make_shared<Args>();
  cmd->add_option("--db", args->db, "Index file")->required()->check(CLI::ExistingFile);
  cmd->add_option("--labels", args->labels, "Princeton .cla labels (model names = file stems)")
      ->required();
  cmd->add_option("--metric", args->metric, "Distance: l1, l2 or chi2")
      ->capture_default_str()
      ->check(CLI::IsMember({"l1", "l2", "chi2"}));
  cmd->add_flag("--json", args->json,
                "One JSON object on stdout (with each descriptor's precision-recall curve)");
  cmd->add_flag("--per-class", args->per_class,
                "Also the scores of each class (a table per descriptor, or \"per_class\" in JSON)");
  add_plot_option(cmd, args->plot,
                  "the precision-recall curves of every descriptor (21 recall levels, "
                  "interpolated precision averaged over the queries)");
  return {cmd, [args]() -> int {
            if (!plot_usable(args->plot, args->json,
                             {{args->db, "the index"}, {args->labels, "the labels"}}))
              return kBadInput;
            std::map<std::string, std::string> labels;
            try {
              labels = read_cla(args->labels);
            } catch (const std::exception& e) {
              print_error(e.what());
              return kBadInput;
            }
            IndexDb db(args->db, IndexAccess::ReadOnly);
            const IndexEvaluation e = evaluate_index(db, labels, parse_metric(args->metric));
            if (e.models == 0) {  // a table of zeros would hide a wrong --labels or --db
              print_error(args->labels + ": none of its " + std::to_string(labels.size()) +
                          " models is in the index " + args->db);
              return kBadInput;
            }
            // Label names the index does not hold are left out of the scores: say how many, as a
            // misspelt or stale label file would otherwise only lower the scores silently.
            std::set<std::string> indexed;
            for (const IndexedMesh& m : db.load(false, {})) indexed.insert(m.name);
            std::size_t not_indexed = 0;
            for (const auto& [name, label] : labels) not_indexed += !indexed.count(name);
            if (!args->plot.empty()) {
              const std::string title =
                  "Precision-recall: " + fs::path(args->labels).filename().string() + ", " +
                  std::to_string(e.models) + " models, metric " + args->metric;
              write_plot(args->plot,
                         Figure{"", {precision_recall_chart(e.precision_recall, title)}, 1});
              if (args->plot == "-") return kSuccess;
            }
            nlohmann::json j = {{"models", e.models},
                                {"metric", args->metric},
                                {"unlabelled", e.unlabelled},
                                {"labels_not_indexed", not_indexed},
                                {"descriptors", nlohmann::json::object()}};
            if (!args->plot.empty()) j["plot"] = args->plot;
            if (!args->json) print_scores_header("descriptor", 18);
            for (std::size_t k = 0; k < e.scores.size(); ++k) {
              const auto& [kind, s] = e.scores[k];
              nlohmann::json& d = j["descriptors"][kind] = s;
              d["precision_recall"] = e.precision_recall[k].second;
              if (args->per_class)
                for (const ClassScores& c : e.per_class[k].second) d["per_class"][c.name] = c;
              if (!args->json) print_scores_row(kind, 18, s);
            }
            if (args->json) {
              std::cout << j.dump() << std::endl;
              return kSuccess;
            }
            std::cout << e.models << " labelled models"
                      << (e.unlabelled ? ", " + std::to_string(e.unlabelled) +
                                             " indexed models without a label skipped"
                                       : "")
                      << (not_indexed ? ", " + std::to_string(not_indexed) +
                                            " labelled names not in the index skipped"
                                      : "")
                      << '\n';
            if (args->per_class) print_per_class(e);
            if (!args->plot.empty()) std::cout << "wrote " << args->plot << '\n';
            return kSuccess;
          }};
}

}  // namespace

std::vector<Command> add_retrieval_commands(CLI::App& app) {
  return {add_describe_command(app), add_generate_command(app), add_query_command(app),
          add_evaluate_command(app)};
}

}  // namespace morphex::cli

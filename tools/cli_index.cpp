// SPDX-License-Identifier: GPL-3.0-or-later
// The collection manager: `morphex index` (in one process, or across MPI ranks when started by
// mpirun or srun), `morphex ls` and `morphex rm`.
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <memory>
#include <set>

#include "cli_common.h"
#include "morphex/index.h"
#include "morphex/pipeline.h"
#include "morphex/retrieval_json.h"
#ifdef MORPHEX_HAVE_MPI
#include "morphex/index_mpi.h"
#endif

namespace morphex::cli {
namespace {

namespace mp = morphex::pipeline;
namespace fs = std::filesystem;

// How many processes an MPI launcher started, from the variables mpirun (Open MPI, MPICH's hydra)
// and Slurm's srun set; 0 when no launcher started this process.
int launched_processes() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "SLURM_STEP_NUM_TASKS"})
    if (const char* value = std::getenv(name)) return std::max(1, std::atoi(value));
  return std::getenv("PMIX_RANK") ? 1 : 0;
}

struct IndexArgs {
  std::vector<std::string> inputs, sets;
  std::string db, pipeline;
  std::optional<double> repair_budget;
  bool repair = true, retry_failed = false, quiet = false, json = false;
};

// A mesh's error as the user who gave no --pipeline reads it: without the location in the
// default pipeline ("pipeline[0] (read): ") that they never wrote.
std::string user_error(const IndexArgs& args, const std::string& error) {
  if (!args.pipeline.empty() || error.rfind("pipeline[", 0) != 0) return error;
  const std::size_t end = error.find("): ");
  return end == std::string::npos ? error : error.substr(end + 3);
}

// Settings as stored ("<pipeline JSON>|<variables>|descriptors <version>") in words: the
// pipeline's description or stages, its variables and the descriptors' version.
std::string readable_settings(const std::string& settings) {
  const std::size_t version = settings.rfind("|descriptors ");
  if (version == std::string::npos) return settings;
  const std::string rest = settings.substr(0, version);
  const std::size_t sets = rest.rfind('|');
  if (sets == std::string::npos) return settings;
  std::string out;
  try {
    const nlohmann::json document = mp::parse_document(rest.substr(0, sets), "settings");
    const nlohmann::json& stages = document.is_array() ? document : document.at("pipeline");
    std::string types;
    for (const auto& stage : stages)
      types += (types.empty() ? "" : ", ") + stage.value("type", "?");
    out = (document.is_object() && document.contains("description")
               ? document["description"].get<std::string>() + " ("
               : std::string("pipeline (")) +
          types + ")";
  } catch (const std::exception&) {
    out = "pipeline (unreadable)";
  }
  std::string variables = rest.substr(sets + 1);
  if (!variables.empty() && variables.back() == ';') variables.pop_back();
  return out + (variables.empty() ? "" : "; variables " + variables) + "; descriptors version " +
         settings.substr(version + 13);
}

std::optional<IndexPipeline> index_pipeline(const IndexArgs& args) {
  try {
    std::optional<nlohmann::json> document;
    if (!args.pipeline.empty()) document = mp::load_document(args.pipeline);
    return make_index_pipeline(document ? &*document : nullptr, args.pipeline,
                               mp::parse_assignments(args.sets), args.repair, args.repair_budget);
  } catch (const mp::PipelineError& e) {
    for (const auto& p : e.problems())
      print_error(p.location.rfind("--set", 0) == 0 || args.pipeline.empty()
                      ? p.text()
                      : args.pipeline + ": " + p.text());
    return std::nullopt;
  }
}

int print_summary(const IndexArgs& args, const IndexSummary& summary) {
  const std::size_t failed = summary.errors.size();
  const double per_minute =
      summary.seconds > 0 ? 60.0 * double(summary.indexed + failed) / summary.seconds : 0;
  if (args.json) {
    nlohmann::json j = summary;
    j["db"] = args.db;
    for (nlohmann::json& e : j["errors"])
      e["error"] = user_error(args, e["error"].get<std::string>());
    std::cout << j.dump() << std::endl;
  } else {
    std::cout << args.db << ": indexed " << summary.indexed << " meshes (" << summary.skipped
              << " already up to date, " << failed << " failed) in " << std::setprecision(3)
              << summary.seconds << " s";
    if (summary.indexed + failed > 0) std::cout << ", " << per_minute << " meshes/min";
    if (summary.processes > 1) std::cout << ", " << summary.processes << " processes";
    std::cout << '\n';
    if (summary.skipped_failed > 0)
      std::cout << summary.skipped_failed
                << " meshes failed before with the same content and settings and were skipped "
                   "(--retry-failed describes them again; `morphex ls --failed` lists them)\n";
  }
  return failed == 0 ? kSuccess : kFailed;
}

// Runs the index in this process, or as one rank of an MPI job (only rank 0 opens the index,
// draws progress and prints the summary).
int run_index(const IndexArgs& args, const IndexPipeline& pipeline, unsigned threads) {
  const int launched = launched_processes();
#ifndef MORPHEX_HAVE_MPI
  if (launched > 1) {
    print_error("started as one of " + std::to_string(launched) +
                " MPI processes, but this morphex was built without MPI (MORPHEX_MPI): each "
                "process would index the whole collection; run one process or rebuild with MPI");
    return kBadInput;
  }
#endif
  std::vector<IndexItem> items;
  for (const std::string& input : expand_inputs(args.inputs)) items.push_back(index_item(input));
  IndexOptions options;
  options.retry_failed = args.retry_failed;
  options.threads = threads;  // 0: the library's default (MPI ranks share their node's cores)
  ProgressDisplay bar("indexed", "meshes", !args.quiet);
  auto on_mesh = [&](const IndexItem& item, const std::string& error, const IndexProgress& p) {
    if (!error.empty()) print_error(item.path + ": " + user_error(args, error));
    if (p.total > 0 && !args.quiet) bar.update(p.done, p.total, p.failed);
  };
  options.on_stage = [&](const IndexProgress& p) {
    if (!args.quiet) bar.update(p.done, p.total, p.failed, "", p.running);
  };
#ifdef MORPHEX_HAVE_MPI
  if (launched > 0) {
    MpiSession session;
    if (session.size() < launched) {
      print_error("the launcher started " + std::to_string(launched) +
                  " processes but MPI sees one (with srun, pass --mpi=pmix or --mpi=pmi2)");
      return kBadInput;
    }
    if (session.size() == 1) {  // mpirun -n 1: a single process describes meshes in parallel
      IndexDb db(args.db);
      return print_summary(args, index_meshes(db, pipeline, items, on_mesh, options));
    }
    const IndexSummary summary =
        index_meshes_mpi(session, args.db, pipeline, items, on_mesh, options);
    return session.rank() == 0 ? print_summary(args, summary) : kSuccess;
  }
#endif
  IndexDb db(args.db);
  return print_summary(args, index_meshes(db, pipeline, items, on_mesh, options));
}

Command add_index_command(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "index",
      "Describe meshes into a SQLite retrieval index (across MPI ranks under mpirun/srun)");
  auto args = std::make_shared<IndexArgs>();
  cmd->add_option("INPUT", args->inputs,
                  "Meshes, folders (their meshes, all levels down) or quoted globs")
      ->required();
  cmd->add_flag("--repair,!--no-repair", args->repair,
                "Make meshes that are not valid solids into one before describing them (morphex "
                "solidify: soups, open surfaces, flipped, repeated or degenerate faces, cracks, "
                "overlapping parts); on by default, what was done recorded per mesh");
  cmd->add_option("--repair-budget", args->repair_budget,
                  "The repair's work budget per input face (morphex repair --budget; default "
                  "1000, 0: no bound): a mesh that would exceed it is recorded as failed")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--db", args->db, "Index file (SQLite), created if missing")->required();
  cmd->add_option("--pipeline", args->pipeline,
                  "Descriptor pipeline run on each ${input}; its last describe stage is stored "
                  "(default: read, then describe with default settings)");
  cmd->add_option("--set", args->sets, "Pipeline variable name=value (repeatable)");
  cmd->add_flag("--retry-failed", args->retry_failed,
                "Describe again meshes that failed before with the same content and settings");
  cmd->add_flag("-q,--quiet", args->quiet, "No progress on stderr (errors are still reported)");
  cmd->add_flag("--json", args->json, "The summary as one JSON object on stdout");
  return {cmd, [args, &app]() -> int {
            const std::optional<IndexPipeline> pipeline = index_pipeline(*args);
            if (!pipeline) return kBadInput;
            try {
              // The user's --threads, or 0 for the library's default.
              const unsigned threads =
                  app.count("--threads") > 0 ? app.get_option("--threads")->as<unsigned>() : 0;
              return run_index(*args, *pipeline, threads);
            } catch (const mp::PipelineError& e) {
              for (const auto& p : e.problems()) print_error(pipeline->name + ": " + p.text());
              return kBadInput;
            }
          }};
}

nlohmann::json entry_json(const IndexedMesh& m, bool with_descriptors) {
  nlohmann::json j = m;
  if (!with_descriptors) j.erase("descriptors");
  return j;
}

void print_entries(const std::vector<IndexedMesh>& entries) {
  std::cout << std::left << std::setw(24) << "name" << std::setw(8) << "status" << std::right
            << std::setw(9) << "faces" << std::setw(10) << "repaired" << std::setw(10) << "seconds"
            << "  " << std::left << std::setw(10) << "settings"
            << "path\n";
  std::set<std::string> settings;
  for (const IndexedMesh& m : entries) {
    settings.insert(m.settings);
    std::cout << std::left << std::setw(24) << m.name << std::setw(8) << m.status << std::right
              << std::setw(9) << m.faces << std::setw(10) << (m.repair.empty() ? "no" : "yes")
              << std::setw(10) << std::fixed << std::setprecision(2) << m.seconds
              << std::defaultfloat << "  " << std::left << std::setw(10)
              << text_hash(m.settings).substr(0, 8) << m.path << '\n';
    if (!m.error.empty()) std::cout << "    error: " << m.error << '\n';
  }
  for (const std::string& s : settings)
    std::cout << "settings " << text_hash(s).substr(0, 8) << ": " << readable_settings(s) << '\n';
}

Command add_ls_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("ls", "List the meshes of a retrieval index");
  struct Args {
    std::string db;
    bool json = false, failed = false, descriptors = false;
  };
  auto args = std::make_shared<Args>();
  cmd->add_option("--db", args->db, "Index file")->required()->check(CLI::ExistingFile);
  cmd->add_flag("--failed", args->failed, "Only the meshes that failed");
  cmd->add_flag("--json", args->json, "One JSON object per mesh, one per line");
  cmd->add_flag("--descriptors", args->descriptors, "With --json: the descriptor vectors too");
  return {cmd, [args]() -> int {
            IndexDb db(args->db, IndexAccess::ReadOnly);
            std::vector<IndexedMesh> entries =
                db.load(false, args->json && args->descriptors ? std::vector<std::string>{"*"}
                                                               : std::vector<std::string>{});
            if (args->failed)
              entries.erase(std::remove_if(entries.begin(), entries.end(),
                                           [](const IndexedMesh& m) { return m.status == "ok"; }),
                            entries.end());
            if (!args->json) {
              print_entries(entries);
              return kSuccess;
            }
            for (const IndexedMesh& m : entries)
              std::cout << entry_json(m, args->descriptors).dump() << '\n';
            return kSuccess;
          }};
}

Command add_rm_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("rm", "Remove meshes from a retrieval index");
  struct Args {
    std::string db;
    std::vector<std::string> keys;
  };
  auto args = std::make_shared<Args>();
  cmd->add_option("--db", args->db, "Index file")->required()->check(CLI::ExistingFile);
  cmd->add_option("MESH", args->keys, "Names or paths of indexed meshes")->required();
  return {cmd, [args]() -> int {
            IndexDb db(args->db);
            const std::size_t removed = remove_indexed(db, args->keys);  // all keys, or none
            std::cout << args->db << ": removed " << removed << " meshes\n";
            return kSuccess;
          }};
}

}  // namespace

std::vector<Command> add_index_commands(CLI::App& app) {
  return {add_index_command(app), add_ls_command(app), add_rm_command(app)};
}

}  // namespace morphex::cli

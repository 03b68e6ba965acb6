// SPDX-License-Identifier: GPL-3.0-or-later
// Indexing a collection through a descriptor pipeline, nearest-neighbour queries and evaluation.
#include "morphex/index.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>
#include <set>

#include <tbb/global_control.h>

#include "index_internal.h"
#include "morphex/internal/stopwatch.h"
#include "morphex/knn.h"

namespace morphex {

namespace mp = morphex::pipeline;
namespace fs = std::filesystem;

const char* const kDefaultIndexPipeline =
    R"({"pipeline": [{"type": "read", "path": "${input}"}, {"type": "describe"}]})";

namespace {

// The document with a solidify stage after every read (morphex/solidify.h: a valid solid passes
// unchanged, anything else becomes one): it takes the read's tag (the read gets
// "<tag>.as-read"), so that every stage that took the read's mesh takes the solid.
nlohmann::json with_repairs(const nlohmann::json& document, std::optional<double> budget) {
  nlohmann::json out = document;
  nlohmann::json& stages = out.is_array() ? out : out["pipeline"];
  nlohmann::json rewritten = nlohmann::json::array();
  for (const nlohmann::json& stage : stages) {
    if (!stage.is_object() || stage.value("type", "") != "read") {
      rewritten.push_back(stage);
      continue;
    }
    nlohmann::json read = stage, repair = {{"type", "solidify"}};
    if (budget) repair["budget"] = *budget;
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

// What the repair or solidify stage of a finished input changed, as JSON text (empty when
// nothing): recorded per mesh in the index.
std::string repair_of(const mp::InputReport& input) {
  for (const mp::StageReport& s : input.stages)
    for (const char* kind : {"repair", "solidify"})
      if (s.type == kind && s.extra.contains(kind) && s.extra[kind].value("changed", false))
        return s.extra[kind].dump();
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

// The stage types an index pipeline may hold: they read the mesh being described and compute
// from it. `write` is not one (a crafted index would write wherever its pipeline says, on every
// query), nor is a read of another file or a structuring element read from a file.
const std::set<std::string>& descriptor_stage_types() {
  static const std::set<std::string> types = {
      "read",      "repair", "solidify",     "describe",   "check",    "simplify",
      "translate", "scale",  "rotate",       "dilate",     "erode",    "open",
      "close",     "union",  "intersection", "difference", "minkowski"};
  return types;
}

// Whether a structuring element option (text "shape:..." or {"shape": ...}) names a literal
// shape other than "mesh" (which reads a file).
bool computed_element(const nlohmann::json& se) {
  std::string shape;
  if (se.is_string())
    shape = se.get<std::string>().substr(0, se.get<std::string>().find(':'));
  else if (se.is_object() && se.contains("shape") && se["shape"].is_string())
    shape = se["shape"].get<std::string>();
  return !shape.empty() && shape != "mesh" && shape.find('$') == std::string::npos;
}

}  // namespace

void require_descriptor_pipeline(const nlohmann::json& document) {
  const nlohmann::json& stages =
      document.is_object() && document.contains("pipeline") ? document["pipeline"] : document;
  std::vector<mp::Problem> problems;
  if (!stages.is_array())
    problems.push_back({"pipeline", "expected an array of stages"});
  else
    for (std::size_t i = 0; i < stages.size(); ++i) {
      const nlohmann::json& stage = stages[i];
      const std::string at = "pipeline[" + std::to_string(i) + "]";
      const std::string type =
          stage.is_object() && stage.contains("type") && stage["type"].is_string()
              ? stage["type"].get<std::string>()
              : "";
      if (!descriptor_stage_types().count(type)) {
        problems.push_back({at,
                            "an index pipeline may hold only stages that compute from the "
                            "mesh being described (read of ${input}, repair, solidify, describe, "
                            "check, operations); '" +
                                type + "' is not one"});
        continue;
      }
      if (type == "read" && stage.value("path", nlohmann::json()) != "${input}")
        problems.push_back({at + ".path", "an index pipeline reads only \"${input}\""});
      if (stage.contains("se") && !computed_element(stage["se"]))
        problems.push_back({at + ".se",
                            "an index pipeline takes only structuring elements of "
                            "a literal shape other than mesh (no file is read)"});
    }
  if (!problems.empty()) throw mp::PipelineError(problems);
}

std::string IndexPipeline::settings() const {
  std::string sets;
  for (const auto& [name, value] : variables) sets += name + "=" + value + ";";
  return document.dump() + "|" + sets + "|descriptors " + descriptor_version();
}

IndexPipeline make_index_pipeline(const nlohmann::json* document, const std::string& name,
                                  mp::Variables variables, bool repair,
                                  std::optional<double> repair_budget) {
  IndexPipeline out;
  out.name = document ? name : "default";
  out.document = document ? *document : mp::parse_document(kDefaultIndexPipeline, "default");
  require_descriptor_pipeline(out.document);
  if (repair) out.document = with_repairs(out.document, repair_budget);
  mp::check_assignments_used(out.document, variables);
  out.variables = std::move(variables);
  const mp::Pipeline p = mp::validate(out.document, out.name, out.variables, {"input", "stem"});
  if (std::none_of(p.stages.begin(), p.stages.end(),
                   [](const mp::Stage& s) { return s.type == "describe"; }))
    throw mp::PipelineError(
        std::vector<mp::Problem>{{"pipeline", "an index pipeline needs a describe stage"}});
  return out;
}

IndexItem index_item(const std::string& file) {
  return {file, fs::absolute(file).lexically_normal().string(), fs::path(file).stem().string()};
}

namespace detail {

IndexRun::IndexRun(IndexDb& db, const IndexPipeline& pipeline, const IndexOptions& options,
                   const IndexCallback& on_mesh)
    : db_(db),
      options_(options),
      on_mesh_(on_mesh),
      settings_(pipeline.settings()),
      document_(pipeline.document.dump()),
      sets_(nlohmann::json(pipeline.variables).dump()) {}

// Descriptors made under other settings do not compare (a mesh's distance to its own copy would
// not be 0): a run may change the index's settings only when it describes again every mesh
// described under others. Checked before anything is written.
void IndexRun::require_one_setting(const std::vector<IndexItem>& items) {
  std::set<std::string> described;
  for (const IndexItem& item : items) described.insert(item.path);
  std::size_t others = 0;
  std::string first;
  for (const IndexedMesh& m : db_.load(true, {}))
    if (m.settings != settings_ && !described.count(m.path) && others++ == 0) first = m.path;
  if (others > 0)
    throw InputError(db_.path(),
                     std::to_string(others) + " indexed meshes (first " + first +
                         ") were described under other settings (another pipeline, --set or "
                         "descriptor version); their descriptors would not compare with this "
                         "run's: index them too, remove them (morphex rm), or use another index");
  db_.set_meta("pipeline", document_);
  db_.set_meta("sets", sets_);
}

void IndexRun::report(const IndexItem& item, const std::string& error) {
  if (!error.empty()) {
    summary_.errors.emplace_back(item.path, error);
    ++progress_.failed;
  }
  if (on_mesh_) on_mesh_(item, error, progress_);
}

std::vector<PendingMesh> IndexRun::plan(const std::vector<IndexItem>& items) {
  require_one_setting(items);
  std::vector<PendingMesh> pending;
  std::set<std::string> seen;
  for (const IndexItem& item : items) {
    if (!seen.insert(item.path).second) continue;  // named twice (a glob and a path)
    PendingMesh p{item, "", 0};
    try {
      p.hash = content_hash(item.file);
      p.bytes = fs::file_size(item.file);
    } catch (const std::exception&) {
      IndexedMesh failed;
      failed.name = item.name;
      failed.path = item.path;
      failed.settings = settings_;
      failed.status = "failed";
      failed.error = "cannot read the file";
      db_.store(failed);
      report(item, failed.error);
      continue;
    }
    const std::string status = db_.status(item.path, p.hash, settings_);
    if (status == "ok")
      ++summary_.skipped;
    else if (status == "failed" && !options_.retry_failed)
      ++summary_.skipped_failed;
    else
      pending.push_back(std::move(p));
  }
  // Largest first: a huge mesh started last would hold the whole run back.
  std::stable_sort(pending.begin(), pending.end(),
                   [](const PendingMesh& a, const PendingMesh& b) { return a.bytes > b.bytes; });
  progress_.total = pending.size();
  return pending;
}

void IndexRun::stage_done(double meshes) {
  if (!options_.on_stage) return;
  std::lock_guard<std::mutex> lock(mutex_);
  IndexProgress p = progress_;
  p.running = std::max(0.0, meshes - double(p.done));
  options_.on_stage(p);
}

void IndexRun::commit(const IndexedMesh& mesh) {
  std::lock_guard<std::mutex> lock(mutex_);
  db_.store(mesh);
  ++progress_.done;
  if (mesh.status == "ok") ++summary_.indexed;
  report({mesh.path, mesh.path, mesh.name}, mesh.error);
}

IndexSummary IndexRun::finish() {
  return summary_;
}

IndexedMesh described_from_report(const mp::InputReport& r, const PendingMesh& p,
                                  const std::string& settings) {
  IndexedMesh d;
  d.name = p.item.name;
  d.path = p.item.path;
  d.hash = p.hash;
  d.settings = settings;
  d.status = r.ok ? "ok" : "failed";
  d.error = r.error;
  if (r.ok) d.descriptors = descriptors_of(r);
  for (const auto& [kind, v] : d.descriptors)
    if (!std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); })) {
      // Stored, it would make the index refuse every query (NaN ranks first).
      d.status = "failed";
      d.error = "the '" + kind + "' descriptor is not finite";
      d.descriptors.clear();
      break;
    }
  d.repair = repair_of(r);
  d.faces = r.stages.empty() ? 0 : r.stages.front().faces;
  d.volume = r.stages.empty() ? "" : r.stages.front().volume;
  d.seconds = r.seconds;
  return d;
}

IndexedMesh describe_mesh(const IndexPipeline& pipeline, const PendingMesh& mesh,
                          const std::string& settings) {
  mp::RunOptions options;
  options.variables = pipeline.variables;
  options.inputs = {mesh.item.file};
  const mp::RunReport r = mp::run(pipeline.document, pipeline.name, options);
  return described_from_report(r.inputs.front(), mesh, settings);
}

}  // namespace detail

IndexSummary index_meshes(IndexDb& db, const IndexPipeline& pipeline,
                          const std::vector<IndexItem>& items, const IndexCallback& on_mesh,
                          const IndexOptions& options) {
  std::optional<tbb::global_control> limit;
  if (options.threads > 0)
    limit.emplace(tbb::global_control::max_allowed_parallelism, options.threads);
  const Stopwatch clock;
  detail::IndexRun run(db, pipeline, options, on_mesh);
  const std::vector<detail::PendingMesh> pending = run.plan(items);
  mp::RunOptions run_options;
  run_options.variables = pipeline.variables;
  std::map<std::string, const detail::PendingMesh*> by_file;
  for (const detail::PendingMesh& p : pending) {
    by_file[p.item.file] = &p;
    run_options.inputs.push_back(p.item.file);
  }
  // The inputs run in parallel; each mesh is committed as soon as its pipeline finishes.
  run_options.on_input_done = [&](const mp::InputReport& r) {
    run.commit(detail::described_from_report(r, *by_file.at(r.input), run.settings()));
  };
  run_options.on_progress = [&](double done, std::size_t total, const std::string&,
                                const std::string&) {
    run.stage_done(done * double(pending.size()) / double(total));
  };
  if (!pending.empty()) mp::run(pipeline.document, pipeline.name, run_options);
  IndexSummary summary = run.finish();
  summary.seconds = clock.seconds();
  return summary;
}

namespace {

// The recorded paths that `key` names, or "" and the problem in `problem`.
std::vector<std::string> resolve_entry(const std::vector<IndexedMesh>& entries,
                                       const std::string& key, std::string& problem) {
  const std::string absolute = fs::absolute(key).lexically_normal().string();
  std::vector<std::string> by_path, by_name;
  for (const IndexedMesh& m : entries) {
    if (m.path == key || m.path == absolute) by_path.push_back(m.path);
    if (m.name == key) by_name.push_back(m.path);
  }
  if (!by_path.empty()) return by_path;
  if (by_name.size() == 1) return by_name;
  if (by_name.empty())
    problem = key + ": no indexed mesh has this name or path";
  else
    problem = key + ": " + std::to_string(by_name.size()) +
              " indexed meshes have this name (give the path): " + by_name[0] + ", " + by_name[1] +
              (by_name.size() > 2 ? ", ..." : "");
  return {};
}

// The one setting every mesh of `meshes` was described under ("" when there is none); meshes
// described under several are refused rather than compared.
std::string one_setting(const IndexDb& db, const std::vector<IndexedMesh>& meshes) {
  std::set<std::string> settings;
  for (const IndexedMesh& m : meshes) settings.insert(m.settings);
  if (settings.size() > 1)
    throw InputError(db.path(), "its meshes were described under " +
                                    std::to_string(settings.size()) +
                                    " different settings, whose descriptors do not compare: "
                                    "index them again under one (morphex ls shows the settings)");
  return settings.empty() ? "" : *settings.begin();
}

// The pipeline stored in the index, checked like any untrusted document: only descriptor
// stages may run from it.
IndexPipeline stored_pipeline(IndexDb& db) {
  IndexPipeline p;
  p.name = db.path();
  try {
    p.document = nlohmann::json::parse(db.meta("pipeline").value_or(kDefaultIndexPipeline));
    if (const auto sets = db.meta("sets"))
      p.variables = nlohmann::json::parse(*sets).get<mp::Variables>();
    require_descriptor_pipeline(p.document);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(db.path(), std::string("the index's stored pipeline is damaged: ") + e.what());
  } catch (const mp::PipelineError& e) {
    throw InputError(db.path(), std::string("the index's stored pipeline is refused: ") + e.what());
  }
  return p;
}

}  // namespace

std::size_t remove_indexed(IndexDb& db, const std::vector<std::string>& keys) {
  const std::vector<IndexedMesh> entries = db.load(false, {});
  std::set<std::string> paths;
  std::string problems;
  for (const std::string& key : keys) {
    std::string problem;
    for (const std::string& p : resolve_entry(entries, key, problem)) paths.insert(p);
    if (!problem.empty()) problems += (problems.empty() ? "" : "; ") + problem;
  }
  if (!problems.empty()) throw InputError(db.path(), problems);
  for (const std::string& p : paths) db.remove(p);
  return paths.size();
}

namespace {

// Checks the index's meshes against the stored pipeline: a query file is described by that
// pipeline, so its vector compares only with meshes described under the same settings.
void require_stored_settings(const IndexDb& db, const std::string& setting,
                             const IndexPipeline& stored) {
  if (!setting.empty() && setting != stored.settings())
    throw InputError(db.path(),
                     "its meshes were described under other settings than its "
                     "stored pipeline gives today (another descriptor version): "
                     "index them again");
}

// The k meshes of `meshes` nearest to `query` by `kind`, leaving out the mesh with id `exclude`.
std::vector<Neighbour> rank_meshes(const std::vector<IndexedMesh>& meshes,
                                   const std::vector<double>& query, std::size_t k,
                                   const std::string& kind, Metric metric, long long exclude) {
  // One contiguous matrix of the stored vectors, in the order of `meshes` (by name), so that the
  // scan breaks ties by name.
  DescriptorMatrix matrix(query.size());
  std::vector<const IndexedMesh*> rows;
  std::size_t exclude_row = DescriptorMatrix::kNone;
  for (const IndexedMesh& m : meshes) {
    const auto it = m.descriptors.find(kind);
    if (it == m.descriptors.end()) continue;
    if (m.id == exclude) exclude_row = rows.size();
    matrix.add(it->second);
    rows.push_back(&m);
  }
  std::vector<Neighbour> ranked;
  for (const Match& match : matrix.nearest(query, k, metric, exclude_row))
    ranked.push_back(
        {rows[match.row]->name, rows[match.row]->path, match.distance, rows[match.row]->id});
  return ranked;
}

}  // namespace

IndexPipeline query_pipeline(IndexDb& db) {
  const IndexPipeline pipeline = stored_pipeline(db);
  require_stored_settings(db, one_setting(db, db.load(true, {})), pipeline);
  return pipeline;
}

std::map<std::string, std::vector<double>> describe_query(const IndexPipeline& pipeline,
                                                          const std::string& file) {
  mp::RunOptions options;
  options.inputs = {file};
  options.variables = pipeline.variables;
  const mp::RunReport r = mp::run(pipeline.document, pipeline.name, options);
  if (!r.ok()) throw InputError(file, r.inputs.front().error);
  return descriptors_of(r.inputs.front());
}

std::vector<Neighbour> rank_index(IndexDb& db, const std::vector<double>& query, std::size_t k,
                                  const std::string& kind, Metric metric, long long exclude) {
  const std::vector<IndexedMesh> meshes = db.load(true, {kind});
  one_setting(db, meshes);
  return rank_meshes(meshes, query, k, kind, metric, exclude);
}

std::vector<Neighbour> query_index(IndexDb& db, const std::string& target, std::size_t k,
                                   const std::string& kind, Metric metric, bool by_name) {
  const std::vector<IndexedMesh> meshes = db.load(true, {kind});
  const std::string setting = one_setting(db, meshes);
  // The stored pipeline is checked on every query, also one that only uses stored vectors: an
  // index whose pipeline morphex would not run is not one it made (index files are untrusted).
  const IndexPipeline pipeline = stored_pipeline(db);
  std::vector<double> query;
  long long exclude = -1;
  // A file the index recorded (by the absolute path index_item gives it) is an indexed mesh, as
  // its name is: both use the stored vector and leave the mesh out of its own neighbours.
  const bool file = fs::exists(target);
  const std::string absolute = fs::absolute(target).lexically_normal().string();
  const auto stored = std::find_if(meshes.begin(), meshes.end(), [&](const IndexedMesh& m) {
    return (!file && m.name == target) || m.path == target || m.path == absolute;
  });
  if (by_name && stored != meshes.end()) {
    if (!stored->descriptors.count(kind))
      throw InputError(db.path(), stored->name + " has no '" + kind +
                                      "' descriptor (indexed by another version of morphex: "
                                      "index it again)");
    query = stored->descriptors.at(kind);
    exclude = stored->id;
  } else {
    if (!fs::exists(target))
      throw InputError(target, by_name ? "neither a mesh file nor the name of an indexed mesh"
                                       : "cannot open file: no such file");
    // Described as the index's meshes were: its pipeline and variables.
    require_stored_settings(db, setting, pipeline);
    const auto descriptors = describe_query(pipeline, target);
    if (!descriptors.count(kind))
      throw InputError(target, "the index's pipeline gives no '" + kind + "' descriptor");
    query = descriptors.at(kind);
  }
  return rank_meshes(meshes, query, k, kind, metric, exclude);
}

IndexEvaluation evaluate_index(IndexDb& db, const std::map<std::string, std::string>& labels,
                               Metric metric) {
  IndexEvaluation out;
  std::vector<IndexedMesh> meshes;
  for (IndexedMesh& m : db.load())
    if (labels.count(m.name))
      meshes.push_back(std::move(m));
    else
      ++out.unlabelled;
  out.models = meshes.size();
  one_setting(db, meshes);
  std::vector<std::string> names, classes;
  for (const IndexedMesh& m : meshes) {
    names.push_back(m.name);
    classes.push_back(labels.at(m.name));
  }
  for (const std::string& kind : descriptor_kinds()) {
    if (std::any_of(meshes.begin(), meshes.end(),
                    [&](const IndexedMesh& m) { return !m.descriptors.count(kind); }))
      continue;
    std::vector<std::vector<double>> d(meshes.size(), std::vector<double>(meshes.size()));
    for (std::size_t a = 0; a < meshes.size(); ++a)
      for (std::size_t b = 0; b < meshes.size(); ++b)
        d[a][b] = distance(meshes[a].descriptors.at(kind), meshes[b].descriptors.at(kind), metric);
    const std::vector<QueryScores> queries = score_queries(names, classes, d);
    out.scores.emplace_back(kind, mean_scores(queries));
    out.per_class.emplace_back(kind, class_scores(queries, classes));
    out.precision_recall.emplace_back(kind, precision_recall(queries));
  }
  return out;
}

}  // namespace morphex

// SPDX-License-Identifier: GPL-3.0-or-later
// Pipeline execution: inputs in parallel, each input's stage graph in waves of independent stages,
// exact meshes passed in memory, a per-stage report, and failures kept to the input they hit.
#include <tbb/parallel_for.h>
#include <tbb/parallel_for_each.h>

#include <unistd.h>
#include <algorithm>
#include <chrono>
#include <filesystem>
#include <map>
#include <mutex>
#include <optional>
#include <set>

#include "morphex/internal/stopwatch.h"
#include "morphex/pipeline.h"

namespace morphex::pipeline {
namespace {

// Counts finished stages over the whole run, plus the finished share of the stages running, and
// passes them to the caller's callback.
class Progress {
 public:
  Progress(const RunOptions& options, std::size_t total) : options_(options), total_(total) {}
  void stage_advanced(const std::string& input, const Stage& stage, double share) {
    if (!options_.on_progress) return;
    std::lock_guard<std::mutex> lock(mutex_);
    running_[{input, stage.index}] = std::clamp(share, 0.0, 1.0);
    report(input, stage);
  }
  void stage_done(const std::string& input, const Stage& stage) {
    if (!options_.on_progress) return;
    std::lock_guard<std::mutex> lock(mutex_);
    running_.erase({input, stage.index});
    ++done_;
    report(input, stage);
  }

 private:
  void report(const std::string& input, const Stage& stage) {
    double done = double(done_);
    for (const auto& [key, share] : running_) done += share;
    options_.on_progress(done, total_, input, stage.type);
  }
  const RunOptions& options_;
  std::size_t total_, done_ = 0;
  std::map<std::pair<std::string, std::size_t>, double> running_;
  std::mutex mutex_;
};

InputReport run_one(const Pipeline& pipeline, const std::string& input, Progress& progress) {
  const Stopwatch start;
  InputReport report;
  report.input = input;
  const std::size_t n = pipeline.stages.size();
  std::vector<std::optional<StageValue>> results(n);
  std::vector<StageReport> stage_reports(n);
  std::vector<char> done(n, 0);
  std::mutex failure_mutex;
  std::size_t remaining = n;
  while (remaining > 0 && report.ok) {
    std::vector<std::size_t> ready;
    for (std::size_t s : pipeline.order) {
      if (done[s]) continue;
      const auto& inputs = pipeline.stages[s].inputs;
      if (std::all_of(inputs.begin(), inputs.end(), [&](std::size_t i) { return done[i] != 0; }))
        ready.push_back(s);
    }
    tbb::parallel_for_each(ready.begin(), ready.end(), [&](std::size_t s) {
      const Stage& stage = pipeline.stages[s];
      StageContext context{stage, {}, nlohmann::json::object(), [&](double share) {
                             progress.stage_advanced(input, stage, share);
                           }};
      for (std::size_t i : stage.inputs) context.inputs.push_back(&*results[i]);
      const Stopwatch stage_start;
      try {
        results[s] = stage.info->run(context);
      } catch (const std::exception& e) {
        std::lock_guard<std::mutex> lock(failure_mutex);
        if (report.ok) {
          report.ok = false;
          report.error = "pipeline[" + std::to_string(s) + "] (" + stage.type + "): " + e.what();
          report.failed_stage = s;
          report.stage_error = e.what();
        }
        return;
      }
      StageReport& r = stage_reports[s];
      r.seconds = stage_start.seconds();
      r.index = s;
      r.type = stage.type;
      r.tag = stage.tag;
      const Mesh& mesh = results[s]->index() == 0 ? std::get<Solid>(*results[s]).mesh()
                                                  : std::get<Mesh>(*results[s]);
      r.faces = mesh.num_triangles();
      r.vertices = mesh.num_vertices();
      const FT volume = signed_volume(mesh);
      r.volume = to_rational_string(volume);
      r.volume_approx = CGAL::to_double(volume);
      r.extra = std::move(context.extra);
      progress.stage_done(input, stage);
    });
    for (std::size_t s : ready) {
      if (!results[s]) continue;
      done[s] = 1;
      --remaining;
    }
  }
  for (std::size_t s = 0; s < n; ++s)
    if (done[s]) report.stages.push_back(std::move(stage_reports[s]));
  report.seconds = start.seconds();
  return report;
}

std::string stem_of(const std::string& path) {
  return std::filesystem::path(path).stem().string();
}

// The stage index of a location "pipeline[N]...".
std::size_t stage_of(const FileUse& use) {
  return std::stoul(use.location.substr(use.location.find('[') + 1));
}

// A file as the checks compare it: through links, relative to the working folder.
std::string file_key(const std::string& path) {
  std::error_code error;
  const auto canonical = std::filesystem::weakly_canonical(path, error);
  return error ? path : canonical.string();
}

// What validating each input's pipeline alone cannot see: one input's write replacing a file
// another input reads, two inputs writing one file (results lost), and the caller's own outputs
// (--report) among the pipeline's files. Keyed by canonical path: linear in the inputs.
void check_files_across(const std::vector<Pipeline>& pipelines,
                        const std::vector<std::string>& inputs,
                        const std::vector<std::pair<std::string, std::string>>& caller_writes,
                        std::vector<Problem>& problems) {
  struct Use {
    std::size_t input;
    FileUse use;
  };
  std::map<std::string, Use> reads, writes;
  for (std::size_t i = 0; i < pipelines.size(); ++i)
    for (const FileUse& r : files_read(pipelines[i])) reads.emplace(file_key(r.path), Use{i, r});
  const bool several = pipelines.size() > 1;
  std::set<std::string> seen;
  const auto add = [&](const std::string& location, const std::string& message) {
    if (seen.insert(location + message).second) problems.push_back({location, message});
  };
  // A write whose path every input shares does not depend on the input at all: said once.
  std::set<std::string> fixed;
  const bool one_stem = std::all_of(inputs.begin(), inputs.end(), [&](const std::string& input) {
    return stem_of(input) == stem_of(inputs[0]);
  });
  if (several && !one_stem)
    for (const FileUse& w : files_written(pipelines[0]))
      if (std::all_of(pipelines.begin() + 1, pipelines.end(), [&](const Pipeline& p) {
            const std::vector<FileUse> others = files_written(p);
            return std::any_of(others.begin(), others.end(), [&](const FileUse& o) {
              return o.location == w.location && o.path == w.path;
            });
          })) {
        fixed.insert(w.location);
        add(w.location,
            "every input would write the same file " + w.path + " (put ${stem} in the path)");
      }
  for (std::size_t i = 0; i < pipelines.size(); ++i)
    for (const FileUse& w : files_written(pipelines[i])) {
      const std::string key = file_key(w.path);
      if (const auto r = reads.find(key); r != reads.end() && r->second.input != i)
        add(w.location, inputs[i] + " would overwrite " + r->second.use.what + " for " +
                            inputs[r->second.input] + " (" + w.path + ")");
      const auto [first, inserted] = writes.emplace(key, Use{i, w});
      if (!inserted && first->second.input != i && !fixed.count(w.location))
        add(w.location, inputs[first->second.input] + " and " + inputs[i] + " would both write " +
                            w.path +
                            " (their names are the same: put more of the path in the output, "
                            "or rename one)");
    }
  // Write stages make their folders: one that cannot be made is known now, not after the work.
  std::set<std::string> folders;
  for (const auto& [key, w] : writes)
    if (folders.insert(std::filesystem::path(key).parent_path().string()).second)
      if (const std::string problem = folder_problem(w.use.path); !problem.empty())
        add(w.use.location,
            problem + " (stage " + pipelines[w.input].stages[stage_of(w.use)].tag + ")");
  for (const auto& [location, path] : caller_writes) {
    const std::string key = file_key(path);
    if (const auto r = reads.find(key); r != reads.end())
      add(location, "refusing to overwrite " + r->second.use.what +
                        (several ? " for " + inputs[r->second.input] : "") + " (" + path + ")");
    else if (const auto w = writes.find(key); w != writes.end())
      add(location, "refusing to overwrite " + w->second.use.what + " (" + path + ")");
  }
}

}  // namespace

// Why the folders of `path` cannot be created or written in ("" when they can): the nearest
// ancestor that exists must be a folder this process may write in.
std::string folder_problem(const std::string& path) {
  std::error_code error;
  const std::filesystem::path parent = std::filesystem::absolute(path, error).parent_path();
  std::filesystem::path existing = parent;
  while (!existing.empty() && !std::filesystem::exists(existing, error) &&
         existing != existing.root_path())
    existing = existing.parent_path();
  if (!std::filesystem::is_directory(existing, error))
    return "cannot create the folder " + parent.string() + ": " + existing.string() +
           " is not a folder";
  if (access(existing.c_str(), W_OK | X_OK) != 0)
    return (existing == parent ? "cannot write in the folder " : "cannot create the folder ") +
           parent.string() + ": no permission to write in " + existing.string();
  return "";
}

bool RunReport::ok() const {
  return std::all_of(inputs.begin(), inputs.end(), [](const InputReport& r) { return r.ok; });
}

nlohmann::json RunReport::to_json() const {
  nlohmann::json out = {{"ok", ok()}, {"seconds", seconds}, {"inputs", nlohmann::json::array()}};
  for (const InputReport& input : inputs) {
    nlohmann::json j = {{"input", input.input},
                        {"name", input.input.empty() ? "" : stem_of(input.input)},
                        {"ok", input.ok},
                        {"seconds", input.seconds},
                        {"stages", nlohmann::json::array()}};
    if (!input.ok) j["error"] = input.error;
    for (const StageReport& s : input.stages) {
      nlohmann::json stage = {{"index", s.index},   {"type", s.type},
                              {"tag", s.tag},       {"seconds", s.seconds},
                              {"faces", s.faces},   {"vertices", s.vertices},
                              {"volume", s.volume}, {"volume_approx", s.volume_approx}};
      for (const auto& [key, value] : s.extra.items()) stage[key] = value;
      j["stages"].push_back(stage);
    }
    out["inputs"].push_back(j);
  }
  return out;
}

std::vector<Pipeline> prepare_run(const nlohmann::json& document, const std::string& name,
                                  const RunOptions& options, const StageRegistry& registry) {
  std::vector<Pipeline> pipelines;
  std::vector<Problem> problems;
  std::set<std::string> seen;
  const std::vector<std::string> inputs =
      options.inputs.empty() ? std::vector<std::string>{""} : options.inputs;
  for (const std::string& input : inputs) {
    Variables variables = options.variables;
    if (!input.empty()) {
      variables["input"] = input;
      variables["stem"] = stem_of(input);
    }
    try {
      pipelines.push_back(validate(document, name, variables, {}, registry));
    } catch (const PipelineError& e) {
      for (const Problem& p : e.problems())
        if (seen.insert(p.text()).second) problems.push_back(p);
    }
  }
  if (problems.empty()) check_files_across(pipelines, inputs, options.caller_writes, problems);
  if (!problems.empty()) throw PipelineError(std::move(problems));
  return pipelines;
}

RunReport run(const nlohmann::json& document, const std::string& name, const RunOptions& options,
              const StageRegistry& registry) {
  // Validate for every input before running any, so that a bad pipeline runs nothing.
  const std::vector<Pipeline> pipelines = prepare_run(document, name, options, registry);
  const std::vector<std::string> inputs =
      options.inputs.empty() ? std::vector<std::string>{""} : options.inputs;
  const Stopwatch start;
  Progress progress(options, pipelines.size() * pipelines[0].stages.size());
  RunReport report;
  report.inputs.resize(pipelines.size());
  std::mutex done_mutex;
  tbb::parallel_for(std::size_t(0), pipelines.size(), [&](std::size_t i) {
    report.inputs[i] = run_one(pipelines[i], options.inputs.empty() ? "" : inputs[i], progress);
    if (options.on_input_done) {
      std::lock_guard<std::mutex> lock(done_mutex);
      options.on_input_done(report.inputs[i]);
    }
  });
  report.seconds = start.seconds();
  return report;
}

}  // namespace morphex::pipeline

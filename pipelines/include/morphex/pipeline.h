// SPDX-License-Identifier: GPL-3.0-or-later
// JSON pipelines: a chain (or graph) of mesh filters described as
//   {"pipeline": [{"type": "read", "path": "${input}", "tag": "in"},
//                 {"type": "open", "se": {"shape": "ball", "r": 0.05, "level": 1}},
//                 {"type": "write", "path": "${out_dir}/${stem}-opened.off"}]}
// Each stage has a "type", an optional unique "tag", optional "inputs" (tags; by default the
// previous stage) and the options its type declares. "${name}" in any string is replaced by a
// variable: those given with --set, then the defaults in the document's optional "variables"
// object, plus "input" (the mesh being processed) and "stem" (its file name without extension) when
// the pipeline runs over input meshes. A variable used in a number option holds the number's text.
//
// A pipeline is validated completely before anything runs: every problem is reported at once with
// its JSON location ("pipeline[2].se.r: expected a positive number, got -1").
#pragma once

#include <nlohmann/json.hpp>

#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include "morphex/descriptors.h"
#include "morphex/mesh.h"
#include "morphex/repair.h"
#include "morphex/solid.h"
#include "morphex/solidify.h"
#include "morphex/structuring_element.h"

namespace morphex::pipeline {

// ---- the stage registry ----------------------------------------------------------------------

enum class OptionType {
  String,
  Path,
  Bool,
  Integer,
  Number,
  NumberList,
  Vector3,
  StructuringElement
};
const char* to_string(OptionType type);

struct OptionInfo {
  std::string name;
  OptionType type;
  std::string description;
  std::optional<nlohmann::json> default_value;  // none: the option is required
  std::optional<double> min, max;               // for Integer and Number
  std::vector<std::string> choices;             // for String, when restricted
  bool positive = false;                        // Number: strictly greater than zero
};

struct StageContext;  // what a running stage sees (run.cpp)
// What flows from a stage to the next: a valid solid (morphex/solid.h), or the mesh of a read not
// checked because every stage it feeds repairs it (Stage::unchecked).
using StageValue = std::variant<Solid, Mesh>;
using StageRunner = std::function<StageValue(StageContext&)>;

struct StageInfo {
  std::string type;
  std::string description;  // one line
  int inputs = 1;           // meshes consumed: 0 (read), 1, or 2 (Booleans, minkowski)
  std::vector<OptionInfo> options;
  StageRunner run;
};

// The stages, registered explicitly at first use (no static initialisers to lose at link time).
class StageRegistry {
 public:
  static const StageRegistry& builtin();
  void add(StageInfo stage);
  const StageInfo* find(const std::string& type) const;
  const std::vector<StageInfo>& stages() const { return stages_; }
  // The known type nearest to `type` by edit distance, for "did you mean" hints.
  std::string closest(const std::string& type) const;

 private:
  std::vector<StageInfo> stages_;
};

// ---- validation --------------------------------------------------------------------------------

struct Problem {
  std::string location;  // JSON path such as "pipeline[2].se.r", or "file:line:column"
  std::string message;
  std::string text() const { return location.empty() ? message : location + ": " + message; }
};

// Thrown by load/validate with every problem found (a morphex::InputError, morphex/error.h: where()
// and problem() are the first problem's location and message; what() lists them all).
class PipelineError : public InputError {
 public:
  explicit PipelineError(std::vector<Problem> problems);
  const std::vector<Problem>& problems() const { return problems_; }

 private:
  std::vector<Problem> problems_;
};

using Variables = std::map<std::string, std::string>;

// Variables from `name=value` assignments (the CLI's --set), later ones winning. A malformed one
// (no '=', or an empty or non-identifier name) throws PipelineError located at "--set <text>".
Variables parse_assignments(const std::vector<std::string>& assignments);
// Throws PipelineError for every assignment whose ${name} the document never uses (a mistyped
// --set would otherwise be ignored silently), located at "--set <name>".
void check_assignments_used(const nlohmann::json& document, const Variables& assignments);

struct Stage {
  std::size_t index;                // position in the "pipeline" array
  std::string type, tag;            // tag defaults to "<type>#<index>"
  std::vector<std::size_t> inputs;  // indices of the stages it reads
  nlohmann::json options;           // validated, defaults filled in, variables substituted
  const StageInfo* info = nullptr;
  // A read whose mesh goes only to repair stages: passed on as read, not refused when it is not
  // a valid solid (the repair says what it cannot repair).
  bool unchecked = false;
  // Structuring-element options, built once by validation (a mesh SE reads its file then).
  std::map<std::string, std::shared_ptr<const StructuringElement>> elements;
};

struct Pipeline {
  std::string name;                // file name, for messages
  nlohmann::json document;         // as written, variables not yet substituted
  std::vector<Stage> stages;       // in array order
  std::vector<std::size_t> order;  // a topological order of the stage graph
};

// Parses JSON text; malformed JSON is reported with line and column, and so is nesting deeper than
// kMaxJsonDepth brackets (refused before parsing: deeper documents would overflow the stack).
constexpr std::size_t kMaxJsonDepth = 64;
nlohmann::json parse_document(const std::string& text, const std::string& name);
// Reads and parses a pipeline file.
nlohmann::json load_document(const std::string& path);

// Validates a document with the given variables bound, filling defaults. Variables named in
// `deferred` (such as "input" while no input is known) may stay unsubstituted.
// Throws PipelineError listing every problem.
Pipeline validate(const nlohmann::json& document, const std::string& name,
                  const Variables& variables, const std::vector<std::string>& deferred = {},
                  const StageRegistry& registry = StageRegistry::builtin());

// The files a validated pipeline reads (read stages, mesh structuring elements) and writes, with
// their JSON location and what they are to the user ("the input read by pipeline[0]").
struct FileUse {
  std::string path, location, what;
};
std::vector<FileUse> files_read(const Pipeline& pipeline);
std::vector<FileUse> files_written(const Pipeline& pipeline);

// The settings of a validated describe stage: its options read through the table of
// morphex/descriptor_settings.h (a number given as text, from a ${variable}, is read as one).
// Throws InputError naming the setting when they do not go together (open_from > open_to).
DescriptorSettings descriptor_settings(const Stage& describe_stage);

// Why the folders of `path` cannot be created or written in ("" when they can): the nearest
// ancestor that exists must be a folder this process may write in.
std::string folder_problem(const std::string& path);

// ---- execution ---------------------------------------------------------------------------------

struct StageReport {
  std::size_t index;
  std::string type, tag;
  double seconds = 0;
  std::size_t faces = 0, vertices = 0;
  std::string volume;  // exact rational
  double volume_approx = 0;
  nlohmann::json extra;  // stage-specific facts (check results, written path)
};

struct InputReport {
  std::string input;  // the mesh path, or "" for a pipeline without inputs
  bool ok = true;
  std::string error;  // "pipeline[3] (difference): ..." when !ok
  // When !ok, the stage that failed and its error without the location, for callers that say it
  // in their own words (`morphex describe` runs a pipeline the user never wrote).
  std::size_t failed_stage = 0;
  std::string stage_error;
  double seconds = 0;
  std::vector<StageReport> stages;
};

struct RunOptions {
  Variables variables;              // from --set
  std::vector<std::string> inputs;  // each run binds ${input} and ${stem}
  // Called after every stage of every input, and as long stages (describe) advance (one call at a
  // time, from worker threads): how many stages of the whole run are done, counting the finished
  // share of stages still running, and which stage reported. The libraries never print; the
  // command line draws this as its progress bar.
  std::function<void(double done, std::size_t total, const std::string& input,
                     const std::string& stage)>
      on_progress;
  // Called once per input as soon as it finishes (from a worker thread, one call at a time), so a
  // caller can commit results before the whole run ends.
  std::function<void(const InputReport&)> on_input_done;
  // Files the caller will write besides the pipeline's own (the CLI's --report), as {location,
  // path}: refused before anything runs when one is a file the pipeline reads or writes.
  std::vector<std::pair<std::string, std::string>> caller_writes;
};

struct RunReport {
  std::vector<InputReport> inputs;
  double seconds = 0;
  bool ok() const;
  nlohmann::json to_json() const;
};

// Validates the pipeline for every input first (throws PipelineError before anything runs: also
// when a write of one input would replace a file another input reads, two inputs would write one
// file, or a caller_writes file is read or written by the pipeline), then
// runs the inputs in parallel, independent branches in parallel; a failing input is reported in
// its InputReport and the others go on.
RunReport run(const nlohmann::json& document, const std::string& name, const RunOptions& options,
              const StageRegistry& registry = StageRegistry::builtin());
// What run does before it runs anything: the pipeline of every input, validated, and the checks
// across inputs above; throws PipelineError. `morphex validate --input` refuses what run would.
std::vector<Pipeline> prepare_run(const nlohmann::json& document, const std::string& name,
                                  const RunOptions& options,
                                  const StageRegistry& registry = StageRegistry::builtin());

// What a stage sees while it runs.

struct StageContext {
  const Stage& stage;
  std::vector<const StageValue*> inputs;
  nlohmann::json extra;  // facts for the report
  // A long stage reports the finished share of its work (0 to 1) here, for progress displays.
  std::function<void(double share)> progress;
  const nlohmann::json& option(const std::string& name) const { return stage.options.at(name); }
  // Input i as a valid solid: every input is one, except an unchecked read's mesh, which
  // validation lets reach only repair and solidify stages (they read mesh(i)).
  const Solid& solid(std::size_t i) const { return std::get<Solid>(*inputs.at(i)); }
  // Input i as a mesh, whichever it is.
  const Mesh& mesh(std::size_t i) const {
    const StageValue& value = *inputs.at(i);
    return value.index() == 0 ? std::get<Solid>(value).mesh() : std::get<Mesh>(value);
  }
  const StructuringElement& element(const std::string& name) const {
    return *stage.elements.at(name);
  }
};

}  // namespace morphex::pipeline

// SPDX-License-Identifier: GPL-3.0-or-later
// `morphex run P.json [--set k=v ...] [--input MESH|GLOB ...] [--report FILE]`,
// `morphex validate P.json [--set k=v ...] [--input ...]` and `morphex stages [NAME]`.
#include <glob.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "cli_common.h"
#include "morphex/pipeline.h"
#include "morphex/structuring_element.h"

namespace morphex::cli {
namespace {

namespace mp = morphex::pipeline;

struct PipelineArgs {
  std::string file;
  std::vector<std::string> sets, inputs;
};

void add_pipeline_options(CLI::App* cmd, PipelineArgs& args) {
  cmd->add_option("PIPELINE", args.file, "Pipeline JSON file")->required();
  cmd->add_option("--set", args.sets, "Variable for ${name}, as name=value (repeatable)");
  cmd->add_option("--input", args.inputs,
                  "Meshes, folders (their meshes, all levels down) or quoted globs to run the "
                  "pipeline over, each bound to ${input} and ${stem}");
}

namespace fs = std::filesystem;

// What validation of the document alone cannot see: read stages whose file does not exist and
// write stages whose folder cannot be created. Paths still holding a ${variable} (deferred, such
// as ${input} without --input) are skipped: they are only known when the pipeline runs.
void check_files(const mp::Pipeline& pipeline) {
  std::vector<mp::Problem> problems;
  for (const mp::Stage& stage : pipeline.stages) {
    if (stage.type != "read" && stage.type != "write") continue;
    const std::string path = stage.options.value("path", "");
    if (path.empty() || path.find("${") != std::string::npos) continue;
    const std::string location = "pipeline[" + std::to_string(stage.index) + "].path";
    std::error_code error;
    if (stage.type == "read" && !fs::exists(path, error))
      problems.push_back({location, "no such file '" + path + "' (stage " + stage.tag + ")"});
    if (stage.type == "write")
      if (const std::string problem = mp::folder_problem(path); !problem.empty())
        problems.push_back({location, problem + " (stage " + stage.tag + ")"});
  }
  if (!problems.empty()) throw mp::PipelineError(problems);
}

void print_problems(const std::string& file, const mp::PipelineError& e) {
  for (const mp::Problem& p : e.problems())
    print_error(p.location.rfind(file, 0) == 0 ? p.text() : file + ": " + p.text());
}

void print_table(const mp::RunReport& report) {
  std::cout << std::left << std::setw(20) << "input" << std::setw(16) << "stage" << std::setw(12)
            << "type" << std::right << std::setw(9) << "faces" << std::setw(14) << "volume"
            << std::setw(10) << "seconds" << '\n';
  for (const mp::InputReport& input : report.inputs)
    for (const mp::StageReport& s : input.stages)
      std::cout << std::left << std::setw(20)
                << std::filesystem::path(input.input).stem().string().substr(0, 19) << std::setw(16)
                << s.tag.substr(0, 15) << std::setw(12) << s.type << std::right << std::setw(9)
                << s.faces << std::setw(14) << std::setprecision(6) << s.volume_approx
                << std::setw(10) << std::setprecision(3) << s.seconds << '\n';
}

Command add_run_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("run", "Run a JSON pipeline, once or over many input meshes");
  auto args = std::make_shared<PipelineArgs>();
  auto report_path = std::make_shared<std::string>();
  auto table = std::make_shared<bool>(false);
  add_pipeline_options(cmd, *args);
  cmd->add_option("--report", *report_path, "Per-stage timings and sizes as JSON (FILE or '-')");
  cmd->add_flag("--table", *table, "Print every stage's size, volume and time on stdout");
  return {cmd, [args, report_path, table]() -> int {
            mp::RunOptions options;
            try {
              options.variables = mp::parse_assignments(args->sets);
            } catch (const mp::PipelineError& e) {
              print_problems("", e);
              return kBadInput;
            }
            options.inputs = expand_inputs(args->inputs);
            if (!report_path->empty()) {
              if (!writes_safe({{*report_path, "--report"}}, {})) return kBadInput;
              options.caller_writes.push_back({"--report", *report_path});
            }
            // The stages of every input, on a terminal only (a log gets the summary line).
            ProgressDisplay display("ran", "stages", false);
            std::atomic<std::size_t> failed_inputs{0};
            options.on_input_done = [&](const mp::InputReport& r) { failed_inputs += !r.ok; };
            options.on_progress = [&](double done, std::size_t total, const std::string& input,
                                      const std::string& stage) {
              display.update(
                  std::size_t(done), total, failed_inputs,
                  (input.empty() ? "" : std::filesystem::path(input).filename().string() + ": ") +
                      stage,
                  done - std::floor(done));
            };
            mp::RunReport report;
            try {
              const nlohmann::json document = mp::load_document(args->file);
              mp::check_assignments_used(document, options.variables);
              report = mp::run(document, args->file, options);
            } catch (const mp::PipelineError& e) {
              print_problems(args->file, e);
              return kBadInput;
            }
            std::size_t failed = 0;
            for (const mp::InputReport& input : report.inputs)
              if (!input.ok) {
                ++failed;
                print_error((input.input.empty() ? args->file : input.input) + ": " + input.error);
              }
            if (!report_path->empty()) emit_json(report.to_json(), *report_path);
            if (*report_path != "-" && *table) print_table(report);
            if (*report_path != "-")
              std::cout << args->file << ": " << report.inputs.size() << " run"
                        << (report.inputs.size() == 1 ? "" : "s") << ", "
                        << report.inputs.size() - failed << " succeeded, " << failed << " failed, "
                        << std::setprecision(3) << report.seconds << " s\n";
            return failed == 0 ? kSuccess : kFailed;
          }};
}

Command add_validate_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("validate", "Check a pipeline without running it");
  auto args = std::make_shared<PipelineArgs>();
  add_pipeline_options(cmd, *args);
  return {
      cmd, [args]() -> int {
        mp::Variables variables;
        try {
          variables = mp::parse_assignments(args->sets);
        } catch (const mp::PipelineError& e) {
          print_problems("", e);
          return kBadInput;
        }
        const auto inputs = expand_inputs(args->inputs);
        try {
          const nlohmann::json document = mp::load_document(args->file);
          mp::check_assignments_used(document, variables);
          std::size_t stages = 0;
          if (inputs.empty()) {
            const mp::Pipeline pipeline =
                mp::validate(document, args->file, variables, {"input", "stem"});
            check_files(pipeline);
            stages = pipeline.stages.size();
          } else {
            mp::RunOptions options;
            options.variables = variables;
            options.inputs = inputs;
            for (const mp::Pipeline& pipeline : mp::prepare_run(document, args->file, options)) {
              check_files(pipeline);
              stages = pipeline.stages.size();
            }
          }
          std::cout << args->file << ": valid pipeline, " << stages << " stages\n";
        } catch (const mp::PipelineError& e) {
          print_problems(args->file, e);
          return kBadInput;
        }
        return kSuccess;
      }};
}

std::string describe_option(const mp::OptionInfo& o) {
  std::ostringstream out;
  out << "  " << std::left << std::setw(14) << o.name << std::setw(22) << mp::to_string(o.type)
      << (o.default_value ? "default " + o.default_value->dump() : std::string("required"));
  if (o.positive) out << ", > 0";
  if (o.min) out << ", min " << *o.min;
  if (o.max) out << ", max " << *o.max;
  if (!o.choices.empty()) {
    out << ", one of";
    for (const auto& c : o.choices) out << ' ' << c;
  }
  out << "\n      " << o.description << '\n';
  return out.str();
}

Command add_stages_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("stages", "List the pipeline stages, or show one stage's options");
  auto name = std::make_shared<std::string>();
  cmd->add_option("NAME", *name, "Stage type");
  return {cmd, [name]() -> int {
            const auto& registry = mp::StageRegistry::builtin();
            if (name->empty()) {
              for (const mp::StageInfo& s : registry.stages())
                std::cout << std::left << std::setw(14) << s.type << s.description << '\n';
              return kSuccess;
            }
            const mp::StageInfo* s = registry.find(*name);
            if (!s) {
              print_error("unknown stage '" + *name + "' (did you mean '" +
                          registry.closest(*name) + "'?)");
              return kBadInput;
            }
            std::cout << s->type << ": " << s->description << "\ninputs: " << s->inputs
                      << (s->inputs == 2 ? " (\"inputs\": [first, second])" : "")
                      << "\noptions:" << (s->options.empty() ? " none\n" : "\n");
            for (const mp::OptionInfo& o : s->options) std::cout << describe_option(o);
            if (std::any_of(s->options.begin(), s->options.end(), [](const mp::OptionInfo& o) {
                  return o.type == mp::OptionType::StructuringElement;
                })) {
              std::cout << "structuring element shapes:\n";
              for (const SeShapeInfo& shape : structuring_element_shapes()) {
                std::cout << "  " << shape.shape << ": " << shape.description << "\n";
                for (const SeParameterInfo& p : shape.parameters)
                  std::cout << "      " << std::left << std::setw(10) << p.key << std::setw(9)
                            << p.type
                            << (p.default_value.empty() ? "required" : "default " + p.default_value)
                            << "  " << p.description << '\n';
              }
            }
            return kSuccess;
          }};
}

}  // namespace

namespace {

bool is_mesh_file(const fs::path& path) {
  std::string extension = path.extension().string();
  for (char& c : extension) c = char(std::tolower(static_cast<unsigned char>(c)));
  for (const char* known : {".off", ".obj", ".stl", ".ply", ".3mf"})
    if (extension == known) return true;
  return false;
}

// The mesh files under a folder, all levels down, in name order.
std::vector<std::string> folder_meshes(const std::string& folder) {
  std::vector<std::string> out;
  for (const auto& entry :
       fs::recursive_directory_iterator(folder, fs::directory_options::skip_permission_denied))
    if (entry.is_regular_file() && is_mesh_file(entry.path())) out.push_back(entry.path().string());
  std::sort(out.begin(), out.end());
  if (out.empty())
    throw InputError(folder, "no mesh file (OFF, OBJ, STL, PLY, 3MF) in this folder");
  return out;
}

}  // namespace

std::vector<std::string> expand_inputs(const std::vector<std::string>& patterns) {
  std::vector<std::string> out;
  for (const std::string& p : patterns) {
    std::error_code error;
    if (fs::is_directory(p, error)) {
      for (std::string& file : folder_meshes(p)) out.push_back(std::move(file));
      continue;
    }
    if (p.find_first_of("*?[") == std::string::npos) {
      out.push_back(p);
      continue;
    }
    glob_t matches{};
    const int found = glob(p.c_str(), 0, nullptr, &matches);
    if (found == 0)
      for (std::size_t i = 0; i < matches.gl_pathc; ++i) out.emplace_back(matches.gl_pathv[i]);
    globfree(&matches);
    // A quoted pattern that matches nothing is a mistake to say, not a file name to try.
    if (found != 0) throw InputError("'" + p + "'", "no file matches this pattern");
  }
  return out;
}

std::vector<Command> add_pipeline_commands(CLI::App& app) {
  return {add_run_command(app), add_validate_command(app), add_stages_command(app)};
}

}  // namespace morphex::cli

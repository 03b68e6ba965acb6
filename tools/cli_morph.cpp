// SPDX-License-Identifier: GPL-3.0-or-later
// `morphex dilate|erode|open|close IN -o OUT --se SPEC [--exact] [--stats FILE|-]` and
// `morphex minkowski A B -o OUT [--exact] [--stats FILE|-]`.
#include <chrono>

#include "cli_common.h"
#include "morphex/internal/stopwatch.h"
#include "morphex/io.h"
#include "morphex/minkowski.h"
#include "morphex/morph_json.h"
#include "morphex/morphology.h"

namespace morphex::cli {
namespace {

std::string se_help() {
  std::string help = "Structuring element, shape:key=value,... with shapes";
  for (const SeShapeInfo& s : structuring_element_shapes()) {
    help += "\n  " + s.shape + ":";
    for (std::size_t i = 0; i < s.parameters.size(); ++i)
      help += (i ? "," : "") + s.parameters[i].key + "=" +
              (s.parameters[i].default_value.empty() ? "<" + s.parameters[i].type + ">"
                                                     : s.parameters[i].default_value);
  }
  return help;
}

Command add_morphology_command(CLI::App& app, MorphologyOp op, const std::string& summary) {
  auto* cmd = app.add_subcommand(to_string(op), summary);
  struct Args {
    std::string in, se;
    OutputArgs output;
  };
  auto args = std::make_shared<Args>();
  cmd->add_option("IN", args->in, "Input closed mesh")->required();
  cmd->add_option("--se", args->se, se_help())->required();
  add_output_options(cmd, args->output);
  return {cmd, [args, op]() -> int {
            if (!output_usable(args->output, {args->in},
                               {{se_file(args->se), "the structuring element"}}))
              return kBadInput;
            StructuringElement se;
            try {
              se = parse_structuring_element(args->se);
            } catch (const std::bad_alloc&) {
              throw;  // reported by main as out of memory
            } catch (const std::exception& e) {
              print_error("--se " + args->se + ": " + e.what());
              return kBadInput;
            }
            const auto a = read_solid(args->in);
            if (!a) return kBadInput;
            const Stopwatch start;
            MorphologyStats stats;
            Solid result;
            try {
              const OperationProgress progress(to_string(op));
              // Refuses an element out of proportion with the mesh before any work.
              result = apply_morphology(op, *a, se, &stats);
            } catch (const StructuringElementError& e) {
              print_error("--se " + args->se + ": " + e.what());
              return kBadInput;
            }
            const double seconds = start.seconds();
            write_result(result, args->output, [&] {
              nlohmann::json j = result_stats(result, seconds);
              j["operation"] = to_string(op);
              j["se"] = se.spec;
              j["se_convex"] = se.convex;
              const nlohmann::json s = stats;
              for (const char* key : {"pieces", "binary_unions", "arrangements"})
                j[key] = s.at(key);
              return j;
            });
            return kSuccess;
          }};
}

Command add_minkowski_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("minkowski", "Exact Minkowski sum A + B of two closed meshes");
  struct Args {
    std::string a, b;
    OutputArgs output;
  };
  auto args = std::make_shared<Args>();
  cmd->add_option("A", args->a, "First operand")->required();
  cmd->add_option("B", args->b, "Second operand (convex or not)")->required();
  add_output_options(cmd, args->output);
  return {cmd, [args]() -> int {
            if (!output_usable(args->output, {args->a, args->b})) return kBadInput;
            const auto a = read_solid(args->a);
            if (!a) return kBadInput;
            const auto b = read_solid(args->b);
            if (!b) return kBadInput;
            const Stopwatch start;
            MinkowskiStats stats;
            Solid result;
            {
              const OperationProgress progress("minkowski");
              result = minkowski_sum(*a, *b, &stats);
            }
            const double seconds = start.seconds();
            write_result(result, args->output, [&] {
              nlohmann::json j = result_stats(result, seconds);
              j["operation"] = "minkowski";
              const nlohmann::json s = stats;
              for (const char* key : {"pieces", "binary_unions", "arrangements", "phases"})
                j[key] = s.at(key);
              return j;
            });
            return kSuccess;
          }};
}

}  // namespace

std::vector<Command> add_morphology_commands(CLI::App& app) {
  return {
      add_morphology_command(app, MorphologyOp::Dilate, "Dilation A + B by a structuring element"),
      add_morphology_command(app, MorphologyOp::Erode,
                             "Erosion {x : x + B inside A} by a structuring element"),
      add_morphology_command(app, MorphologyOp::Open, "Opening: erosion, then dilation"),
      add_morphology_command(app, MorphologyOp::Close, "Closing: dilation, then erosion"),
      add_minkowski_command(app)};
}

}  // namespace morphex::cli

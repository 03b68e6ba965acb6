// SPDX-License-Identifier: GPL-3.0-or-later
// `morphex bool union|intersection|difference A B -o OUT [--exact] [--stats FILE|-]`.
#include <chrono>
#include <iostream>

#include "cli_common.h"
#include "morphex/boolean.h"
#include "morphex/check.h"
#include "morphex/io.h"
#include "morphex/json.h"
#include "morphex/internal/stopwatch.h"

namespace morphex::cli {

Command add_bool_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("bool", "Exact Boolean operation on two closed meshes");
  struct Args {
    std::string op, a, b;
    OutputArgs output;
  };
  auto args = std::make_shared<Args>();
  cmd->add_option("OP", args->op, "union, intersection or difference (A minus B)")
      ->required()
      ->check(CLI::IsMember({"union", "intersection", "difference"}));
  cmd->add_option("A", args->a, "First operand")->required();
  cmd->add_option("B", args->b, "Second operand")->required();
  add_output_options(cmd, args->output);
  return {cmd, [args]() -> int {
            if (!output_usable(args->output, {args->a, args->b})) return kBadInput;
            Mesh a, b;
            try {
              a = read_mesh(args->a);
              b = read_mesh(args->b);
            } catch (const std::exception& e) {
              print_error(e.what());
              return kBadInput;
            }
            const Stopwatch start;
            BooleanResult result;
            {
              const OperationProgress progress(args->op);
              result = compute_boolean(a, b, parse_boolean_op(args->op));
            }
            const double seconds = start.seconds();
            if (!result.ok()) {
              const std::string& file =
                  result.status == BooleanStatus::InvalidInputA ? args->a : args->b;
              print_error(solid_problem(file, result.message));
              return kBadInput;
            }
            write_result(result.mesh, args->output, [&] {
              nlohmann::json stats = result_stats(result.mesh, seconds);
              const nlohmann::json s = result.stats;
              stats["operation"] = args->op;
              for (const char* key : {"intersected_facets", "segments", "phases"})
                stats[key] = s.at(key);
              return stats;
            });
            return kSuccess;
          }};
}

}  // namespace morphex::cli

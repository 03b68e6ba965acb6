// SPDX-License-Identifier: GPL-3.0-or-later
// `morphex bool union|intersection|difference A B -o OUT [--exact] [--stats FILE|-]`.
#include <chrono>
#include <iostream>

#include "cli_common.h"
#include "morphex/boolean.h"
#include "morphex/check.h"
#include "morphex/internal/stopwatch.h"
#include "morphex/io.h"
#include "morphex/json.h"
#include "morphex/progress.h"
#include "morphex/solid.h"

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
            double checking = 0;
            {
              const OperationProgress progress(args->op);
              std::optional<std::pair<Solid, Solid>> solids;
              {
                // About the check's share of a Boolean's time on bench_bool's real pairs.
                const ProgressPhase phase(0, 0.4, "checking inputs");
                try {
                  solids = check_solids(std::move(a), "first", std::move(b), "second");
                } catch (const InvalidSolid& e) {
                  print_error(
                      solid_problem(e.where() == "first" ? args->a : args->b,
                                    e.where() + " operand is not a valid solid: " + e.problem()));
                  return kBadInput;
                }
              }
              checking = start.seconds();
              const ProgressPhase phase(0.4, 1);
              result = compute_boolean(solids->first, solids->second, parse_boolean_op(args->op));
            }
            const double seconds = start.seconds();
            write_result(result.solid, args->output, [&] {
              nlohmann::json stats = result_stats(result.solid, seconds);
              const nlohmann::json s = result.stats;
              stats["operation"] = args->op;
              for (const char* key : {"intersected_facets", "segments", "phases"})
                stats[key] = s.at(key);
              // The input check is the command's (check_solids), not the Boolean's.
              stats["phases"]["validate"] = checking;
              return stats;
            });
            return kSuccess;
          }};
}

}  // namespace morphex::cli

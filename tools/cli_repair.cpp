// SPDX-License-Identifier: GPL-3.0-or-later
// `morphex repair IN -o OUT [--exact] [--stats FILE|-]`.
#include <chrono>

#include "cli_common.h"
#include "morphex/io.h"
#include "morphex/pipeline.h"
#include "morphex/repair.h"
#include "morphex/stopwatch.h"

namespace morphex::cli {

Command add_repair_command(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "repair",
      "Exact repair: the valid solid a closed mesh bounds, where it crosses or touches itself, "
      "repeats vertices or faces, or has faces without area (its positive winding region)");
  struct Args {
    std::string in;
    OutputArgs output;
    RepairOptions repair;
  };
  auto args = std::make_shared<Args>();
  cmd->add_option("IN", args->in, "Closed, consistently oriented mesh")->required();
  add_output_options(cmd, args->output);
  cmd->add_option("--budget", args->repair.budget,
                  "Work budget of the exact arrangement per input face (0: no bound): a mesh "
                  "whose faces cross so often that it would exceed it is refused (exit 2)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  return {cmd, [args]() -> int {
            if (!output_usable(args->output, {args->in})) return kBadInput;
            Mesh mesh;
            try {
              mesh = read_mesh(args->in);
            } catch (const std::bad_alloc&) {
              throw;
            } catch (const std::exception& e) {
              print_error(e.what());
              return kBadInput;
            }
            const Stopwatch start;
            RepairResult result;
            try {
              result = repair_mesh(mesh, args->repair);
            } catch (const InputError& e) {
              print_error(shown_path(args->in) + ": cannot repair: " + e.what());
              return kBadInput;
            }
            const double seconds = start.seconds();
            write_result(result.mesh, args->output, [&] {
              nlohmann::json stats = result_stats(result.mesh, seconds);
              stats["operation"] = "repair";
              stats["input_faces"] = result.report.input_faces;
              stats["repair"] = pipeline::to_json(result.report);
              return stats;
            });
            return kSuccess;
          }};
}

}  // namespace morphex::cli

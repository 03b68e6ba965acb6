// SPDX-License-Identifier: GPL-3.0-or-later
// `morphex repair IN -o OUT [--exact] [--stats FILE|-]` and
// `morphex solidify IN -o OUT [--weld-tolerance F] [--no-fill] [--exact] [--stats FILE|-]`.
#include <chrono>

#include "cli_common.h"
#include "morphex/internal/stopwatch.h"
#include "morphex/io.h"
#include "morphex/json.h"
#include "morphex/repair.h"
#include "morphex/solidify.h"

namespace morphex::cli {
namespace {

// The mesh of `path` as it is (no validity check: these commands take broken meshes), or the
// reader's located message and false.
bool read_input(const std::string& path, Mesh& mesh) {
  try {
    mesh = read_mesh(path);
    return true;
  } catch (const std::bad_alloc&) {
    throw;  // reported once, by main, as out of memory
  } catch (const std::exception& e) {
    print_error(e.what());
    return false;
  }
}

}  // namespace

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
            if (!read_input(args->in, mesh)) return kBadInput;
            const Stopwatch start;
            RepairResult result;
            try {
              const OperationProgress progress("repair");
              result = repair_mesh(mesh, args->repair);
            } catch (const InputError& e) {
              print_error(shown_path(args->in) + ": cannot repair: " + e.what());
              return kBadInput;
            }
            const double seconds = start.seconds();
            write_result(result.solid, args->output, [&] {
              nlohmann::json stats = result_stats(result.solid, seconds);
              stats["operation"] = "repair";
              stats["input_faces"] = result.report.input_faces;
              stats["repair"] = result.report;
              return stats;
            });
            return kSuccess;
          }};
}

Command add_solidify_command(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "solidify",
      "The valid solid of a mesh as real collections hold them: soups, open surfaces, flipped, "
      "duplicated or degenerate faces, cracks, overlapping or inward parts (a valid solid "
      "passes unchanged)");
  struct Args {
    std::string in;
    SolidifyOptions options;
    bool no_fill = false;
    OutputArgs output;
  };
  auto args = std::make_shared<Args>();
  cmd->add_option("IN", args->in, "Any triangle mesh or soup")->required();
  cmd->add_option("--weld-tolerance", args->options.weld_tolerance,
                  "Merge vertices closer than this fraction of the bounding-box diagonal "
                  "(default 1e-5; 0: equal positions only)")
      ->check(CLI::Range(0.0, 0.1));
  cmd->add_flag("--no-fill", args->no_fill, "Leave holes open (the mesh must then close itself)");
  cmd->add_option("--budget", args->options.repair.budget,
                  "Work budget of the exact repair per input face (as morphex repair --budget)")
      ->check(CLI::NonNegativeNumber);
  add_output_options(cmd, args->output);
  cmd->footer("Example: morphex solidify scan.stl -o solid.off --stats -");
  return {cmd, [args]() -> int {
            if (!output_usable(args->output, {args->in})) return kBadInput;
            Mesh mesh;
            if (!read_input(args->in, mesh)) return kBadInput;
            args->options.fill_holes = !args->no_fill;
            const Stopwatch start;
            SolidifyResult result;
            try {
              const OperationProgress progress("solidify");
              result = solidify(mesh, args->options);
            } catch (const InputError& e) {
              print_error(shown_path(args->in) + ": cannot solidify: " + e.what());
              return kFailed;
            }
            const double seconds = start.seconds();
            write_result(result.solid, args->output, [&] {
              nlohmann::json stats = result_stats(result.solid, seconds);
              const SolidifyReport& r = result.report;
              stats["operation"] = "solidify";
              stats["input_faces"] = r.input_faces;
              stats["solidify"] = r;
              return stats;
            });
            return kSuccess;
          }};
}

}  // namespace morphex::cli

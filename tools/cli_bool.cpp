// SPDX-License-Identifier: GPL-3.0-or-later
// `morphex bool union|intersection|difference A B -o OUT [--exact] [--stats FILE|-]`.
#include <chrono>
#include <iostream>

#include "cli_common.h"
#include "morphex/boolean.h"
#include "morphex/check.h"
#include "morphex/io.h"
#include "morphex/stopwatch.h"

namespace morphex::cli {

Command add_bool_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("bool", "Exact Boolean operation on two closed meshes");
  struct Args {
    std::string op, a, b, out, stats;
    bool exact = false;
  };
  auto args = std::make_shared<Args>();
  cmd->add_option("OP", args->op, "union, intersection or difference (A minus B)")
      ->required()
      ->check(CLI::IsMember({"union", "intersection", "difference"}));
  cmd->add_option("A", args->a, "First operand")->required();
  cmd->add_option("B", args->b, "Second operand")->required();
  cmd->add_option("-o,--output", args->out, "Output mesh (format from the extension)")->required();
  cmd->add_flag("--exact", args->exact, "Write the lossless exact OFF format");
  cmd->add_option("--stats", args->stats, "Write statistics as JSON to FILE, or '-' for stdout");
  return {cmd, [args]() -> int {
            for (const std::string& input : {args->a, args->b})
              if (same_file(input, args->out)) {
                print_error(args->out + ": refusing to overwrite an input");
                return kBadInput;
              }
            Mesh a, b;
            try {
              a = read_mesh(args->a);
              b = read_mesh(args->b);
            } catch (const std::exception& e) {
              print_error(e.what());
              return kBadInput;
            }
            const Stopwatch start;
            const BooleanResult result = compute_boolean(a, b, parse_boolean_op(args->op));
            const double seconds = start.seconds();
            if (!result.ok()) {
              const std::string& file =
                  result.status == BooleanStatus::InvalidInputA ? args->a : args->b;
              print_error(file + ": " + result.message);
              return kBadInput;
            }
            WriteOptions write_options;
            write_options.exact = args->exact;
            write_mesh(result.mesh, args->out, write_options);
            if (!args->stats.empty()) {
              nlohmann::json stats = result_stats(result.mesh, seconds);
              const BooleanStats& s = result.stats;
              stats["operation"] = args->op;
              stats["intersected_facets"] = s.cut_facets_a + s.cut_facets_b;
              stats["segments"] = s.segments;
              stats["phases"] = {
                  {"validate", s.seconds.validate}, {"pairs", s.seconds.pairs},
                  {"segments", s.seconds.segments}, {"retriangulate", s.seconds.retriangulate},
                  {"classify", s.seconds.classify}, {"assemble", s.seconds.assemble}};
              emit_json(stats, args->stats);
            }
            return kSuccess;
          }};
}

}  // namespace morphex::cli

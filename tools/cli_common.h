// SPDX-License-Identifier: GPL-3.0-or-later
// Shared plumbing of the morphex subcommands: exit codes, error reporting, JSON output.
#pragma once

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "morphex/internal/stopwatch.h"
#include "morphex/mesh.h"
#include "morphex/progress.h"
#include "morphex/rounding.h"
#include "morphex/solid.h"

namespace morphex::cli {

// The exit-code contract of docs/conventions.md.
enum ExitCode : int { kSuccess = 0, kFailed = 1, kBadInput = 2 };

// Prints "morphex: MESSAGE" on stderr.
void print_error(const std::string& message);

// Writes `value` as one line to stdout when target is "-", else atomically to the file.
void emit_json(const nlohmann::json& value, const std::string& target);

// The --stats keys every mesh-producing command shares (docs/conventions.md): sizes, exact volume,
// validity and the operation's wall time.
nlohmann::json result_stats(const Mesh& mesh, double seconds);
// What writing a plain format's rounding did (--stats key "rounding"): vertices moved, rounds
// that resolved what rounding broke, the largest displacement and the volume change.
nlohmann::json rounding_json(const RoundingReport& report);
// An output path as messages name it ("-" is <stdout>).
std::string shown_output(const std::string& path);

// Reads an operand; a read error or an invalid solid is reported as "FILE: problem" and nullopt.
std::optional<Solid> read_solid(const std::string& path);

// Refuses an output path that names one of the inputs, and standard input ("-") named twice.
bool output_overwrites_input(const std::string& output, const std::vector<std::string>& inputs);

// A file a command reads or writes, with what it is to the user ("the input", "the structuring
// element" for reads; the option, "--stats", for writes).
struct NamedFile {
  std::string path, role;
};
// Why the folder of `path` cannot take a new file ("" when it can): it must exist, be a folder and
// be writable. Standard output ("-") always can.
std::string output_folder_problem(const std::string& path);
// Every file a command writes checked before any work against every file it reads (through links)
// and against the other writes, and its folder checked: problems are printed ("morphex: OUT:
// refusing to overwrite the input IN (--stats)") and false returned. Standard streams are skipped.
bool writes_safe(const std::vector<NamedFile>& writes, const std::vector<NamedFile>& reads);
// The file a structuring element's text reads (mesh:path=FILE), or "".
std::string se_file(const std::string& spec);

// "FILE: PROBLEM", with the advice to run `morphex repair` when the repair fixes that problem
// (self-intersections, touching parts, degenerate faces, inward orientation; not holes).
std::string solid_problem(const std::string& file, const std::string& problem);

// A path as messages show it: "-" is "<stdin>".
std::string shown_path(const std::string& path);

// The output options every mesh-producing command shares: -o/--output (required), --exact and
// --stats FILE|-.
// The command line as typed, for the provenance comment of written files (set by main).
std::string& command_line();

// -o - writes the mesh to standard output, in --format (default off).
struct OutputArgs {
  std::string out, stats, format;
  bool exact = false;
};
void add_output_options(CLI::App* cmd, OutputArgs& args);
// What the output options cannot do together, reported (exit 2) before any work: --stats - with
// -o -, --format with a file, --exact with a format other than OFF. Also refuses an output that is
// one of the inputs (output_overwrites_input). False when refused.
bool output_usable(const OutputArgs& args, const std::vector<std::string>& inputs,
                   const std::vector<NamedFile>& other_reads = {});
// Writes the mesh (atomically, in the format of the extension) and, if asked, the statistics that
// `stats` builds (only then: they check the result, which costs as much as a check).
void write_result(const Mesh& mesh, const OutputArgs& args,
                  const std::function<nlohmann::json()>& stats);

// A whole number > 0, refused as "expected a positive whole number, got '0'" (CLI11's
// PositiveNumber would print the range up to the largest double, 300 digits).
CLI::Validator positive_integer();

// Each subcommand registers itself on the app and returns the function that runs it.
using Runner = std::function<int()>;
struct Command {
  CLI::App* app;
  Runner run;
};
Command add_check_command(CLI::App& app);
Command add_bool_command(CLI::App& app);
Command add_repair_command(CLI::App& app);
Command add_solidify_command(CLI::App& app);
std::vector<Command> add_morphology_commands(CLI::App& app);
std::vector<Command> add_pipeline_commands(CLI::App& app);
std::vector<Command> add_retrieval_commands(CLI::App& app);
std::vector<Command> add_index_commands(CLI::App& app);  // index, ls, rm
Command add_serve_command(CLI::App& app);

// Expands glob patterns and folders (their mesh files, all levels down, in name order); plain
// paths are kept even if missing (reading reports them). Throws InputError for a pattern that
// matches nothing and a folder without meshes.
std::vector<std::string> expand_inputs(const std::vector<std::string>& patterns);

// Progress on stderr, drawn from the libraries' progress callbacks: a bar redrawn in place on a
// terminal; in a log (stderr not a terminal) a plain line at most every five seconds and one at
// the end ("indexed 120/400 meshes, 2 failed, ETA 14m05s"), or nothing when `in_logs` is false.
class ProgressDisplay {
 public:
  ProgressDisplay(std::string verb, std::string units, bool in_logs = true);
  // `running`: the finished share of the units in progress (the bar moves inside a long one).
  void update(std::size_t done, std::size_t total, std::size_t failed, const std::string& note = "",
              double running = 0);

 private:
  std::string verb_, units_;
  bool tty_, in_logs_;
  double last_line_ = -1;
  Stopwatch clock_;
};

// A bar on a terminal for one long operation (a Boolean, a morphology, a check, a repair), drawn
// from the libraries' progress reports once the operation has run for two seconds
// (MORPHEX_PROGRESS_AFTER=SECONDS changes the delay; tests set 0) and cleared when it ends. In a
// log (stderr not a terminal) it prints nothing: the result's statistics carry the time.
class OperationProgress {
 public:
  explicit OperationProgress(std::string verb);
  ~OperationProgress();
  OperationProgress(const OperationProgress&) = delete;
  OperationProgress& operator=(const OperationProgress&) = delete;

 private:
  void draw(double share, const std::string& phase);
  std::string verb_;
  bool tty_;
  double after_;
  double last_draw_ = -1;
  bool drawn_ = false;
  Stopwatch clock_;
  ProgressScope scope_;
};

}  // namespace morphex::cli

// SPDX-License-Identifier: GPL-3.0-or-later
// `morphex`: the command line of the morphex framework. Each subcommand lives in its own file.
#include <signal.h>
#include <sys/resource.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <iostream>
#include <memory>
#include <thread>
#include <vector>

#include "cli_common.h"
#include "morphex/io.h"

namespace {

// SIGINT/SIGTERM: outputs are only ever renamed into place when complete, so removing the
// temporaries of writes in progress leaves nothing half-written; SQLite rolls back an open
// transaction of `morphex index` on the next open.
void on_interrupt(int signal) {
  morphex::remove_pending_temporary_files();
  const char message[] = "morphex: interrupted; no partial output was left\n";
  [[maybe_unused]] const auto written = write(STDERR_FILENO, message, sizeof message - 1);
  _exit(128 + signal);
}

}  // namespace

int main(int argc, char** argv) {
  using namespace morphex::cli;
  CLI::App app{"morphex: exact mathematical morphology on 3D triangle meshes"};
  app.set_version_flag("--version", std::string("morphex ") + MORPHEX_VERSION);
  app.require_subcommand(1);
  // Global options are accepted after the subcommand too (`morphex bool --threads 2 ...`), as
  // ../shared/conventions.md promises.
  app.fallthrough();
  unsigned threads = std::max(1u, std::thread::hardware_concurrency());
  app.add_option("--threads", threads, "Worker threads (default: all cores)")
      ->check(CLI::Validator(
          [](std::string& value) -> std::string {
            return value.find_first_not_of("0123456789") == std::string::npos &&
                           value.find_first_not_of('0') != std::string::npos
                       ? ""
                       : "expected a positive number of threads, got '" + value + "'";
          },
          "POSITIVE"));
  morphex::InputLimits limits = morphex::input_limits();
  std::uint64_t max_input_mb = limits.max_file_bytes >> 20, max_memory_mb = 0;
  app.add_option("--max-faces", limits.max_faces, "Refuse input meshes with more faces")
      ->default_val(limits.max_faces)
      ->check(CLI::PositiveNumber);
  app.add_option("--max-input-mb", max_input_mb, "Refuse input files larger than this (MiB)")
      ->default_val(max_input_mb)
      ->check(CLI::PositiveNumber);
  app.add_option("--max-memory-mb", max_memory_mb,
                 "Fail cleanly (exit 1, 'out of memory') instead of being killed when the process "
                 "would use more address space than this (MiB; default: no limit)");

  std::vector<Command> commands = {add_check_command(app), add_repair_command(app),
                                   add_solidify_command(app), add_bool_command(app)};
  for (Command& c : add_morphology_commands(app)) commands.push_back(std::move(c));
  for (Command& c : add_pipeline_commands(app)) commands.push_back(std::move(c));
  for (Command& c : add_retrieval_commands(app)) commands.push_back(std::move(c));
  for (Command& c : add_index_commands(app)) commands.push_back(std::move(c));

  for (int i = 0; i < argc; ++i)
    command_line() += (i ? " " : "") + std::string(i ? argv[i] : "morphex");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version are "errors" with exit code 0 in CLI11.
    const int code = app.exit(e);
    return code == 0 ? kSuccess : kBadInput;
  }

  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  limits.max_file_bytes = max_input_mb << 20;
  morphex::set_input_limits(limits);
  if (max_memory_mb > 0) {
    // Start the worker threads first: the cap is on the operation's memory, and a thread whose
    // stack could not be mapped would fail with a thread error instead of "out of memory".
    // Each task waits for the others, so every worker the arena can have must join; on a
    // loaded machine a thread may take a while to start (the bound only guards against a worker
    // that never comes).
    const unsigned workers = std::min(threads, unsigned(tbb::this_task_arena::max_concurrency()));
    std::atomic<unsigned> started{0};
    tbb::parallel_for(0u, workers, [&](unsigned) {
      ++started;
      const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(10);
      while (started < workers && std::chrono::steady_clock::now() < until)
        std::this_thread::yield();
    });
    const rlimit cap{rlim_t(max_memory_mb) << 20, rlim_t(max_memory_mb) << 20};
    setrlimit(RLIMIT_AS, &cap);
  }
  signal(SIGINT, on_interrupt);
  signal(SIGTERM, on_interrupt);
  for (const Command& command : commands) {
    if (!command.app->parsed()) continue;
    try {
      return command.run();
    } catch (const std::bad_alloc&) {
      print_error(
          "out of memory: the operation needs more memory than is available (see "
          "--max-memory-mb and --max-faces); no output was written");
      return kFailed;
    } catch (const morphex::Error& e) {
      // morphex/error.h: the input is unusable (a file, an option, a structuring element).
      print_error(e.what());
      return kBadInput;
    } catch (const std::exception& e) {
      print_error(e.what());
      return kFailed;
    }
  }
  return kBadInput;
}

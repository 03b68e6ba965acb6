// SPDX-License-Identifier: GPL-3.0-or-later
// `morphex`: the command line of the morphex framework. Each subcommand lives in its own file.
#include <tbb/global_control.h>

#include <iostream>
#include <memory>
#include <thread>
#include <vector>

#include "cli_common.h"

int main(int argc, char** argv) {
  using namespace morphex::cli;
  CLI::App app{"morphex: exact mathematical morphology on 3D triangle meshes"};
  app.set_version_flag("--version", std::string("morphex ") + MORPHEX_VERSION);
  app.require_subcommand(1);
  unsigned threads = std::max(1u, std::thread::hardware_concurrency());
  app.add_option("--threads", threads, "Worker threads (default: all cores)")
      ->check(CLI::PositiveNumber);

  std::vector<Command> commands = {add_check_command(app), add_bool_command(app)};
  for (Command& c : add_morphology_commands(app)) commands.push_back(std::move(c));
  for (Command& c : add_pipeline_commands(app)) commands.push_back(std::move(c));
  for (Command& c : add_retrieval_commands(app)) commands.push_back(std::move(c));

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version are "errors" with exit code 0 in CLI11.
    const int code = app.exit(e);
    return code == 0 ? kSuccess : kBadInput;
  }

  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  for (const Command& command : commands) {
    if (!command.app->parsed()) continue;
    try {
      return command.run();
    } catch (const std::exception& e) {
      print_error(e.what());
      return kFailed;
    }
  }
  return kBadInput;
}

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

  std::vector<std::pair<CLI::App*, Runner>> commands;
  auto add = [&](Runner (*adder)(CLI::App&)) {
    const std::size_t before = app.get_subcommands({}).size();
    Runner runner = adder(app);
    commands.emplace_back(app.get_subcommands({})[before], std::move(runner));
  };
  add(add_check_command);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version are "errors" with exit code 0 in CLI11.
    const int code = app.exit(e);
    return code == 0 ? kSuccess : kBadInput;
  }

  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  for (auto& [sub, run] : commands) {
    if (!sub->parsed()) continue;
    try {
      return run();
    } catch (const std::exception& e) {
      print_error(e.what());
      return kFailed;
    }
  }
  return kBadInput;
}

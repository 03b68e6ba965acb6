// SPDX-License-Identifier: GPL-3.0-or-later
// `morphex`: the command line of the morphex framework. Each subcommand lives in its own file.
#include <dlfcn.h>
#include <gmp.h>
#include <signal.h>
#include <sys/resource.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <system_error>
#include <thread>
#include <vector>

#include "cli_common.h"
#include "morphex/internal/huge_pages.h"
#include "morphex/internal/nearest.h"
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

// GMP aborts when an allocation fails. Unwinding a C++ exception through GMP's C frames would
// leave its numbers in an undetermined state (GMP's manual, "Custom Allocation"), so a failed
// allocation ends the process here, as main reports std::bad_alloc: exit 1, no output left.
[[noreturn]] void gmp_out_of_memory() {
  morphex::remove_pending_temporary_files();
  const char message[] =
      "morphex: out of memory: the operation needs more memory than is available (see "
      "--max-memory-mb and --max-faces); no output was written\n";
  [[maybe_unused]] const auto written = write(STDERR_FILENO, message, sizeof message - 1);
  _exit(morphex::cli::kFailed);
}
void* gmp_allocate(std::size_t size) {
  void* p = std::malloc(size);
  if (!p) gmp_out_of_memory();
  return p;
}
void* gmp_reallocate(void* old, std::size_t, std::size_t size) {
  void* p = std::realloc(old, size);
  if (!p) gmp_out_of_memory();
  return p;
}
void gmp_free(void* p, std::size_t) {
  std::free(p);
}

// Caps the address space at `mb` MiB, after what a capped process could no longer map: the worker
// threads and their stacks, and the unwinder glibc loads on first use (it would otherwise abort
// with "libgcc_s.so.1 must be installed for unwinding to work").
void cap_memory(std::uint64_t mb, unsigned threads) {
  dlopen("libgcc_s.so.1", RTLD_NOW | RTLD_NODELETE);
  // Each task waits for the others, so every worker the arena can have must join; on a
  // loaded machine a thread may take a while to start (the bound only guards against a worker
  // that never comes).
  const unsigned workers = std::min(threads, unsigned(tbb::this_task_arena::max_concurrency()));
  std::atomic<unsigned> started{0};
  tbb::parallel_for(0u, workers, [&](unsigned) {
    ++started;
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(10);
    while (started < workers && std::chrono::steady_clock::now() < until) std::this_thread::yield();
  });
  const rlimit cap{rlim_t(mb) << 20, rlim_t(mb) << 20};
  setrlimit(RLIMIT_AS, &cap);
}

// One example per subcommand, shown at the end of its --help.
const std::map<std::string, std::string>& examples() {
  static const std::map<std::string, std::string> text = {
      {"check", "morphex check part.off\n  morphex check --json --exact *.off"},
      {"repair", "morphex repair soup.stl -o solid.off --stats -"},
      {"bool", "morphex bool difference block.off hole.off -o result.off --stats stats.json"},
      {"dilate", "morphex dilate part.off --se ball:r=0.5,level=2 -o grown.off"},
      {"erode", "morphex erode part.off --se cube:r=1/4 -o shrunk.off"},
      {"open", "morphex open part.off --se octahedron:r=0.1 -o opened.off"},
      {"close", "morphex close part.off --se cylinder:r=0.2,h=1 -o closed.off"},
      {"minkowski", "morphex minkowski part.off tool.off -o swept.off"},
      {"run",
       "morphex run pipelines/examples/top-hat.json --input 'meshes/*.off' --set "
       "out_dir=out"},
      {"validate", "morphex validate pipeline.json --set out_dir=out"},
      {"stages", "morphex stages\n  morphex stages dilate"},
      {"describe", "morphex describe part.off --json\n  morphex describe part.off --plot c.svg"},
      {"generate", "morphex generate collection --per-class 4"},
      {"index", "morphex index meshes/ --db index.sqlite"},
      {"query", "morphex query --db index.sqlite part.off -k 5"},
      {"evaluate", "morphex evaluate --db index.sqlite --labels labels.cla --plot pr.svg"},
      {"ls", "morphex ls --db index.sqlite --failed"},
      {"rm", "morphex rm --db index.sqlite part old/other.off"},
      {"serve", "morphex serve --db index.sqlite --port 8080"},
  };
  return text;
}

// Every option name of `app` ("--output", "-o"), for hints.
std::vector<std::string> option_names(const CLI::App& app) {
  std::vector<std::string> names;
  for (const CLI::Option* o : app.get_options()) {
    for (const std::string& n : o->get_lnames()) names.push_back("--" + n);
    for (const std::string& n : o->get_snames()) names.push_back("-" + n);
    for (const std::string& n : o->get_fnames()) names.push_back("--" + n);
  }
  return names;
}

// An unknown command or option, with the nearest known one, before CLI11 parses: CLI11 would
// report a missing subcommand or a missing required option instead of the typo itself. True
// when one was reported.
bool report_unknown_words(const CLI::App& app, int argc, char** argv) {
  const CLI::App* command = nullptr;
  const auto fail = [](const std::string& where, const std::string& word, const std::string& kind,
                       const std::string& hint) {
    morphex::cli::print_error(
        where + "unknown " + kind + " '" + word + "'" +
        (hint.empty() ? "" : " (did you mean '" + hint + "'?)") + "; see morphex " +
        (where.empty() ? "" : where.substr(0, where.size() - 2) + " ") + "--help");
    return true;
  };
  for (int i = 1; i < argc; ++i) {
    const std::string word = argv[i];
    if (word == "--") return false;  // the rest are operands
    const bool option = word.size() > 1 && word[0] == '-' &&
                        !std::isdigit(static_cast<unsigned char>(word[1])) && word[1] != '.';
    if (!option) {
      if (command) continue;  // an operand or an option's value
      std::vector<std::string> names;
      for (const CLI::App* sub : app.get_subcommands({})) names.push_back(sub->get_name());
      if (std::find(names.begin(), names.end(), word) == names.end())
        return fail("", word, "command", morphex::nearest_name(word, names));
      command = app.get_subcommand_ptr(word).get();
      continue;
    }
    const std::string name = word.substr(0, word.find('='));
    const CLI::Option* known = app.get_option_no_throw(name);
    if (!known && command) known = command->get_option_no_throw(name);
    if (name == "--help" || name == "-h" || name == "--version") return false;
    if (!known) {
      if (word.rfind("--", 0) != 0 && word.size() > 2) continue;  // -xyz: a value such as -0.5
      std::vector<std::string> names = option_names(app);
      if (command)
        for (const std::string& n : option_names(*command)) names.push_back(n);
      return fail(command ? command->get_name() + ": " : "", name, "option",
                  morphex::nearest_name(name, names));
    }
    // Skip an option's value, so that a value such as "dilat" is not taken for a command.
    if (known->get_type_size() != 0 && word.find('=') == std::string::npos && !command) ++i;
  }
  return false;
}

// Whether the command ahead will touch enough fresh memory to pay for restarting with huge pages
// (morphex/internal/huge_pages.h). The restart costs one more start of this executable, about
// 7 ms on the 2-core machine since the libraries only some commands need are loaded by those
// alone; huge pages save about 10 us per 4 KiB page first touched there. Measured by command
// (always restarting against not, 2026-11-29, docs/benchmarks.md "Process start"): a check or a
// Boolean touches some 20 times its input files' size and gains from about half a mebibyte of
// input (cheese, 0.65 MB: 0.078 -> 0.066 s; femur, 0.25 MB: 0.044 -> 0.047), a morphology touches
// far more per input byte and gains from small inputs on (anchor, 29 kB, dilated by a ball: 0.38
// -> 0.35 s; the unit cube: 0.024 -> 0.031), a description works on a 300-facet copy and does
// not gain. So: input files of 512 KiB or more in all, 16 KiB for a morphology, or work not
// bounded by the files named: a folder or a pattern of them, pipelines, the index and the
// server.
bool huge_pages_pay(int argc, char** argv) {
  constexpr std::uintmax_t kMinimumInput = std::uintmax_t(512) << 10;
  constexpr std::uintmax_t kMinimumMorphologyInput = std::uintmax_t(16) << 10;
  std::uintmax_t input = 0, minimum = kMinimumInput;
  bool command_seen = false;
  for (int i = 1; i < argc; ++i) {
    const std::string word = argv[i], before = argv[i - 1];
    // The command: the first word that is neither an option nor a global option's value.
    if (!command_seen && word[0] != '-' && before.rfind("--max-", 0) != 0 &&
        before != "--threads") {
      command_seen = true;
      if (word == "run" || word == "index" || word == "serve") return true;
      if (word == "dilate" || word == "erode" || word == "open" || word == "close" ||
          word == "minkowski")
        minimum = kMinimumMorphologyInput;
      continue;
    }
    if (word.find_first_of("*?[") != std::string::npos) return true;
    std::error_code error;
    const auto status = std::filesystem::status(word, error);
    if (error) continue;
    if (std::filesystem::is_directory(status)) return true;
    if (!std::filesystem::is_regular_file(status)) continue;
    const std::uintmax_t size = std::filesystem::file_size(word, error);
    if (!error) input += size;
    if (input >= minimum) return true;
  }
  return false;
}

// Output lost on the way to standard output (a full disk, a closed pipe) is a failure, not
// success: the data a script reads there is incomplete.
int check_stdout(int code) {
  errno = 0;
  std::cout.flush();
  const bool failed = !std::cout || std::fflush(stdout) != 0 || std::ferror(stdout);
  if (!failed) return code;
  // The failed write may be long past (a flushed line): one more byte finds out why it fails.
  [[maybe_unused]] const auto probe = errno == 0 ? write(STDOUT_FILENO, "\n", 1) : 0;
  const int error = errno;
  morphex::cli::print_error(std::string("standard output: cannot write: ") +
                            (error ? std::strerror(error) : "write error"));
  return std::max(code, int(morphex::cli::kFailed));  // bad input (2) stays the worse
}

}  // namespace

int main(int argc, char** argv) {
  if (huge_pages_pay(argc, argv)) morphex::use_huge_page_malloc(argv);  // first: may restart
  using namespace morphex::cli;
  mp_set_memory_functions(gmp_allocate, gmp_reallocate, gmp_free);
  CLI::App app{"morphex: exact mathematical morphology on 3D triangle meshes"};
  app.set_version_flag("--version", std::string("morphex ") + MORPHEX_VERSION);
  app.require_subcommand(1);
  // Global options are accepted after the subcommand too (`morphex bool --threads 2 ...`), as
  // docs/conventions.md promises.
  app.fallthrough();
  // CLI11's own errors in the morphex voice ("morphex: --output is required").
  app.failure_message([](const CLI::App*, const CLI::Error& e) {
    return "morphex: " + std::string(e.what()) + "\nRun with --help for more information.\n";
  });
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
      ->check(positive_integer());
  app.add_option("--max-input-mb", max_input_mb, "Refuse input files larger than this (MiB)")
      ->default_val(max_input_mb)
      ->check(positive_integer());
  app.add_option("--max-memory-mb", max_memory_mb,
                 "Fail cleanly (exit 1, 'out of memory') instead of being killed when the process "
                 "would use more address space than this (MiB; default: no limit)");

  std::vector<Command> commands = {add_check_command(app), add_repair_command(app),
                                   add_solidify_command(app), add_bool_command(app)};
  for (Command& c : add_morphology_commands(app)) commands.push_back(std::move(c));
  for (Command& c : add_pipeline_commands(app)) commands.push_back(std::move(c));
  for (Command& c : add_retrieval_commands(app)) commands.push_back(std::move(c));
  for (Command& c : add_index_commands(app)) commands.push_back(std::move(c));
  commands.push_back(add_serve_command(app));

  for (const Command& c : commands)
    if (const auto e = examples().find(c.app->get_name()); e != examples().end())
      c.app->footer("\nExample:\n  " + e->second);
  for (int i = 0; i < argc; ++i)
    command_line() += (i ? " " : "") + std::string(i ? argv[i] : "morphex");
  if (report_unknown_words(app, argc, argv)) return kBadInput;
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
  if (max_memory_mb > 0) cap_memory(max_memory_mb, threads);
  signal(SIGINT, on_interrupt);
  signal(SIGTERM, on_interrupt);
  for (const Command& command : commands) {
    if (!command.app->parsed()) continue;
    try {
      return check_stdout(command.run());
    } catch (const std::system_error& e) {
      // A thread that cannot be started under the memory cap (its stack cannot be mapped).
      if (e.code() != std::errc::resource_unavailable_try_again &&
          e.code() != std::errc::not_enough_memory) {
        print_error(e.what());
        return kFailed;
      }
      print_error(
          "out of memory: cannot start a worker thread (see --max-memory-mb and --threads); no "
          "output was written");
      return kFailed;
    } catch (const std::bad_alloc&) {
      print_error(
          "out of memory: the operation needs more memory than is available (see "
          "--max-memory-mb and --max-faces); no output was written");
      return kFailed;
    } catch (const morphex::InputError& e) {
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

// SPDX-License-Identifier: GPL-3.0-or-later
// `morphex serve`: a local web page over a retrieval index (morphex/server.h does the serving).
#include <pthread.h>
#include <signal.h>

#include <atomic>
#include <chrono>
#include <iostream>
#include <memory>
#include <thread>

#include "cli_common.h"
#include "morphex/internal/modules.h"
#include "morphex/server.h"

namespace morphex::cli {

Command add_serve_command(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "serve",
      "A local web page over a retrieval index: meshes in 3D, granulometry curves, nearest "
      "neighbours, queries by upload, failures (the index is only read)");
  struct Args {
    std::string db, labels;
    ServerOptions options;
    std::uint64_t max_upload_mb = 32;
  };
  auto args = std::make_shared<Args>();
  cmd->add_option("--db", args->db, "Index file")->required()->check(CLI::ExistingFile);
  cmd->add_option("--host", args->options.host,
                  "Address to listen on (127.0.0.1: this machine only; 0.0.0.0: every "
                  "interface, shares the index with whoever can reach this machine)")
      ->capture_default_str();
  cmd->add_option("--port", args->options.port, "Port (0: a free one, printed)")
      ->capture_default_str()
      ->check(CLI::Range(0, 65535));
  cmd->add_option("--max-upload-mb", args->max_upload_mb, "Largest mesh file a query may upload")
      ->capture_default_str()
      ->check(positive_integer());
  cmd->add_option("--labels", args->options.labels,
                  "Princeton .cla labels: each mesh's class beside its name")
      ->check(CLI::ExistingFile);
  return {cmd, [args]() -> int {
            ServerOptions options = args->options;
            options.max_upload_bytes = args->max_upload_mb << 20;
            // SIGINT and SIGTERM stop the server cleanly (uploads in progress finish and remove
            // their temporary folders): blocked here, before any thread starts, so that every
            // thread inherits the mask and only the waiter below receives them.
            sigset_t stops;
            sigemptyset(&stops);
            sigaddset(&stops, SIGINT);
            sigaddset(&stops, SIGTERM);
            pthread_sigmask(SIG_BLOCK, &stops, nullptr);
            std::unique_ptr<IndexServer> server;
            int port = 0;
            try {
              server = std::make_unique<IndexServer>(args->db, options);
              port = server->bind();
            } catch (const ModuleError& e) {  // an installation without its HTTP module
              print_error(e.what());
              return kFailed;
            } catch (const std::runtime_error& e) {  // an address that cannot be bound
              print_error(e.what());
              return kBadInput;
            }
            const bool local = options.host == "localhost" || options.host == "::1" ||
                               options.host.rfind("127.", 0) == 0;
            const std::string host = options.host.find(':') != std::string::npos
                                         ? "[" + options.host + "]"
                                         : options.host;
            std::cout << "serving http://" << host << ":" << port << "/ "
                      << (local ? "(local only; --host 0.0.0.0 to share)"
                                : "(every interface: whoever reaches this machine sees the index)")
                      << std::endl;
            std::cout << args->db << ": " << server->meshes() << " meshes, " << server->failed()
                      << " failed; read only (the page never writes to the index); Ctrl-C stops"
                      << std::endl;
            std::atomic<bool> done{false};
            std::thread waiter([&] {
              int received = 0;
              sigwait(&stops, &received);
              // A signal before run() started listening finds nothing to stop yet: try again.
              while (!done) {
                server->stop();
                std::this_thread::sleep_for(std::chrono::milliseconds(20));
              }
            });
            server->run();
            done = true;
            // run() may also return without a signal (the listening socket failed): wake the
            // waiter then.
            pthread_kill(waiter.native_handle(), SIGTERM);
            waiter.join();
            std::cout << "stopped" << std::endl;
            return kSuccess;
          }};
}

}  // namespace morphex::cli

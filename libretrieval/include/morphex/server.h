// SPDX-License-Identifier: GPL-3.0-or-later
// `morphex serve`: a local web server over a retrieval index. The page lists the indexed meshes
// with thumbnails, shows one in 3D (three.js, from Debian's libjs-three), its granulometry curves
// and its nearest neighbours, answers a query by an uploaded mesh, and lists the failed meshes.
// docs/serve.md has the routes and the design.
//
// Safe by construction:
//   - the index is opened read-only and no route writes to it;
//   - only the index's own meshes are served: a request names a mesh by its row id or name, which
//     is looked up in the index; the file read is the path the index records, and only when its
//     content hash is still the recorded one. No path from a request is ever opened;
//   - uploads are limited in size (max_upload_bytes, 413 beyond), written under a fixed name into
//     a private temporary folder (mkdtemp) that is removed after the query, and read with the
//     same readers and limits as the command line, their format from the whitelisted extension of
//     the uploaded file's name;
//   - a malformed request gets a 4xx answer {"error": "..."} and the server keeps serving.
//
// Not part of the installed library: it links cpp-httplib, which the command line uses and the
// package configuration does not look for.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

namespace morphex {

struct ServerOptions {
  // 127.0.0.1: this machine only. Another address (0.0.0.0: every interface) shares the index
  // with whoever can reach the machine.
  std::string host = "127.0.0.1";
  int port = 8080;  // 0: a free port chosen by the system
  std::uint64_t max_upload_bytes = std::uint64_t(32) << 20;
  // Request threads (each holds a connection while it is kept alive).
  int threads = 8;
  // Princeton .cla labels (model name -> class), shown beside the names; "" for none.
  std::string labels;
  // Where Debian's libjs-three installs three.js ("" = the one found at configure time).
  std::string three_dir;
  // Rendered thumbnails and glb files kept in memory, in bytes.
  std::size_t cache_bytes = std::size_t(64) << 20;
};

class IndexServer {
 public:
  // Opens the index read-only (InputError when it is not a sound morphex index), reads the labels
  // and the three.js files (InputError naming what is missing and the package to install).
  IndexServer(const std::string& index_path, ServerOptions options);
  ~IndexServer();
  IndexServer(const IndexServer&) = delete;
  IndexServer& operator=(const IndexServer&) = delete;

  // Binds options.host:options.port and returns the port (the chosen one for port 0). Throws
  // std::runtime_error when the address cannot be bound.
  int bind();
  // Serves until stop(); requests in progress finish first.
  void run();
  // From any thread (a signal-waiting thread): makes run() return.
  void stop();
  // The index's meshes and failures, for the command's first lines.
  std::size_t meshes() const;
  std::size_t failed() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace morphex

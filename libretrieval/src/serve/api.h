// SPDX-License-Identifier: GPL-3.0-or-later
// What `morphex serve` answers, without HTTP: the JSON of each API route, the glb and thumbnail
// bytes, and the query by an uploaded mesh. http.cpp maps routes to these functions; refusals are
// RequestError with the HTTP status, which it sends as {"error": message}.
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <map>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>

#include "morphex/index.h"
#include "morphex/index_db.h"
#include "morphex/server.h"

namespace morphex::serve {

class RequestError : public std::runtime_error {
 public:
  RequestError(int status, const std::string& message)
      : std::runtime_error(message), status_(status) {}
  int status() const { return status_; }

 private:
  int status_;
};

// A request's query parameters (the first value of each name).
using Params = std::map<std::string, std::string>;

// Bytes kept in memory up to a total size: rendered glb files and thumbnails, by mesh file and
// its size and modification time (a changed file is rendered again). Cleared when full: a page
// asks for each mesh once, so recency would buy little.
class ByteCache {
 public:
  explicit ByteCache(std::size_t capacity) : capacity_(capacity) {}
  std::optional<std::string> find(const std::string& key);
  void put(const std::string& key, const std::string& bytes);

 private:
  std::mutex mutex_;
  std::map<std::string, std::string> entries_;
  std::size_t capacity_, size_ = 0;
};

class IndexApi {
 public:
  // Opens the index read-only and reads the labels (InputError).
  IndexApi(const std::string& index_path, const ServerOptions& options);

  nlohmann::json info();
  nlohmann::json meshes();    // the described meshes, by name
  nlohmann::json failures();  // the failed ones with their errors
  // One mesh: what the index records, its descriptor vectors and granulometry curves.
  nlohmann::json mesh(long long id);
  std::string glb(long long id);        // the mesh as read, rounded to floats (glTF binary)
  std::string thumbnail(long long id);  // PNG
  // ?name=NAME or ?id=ID, with k, kind and metric: what `morphex query --db INDEX NAME` ranks.
  nlohmann::json query_indexed(const Params& params);
  // An uploaded mesh file, described with the index's own pipeline, against every indexed mesh.
  nlohmann::json query_upload(const std::string& filename, const std::string& content,
                              const Params& params);

  std::size_t count(bool failed);
  const ServerOptions& options() const { return options_; }

 private:
  IndexedMesh row(long long id, bool with_descriptors);
  std::string mesh_file(const IndexedMesh& m);
  std::string cached(const std::string& what, const IndexedMesh& m,
                     std::string (*render)(const std::string& file));
  nlohmann::json curves(const std::map<std::string, std::vector<double>>& descriptors);
  nlohmann::json neighbours_json(const std::vector<Neighbour>& ranked);
  std::string label(const std::string& name) const;

  ServerOptions options_;
  IndexDb db_;
  std::mutex db_mutex_;        // one SQLite connection, used by one request at a time
  std::mutex describe_mutex_;  // one upload described at a time; others are told to retry
  std::map<std::string, std::string> labels_;
  ByteCache cache_;
};

}  // namespace morphex::serve

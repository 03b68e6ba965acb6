// SPDX-License-Identifier: GPL-3.0-or-later
// The retrieval index: one SQLite file. Tables:
//   meta(key PRIMARY KEY, value)            "describe_options": the describe stage's options (JSON)
//   meshes(id, name, path UNIQUE, hash, settings, status 'ok'|'failed', error, faces, volume,
//          seconds, indexed_at, repair)  repair: what the repair changed (JSON), NULL when the
//          mesh was a valid solid as read
//   descriptors(mesh_id, kind, vector)       vector: IEEE doubles, little endian, as a BLOB
//                                            (indexes written before 0.1 hold JSON arrays: read too)
// Every mesh is committed in its own transaction, so a run killed midway keeps what it committed.
#pragma once

#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <vector>

struct sqlite3;  // SQLite's connection, used through pointers only

namespace morphex {

// One row of the index: a mesh described (status "ok") or refused ("failed", with its error).
struct IndexedMesh {
  long long id = 0;
  std::string name, path, hash, settings, status, error;
  std::string repair;  // the repair report (JSON) when the mesh was repaired, else empty
  std::map<std::string, std::vector<double>> descriptors;
  std::size_t faces = 0;   // of the mesh as read
  std::string volume;      // its exact volume as read ("" when unknown)
  double seconds = 0;      // its pipeline's wall time
  std::string indexed_at;  // UTC, set by the database
};

class IndexDb {
 public:
  explicit IndexDb(const std::string& path);  // creates the schema; throws on failure
  ~IndexDb();
  IndexDb(const IndexDb&) = delete;
  IndexDb& operator=(const IndexDb&) = delete;

  std::optional<std::string> meta(const std::string& key);
  void set_meta(const std::string& key, const std::string& value);
  // "ok" or "failed" when `path` was indexed with this content hash and these settings, else "".
  std::string status(const std::string& path, const std::string& hash, const std::string& settings);
  // Inserts or replaces the row of mesh.path (id and indexed_at are the database's).
  void store(const IndexedMesh& mesh);
  // Every row (only the successful ones by default), ordered by name then path, with the
  // descriptors of `kinds` ({"*"}: every kind; {}: none).
  std::vector<IndexedMesh> load(bool only_ok = true,
                                const std::vector<std::string>& kinds = {"*"});
  // Removes the row of this recorded path and its descriptors; false when there is none.
  bool remove(const std::string& path);
  const std::string& path() const { return path_; }

 private:
  void exec(const std::string& sql);
  sqlite3* db_ = nullptr;
  std::string path_;
};

// 64-bit FNV-1a of the file's bytes, as 16 hex digits.
std::string content_hash(const std::string& path);
// The same of a text (settings, for short names of them).
std::string text_hash(const std::string& text);

}  // namespace morphex

// SPDX-License-Identifier: GPL-3.0-or-later
// The retrieval index: one SQLite file. Tables:
//   meta(key PRIMARY KEY, value)            "describe_options": the describe stage's options (JSON)
//   meshes(id, name, path UNIQUE, hash, settings, status 'ok'|'failed', error, faces, volume,
//          seconds, indexed_at, repair)  repair: what the repair changed (JSON), NULL when the
//          mesh was a valid solid as read
//   descriptors(mesh_id, kind, vector)       vector: IEEE doubles, little endian, as a BLOB
//                                            (indexes written before 0.1 hold JSON arrays: read
//                                            too)
// Every mesh is committed in its own transaction, so a run killed midway keeps what it committed.
// The file carries the marker PRAGMA application_id = kIndexApplicationId and user_version = the
// schema version (indexes made before the marker have 0 and are recognised by their tables).
//
// Index files are untrusted input: a file that is not a morphex index (another program's
// database, an empty or non-SQLite file) or a damaged one (PRAGMA quick_check) is refused with
// InputError before anything is written, and stored vectors that are not finite are refused when
// read. Read-only access never writes (not even the journal mode) and works on read-only storage.
#pragma once

#include <cstddef>
#include <cstdint>
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

// "MPXI": what PRAGMA application_id holds in a morphex index.
inline constexpr int kIndexApplicationId = 0x4d505849;

enum class IndexAccess {
  ReadOnly,   // the file must be a morphex index; never written
  ReadWrite,  // a missing or empty file becomes a new index; another file must be one
};

class IndexDb {
 public:
  // Opens (ReadWrite: creates) the index. Throws InputError for a file that is not a morphex
  // index or is damaged (PRAGMA quick_check: always before writing; when reading, for files up to
  // kQuickCheckBytes, since it reads the whole file), std::runtime_error when SQLite fails.
  explicit IndexDb(const std::string& path, IndexAccess access = IndexAccess::ReadWrite);
  static constexpr std::uintmax_t kQuickCheckBytes = std::uintmax_t(256) << 20;
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
  std::vector<IndexedMesh> load(bool only_ok = true, const std::vector<std::string>& kinds = {"*"});
  // The row of this id (any status), with every descriptor kind when asked; nullopt when none.
  std::optional<IndexedMesh> entry(long long id, bool with_descriptors = true);
  // The descriptor kinds stored for any mesh, by name.
  std::vector<std::string> kinds();
  // Removes the row of this recorded path and its descriptors; false when there is none.
  bool remove(const std::string& path);
  const std::string& path() const { return path_; }
  IndexAccess access() const { return access_; }

 private:
  // The constructor's work: open, check what the file is, create or upgrade the schema.
  void open_checked(const std::string& path, IndexAccess access);
  void open(int flags, const std::string& uri);
  void create_or_upgrade();
  void require_index();
  void quick_check();
  void exec(const std::string& sql);
  std::vector<IndexedMesh> load_rows(bool only_ok, long long id,
                                     const std::vector<std::string>& kinds);
  sqlite3* db_ = nullptr;
  std::string path_;
  IndexAccess access_;
};

// 64-bit FNV-1a of the file's bytes, as 16 hex digits.
std::string content_hash(const std::string& path);
// The same of a text (settings, for short names of them).
std::string text_hash(const std::string& text);

}  // namespace morphex

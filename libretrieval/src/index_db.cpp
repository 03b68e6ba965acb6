// SPDX-License-Identifier: GPL-3.0-or-later
#include "morphex/index_db.h"

#include <sqlite3.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <stdexcept>
#include <thread>

#include "morphex/error.h"

namespace morphex {
namespace {

namespace fs = std::filesystem;

constexpr long long kSchemaVersion = 1;

// SQLite's error as the exception to throw: a file that is not a database or is damaged is bad
// input (InputError, exit 2 on the command line); anything else is the environment failing.
[[noreturn]] void throw_sqlite(sqlite3* db, const std::string& where) {
  const int code = sqlite3_errcode(db) & 0xff;
  const std::string message = sqlite3_errmsg(db);
  if (code == SQLITE_NOTADB)
    throw InputError(where,
                     "not a morphex index (not an SQLite database, or its header is "
                     "damaged: " +
                         message + ")");
  if (code == SQLITE_CORRUPT)
    throw InputError(where, "the index is damaged (" + message +
                                "): restore it from a copy, or index the meshes again into a "
                                "new file");
  throw StorageError(where, "index database: " + message);
}

// A file name as an SQLite URI ("file:" and the path, percent-encoded), so that options such as
// immutable=1 can follow.
std::string sqlite_uri(const std::string& path) {
  std::string out = "file:";
  for (const unsigned char c : path) {
    if (std::isalnum(c) || std::strchr("/._-~", c)) {
      out += char(c);
    } else {
      char hex[4];
      std::snprintf(hex, sizeof hex, "%%%02X", c);
      out += hex;
    }
  }
  return out;
}

constexpr bool kBigEndian = __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__;

double byteswap(double d) {
  unsigned char bytes[8];
  std::memcpy(bytes, &d, 8);
  std::reverse(bytes, bytes + 8);
  std::memcpy(&d, bytes, 8);
  return d;
}

// A prepared statement that finalises itself.
class Statement {
 public:
  Statement(sqlite3* db, const std::string& where, const std::string& sql)
      : db_(db), where_(where) {
    if (sqlite3_prepare_v2(db, sql.c_str(), -1, &stmt_, nullptr) != SQLITE_OK)
      throw_sqlite(db, where);
  }
  ~Statement() { sqlite3_finalize(stmt_); }
  Statement& bind(int i, const std::string& v) {
    sqlite3_bind_text(stmt_, i, v.c_str(), int(v.size()), SQLITE_TRANSIENT);
    return *this;
  }
  Statement& bind(int i, double v) {
    sqlite3_bind_double(stmt_, i, v);
    return *this;
  }
  // Doubles as a BLOB of little-endian IEEE values: loading is a copy per vector, where JSON text
  // would need every number parsed, which dominated loading a large index.
  Statement& bind(int i, const std::vector<double>& v) {
    static_assert(sizeof(double) == 8 && std::numeric_limits<double>::is_iec559);
    if constexpr (kBigEndian) {
      std::vector<double> swapped(v);
      for (double& d : swapped) d = byteswap(d);
      sqlite3_bind_blob(stmt_, i, swapped.data(), int(swapped.size() * 8), SQLITE_TRANSIENT);
    } else {
      sqlite3_bind_blob(stmt_, i, v.data(), int(v.size() * 8), SQLITE_TRANSIENT);
    }
    return *this;
  }
  Statement& bind(int i, long long v) {
    sqlite3_bind_int64(stmt_, i, v);
    return *this;
  }
  bool step() {
    const int rc = sqlite3_step(stmt_);
    if (rc == SQLITE_ROW) return true;
    if (rc == SQLITE_DONE) return false;
    throw_sqlite(db_, where_);
  }
  std::string text(int col) const {
    const auto* t = sqlite3_column_text(stmt_, col);
    return t ? reinterpret_cast<const char*>(t) : "";
  }
  long long integer(int col) const { return sqlite3_column_int64(stmt_, col); }
  double real(int col) const { return sqlite3_column_double(stmt_, col); }
  // The vector of a column; a crafted or damaged one (not whole doubles, not finite) is refused:
  // NaN would rank first in every query.
  std::vector<double> doubles(int col, const std::string& what) const {
    std::vector<double> v;
    if (sqlite3_column_type(stmt_, col) != SQLITE_BLOB) {  // an index written as JSON text
      try {
        v = nlohmann::json::parse(text(col)).get<std::vector<double>>();
      } catch (const nlohmann::json::exception&) {
        throw InputError(where_, "the index is damaged: " + what + " is not a list of numbers");
      }
    } else {
      v = blob_doubles(col, what);
    }
    if (!std::all_of(v.begin(), v.end(), [](double d) { return std::isfinite(d); }))
      throw InputError(where_, "the index is damaged or crafted: " + what +
                                   " holds a value that is not a finite number");
    return v;
  }

 private:
  std::vector<double> blob_doubles(int col, const std::string& what) const {
    const std::size_t bytes = std::size_t(sqlite3_column_bytes(stmt_, col));
    if (bytes % 8 != 0)
      throw InputError(where_, "the index is damaged: " + what + " is not a vector of doubles");
    std::vector<double> v(bytes / 8);
    if (!v.empty()) std::memcpy(v.data(), sqlite3_column_blob(stmt_, col), v.size() * 8);
    if constexpr (kBigEndian)
      for (double& d : v) d = byteswap(d);
    return v;
  }

  sqlite3* db_;
  std::string where_;
  sqlite3_stmt* stmt_ = nullptr;
};

}  // namespace

IndexDb::IndexDb(const std::string& path, IndexAccess access) : path_(path), access_(access) {
  // A constructor that throws runs no destructor: the connection is closed here.
  try {
    open_checked(path, access);
  } catch (...) {
    sqlite3_close_v2(db_);
    db_ = nullptr;
    throw;
  }
}

void IndexDb::open_checked(const std::string& path, IndexAccess access) {
  std::error_code error;
  const bool exists = fs::exists(path, error);
  if (exists && !fs::is_regular_file(path, error))
    throw InputError(path, "not a morphex index (not a regular file)");
  const std::uintmax_t bytes = exists ? fs::file_size(path, error) : 0;
  if (access == IndexAccess::ReadOnly) {
    if (!exists) throw InputError(path, "no such index file");
    if (bytes == 0) throw InputError(path, "not a morphex index (an empty file)");
    // Another process closing the index as its last connection removes the write-ahead log and
    // its shared memory; a reader opening at that moment is told "busy" without waiting (SQLite's
    // busy handler does not cover recovery): tried again for a while.
    for (int attempt = 0;; ++attempt) {
      open(SQLITE_OPEN_READONLY | SQLITE_OPEN_URI, sqlite_uri(path));
      try {
        require_index();
        break;
      } catch (const std::runtime_error&) {
        const int code = sqlite3_errcode(db_) & 0xff;
        if ((code == SQLITE_BUSY || code == SQLITE_LOCKED) && attempt < 40) {
          std::this_thread::sleep_for(std::chrono::milliseconds(25));
          continue;
        }
        // A write-ahead-log index on read-only storage: SQLite cannot make the shared-memory
        // file that readers use. Nothing can write the file there, so it may be read as
        // immutable.
        if (code != SQLITE_CANTOPEN && code != SQLITE_READONLY) throw;
        open(SQLITE_OPEN_READONLY | SQLITE_OPEN_URI, sqlite_uri(path) + "?immutable=1");
        require_index();
        break;
      }
    }
    if (bytes <= kQuickCheckBytes) quick_check();
    sqlite3_busy_timeout(db_, 5000);
    return;
  }
  open(SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE | SQLITE_OPEN_URI, sqlite_uri(path));
  if (bytes > 0) {  // nothing is written into a file before it is known to be a sound index
    require_index();
    quick_check();
  }
  create_or_upgrade();
}

void IndexDb::open(int flags, const std::string& uri) {
  if (db_) sqlite3_close(db_);
  db_ = nullptr;
  if (sqlite3_open_v2(uri.c_str(), &db_, flags, nullptr) != SQLITE_OK) {
    const std::string message = db_ ? sqlite3_errmsg(db_) : "out of memory";
    sqlite3_close(db_);
    db_ = nullptr;
    throw StorageError(path_, "cannot open the index database: " + message);
  }
  sqlite3_busy_timeout(db_, 5000);
}

// The marker, or (indexes made before it) the tables and columns of a morphex index. An SQLite
// database without tables is accepted for writing only: it is a new index.
void IndexDb::require_index() {
  Statement application(db_, path_, "PRAGMA application_id");
  application.step();
  const long long id = application.integer(0);
  if (id != 0 && id != kIndexApplicationId)
    throw InputError(path_,
                     "not a morphex index (an SQLite database of another program, "
                     "application_id " +
                         std::to_string(id) + ")");
  Statement version(db_, path_, "PRAGMA user_version");
  version.step();
  if (version.integer(0) > kSchemaVersion)
    throw InputError(path_, "an index of a newer morphex (schema version " +
                                std::to_string(version.integer(0)) + "; this one reads up to " +
                                std::to_string(kSchemaVersion) + ")");
  Statement tables(db_, path_, "SELECT count(*) FROM sqlite_master WHERE name NOT LIKE 'sqlite_%'");
  tables.step();
  if (tables.integer(0) == 0) {
    if (access_ == IndexAccess::ReadWrite) return;
    throw InputError(path_, "not a morphex index (an SQLite database without tables)");
  }
  const std::pair<const char*, std::vector<const char*>> expected[] = {
      {"meta", {"key", "value"}},
      {"meshes",
       {"id", "name", "path", "hash", "settings", "status", "error", "faces", "volume", "seconds",
        "indexed_at"}},
      {"descriptors", {"mesh_id", "kind", "vector"}}};
  for (const auto& [table, columns] : expected) {
    Statement info(db_, path_, "SELECT name FROM pragma_table_info(?)");
    info.bind(1, std::string(table));
    std::set<std::string> found;
    while (info.step()) found.insert(info.text(0));
    for (const char* column : columns)
      if (!found.count(column))
        throw InputError(path_, std::string("not a morphex index (") +
                                    (found.empty() ? "no table '" + std::string(table) + "'"
                                                   : "its table '" + std::string(table) +
                                                         "' has no column '" + column + "'") +
                                    ")");
  }
}

// The file's b-trees and pages are sound: a damaged index is refused rather than read as garbage
// or written further.
void IndexDb::quick_check() {
  Statement check(db_, path_, "PRAGMA quick_check(3)");
  std::string problems;
  while (check.step())
    if (check.text(0) != "ok") problems += (problems.empty() ? "" : "; ") + check.text(0);
  if (!problems.empty())
    throw InputError(path_, "the index is damaged (" + problems +
                                "): restore it from a copy, or index the meshes again into a "
                                "new file");
}

void IndexDb::create_or_upgrade() {
  exec("PRAGMA foreign_keys = ON");
  exec("PRAGMA journal_mode = WAL");
  // Commits survive a killed process (the write-ahead log is in the file system); only a power
  // loss may drop the last few, which a re-run describes again. Full syncs made every commit of a
  // small mesh wait for the disk.
  exec("PRAGMA synchronous = NORMAL");
  // One transaction: another process opening the file at the same time sees no table or all.
  exec("BEGIN IMMEDIATE");
  try {
    exec("CREATE TABLE IF NOT EXISTS meta(key TEXT PRIMARY KEY, value TEXT NOT NULL)");
    exec(
        "CREATE TABLE IF NOT EXISTS meshes(id INTEGER PRIMARY KEY, name TEXT NOT NULL, "
        "path TEXT NOT NULL UNIQUE, hash TEXT NOT NULL, settings TEXT NOT NULL, "
        "status TEXT NOT NULL, error TEXT, faces INTEGER, volume TEXT, seconds REAL, "
        "indexed_at TEXT DEFAULT CURRENT_TIMESTAMP)");
    {
      // Indexes made before repairs were recorded lack the column.
      Statement columns(db_, path_,
                        "SELECT 1 FROM pragma_table_info('meshes') WHERE name = 'repair'");
      if (!columns.step()) exec("ALTER TABLE meshes ADD COLUMN repair TEXT");
    }
    exec(
        "CREATE TABLE IF NOT EXISTS descriptors(mesh_id INTEGER NOT NULL REFERENCES meshes(id) "
        "ON DELETE CASCADE, kind TEXT NOT NULL, vector TEXT NOT NULL, PRIMARY KEY(mesh_id, kind))");
    exec("PRAGMA application_id = " + std::to_string(kIndexApplicationId));
    exec("PRAGMA user_version = " + std::to_string(kSchemaVersion));
    exec("COMMIT");
  } catch (...) {
    sqlite3_exec(db_, "ROLLBACK", nullptr, nullptr, nullptr);
    throw;
  }
}

IndexDb::~IndexDb() {
  sqlite3_close(db_);
}

void IndexDb::exec(const std::string& sql) {
  if (sqlite3_exec(db_, sql.c_str(), nullptr, nullptr, nullptr) != SQLITE_OK)
    throw_sqlite(db_, path_);
}

std::optional<std::string> IndexDb::meta(const std::string& key) {
  Statement s(db_, path_, "SELECT value FROM meta WHERE key = ?");
  s.bind(1, key);
  if (s.step()) return s.text(0);
  return std::nullopt;
}

void IndexDb::set_meta(const std::string& key, const std::string& value) {
  Statement s(db_, path_,
              "INSERT INTO meta(key, value) VALUES(?, ?) "
              "ON CONFLICT(key) DO UPDATE SET value = excluded.value");
  s.bind(1, key).bind(2, value).step();
}

std::string IndexDb::status(const std::string& path, const std::string& hash,
                            const std::string& settings) {
  Statement s(db_, path_, "SELECT status FROM meshes WHERE path = ? AND hash = ? AND settings = ?");
  s.bind(1, path).bind(2, hash).bind(3, settings);
  return s.step() ? s.text(0) : "";
}

void IndexDb::store(const IndexedMesh& mesh) {
  exec("BEGIN IMMEDIATE");
  try {
    Statement upsert(db_, path_,
                     "INSERT INTO meshes(name, path, hash, settings, status, error, faces, volume, "
                     "seconds, repair) VALUES(?, ?, ?, ?, ?, ?, ?, ?, ?, NULLIF(?, '')) "
                     "ON CONFLICT(path) DO UPDATE SET "
                     "name = excluded.name, hash = excluded.hash, settings = excluded.settings, "
                     "status = excluded.status, error = excluded.error, faces = excluded.faces, "
                     "volume = excluded.volume, seconds = excluded.seconds, "
                     "repair = excluded.repair, indexed_at = CURRENT_TIMESTAMP");
    upsert.bind(1, mesh.name).bind(2, mesh.path).bind(3, mesh.hash).bind(4, mesh.settings);
    upsert.bind(5, mesh.status).bind(6, mesh.error).bind(7, (long long)mesh.faces);
    upsert.bind(8, mesh.volume).bind(9, mesh.seconds).bind(10, mesh.repair).step();
    Statement id(db_, path_, "SELECT id FROM meshes WHERE path = ?");
    id.bind(1, mesh.path).step();
    const long long mesh_id = id.integer(0);
    Statement clear(db_, path_, "DELETE FROM descriptors WHERE mesh_id = ?");
    clear.bind(1, mesh_id).step();
    for (const auto& [kind, vector] : mesh.descriptors) {
      Statement insert(db_, path_,
                       "INSERT INTO descriptors(mesh_id, kind, vector) VALUES(?, ?, ?)");
      insert.bind(1, mesh_id).bind(2, kind).bind(3, vector).step();
    }
    exec("COMMIT");
  } catch (...) {
    exec("ROLLBACK");
    throw;
  }
}

bool IndexDb::remove(const std::string& path) {
  Statement s(db_, path_, "DELETE FROM meshes WHERE path = ?");  // descriptors cascade
  s.bind(1, path).step();
  return sqlite3_changes(db_) > 0;
}

std::vector<IndexedMesh> IndexDb::load(bool only_ok, const std::vector<std::string>& kinds) {
  return load_rows(only_ok, -1, kinds);
}

std::optional<IndexedMesh> IndexDb::entry(long long id, bool with_descriptors) {
  if (id < 0) return std::nullopt;
  std::vector<IndexedMesh> rows = load_rows(
      false, id, with_descriptors ? std::vector<std::string>{"*"} : std::vector<std::string>{});
  if (rows.empty()) return std::nullopt;
  return std::move(rows.front());
}

std::vector<std::string> IndexDb::kinds() {
  std::vector<std::string> out;
  Statement s(db_, path_, "SELECT DISTINCT kind FROM descriptors ORDER BY kind");
  while (s.step()) out.push_back(s.text(0));
  return out;
}

// load() and entry(): every row (`id` < 0) or the row of `id`.
std::vector<IndexedMesh> IndexDb::load_rows(bool only_ok, long long id,
                                            const std::vector<std::string>& kinds) {
  std::vector<IndexedMesh> out;
  std::map<long long, std::size_t> position;
  std::string where = only_ok ? " WHERE status = 'ok'" : "";
  if (id >= 0) where += (where.empty() ? " WHERE" : " AND") + std::string(" id = ?");
  Statement meshes(db_, path_,
                   "SELECT id, name, path, hash, settings, status, error, repair, faces, volume, "
                   "seconds, indexed_at FROM meshes" +
                       where + " ORDER BY name, path");
  if (id >= 0) meshes.bind(1, id);
  while (meshes.step()) {
    IndexedMesh m;
    m.id = meshes.integer(0);
    m.name = meshes.text(1);
    m.path = meshes.text(2);
    m.hash = meshes.text(3);
    m.settings = meshes.text(4);
    m.status = meshes.text(5);
    m.error = meshes.text(6);
    m.repair = meshes.text(7);
    m.faces = std::size_t(meshes.integer(8));
    m.volume = meshes.text(9);
    m.seconds = meshes.real(10);
    m.indexed_at = meshes.text(11);
    position[m.id] = out.size();
    out.push_back(std::move(m));
  }
  for (const std::string& kind : kinds) {
    std::string filter = kind == "*" ? "" : " WHERE kind = ?";
    if (id >= 0) filter += (filter.empty() ? " WHERE" : " AND") + std::string(" mesh_id = ?");
    Statement descriptors(db_, path_, "SELECT mesh_id, kind, vector FROM descriptors" + filter);
    int next = 1;
    if (kind != "*") descriptors.bind(next++, kind);
    if (id >= 0) descriptors.bind(next, id);
    while (descriptors.step()) {
      const auto it = position.find(descriptors.integer(0));
      if (it == position.end()) continue;
      IndexedMesh& m = out[it->second];
      const std::string kind = descriptors.text(1);
      m.descriptors[kind] = descriptors.doubles(2, "the '" + kind + "' descriptor of " + m.name);
    }
  }
  return out;
}

namespace {

constexpr std::uint64_t kFnvOffset = 1469598103934665603ULL, kFnvPrime = 1099511628211ULL;

std::uint64_t fnv1a(std::uint64_t h, const char* bytes, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) {
    h ^= static_cast<unsigned char>(bytes[i]);
    h *= kFnvPrime;
  }
  return h;
}

std::string hex(std::uint64_t h) {
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(h));
  return text;
}

}  // namespace

std::string content_hash(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw StorageError(path, "cannot open");
  std::uint64_t h = kFnvOffset;
  char buffer[65536];
  while (in.read(buffer, sizeof buffer) || in.gcount() > 0)
    h = fnv1a(h, buffer, std::size_t(in.gcount()));
  return hex(h);
}

std::string text_hash(const std::string& text) {
  return hex(fnv1a(kFnvOffset, text.data(), text.size()));
}

}  // namespace morphex

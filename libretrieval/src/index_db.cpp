// SPDX-License-Identifier: GPL-3.0-or-later
#include "morphex/index_db.h"

#include <sqlite3.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <stdexcept>

namespace morphex {
namespace {

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
  Statement(sqlite3* db, const std::string& sql) : db_(db) {
    if (sqlite3_prepare_v2(db, sql.c_str(), -1, &stmt_, nullptr) != SQLITE_OK)
      throw std::runtime_error(std::string("index database: ") + sqlite3_errmsg(db));
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
  // Doubles as a BLOB of little-endian IEEE values: a million vectors load in a second, where
  // parsing JSON text took a minute.
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
    throw std::runtime_error(std::string("index database: ") + sqlite3_errmsg(db_));
  }
  std::string text(int col) const {
    const auto* t = sqlite3_column_text(stmt_, col);
    return t ? reinterpret_cast<const char*>(t) : "";
  }
  long long integer(int col) const { return sqlite3_column_int64(stmt_, col); }
  double real(int col) const { return sqlite3_column_double(stmt_, col); }
  std::vector<double> doubles(int col) const {
    if (sqlite3_column_type(stmt_, col) != SQLITE_BLOB)  // an index written as JSON text
      return nlohmann::json::parse(text(col)).get<std::vector<double>>();
    std::vector<double> v(std::size_t(sqlite3_column_bytes(stmt_, col)) / 8);
    if (!v.empty()) std::memcpy(v.data(), sqlite3_column_blob(stmt_, col), v.size() * 8);
    if constexpr (kBigEndian)
      for (double& d : v) d = byteswap(d);
    return v;
  }

 private:
  sqlite3* db_;
  sqlite3_stmt* stmt_ = nullptr;
};

}  // namespace

IndexDb::IndexDb(const std::string& path) : path_(path) {
  if (sqlite3_open(path.c_str(), &db_) != SQLITE_OK) {
    const std::string message = db_ ? sqlite3_errmsg(db_) : "out of memory";
    sqlite3_close(db_);
    throw std::runtime_error(path + ": cannot open the index database: " + message);
  }
  sqlite3_busy_timeout(db_, 5000);
  exec("PRAGMA foreign_keys = ON");
  exec("PRAGMA journal_mode = WAL");
  // Commits survive a killed process (the write-ahead log is in the file system); only a power
  // loss may drop the last few, which a re-run describes again. Full syncs made every commit of a
  // small mesh wait for the disk.
  exec("PRAGMA synchronous = NORMAL");
  exec("CREATE TABLE IF NOT EXISTS meta(key TEXT PRIMARY KEY, value TEXT NOT NULL)");
  exec(
      "CREATE TABLE IF NOT EXISTS meshes(id INTEGER PRIMARY KEY, name TEXT NOT NULL, "
      "path TEXT NOT NULL UNIQUE, hash TEXT NOT NULL, settings TEXT NOT NULL, "
      "status TEXT NOT NULL, error TEXT, faces INTEGER, volume TEXT, seconds REAL, "
      "indexed_at TEXT DEFAULT CURRENT_TIMESTAMP)");
  {
    // Indexes made before repairs were recorded lack the column.
    Statement columns(db_, "SELECT 1 FROM pragma_table_info('meshes') WHERE name = 'repair'");
    if (!columns.step()) exec("ALTER TABLE meshes ADD COLUMN repair TEXT");
  }
  exec(
      "CREATE TABLE IF NOT EXISTS descriptors(mesh_id INTEGER NOT NULL REFERENCES meshes(id) "
      "ON DELETE CASCADE, kind TEXT NOT NULL, vector TEXT NOT NULL, PRIMARY KEY(mesh_id, kind))");
}

IndexDb::~IndexDb() {
  sqlite3_close(db_);
}

void IndexDb::exec(const std::string& sql) {
  char* error = nullptr;
  if (sqlite3_exec(db_, sql.c_str(), nullptr, nullptr, &error) != SQLITE_OK) {
    const std::string message = error ? error : "unknown error";
    sqlite3_free(error);
    throw std::runtime_error(path_ + ": index database: " + message);
  }
}

std::optional<std::string> IndexDb::meta(const std::string& key) {
  Statement s(db_, "SELECT value FROM meta WHERE key = ?");
  s.bind(1, key);
  if (s.step()) return s.text(0);
  return std::nullopt;
}

void IndexDb::set_meta(const std::string& key, const std::string& value) {
  Statement s(db_,
              "INSERT INTO meta(key, value) VALUES(?, ?) "
              "ON CONFLICT(key) DO UPDATE SET value = excluded.value");
  s.bind(1, key).bind(2, value).step();
}

std::string IndexDb::status(const std::string& path, const std::string& hash,
                            const std::string& settings) {
  Statement s(db_, "SELECT status FROM meshes WHERE path = ? AND hash = ? AND settings = ?");
  s.bind(1, path).bind(2, hash).bind(3, settings);
  return s.step() ? s.text(0) : "";
}

void IndexDb::store(const IndexedMesh& mesh) {
  exec("BEGIN IMMEDIATE");
  try {
    Statement upsert(db_,
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
    Statement id(db_, "SELECT id FROM meshes WHERE path = ?");
    id.bind(1, mesh.path).step();
    const long long mesh_id = id.integer(0);
    Statement clear(db_, "DELETE FROM descriptors WHERE mesh_id = ?");
    clear.bind(1, mesh_id).step();
    for (const auto& [kind, vector] : mesh.descriptors) {
      Statement insert(db_, "INSERT INTO descriptors(mesh_id, kind, vector) VALUES(?, ?, ?)");
      insert.bind(1, mesh_id).bind(2, kind).bind(3, vector).step();
    }
    exec("COMMIT");
  } catch (...) {
    exec("ROLLBACK");
    throw;
  }
}

bool IndexDb::remove(const std::string& path) {
  Statement s(db_, "DELETE FROM meshes WHERE path = ?");  // descriptors cascade
  s.bind(1, path).step();
  return sqlite3_changes(db_) > 0;
}

std::vector<IndexedMesh> IndexDb::load(bool only_ok, const std::vector<std::string>& kinds) {
  std::vector<IndexedMesh> out;
  std::map<long long, std::size_t> position;
  Statement meshes(db_, std::string("SELECT id, name, path, hash, settings, status, error, "
                                    "repair, faces, volume, seconds, indexed_at FROM meshes") +
                            (only_ok ? " WHERE status = 'ok'" : "") + " ORDER BY name, path");
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
    Statement descriptors(db_, std::string("SELECT mesh_id, kind, vector FROM descriptors") +
                                   (kind == "*" ? "" : " WHERE kind = ?"));
    if (kind != "*") descriptors.bind(1, kind);
    while (descriptors.step()) {
      const auto it = position.find(descriptors.integer(0));
      if (it != position.end())
        out[it->second].descriptors[descriptors.text(1)] = descriptors.doubles(2);
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
  if (!in) throw std::runtime_error(path + ": cannot open");
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

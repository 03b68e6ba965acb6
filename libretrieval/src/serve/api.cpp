// SPDX-License-Identifier: GPL-3.0-or-later
#include "api.h"

#include <stdlib.h>
#include <sys/stat.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "morphex/descriptors.h"
#include "morphex/internal/stopwatch.h"
#include "morphex/io.h"
#include "morphex/pipeline.h"
#include "morphex/retrieval.h"
#include "morphex/retrieval_json.h"
#include "thumbnail.h"

namespace morphex::serve {
namespace {

namespace fs = std::filesystem;
namespace mp = morphex::pipeline;

constexpr std::size_t kMaxNeighbours = 1000;

// A private folder for one upload (mkdtemp: mode 0700, a fresh name), removed with its content
// when the query is answered or refused.
class TemporaryFolder {
 public:
  TemporaryFolder() {
    std::string pattern = (fs::temp_directory_path() / "morphex-upload-XXXXXX").string();
    if (!mkdtemp(pattern.data()))
      throw StorageError("", "cannot make a temporary folder for the upload");
    path_ = pattern;
  }
  ~TemporaryFolder() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  TemporaryFolder(const TemporaryFolder&) = delete;
  TemporaryFolder& operator=(const TemporaryFolder&) = delete;
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

std::string lower(std::string text) {
  for (char& c : text) c = char(std::tolower(static_cast<unsigned char>(c)));
  return text;
}

bool ends_with(const std::string& text, const std::string& end) {
  return text.size() >= end.size() && text.compare(text.size() - end.size(), end.size(), end) == 0;
}

std::string replace_all(std::string text, const std::string& from, const std::string& to) {
  if (from.empty()) return text;
  for (std::size_t at = text.find(from); at != std::string::npos;
       at = text.find(from, at + to.size()))
    text.replace(at, from.size(), to);
  return text;
}

// The uploaded file's name as messages show it: its last path component, without control
// characters, at most 120 characters.
std::string shown_name(const std::string& filename) {
  std::string name = filename.substr(filename.find_last_of("/\\") + 1), out;
  for (const char c : name)
    if (static_cast<unsigned char>(c) >= 0x20 && c != 0x7f) out += c;
  if (out.size() > 120) out = out.substr(0, 120);
  return out.empty() || out == "." || out == ".." ? "upload" : out;
}

// The mesh formats an upload may have, by the extension of its name (".off", or ".off.gz" for a
// compressed one): the name chooses the reader and nothing else.
std::string upload_suffix(const std::string& name) {
  const std::string lowered = lower(name);
  const bool gz = ends_with(lowered, ".gz");
  const std::string inner = gz ? lowered.substr(0, lowered.size() - 3) : lowered;
  std::vector<std::string> known = {".off", ".obj", ".stl", ".ply"};
  if (format_available(MeshFormat::ThreeMf)) known.push_back(".3mf");
  for (const std::string& ext : known)
    if (ends_with(inner, ext)) return ext + (gz ? ".gz" : "");
  std::string list;
  for (const std::string& ext : known) list += (list.empty() ? "" : ", ") + ext;
  throw RequestError(415, name + ": not a mesh file name (expected " + list +
                              ", optionally gzip-compressed as .gz)");
}

std::size_t parse_count(const std::string& text, const char* what, std::size_t most) {
  if (text.empty() || text.size() > 9 || text.find_first_not_of("0123456789") != std::string::npos)
    throw RequestError(400, std::string(what) + ": expected a whole number, got '" + text + "'");
  const std::size_t value = std::stoul(text);
  if (value < 1 || value > most)
    throw RequestError(
        400, std::string(what) + ": expected 1 to " + std::to_string(most) + ", got " + text);
  return value;
}

long long parse_id(const std::string& text) {
  if (text.empty() || text.size() > 18 || text.find_first_not_of("0123456789") != std::string::npos)
    throw RequestError(400, "id: expected a mesh id (a whole number), got '" + text + "'");
  return std::stoll(text);
}

struct QueryArgs {
  std::size_t k = 10;
  std::string kind = default_descriptor_kind(), metric = "l1";
};

QueryArgs query_args(const Params& params) {
  QueryArgs q;
  if (const auto k = params.find("k"); k != params.end())
    q.k = parse_count(k->second, "k", kMaxNeighbours);
  if (const auto kind = params.find("kind"); kind != params.end()) q.kind = kind->second;
  const std::vector<std::string> kinds = descriptor_kinds();
  if (std::find(kinds.begin(), kinds.end(), q.kind) == kinds.end())
    throw RequestError(400, "kind: unknown descriptor '" + q.kind + "'");
  if (const auto metric = params.find("metric"); metric != params.end()) q.metric = metric->second;
  if (q.metric != "l1" && q.metric != "l2" && q.metric != "chi2")
    throw RequestError(400, "metric: expected l1, l2 or chi2, got '" + q.metric + "'");
  return q;
}

std::string base64(const std::string& bytes) {
  static const char digits[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::size_t n = std::min<std::size_t>(3, bytes.size() - i);
    std::uint32_t group = 0;
    for (std::size_t k = 0; k < 3; ++k)
      group = (group << 8) | (k < n ? static_cast<unsigned char>(bytes[i + k]) : 0u);
    for (std::size_t k = 0; k < 4; ++k) out += k <= n ? digits[(group >> (18 - 6 * k)) & 63] : '=';
  }
  return out;
}

std::string render_glb(const std::string& file) {
  WriteOptions options;
  options.provenance = "morphex serve";
  std::ostringstream out;
  write_mesh(read_mesh(file), out, MeshFormat::Glb, options);
  return std::move(out).str();
}

std::string render_png(const std::string& file) {
  return encode_png(render_thumbnail(to_double(read_mesh(file))));
}

// The exact volume as recorded ("num/den") as the nearest double; null when unknown.
nlohmann::json decimal(const std::string& exact) {
  if (exact.empty()) return nullptr;
  try {
    const double value = CGAL::to_double(parse_exact_number(exact));
    return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
  } catch (const std::exception&) {
    return nullptr;
  }
}

// r_k = from * (to / from)^(k / (n - 1)): the radii of descriptors.h, in units of T (openings)
// or L (closings).
std::vector<double> geometric_radii(double from, double to, int n) {
  std::vector<double> out;
  for (int k = 0; k < n; ++k)
    out.push_back(n == 1 ? from : from * std::pow(to / from, double(k) / double(n - 1)));
  return out;
}

// The settings of the last describe stage of the index's stored pipeline (read by the library's
// table, as the stage reads them); none when the stored pipeline is not one morphex would run.
std::optional<DescriptorSettings> stored_settings(const std::string& document,
                                                  const std::string& sets) {
  try {
    const nlohmann::json doc = nlohmann::json::parse(document);
    mp::Variables variables;
    if (!sets.empty()) variables = nlohmann::json::parse(sets).get<mp::Variables>();
    require_descriptor_pipeline(doc);
    const mp::Pipeline p = mp::validate(doc, "stored pipeline", variables, {"input", "stem"});
    for (auto s = p.stages.rbegin(); s != p.stages.rend(); ++s)
      if (s->type == "describe") return mp::descriptor_settings(*s);
  } catch (const std::exception&) {
  }
  return std::nullopt;
}

}  // namespace

std::optional<std::string> ByteCache::find(const std::string& key) {
  std::lock_guard<std::mutex> lock(mutex_);
  const auto it = entries_.find(key);
  if (it == entries_.end()) return std::nullopt;
  return it->second;
}

void ByteCache::put(const std::string& key, const std::string& bytes) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (bytes.size() > capacity_ / 4) return;  // one huge mesh would evict everything
  if (size_ + bytes.size() > capacity_) {
    entries_.clear();
    size_ = 0;
  }
  if (entries_.emplace(key, bytes).second) size_ += bytes.size();
}

IndexApi::IndexApi(const std::string& index_path, const ServerOptions& options)
    : options_(options), db_(index_path, IndexAccess::ReadOnly), cache_(options.cache_bytes) {
  if (!options_.labels.empty()) labels_ = read_cla(options_.labels);
}

std::string IndexApi::label(const std::string& name) const {
  const auto it = labels_.find(name);
  return it == labels_.end() ? "" : it->second;
}

std::size_t IndexApi::count(bool failed) {
  std::lock_guard<std::mutex> lock(db_mutex_);
  std::size_t n = 0;
  for (const IndexedMesh& m : db_.load(false, {})) n += (m.status != "ok") == failed;
  return n;
}

nlohmann::json IndexApi::info() {
  std::vector<std::string> stored;
  {
    std::lock_guard<std::mutex> lock(db_mutex_);
    stored = db_.kinds();
  }
  nlohmann::json kinds = nlohmann::json::array();
  for (const std::string& kind : descriptor_kinds())  // in the order of the command line's help
    if (std::find(stored.begin(), stored.end(), kind) != stored.end()) kinds.push_back(kind);
  std::vector<std::string> formats = {".off", ".obj", ".stl", ".ply"};
  if (format_available(MeshFormat::ThreeMf)) formats.push_back(".3mf");
  return {{"index", fs::path(db_.path()).filename().string()},
          {"version", version()},
          {"meshes", count(false)},
          {"failed", count(true)},
          {"kinds", kinds},
          {"default_kind", default_descriptor_kind()},
          {"metrics", {"l1", "l2", "chi2"}},
          {"default_metric", "l1"},
          {"max_neighbours", kMaxNeighbours},
          {"max_upload_bytes", options_.max_upload_bytes},
          {"formats", formats},
          {"labels", !labels_.empty()},
          {"read_only", true},
          {"view", kViewDirection}};
}

nlohmann::json IndexApi::meshes() {
  std::vector<IndexedMesh> rows;
  {
    std::lock_guard<std::mutex> lock(db_mutex_);
    rows = db_.load(true, {});
  }
  nlohmann::json out = nlohmann::json::array();
  for (const IndexedMesh& m : rows)
    out.push_back({{"id", m.id},
                   {"name", m.name},
                   {"class", label(m.name)},
                   {"faces", m.faces},
                   {"repaired", !m.repair.empty()}});
  return out;
}

nlohmann::json IndexApi::failures() {
  std::vector<IndexedMesh> rows;
  {
    std::lock_guard<std::mutex> lock(db_mutex_);
    rows = db_.load(false, {});
  }
  nlohmann::json out = nlohmann::json::array();
  for (const IndexedMesh& m : rows)
    if (m.status != "ok")
      out.push_back({{"id", m.id},
                     {"name", m.name},
                     {"class", label(m.name)},
                     {"path", m.path},
                     {"error", m.error},
                     {"readable", !m.hash.empty()}});
  return out;
}

IndexedMesh IndexApi::row(long long id, bool with_descriptors) {
  std::lock_guard<std::mutex> lock(db_mutex_);
  std::optional<IndexedMesh> m = db_.entry(id, with_descriptors);
  if (!m) throw RequestError(404, "no indexed mesh has the id " + std::to_string(id));
  return std::move(*m);
}

nlohmann::json IndexApi::curves(const std::map<std::string, std::vector<double>>& descriptors) {
  const auto g = descriptors.find("granulometry");
  if (g == descriptors.end()) return nullptr;
  std::optional<DescriptorSettings> settings;
  {
    std::lock_guard<std::mutex> lock(db_mutex_);
    settings = stored_settings(db_.meta("pipeline").value_or(kDefaultIndexPipeline),
                               db_.meta("sets").value_or(""));
  }
  const auto spectrum = descriptors.find("pattern_spectrum");
  int n = 0;
  bool closings = false;
  if (settings) {
    n = settings->scales;
    closings = settings->closings;
  } else if (spectrum != descriptors.end()) {  // unknown settings: the lengths tell
    n = int(spectrum->second.size());
    closings = g->second.size() == 2 * spectrum->second.size();
  }
  if (n <= 0 || g->second.size() != std::size_t(n) * (closings ? 2 : 1)) return nullptr;
  nlohmann::json out;
  out["granulometry"] = std::vector<double>(g->second.begin(), g->second.begin() + n);
  if (closings)
    out["anti_granulometry"] = std::vector<double>(g->second.begin() + n, g->second.end());
  if (spectrum != descriptors.end() && spectrum->second.size() == std::size_t(n))
    out["pattern_spectrum"] = spectrum->second;
  if (settings) {
    out["open_radii"] = geometric_radii(settings->open_from, settings->open_to, n);
    if (closings) out["close_radii"] = geometric_radii(settings->close_from, settings->close_to, n);
  }
  return out;
}

nlohmann::json IndexApi::mesh(long long id) {
  const IndexedMesh m = row(id, true);
  // The library's entry (morphex/retrieval_json.h) as the page reads it: with its id, class and
  // curves, the volume as a decimal beside the exact one, without the hash and the settings.
  nlohmann::json out = m;
  for (const char* internal : {"hash", "settings", "settings_id"}) out.erase(internal);
  out["id"] = m.id;
  out["class"] = label(m.name);
  out["volume"] = decimal(m.volume);
  out["volume_exact"] = m.volume;
  out["curves"] = curves(m.descriptors);
  return out;
}

// The recorded file of an indexed mesh, only while its content is what was indexed: the server
// never opens a path that a request gives, and shows no other mesh under an indexed one's name.
std::string IndexApi::mesh_file(const IndexedMesh& m) {
  if (m.hash.empty())
    throw RequestError(404, m.name + ": its file could not be read when it was indexed");
  std::error_code error;
  if (!fs::is_regular_file(m.path, error))
    throw RequestError(404, m.name + ": its file " + m.path + " is not there any more");
  std::string hash;
  try {
    hash = content_hash(m.path);
  } catch (const std::exception&) {
    throw RequestError(404, m.name + ": its file " + m.path + " cannot be read");
  }
  if (hash != m.hash)
    throw RequestError(409, m.name + ": " + m.path +
                                " changed since it was indexed; index it again (morphex index)");
  return m.path;
}

std::string IndexApi::cached(const std::string& what, const IndexedMesh& m,
                             std::string (*render)(const std::string& file)) {
  struct stat st {};
  if (::stat(m.path.c_str(), &st) == 0) {
    const std::string key = what + "|" + m.path + "|" + m.hash + "|" + std::to_string(st.st_size) +
                            "|" + std::to_string(st.st_mtim.tv_sec) + "." +
                            std::to_string(st.st_mtim.tv_nsec);
    if (auto hit = cache_.find(key)) return std::move(*hit);
    std::string bytes;
    const std::string file = mesh_file(m);
    try {
      bytes = render(file);
    } catch (const InputError& e) {
      throw RequestError(422, e.what());
    } catch (const LossyOutputError& e) {
      throw RequestError(422, m.name + ": " + e.what());
    }
    cache_.put(key, bytes);
    return bytes;
  }
  mesh_file(m);  // says why the file is missing
  throw RequestError(404, m.name + ": its file " + m.path + " is not there any more");
}

std::string IndexApi::glb(long long id) {
  return cached("glb", row(id, false), render_glb);
}

std::string IndexApi::thumbnail(long long id) {
  return cached("png", row(id, false), render_png);
}

nlohmann::json IndexApi::neighbours_json(const std::vector<Neighbour>& ranked) {
  nlohmann::json out = nlohmann::json::array();
  for (std::size_t i = 0; i < ranked.size(); ++i)
    out.push_back({{"rank", i + 1},
                   {"id", ranked[i].id},
                   {"name", ranked[i].name},
                   {"class", label(ranked[i].name)},
                   {"distance", ranked[i].distance}});
  return out;
}

nlohmann::json IndexApi::query_indexed(const Params& params) {
  const QueryArgs q = query_args(params);
  IndexedMesh target;
  if (const auto id = params.find("id"); id != params.end()) {
    target = row(parse_id(id->second), false);
  } else if (const auto name = params.find("name"); name != params.end()) {
    std::vector<IndexedMesh> named;
    {
      std::lock_guard<std::mutex> lock(db_mutex_);
      for (IndexedMesh& m : db_.load(false, {}))
        if (m.name == name->second) named.push_back(std::move(m));
    }
    if (named.empty()) throw RequestError(404, name->second + ": no indexed mesh has this name");
    if (named.size() > 1)
      throw RequestError(400, name->second + ": " + std::to_string(named.size()) +
                                  " indexed meshes have this name; ask by id");
    target = std::move(named.front());
  } else {
    throw RequestError(400, "expected ?name=NAME or ?id=ID of an indexed mesh");
  }
  if (target.status != "ok")
    throw RequestError(422, target.name + " failed when it was indexed: " + target.error);
  const Stopwatch clock;
  std::vector<Neighbour> ranked;
  {
    // The query of `morphex query --db INDEX MESH`, the mesh named by its recorded path.
    std::lock_guard<std::mutex> lock(db_mutex_);
    try {
      ranked = query_index(db_, target.path, q.k, q.kind, parse_metric(q.metric), true);
    } catch (const InputError& e) {
      throw RequestError(409, e.what());  // the index cannot answer (mixed settings, old kinds)
    }
  }
  return {{"query", {{"id", target.id}, {"name", target.name}, {"class", label(target.name)}}},
          {"kind", q.kind},
          {"metric", q.metric},
          {"k", q.k},
          {"neighbours", neighbours_json(ranked)},
          {"seconds", clock.seconds()}};
}

nlohmann::json IndexApi::query_upload(const std::string& filename, const std::string& content,
                                      const Params& params) {
  const QueryArgs q = query_args(params);
  if (content.size() > options_.max_upload_bytes)
    throw RequestError(413, "the upload is larger than the limit of " +
                                std::to_string(options_.max_upload_bytes) +
                                " bytes (morphex serve --max-upload-mb)");
  const std::string shown = shown_name(filename);
  const std::string suffix = upload_suffix(shown);
  if (content.empty()) throw RequestError(400, shown + ": the upload is empty");
  std::unique_lock<std::mutex> busy(describe_mutex_, std::try_to_lock);
  if (!busy.owns_lock())
    throw RequestError(503, "another upload is being described; try again in a moment");
  const Stopwatch clock;
  TemporaryFolder folder;
  // A fixed name: the uploaded name chose the suffix from the whitelist, and nothing else.
  const std::string file = (folder.path() / ("query" + suffix)).string();
  {
    std::ofstream out(file, std::ios::binary);
    out.write(content.data(), std::streamsize(content.size()));
    if (!out.flush()) throw StorageError("", "cannot write the upload to a temporary folder");
  }
  IndexPipeline pipeline;
  {
    std::lock_guard<std::mutex> lock(db_mutex_);
    try {
      pipeline = query_pipeline(db_);
    } catch (const InputError& e) {
      throw RequestError(409, e.what());
    }
  }
  std::map<std::string, std::vector<double>> descriptors;
  try {
    descriptors = describe_query(pipeline, file);  // without the lock: it may take a while
  } catch (const InputError& e) {
    // Messages name the temporary file: name the upload instead.
    throw RequestError(
        422, replace_all(replace_all(e.what(), file, shown), folder.path().string(), "upload"));
  }
  if (!descriptors.count(q.kind))
    throw RequestError(422, "the index's pipeline gives no '" + q.kind + "' descriptor");
  std::vector<Neighbour> ranked;
  {
    std::lock_guard<std::mutex> lock(db_mutex_);
    ranked = rank_index(db_, descriptors.at(q.kind), q.k, q.kind, parse_metric(q.metric));
  }
  nlohmann::json out = {{"query", {{"name", shown}, {"upload", true}}},
                        {"kind", q.kind},
                        {"metric", q.metric},
                        {"k", q.k},
                        {"neighbours", neighbours_json(ranked)},
                        {"curves", curves(descriptors)}};
  try {
    out["query"]["thumbnail"] = "data:image/png;base64," + base64(render_png(file));
  } catch (const std::exception&) {
    // The ranking stands without a picture.
  }
  out["seconds"] = clock.seconds();
  return out;
}

}  // namespace morphex::serve

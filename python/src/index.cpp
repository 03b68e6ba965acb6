// SPDX-License-Identifier: GPL-3.0-or-later
// morphex.Index: the retrieval index of libretrieval (morphex/index.h), as `morphex index`,
// `query` and `evaluate` use it, so that an index built from Python can be queried by the command
// line and back. What is Python's own: meshes given as Mesh objects (written to a temporary exact
// OFF file, since pipelines read files) and the conversion of arguments and results.
#include <stdlib.h>
#include <cerrno>
#include <cstring>

#include <algorithm>
#include <filesystem>
#include <memory>
#include <mutex>

#include "common.h"
#include "morphex/descriptors.h"
#include "morphex/index.h"
#include "morphex/io.h"
#include "morphex/pipeline.h"
#include "morphex/retrieval.h"
#include "morphex/retrieval_json.h"

namespace morphex::python {
namespace {

namespace mp = morphex::pipeline;
namespace fs = std::filesystem;

// A temporary directory for meshes given as Mesh objects (the pipelines read files), removed with
// everything in it.
class TemporaryDirectory {
 public:
  TemporaryDirectory() {
    std::string pattern = (fs::temp_directory_path() / "morphex-python-XXXXXX").string();
    if (!mkdtemp(pattern.data()))
      throw StorageError(
          "", std::string("cannot create a temporary directory: ") + std::strerror(errno));
    path_ = pattern;
  }
  ~TemporaryDirectory() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  // Writes the mesh exactly as <dir>/<name>.off, so that ${stem} is the name.
  std::string write(const Mesh& mesh, const std::string& name) const {
    if (name.empty() || name.find('/') != std::string::npos)
      throw InputError("", "name: expected a non-empty name without '/', got '" + name + "'");
    const std::string path = (path_ / (name + ".off")).string();
    WriteOptions exact;
    exact.exact = true;
    write_mesh(mesh, path, exact);
    return path;
  }

 private:
  fs::path path_;
};

std::string pipeline_problems(const std::string& name, const mp::PipelineError& e) {
  std::string message;
  for (const mp::Problem& p : e.problems())
    message += (message.empty() ? "" : "\n") + name + ": " + p.text();
  return message;
}

// Safe to share between Python threads: every use of the database holds `mutex_` (SQLite's
// transactions are per connection, so two threads adding at once would nest them), and close()
// waits for a running call. The GIL is released while waiting for the mutex, since the holder may
// need the GIL to finish.
class Index {
 public:
  explicit Index(const py::object& path) : path_(to_path(path)) {
    db_ = std::make_unique<IndexDb>(path_);
  }
  ~Index() {
    std::optional<py::gil_scoped_release> release;
    if (PyGILState_Check()) release.emplace();
    std::lock_guard<std::mutex> held(mutex_);
    db_.reset();
  }

  py::dict add(const py::object& items, const py::object& name,
               const std::optional<std::vector<std::string>>& names, const py::object& pipeline,
               const std::map<std::string, std::string>& variables, bool repair, bool retry_failed,
               const std::optional<int>& threads);
  py::list query(const py::object& target, std::size_t k, const std::string& descriptor,
                 const std::string& metric, const std::optional<int>& threads);
  py::dict evaluate(const py::object& labels, const std::string& metric);

  std::vector<IndexedMesh> load(bool only_ok = true,
                                const std::vector<std::string>& kinds = {"*"}) {
    const auto held = lock();
    py::gil_scoped_release release;
    return db().load(only_ok, kinds);
  }
  std::size_t remove(const std::vector<std::string>& keys) {
    const auto held = lock();
    py::gil_scoped_release release;
    return remove_indexed(db(), keys);
  }
  const std::string& path() const { return path_; }
  void close() {
    const auto held = lock();
    db_.reset();
  }

 private:
  std::unique_lock<std::mutex> lock() {
    py::gil_scoped_release release;
    return std::unique_lock<std::mutex>(mutex_);
  }
  IndexDb& db() {
    if (!db_) throw InputError("", path_ + ": the index is closed");
    return *db_;
  }
  IndexPipeline pipeline(const py::object& pipeline, const mp::Variables& variables, bool repair);
  std::vector<IndexItem> items(const py::object& items, std::vector<std::string> names, bool named,
                               const TemporaryDirectory& temp);

  std::string path_;
  std::mutex mutex_;
  std::unique_ptr<IndexDb> db_;
};

// The descriptor pipeline (default, dict, JSON text or file), with repairs, validated.
IndexPipeline Index::pipeline(const py::object& pipeline, const mp::Variables& variables,
                              bool repair) {
  std::string name = "<pipeline>";
  std::optional<nlohmann::json> doc;
  try {
    if (pipeline.is_none()) {
      name = "default";
    } else if (py::isinstance<py::dict>(pipeline) || py::isinstance<py::list>(pipeline)) {
      doc = to_json(pipeline);
    } else if (py::isinstance<py::str>(pipeline) &&
               pipeline.cast<std::string>().find_first_of("{[") == 0) {
      doc = mp::parse_document(pipeline.cast<std::string>(), name);
    } else {
      name = to_path(pipeline);
      doc = mp::load_document(name);
    }
    return make_index_pipeline(doc ? &*doc : nullptr, name, variables, repair);
  } catch (const mp::PipelineError& e) {
    throw InputError("", pipeline_problems(name, e));
  }
}

// Paths and Mesh objects (one, or an iterable of them). A Mesh is written to `temp` and recorded
// as "mesh:<name>": its name is the one given (`names`, one per item, when `named`), else the
// stem of the file it was read from.
std::vector<IndexItem> Index::items(const py::object& objects, std::vector<std::string> names,
                                    bool named, const TemporaryDirectory& temp) {
  const bool single = py::isinstance<PyMesh>(objects) || py::isinstance<py::str>(objects) ||
                      py::hasattr(objects, "__fspath__");
  std::vector<py::handle> list;
  if (single)
    list.push_back(objects);
  else
    for (const py::handle& h : objects) list.push_back(h);
  if (named && names.size() != list.size())
    throw InputError("", "names: expected one name per mesh, got " + std::to_string(names.size()) +
                             " names for " + std::to_string(list.size()) + " meshes");
  std::vector<IndexItem> out;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const py::handle h = list[i];
    if (py::isinstance<PyMesh>(h)) {
      const PyMesh& m = h.cast<const PyMesh&>();
      const std::string n = named ? names[i] : fs::path(m.source).stem().string();
      if (n.empty())
        throw InputError(
            "",
            "a Mesh not read from a file needs a name (name= for one mesh, names= for several)");
      out.push_back({temp.write(m.mesh(), n), "mesh:" + n, n});
    } else {
      IndexItem item = index_item(to_path(h));  // recorded by absolute path, as `morphex index`
      if (named) item.name = names[i];
      out.push_back(item);
    }
  }
  return out;
}

py::dict Index::add(const py::object& objects, const py::object& name,
                    const std::optional<std::vector<std::string>>& names,
                    const py::object& pipeline_arg,
                    const std::map<std::string, std::string>& variables, bool repair,
                    bool retry_failed, const std::optional<int>& threads) {
  const IndexPipeline pipeline = this->pipeline(pipeline_arg, variables, repair);
  // name= is one name, or (as names=) a list of names for a list of meshes.
  std::vector<std::string> given;
  if (!name.is_none() && names) throw InputError("", "give name= or names=, not both");
  if (names)
    given = *names;
  else if (py::isinstance<py::str>(name))
    given = {name.cast<std::string>()};
  else if (!name.is_none())
    given = name.cast<std::vector<std::string>>();
  TemporaryDirectory temp;
  const std::vector<IndexItem> list = items(objects, given, !name.is_none() || names, temp);
  IndexSummary summary;
  const auto held = lock();
  {
    py::gil_scoped_release release;
    ThreadLimit limit(threads);
    try {
      IndexOptions options;
      options.retry_failed = retry_failed;
      summary = index_meshes(db(), pipeline, list, {}, options);
    } catch (const mp::PipelineError& e) {
      throw InputError("", pipeline_problems(pipeline.name, e));
    }
  }
  // The library's summary, its errors as {path: message} (a path is indexed once per call).
  const nlohmann::json j = summary;
  py::dict out;
  for (const char* key : {"indexed", "skipped", "skipped_failed", "failed"})
    out[key] = from_json(j.at(key));
  out["errors"] = std::map<std::string, std::string>(summary.errors.begin(), summary.errors.end());
  return out;
}

py::list Index::query(const py::object& target, std::size_t k, const std::string& descriptor,
                      const std::string& metric_name, const std::optional<int>& threads) {
  const std::vector<std::string> kinds = descriptor_kinds();
  if (std::find(kinds.begin(), kinds.end(), descriptor) == kinds.end()) {
    std::string known;
    for (const std::string& kind : kinds) known += (known.empty() ? "" : ", ") + kind;
    throw InputError("", "descriptor: expected one of " + known + ", got '" + descriptor + "'");
  }
  const Metric metric = parse_metric(metric_name);
  TemporaryDirectory temp;
  // A Mesh is described from a temporary file; a path that is not a file but names an indexed
  // mesh (its name or recorded path) takes the stored vector, and that mesh is not ranked.
  std::string file, label;
  const bool is_mesh = py::isinstance<PyMesh>(target);
  if (is_mesh) {
    const PyMesh& m = target.cast<const PyMesh&>();
    const std::string stem = fs::path(m.source).stem().string();
    file = temp.write(m.mesh(), stem.empty() ? "query" : stem);
    label = m.source.empty() ? "query mesh" : m.source;
  } else {
    file = label = to_path(target);
  }
  std::vector<Neighbour> ranked;
  const auto held = lock();
  {
    py::gil_scoped_release release;
    ThreadLimit limit(threads);
    try {
      ranked = query_index(db(), file, k, descriptor, metric, !is_mesh);
    } catch (const InputError& e) {
      if (!is_mesh) throw;
      // A Mesh is described from a temporary file: name the mesh, not the file.
      const std::string what = e.what();
      throw InputError(label, what.substr(e.where().empty() ? 0 : e.where().size() + 2));
    }
  }
  py::list out;
  for (const Neighbour& n : ranked) out.append(py::make_tuple(n.name, n.distance));
  return out;
}

py::dict Index::evaluate(const py::object& labels_arg, const std::string& metric_name) {
  const Metric metric = parse_metric(metric_name);
  std::map<std::string, std::string> labels =
      py::isinstance<py::dict>(labels_arg)
          ? labels_arg.cast<std::map<std::string, std::string>>()
          : read_cla(to_path(labels_arg));  // InputError names the file and line
  py::dict out;
  IndexEvaluation evaluation;
  const auto held = lock();
  {
    py::gil_scoped_release release;
    evaluation = evaluate_index(db(), labels, metric);
  }
  for (std::size_t k = 0; k < evaluation.scores.size(); ++k)
    out[evaluation.scores[k].first.c_str()] =
        evaluation_dict(evaluation.scores[k].second, evaluation.per_class[k].second,
                        evaluation.precision_recall[k].second);
  return out;
}

py::dict stored_descriptors(Index& index, const std::string& name) {
  for (const IndexedMesh& m : index.load())
    if (m.name == name || m.path == name) {
      py::dict out;
      for (const auto& [kind, v] : m.descriptors) out[kind.c_str()] = to_numpy(v);
      return out;
    }
  throw py::key_error(name);
}

}  // namespace

void register_index(py::module_& m) {
  py::class_<Index>(m, "Index", R"doc(
The SQLite retrieval index of `morphex index` (same file format: the command line can query an
index built here and back). Index(path) opens it, creating it if missing; a file that is not a
morphex index, or is damaged, raises ValueError. A context manager. Safe to share between
threads: calls are serialised, and close() waits for a running call.)doc")
      .def(py::init<const py::object&>(), py::arg("path"))
      .def("add", &Index::add, py::arg("meshes"), py::kw_only(), py::arg("name") = py::none(),
           py::arg("names") = py::none(), py::arg("pipeline") = py::none(),
           py::arg("variables") = std::map<std::string, std::string>{}, py::arg("repair") = true,
           py::arg("retry_failed") = false, py::arg("threads") = py::none(),
           R"doc(Describes meshes into the index, as `morphex index`.

meshes: a path, a Mesh, or an iterable of them. A path is recorded by its absolute path, with its
file stem as name; a Mesh as "mesh:<name>" (its name given, else the stem of the file it was
read from). name: the name of one mesh; names (or name= as a list): one name per mesh.
pipeline: the descriptor pipeline (dict, JSON text or file; None: read then describe with the
default settings); variables: its ${name} values; repair: repair meshes that are not valid solids
first (recorded per mesh). Meshes already indexed with the same content and settings are
skipped; one that fails is recorded with its error and skipped on later calls unless
retry_failed. Returns {'indexed', 'skipped', 'skipped_failed', 'failed', 'errors': {path:
message}}.)doc")
      .def("query", &Index::query, py::arg("mesh"), py::arg("k") = 10,
           py::arg("descriptor") = default_descriptor_kind(), py::arg("metric") = "l1",
           py::kw_only(), py::arg("threads") = py::none(),
           R"doc(The k nearest indexed meshes, as a list of (name, distance), nearest first.

mesh: a Mesh or a mesh file (described with the index's own pipeline), or the name or recorded
path of an indexed mesh (its stored descriptor; it is left out of the ranking).
descriptor: one of descriptor_kinds() (default 'combined'); metric: 'l1', 'l2' or 'chi2'.)doc")
      .def("evaluate", &Index::evaluate, py::arg("labels"), py::arg("metric") = "l1",
           R"doc(Retrieval scores of every stored descriptor kind, as `morphex evaluate`.

labels: {name: class} or the path of a Princeton .cla file. Each labelled mesh queries all the
others. Returns {kind: {'nearest_neighbor', 'first_tier', 'second_tier', 'e_measure', 'dcg',
'queries', 'per_class': {class: {the same scores, 'models'}}, 'precision_recall': {'recall',
'precision'}}} (see evaluate_retrieval; precision_recall_chart() and plot_svg() draw the curves).)doc")
      .def(
          "names",
          [](Index& index) {
            std::vector<std::string> names;
            for (const IndexedMesh& m : index.load()) names.push_back(m.name);
            return names;
          },
          "Names of the meshes indexed successfully, sorted.")
      .def(
          "failed",
          [](Index& index) {
            std::map<std::string, std::string> out;
            for (const IndexedMesh& m : index.load(false))
              if (m.status != "ok") out[m.path] = m.error;
            return out;
          },
          "{path: error} of the meshes that could not be indexed.")
      .def(
          "entries",
          [](Index& index) {
            py::list out;
            for (const IndexedMesh& m : index.load(false, {})) {
              // The library's entry (morphex/retrieval_json.h), with the repair as a flag and the
              // error always present, as this method has always given them.
              const nlohmann::json j = m;
              py::dict e;
              for (const char* key : {"name", "path", "status", "faces", "volume", "seconds",
                                      "settings", "indexed_at"})
                e[key] = from_json(j.at(key));
              e["error"] = m.error;
              e["repaired"] = !j.at("repair").is_null();
              out.append(e);
            }
            return out;
          },
          "Every entry, as `morphex ls --json`: a list of dicts (name, path, status, error, "
          "faces, volume, repaired, seconds, settings, indexed_at), by name.")
      .def(
          "remove",
          [](Index& index, const std::vector<std::string>& keys) { return index.remove(keys); },
          py::arg("keys"),
          "Removes the meshes named by recorded path, file path or unique name, as `morphex rm`; "
          "raises ValueError, removing nothing, when a key names no mesh or several. Returns how "
          "many were removed.")
      .def("descriptors", &stored_descriptors, py::arg("name"),
           "The stored vectors of an indexed mesh (by name or path): {kind: numpy array}.")
      .def("__len__", [](Index& index) { return index.load().size(); })
      .def("__contains__",
           [](Index& index, const std::string& name) {
             const auto all = index.load();
             return std::any_of(all.begin(), all.end(), [&](const IndexedMesh& m) {
               return m.name == name || m.path == name;
             });
           })
      .def_property_readonly("path", &Index::path)
      .def("close", &Index::close, "Closes the database file.")
      .def(
          "__enter__", [](Index& index) -> Index& { return index; },
          py::return_value_policy::reference)
      .def("__exit__", [](Index& index, const py::args&) { index.close(); })
      .def("__repr__", [](Index& index) { return "<morphex.Index " + index.path() + ">"; });
}

}  // namespace morphex::python

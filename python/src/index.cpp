// SPDX-License-Identifier: GPL-3.0-or-later
// morphex.Index: the SQLite retrieval index of `morphex index`, `query` and `evaluate`, in the same
// file format, so that an index built from Python can be queried by the command line and back.
//
// The index logic lives in tools/cli_retrieval.cpp next to its command-line parsing; until it
// moves into a library, what this file needs of it is mirrored here: the default descriptor
// pipeline, with_repairs, the settings key of an indexed mesh, descriptors_of, repair_of and the
// ranking of a query.
#include <stdlib.h>

#include <algorithm>
#include <filesystem>
#include <memory>

#include "common.h"
#include "index_db.h"
#include "morphex/descriptors.h"
#include "morphex/io.h"
#include "morphex/pipeline.h"
#include "morphex/retrieval.h"

namespace morphex::python {
namespace {

namespace mp = morphex::pipeline;
namespace fs = std::filesystem;

const char* kDefaultPipeline =
    R"({"pipeline": [{"type": "read", "path": "${input}"}, {"type": "describe"}]})";

// As tools/cli_retrieval.cpp: a repair stage after every read, taking the read's tag.
nlohmann::json with_repairs(const nlohmann::json& document) {
  nlohmann::json out = document;
  nlohmann::json& stages = out.is_array() ? out : out["pipeline"];
  nlohmann::json rewritten = nlohmann::json::array();
  for (const nlohmann::json& stage : stages) {
    if (!stage.is_object() || stage.value("type", "") != "read") {
      rewritten.push_back(stage);
      continue;
    }
    nlohmann::json read = stage, repair = {{"type", "repair"}};
    if (stage.contains("tag") && stage["tag"].is_string()) {
      const std::string tag = stage["tag"].get<std::string>();
      read["tag"] = tag + ".as-read";
      repair["tag"] = tag;
      repair["inputs"] = read["tag"];
    }
    rewritten.push_back(read);
    rewritten.push_back(repair);
  }
  stages = rewritten;
  return out;
}

std::string repair_of(const mp::InputReport& input) {
  for (const mp::StageReport& s : input.stages)
    if (s.type == "repair" && s.extra.contains("repair") &&
        s.extra["repair"].value("changed", false))
      return s.extra["repair"].dump();
  return "";
}

std::map<std::string, std::vector<double>> descriptors_of(const mp::InputReport& input) {
  std::map<std::string, std::vector<double>> out;
  for (const mp::StageReport& s : input.stages)
    if (s.type == "describe")
      for (const auto& [kind, v] : s.extra["descriptors"].items())
        out[kind] = v.get<std::vector<double>>();
  return out;
}

// A temporary directory for meshes given as Mesh objects (the pipelines read files), removed with
// everything in it.
class TemporaryDirectory {
 public:
  TemporaryDirectory() {
    std::string pattern = (fs::temp_directory_path() / "morphex-python-XXXXXX").string();
    if (!mkdtemp(pattern.data())) throw std::runtime_error("cannot create a temporary directory");
    path_ = pattern;
  }
  ~TemporaryDirectory() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  // Writes the mesh exactly as <dir>/<name>.off, so that ${stem} is the name.
  std::string write(const Mesh& mesh, const std::string& name) const {
    if (name.empty() || name.find('/') != std::string::npos)
      throw std::invalid_argument("name: expected a non-empty name without '/', got '" + name +
                                  "'");
    const std::string path = (path_ / (name + ".off")).string();
    WriteOptions exact;
    exact.exact = true;
    write_mesh(mesh, path, exact);
    return path;
  }

 private:
  fs::path path_;
};

// One mesh to index: the file the pipeline reads, and the path and name the index records.
struct Item {
  std::string file, path, name;
};

std::string pipeline_problems(const std::string& name, const mp::PipelineError& e) {
  std::string message;
  for (const mp::Problem& p : e.problems())
    message += (message.empty() ? "" : "\n") + name + ": " + p.text();
  return message;
}

class Index {
 public:
  explicit Index(const py::object& path) : path_(to_path(path)) {
    db_ = std::make_unique<cli::IndexDb>(path_);
  }

  py::dict add(const py::object& items, const std::optional<std::string>& name,
               const py::object& pipeline, const std::map<std::string, std::string>& variables,
               bool repair, const std::optional<int>& threads);
  py::list query(const py::object& target, std::size_t k, const std::string& descriptor,
                 const std::string& metric, const std::optional<int>& threads);
  py::dict evaluate(const py::object& labels, const std::string& metric);

  std::vector<cli::IndexedMesh> load(bool only_ok = true) { return db().load(only_ok); }
  const std::string& path() const { return path_; }
  void close() { db_.reset(); }

 private:
  cli::IndexDb& db() {
    if (!db_) throw std::invalid_argument(path_ + ": the index is closed");
    return *db_;
  }
  std::pair<nlohmann::json, std::string> document(const py::object& pipeline, bool repair);
  std::vector<Item> items(const py::object& items, const std::optional<std::string>& name,
                          const TemporaryDirectory& temp);

  std::string path_;
  std::unique_ptr<cli::IndexDb> db_;
};

// The descriptor pipeline (default, dict, JSON text or file), with repairs, validated.
std::pair<nlohmann::json, std::string> Index::document(const py::object& pipeline, bool repair) {
  std::string name = "<pipeline>";
  nlohmann::json doc;
  if (pipeline.is_none()) {
    doc = mp::parse_document(kDefaultPipeline, "default");
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
  if (repair) doc = with_repairs(doc);
  try {
    const mp::Pipeline p = mp::validate(doc, name, {}, {"input", "stem"});
    if (std::none_of(p.stages.begin(), p.stages.end(),
                     [](const mp::Stage& s) { return s.type == "describe"; }))
      throw mp::PipelineError(
          std::vector<mp::Problem>{{"pipeline", "an index pipeline needs a describe stage"}});
  } catch (const mp::PipelineError& e) {
    throw std::invalid_argument(pipeline_problems(name, e));
  }
  return {doc, name};
}

// Paths and Mesh objects (one, or an iterable of them). A Mesh is written to `temp` and recorded
// as "mesh:<name>": its name is `name`, else the stem of the file it was read from.
std::vector<Item> Index::items(const py::object& objects, const std::optional<std::string>& name,
                               const TemporaryDirectory& temp) {
  const bool single = py::isinstance<PyMesh>(objects) || py::isinstance<py::str>(objects) ||
                      py::hasattr(objects, "__fspath__");
  if (name && !single) throw std::invalid_argument("name: only for a single mesh or path");
  std::vector<py::handle> list;
  if (single)
    list.push_back(objects);
  else
    for (const py::handle& h : objects) list.push_back(h);
  std::vector<Item> out;
  for (const py::handle& h : list) {
    if (py::isinstance<PyMesh>(h)) {
      const PyMesh& m = h.cast<const PyMesh&>();
      const std::string n = name ? *name : fs::path(m.source).stem().string();
      if (n.empty()) throw std::invalid_argument("a Mesh not read from a file needs a name=");
      out.push_back({temp.write(m.mesh, n), "mesh:" + n, n});
    } else {
      const std::string p = to_path(h);
      out.push_back({p, p, name ? *name : fs::path(p).stem().string()});
    }
  }
  return out;
}

py::dict Index::add(const py::object& objects, const std::optional<std::string>& name,
                    const py::object& pipeline, const std::map<std::string, std::string>& variables,
                    bool repair, const std::optional<int>& threads) {
  auto [doc, doc_name] = document(pipeline, repair);
  TemporaryDirectory temp;
  const std::vector<Item> list = items(objects, name, temp);
  mp::RunOptions options;
  options.variables = variables;
  std::string sets;
  for (const auto& [k, v] : variables) sets += k + "=" + v + ";";
  // The same key as `morphex index`: a mesh is up to date for this pipeline and these variables.
  const std::string settings = doc.dump() + "|" + sets + "|descriptors " + descriptor_version();
  std::size_t skipped = 0, indexed = 0;
  std::map<std::string, std::string> errors;
  {
    py::gil_scoped_release release;
    ThreadLimit limit(threads);
    cli::IndexDb& db = this->db();
    db.set_meta("pipeline", doc.dump());
    db.set_meta("sets", nlohmann::json(options.variables).dump());
    std::map<std::string, std::pair<const Item*, std::string>> by_file;  // file -> item, hash
    for (const Item& item : list) {
      std::string hash;
      try {
        hash = cli::content_hash(item.file);
      } catch (const std::exception&) {
        errors[item.path] = "cannot read the file";
        db.store({0, item.name, item.path, "", settings, "failed", "cannot read the file", {}}, 0,
                 "", 0);
        continue;
      }
      if (db.up_to_date(item.path, hash, settings)) {
        ++skipped;
        continue;
      }
      by_file[item.file] = {&item, hash};
      options.inputs.push_back(item.file);
    }
    options.on_input_done = [&](const mp::InputReport& r) {
      const auto& [item, hash] = by_file.at(r.input);
      cli::IndexedMesh m;
      m.name = item->name;
      m.path = item->path;
      m.hash = hash;
      m.settings = settings;
      m.status = r.ok ? "ok" : "failed";
      m.error = r.error;
      if (r.ok) m.descriptors = descriptors_of(r);
      m.repair = repair_of(r);
      const std::size_t faces = r.stages.empty() ? 0 : r.stages.front().faces;
      const std::string volume = r.stages.empty() ? "" : r.stages.front().volume;
      db.store(m, faces, volume, r.seconds);
      if (r.ok)
        ++indexed;
      else
        errors[item->path] = r.error;
    };
    if (!options.inputs.empty()) {
      try {
        mp::run(doc, doc_name, options);
      } catch (const mp::PipelineError& e) {
        throw std::invalid_argument(pipeline_problems(doc_name, e));
      }
    }
  }
  py::dict out;
  out["indexed"] = indexed;
  out["skipped"] = skipped;
  out["failed"] = errors.size();
  out["errors"] = errors;
  return out;
}

py::list Index::query(const py::object& target, std::size_t k, const std::string& descriptor,
                      const std::string& metric_name, const std::optional<int>& threads) {
  const std::vector<std::string> kinds = descriptor_kinds();
  if (std::find(kinds.begin(), kinds.end(), descriptor) == kinds.end()) {
    std::string known;
    for (const std::string& kind : kinds) known += (known.empty() ? "" : ", ") + kind;
    throw std::invalid_argument("descriptor: expected one of " + known + ", got '" + descriptor +
                                "'");
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
    file = temp.write(m.mesh, stem.empty() ? "query" : stem);
    label = m.source.empty() ? "query mesh" : m.source;
  } else {
    file = label = to_path(target);
  }
  std::vector<std::pair<double, std::string>> ranked;
  {
    py::gil_scoped_release release;
    ThreadLimit limit(threads);
    cli::IndexDb& db = this->db();
    const std::vector<cli::IndexedMesh> meshes = db.load();
    std::vector<double> query;
    long long exclude = -1;
    const auto stored = std::find_if(meshes.begin(), meshes.end(), [&](const cli::IndexedMesh& m) {
      return m.name == file || m.path == file;
    });
    if (!is_mesh && !fs::exists(file) && stored != meshes.end()) {
      if (!stored->descriptors.count(descriptor))
        throw std::invalid_argument(path_ + ": " + stored->name + " has no '" + descriptor +
                                    "' descriptor (indexed by another version of morphex: index "
                                    "it again)");
      query = stored->descriptors.at(descriptor);
      exclude = stored->id;
    } else {
      mp::RunOptions options;
      options.inputs = {file};
      if (const auto sets = db.meta("sets"))
        options.variables = nlohmann::json::parse(*sets).get<mp::Variables>();
      const std::string pipeline = db.meta("pipeline").value_or(kDefaultPipeline);
      const mp::RunReport r = mp::run(nlohmann::json::parse(pipeline), path_, options);
      if (!r.ok()) throw std::invalid_argument(label + ": " + r.inputs.front().error);
      query = descriptors_of(r.inputs.front()).at(descriptor);
    }
    for (const cli::IndexedMesh& m : meshes)
      if (m.id != exclude && m.descriptors.count(descriptor))
        ranked.emplace_back(distance(query, m.descriptors.at(descriptor), metric), m.name);
  }
  // Nearest first, ties by name (as `morphex query`).
  std::sort(ranked.begin(), ranked.end());
  ranked.resize(std::min(ranked.size(), k));
  py::list out;
  for (const auto& [d, name] : ranked) out.append(py::make_tuple(name, d));
  return out;
}

py::dict Index::evaluate(const py::object& labels_arg, const std::string& metric_name) {
  const Metric metric = parse_metric(metric_name);
  std::map<std::string, std::string> labels =
      py::isinstance<py::dict>(labels_arg)
          ? labels_arg.cast<std::map<std::string, std::string>>()
          : read_cla(to_path(labels_arg));  // InputError names the file and line
  py::dict out;
  std::map<std::string, RetrievalScores> scores;
  {
    py::gil_scoped_release release;
    std::vector<cli::IndexedMesh> meshes;
    for (cli::IndexedMesh& m : db().load())
      if (labels.count(m.name)) meshes.push_back(std::move(m));
    std::vector<std::string> names, classes;
    for (const cli::IndexedMesh& m : meshes) {
      names.push_back(m.name);
      classes.push_back(labels[m.name]);
    }
    for (const std::string& kind : descriptor_kinds()) {
      if (std::any_of(meshes.begin(), meshes.end(),
                      [&](const cli::IndexedMesh& m) { return !m.descriptors.count(kind); }))
        continue;
      std::vector<std::vector<double>> d(meshes.size(), std::vector<double>(meshes.size()));
      for (std::size_t a = 0; a < meshes.size(); ++a)
        for (std::size_t b = 0; b < meshes.size(); ++b)
          d[a][b] =
              distance(meshes[a].descriptors.at(kind), meshes[b].descriptors.at(kind), metric);
      scores[kind] = evaluate_retrieval(names, classes, d);
    }
  }
  for (const auto& [kind, s] : scores) {
    py::dict j;
    j["nearest_neighbor"] = s.nearest_neighbor;
    j["first_tier"] = s.first_tier;
    j["second_tier"] = s.second_tier;
    j["e_measure"] = s.e_measure;
    j["dcg"] = s.dcg;
    j["queries"] = s.queries;
    out[kind.c_str()] = j;
  }
  return out;
}

py::dict stored_descriptors(Index& index, const std::string& name) {
  for (const cli::IndexedMesh& m : index.load())
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
index built here and back). Index(path) opens it, creating it if missing. A context manager.)doc")
      .def(py::init<const py::object&>(), py::arg("path"))
      .def("add", &Index::add, py::arg("meshes"), py::kw_only(), py::arg("name") = py::none(),
           py::arg("pipeline") = py::none(),
           py::arg("variables") = std::map<std::string, std::string>{}, py::arg("repair") = true,
           py::arg("threads") = py::none(),
           R"doc(Describes meshes into the index, as `morphex index`.

meshes: a path, a Mesh, or an iterable of them. A path is recorded with its file stem as name;
a Mesh as "mesh:<name>" (name=, else the stem of the file it was read from).
pipeline: the descriptor pipeline (dict, JSON text or file; None: read then describe with the
default settings); variables: its ${name} values; repair: repair meshes that are not valid solids
first (recorded per mesh). Meshes already indexed with the same content and settings are
skipped; one that fails is recorded with its error. Returns {'indexed', 'skipped', 'failed',
'errors': {path: message}}.)doc")
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
'queries'}}.)doc")
      .def(
          "names",
          [](Index& index) {
            std::vector<std::string> names;
            for (const cli::IndexedMesh& m : index.load()) names.push_back(m.name);
            return names;
          },
          "Names of the meshes indexed successfully, sorted.")
      .def(
          "failed",
          [](Index& index) {
            std::map<std::string, std::string> out;
            for (const cli::IndexedMesh& m : index.load(false))
              if (m.status != "ok") out[m.path] = m.error;
            return out;
          },
          "{path: error} of the meshes that could not be indexed.")
      .def("descriptors", &stored_descriptors, py::arg("name"),
           "The stored vectors of an indexed mesh (by name or path): {kind: numpy array}.")
      .def("__len__", [](Index& index) { return index.load().size(); })
      .def("__contains__",
           [](Index& index, const std::string& name) {
             const auto all = index.load();
             return std::any_of(all.begin(), all.end(), [&](const cli::IndexedMesh& m) {
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

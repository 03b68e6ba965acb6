// SPDX-License-Identifier: GPL-3.0-or-later
// describe() (what `morphex describe --json` prints, with numpy arrays) and
// run_pipeline().
#include <chrono>

#include "common.h"
#include "morphex/descriptor_settings.h"
#include "morphex/descriptors.h"
#include "morphex/json.h"
#include "morphex/morph_json.h"
#include "morphex/pipeline.h"
#include "morphex/repair.h"
#include "morphex/retrieval.h"

namespace morphex::python {
namespace {

namespace mp = morphex::pipeline;

// The library's JSON of the descriptors, its curves and vectors as numpy arrays.
py::dict descriptors_dict(const Descriptors& d) {
  const nlohmann::json j = d;
  py::dict out;
  for (const auto& [key, value] : j.items())
    out[key.c_str()] =
        value.is_array() ? to_numpy(value.get<std::vector<double>>()) : from_json(value);
  py::dict vectors;
  for (const auto& [kind, vector] : j.at("vectors").items())
    vectors[kind.c_str()] = to_numpy(vector.get<std::vector<double>>());
  out["vectors"] = vectors;
  return out;
}

py::dict describe_mesh(const PyMesh& mesh, const DescriptorSettings& s, bool repair,
                       const std::optional<int>& threads) {
  Descriptors d;
  std::optional<RepairReport> repaired;
  double seconds = 0;
  {
    py::gil_scoped_release release;
    ThreadLimit limit(threads);
    std::optional<Solid> solid;
    if (repair) {
      try {
        RepairResult r = repair_mesh(mesh.mesh());
        solid = std::move(r.solid);
        repaired = r.report;
      } catch (const InputError& e) {
        throw InputError("", mesh_prefix(mesh, "") + "cannot repair: " + e.what());
      }
    } else {
      solid = mesh.solid("");
    }
    const auto start = std::chrono::steady_clock::now();
    d = describe(*solid, s);
    seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  py::dict out = descriptors_dict(d);
  if (repaired) out["repair"] = from_json(*repaired);
  if (!mesh.source.empty()) out["path"] = mesh.source;
  out["settings"] = s.to_string();
  out["seconds"] = seconds;
  return out;
}

// A pipeline document: a dict (or list), JSON text, or the path of a JSON file.
std::pair<nlohmann::json, std::string> load_pipeline(const py::object& document) {
  if (py::isinstance<py::dict>(document) || py::isinstance<py::list>(document))
    return {to_json(document), "<pipeline>"};
  if (py::isinstance<py::str>(document)) {
    const std::string text = document.cast<std::string>();
    const auto first = text.find_first_not_of(" \t\r\n");
    if (first != std::string::npos && (text[first] == '{' || text[first] == '['))
      return {mp::parse_document(text, "<pipeline>"), "<pipeline>"};
  }
  const std::string path = to_path(document);
  return {mp::load_document(path), path};
}

py::object run_pipeline(const py::object& document, const py::object& inputs,
                        const std::map<std::string, std::string>& variables,
                        const std::optional<int>& threads) {
  mp::RunOptions options;
  options.variables = variables;
  if (!inputs.is_none()) {
    if (py::isinstance<py::str>(inputs) || py::hasattr(inputs, "__fspath__"))
      options.inputs.push_back(to_path(inputs));
    else
      for (const py::handle& input : inputs) options.inputs.push_back(to_path(input));
  }
  auto [json, name] = load_pipeline(document);
  mp::RunReport report;
  {
    py::gil_scoped_release release;
    ThreadLimit limit(threads);
    try {
      report = mp::run(json, name, options);
    } catch (const mp::PipelineError& e) {
      // Every problem, one a line, as `morphex run` prints them.
      std::string message;
      for (const mp::Problem& p : e.problems())
        message += (message.empty() ? "" : "\n") + name + ": " + p.text();
      throw InputError("", message);
    }
  }
  return from_json(report.to_json());
}

// The keywords of describe(): one per descriptor setting, from the library's table.
std::string settings_doc() {
  const DescriptorSettings defaults;
  std::string out;
  for (const DescriptorSettingInfo& setting : descriptor_settings_table())
    out += std::string("  ") + setting.name + "=" +
           py::repr(from_json(setting.value(defaults))).cast<std::string>() + ": " + setting.doc +
           "\n";
  return out;
}

void bind_describe(py::module_& m) {
  static const std::string doc =
      R"doc(describe(mesh, *, repair=False, threads=None, **settings)

Morphological descriptors and D2 of a valid solid, as `morphex describe --json`.

Returns a dict: scale_length, thickness, filtered_facets, simplified, seconds_morphology, seconds,
settings, and numpy arrays open_radii, close_radii, granulometry, pattern_spectrum,
anti_granulometry, opening_residue, closing_residue, components, d2; 'vectors' maps each
descriptor kind (descriptor_kinds()) to the vector an Index stores and compares.
repair=True repairs an invalid mesh first and adds a 'repair' dict.
Raises InvalidSolid when the mesh is not a valid solid (and repair is False), and InputError
naming the setting for a value out of its range.

Settings (keywords, the describe stage's options; the command line's --name, --no-name for
True/False ones), with their defaults:
)doc" +
      settings_doc();
  m.def(
      "describe",
      [](const PyMesh& mesh, bool repair, const std::optional<int>& threads,
         const py::kwargs& keywords) {
        nlohmann::json given = nlohmann::json::object();
        for (const auto& [key, value] : keywords) {
          const std::string name = py::str(key);
          if (!find_descriptor_setting(name))
            throw py::type_error("describe() got an unexpected keyword argument '" + name + "'");
          given[name] = to_json(value);
        }
        // The library checks each value and the ranges together, naming the setting.
        return describe_mesh(mesh, given.get<DescriptorSettings>(), repair, threads);
      },
      py::arg("mesh"), py::kw_only(), py::arg("repair") = false, py::arg("threads") = py::none(),
      doc.c_str());
  m.def("descriptor_kinds", &descriptor_kinds,
        "The descriptor kinds: morphology, granulometry, pattern_spectrum, spatial, d2, combined.");
  m.def(
      "distance",
      [](const std::vector<double>& a, const std::vector<double>& b, const std::string& metric) {
        return distance(a, b, parse_metric(metric));
      },
      py::arg("a"), py::arg("b"), py::arg("metric") = "l1",
      "Distance between two descriptor vectors: 'l1', 'l2' or 'chi2'.");
}

}  // namespace

void register_retrieval(py::module_& m) {
  bind_describe(m);
  m.def("run_pipeline", &run_pipeline, py::arg("pipeline"), py::arg("inputs") = py::none(),
        py::arg("variables") = std::map<std::string, std::string>{}, py::kw_only(),
        py::arg("threads") = py::none(),
        R"doc(Runs a JSON pipeline (as `morphex run`) and returns its report as a dict.

pipeline: a dict, JSON text, or the path of a pipeline file.
inputs: mesh paths, each bound to ${input} and ${stem} (None: run once).
variables: {name: value} for ${name} (the command line's --set).
The report ('ok', 'seconds', 'inputs': [{'input', 'ok', 'error', 'stages': [...]}]) records an
input that failed; an invalid pipeline raises ValueError listing every problem.)doc");
}

}  // namespace morphex::python

// SPDX-License-Identifier: GPL-3.0-or-later
// describe() (what `morphex describe --json` prints, with numpy arrays) and
// run_pipeline().
#include <chrono>

#include "common.h"
#include "morphex/descriptors.h"
#include "morphex/json.h"
#include "morphex/morph_json.h"
#include "morphex/pipeline.h"
#include "morphex/repair.h"
#include "morphex/retrieval.h"

namespace morphex::python {
namespace {

namespace mp = morphex::pipeline;

void require_in(const char* name, double value, double lo, double hi) {
  if (!(value >= lo && value <= hi))
    throw InputError("", std::string(name) + ": expected a number in [" +
                                std::to_string(lo) + ", " + std::to_string(hi) + "], got " +
                                std::to_string(value));
}

// The command line's checks of `morphex describe`'s options, with the keyword names.
void check_settings(const DescriptorSettings& s) {
  require_in("scales", s.scales, 1, 64);
  const std::pair<const char*, double> numbers[] = {{"open_from", s.open_from},
                                                    {"open_to", s.open_to},
                                                    {"close_from", s.close_from},
                                                    {"close_to", s.close_to}};
  for (const auto& [name, v] : numbers)
    if (!(v > 0))
      throw InputError("", std::string(name) + ": expected a positive number, got " +
                                  std::to_string(v));
  if (s.open_from > s.open_to || s.close_from > s.close_to)
    throw InputError("", "open_from/close_from must not exceed open_to/close_to");
  require_in("d2_samples", s.d2_samples, 16, 1e7);
  require_in("d2_bins", s.d2_bins, 4, 4096);
}

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
  check_settings(s);
  Descriptors d;
  std::optional<RepairReport> repaired;
  double seconds = 0;
  {
    py::gil_scoped_release release;
    ThreadLimit limit(threads);
    Mesh repaired_mesh;
    const Mesh* solid = &mesh.mesh;
    if (repair) {
      try {
        RepairResult r = repair_mesh(mesh.mesh);
        repaired_mesh = std::move(r.mesh);
        repaired = r.report;
        solid = &repaired_mesh;
      } catch (const InputError& e) {
        throw InputError("", mesh_prefix(mesh, "") + "cannot repair: " + e.what());
      }
    } else {
      require_valid_solid(mesh, "");
    }
    const auto start = std::chrono::steady_clock::now();
    d = describe_valid(*solid, s);  // checked or repaired above
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

void bind_describe(py::module_& m) {
  const DescriptorSettings d;
  m.def(
      "describe",
      [](const PyMesh& mesh, int scales, double open_from, double open_to, double close_from,
         double close_to, bool closings, bool pose, std::size_t facet_budget, int d2_samples,
         int d2_bins, std::uint64_t seed, bool repair, const std::optional<int>& threads) {
        DescriptorSettings s;
        s.scales = scales;
        s.open_from = open_from;
        s.open_to = open_to;
        s.close_from = close_from;
        s.close_to = close_to;
        s.closings = closings;
        s.normalise_pose = pose;
        s.facet_budget = facet_budget;
        s.d2_samples = d2_samples;
        s.d2_bins = d2_bins;
        s.seed = seed;
        return describe_mesh(mesh, s, repair, threads);
      },
      py::arg("mesh"), py::kw_only(), py::arg("scales") = d.scales,
      py::arg("open_from") = d.open_from, py::arg("open_to") = d.open_to,
      py::arg("close_from") = d.close_from, py::arg("close_to") = d.close_to,
      py::arg("closings") = d.closings, py::arg("pose") = d.normalise_pose,
      py::arg("facet_budget") = d.facet_budget, py::arg("d2_samples") = d.d2_samples,
      py::arg("d2_bins") = d.d2_bins, py::arg("seed") = d.seed, py::arg("repair") = false,
      py::arg("threads") = py::none(),
      R"doc(Morphological descriptors and D2 of a valid solid, as `morphex describe --json`.

Returns a dict: scale_length, thickness, filtered_facets, simplified, seconds_morphology, seconds,
settings, and numpy arrays open_radii, close_radii, granulometry, pattern_spectrum,
anti_granulometry, opening_residue, closing_residue, components, d2; 'vectors' maps each
descriptor kind (descriptor_kinds()) to the vector an Index stores and compares.
Keywords are the command line's options (closings=False is --no-closings; pose=False skips
the pose normalisation, as the describe stage's "pose": false); repair=True repairs an invalid
mesh first and adds a 'repair' dict.
Raises InvalidSolid when the mesh is not a valid solid (and repair is False).)doc");
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

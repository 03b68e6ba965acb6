// SPDX-License-Identifier: GPL-3.0-or-later
// What the binding files share: the Python-side mesh, exact numbers, errors, threads and JSON.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <tbb/global_control.h>

#include <nlohmann/json.hpp>

#include <optional>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include "morphex/mesh.h"
#include "morphex/retrieval.h"
#include "morphex/solid.h"

namespace morphex::python {

namespace py = pybind11;

// A mesh as Python sees it: the exact mesh, a Solid when an operation made it (so that chains
// check nothing again), and, when it was read from a file, that file's path, so that errors name
// the file as the command line does ("cube.off: mesh is not closed: ...").
class PyMesh {
 public:
  PyMesh(Mesh mesh = {}, std::string source = "")
      : value_(std::move(mesh)), source(std::move(source)) {}
  PyMesh(Solid solid, std::string source = "")
      : value_(std::move(solid)), source(std::move(source)) {}
  const Mesh& mesh() const {
    return value_.index() == 1 ? std::get<Solid>(value_).mesh() : std::get<Mesh>(value_);
  }
  // The mesh as a valid solid: itself when an operation made it, else checked now (InvalidSolid,
  // raised as morphex.InvalidSolid, a ValueError, its message starting with the mesh's file, else
  // with `role`, the parameter name, when not empty, then `what`, then the problem).
  Solid solid(const std::string& role, const std::string& what = "") const;

 private:
  std::variant<Mesh, Solid> value_;

 public:
  std::string source;
};

// "<file or role>: " or "" when neither is known.
std::string mesh_prefix(const PyMesh& m, const std::string& role);

// Python number (int, Fraction or any numbers.Rational, float, or text "1/3", "0.25") -> exact.
// Floats are taken exactly (every double is a dyadic rational), text as parse_exact_number reads
// it.
FT to_exact(const py::handle& value);
Point to_exact_point(const py::handle& xyz, const char* what);
// The exact value as a fractions.Fraction.
py::object to_fraction(const FT& value);

// A path argument: str or os.PathLike.
std::string to_path(const py::handle& path);

// Limits TBB's worker threads while it lives (threads=None: no limit). TBB applies the smallest
// limit in force, so concurrent calls from several Python threads share the strictest one.
class ThreadLimit {
 public:
  explicit ThreadLimit(const std::optional<int>& threads);

 private:
  std::optional<tbb::global_control> control_;
};

// A numpy float64 array holding a copy of `values`.
py::array_t<double> to_numpy(const std::vector<double>& values);

// Python object <-> JSON, through the json module (the documents and reports are small).
nlohmann::json to_json(const py::handle& value);
py::object from_json(const nlohmann::json& value);

// Imports what the conversions below call (numbers, fractions, os, json); the module's
// initialisation calls it first, under the import lock, so that no call imports later.
void import_python_helpers();

// Registration of each part of the module (one file each).
void register_mesh(py::module_& m);
void register_operations(py::module_& m);
void register_retrieval(py::module_& m);
void register_index(py::module_& m);
void register_plots(py::module_& m);

// An evaluation as Index.evaluate and evaluate_retrieval return it: the mean scores, 'per_class'
// and 'precision_recall' (plot.cpp).
py::dict evaluation_dict(const RetrievalScores& scores, const std::vector<ClassScores>& per_class,
                         const PrecisionRecall& curve);

// The text of the `threads` keyword's documentation, shared by every long operation.
inline constexpr const char* kThreadsDoc =
    "threads: maximum number of worker threads (None: all cores).";

}  // namespace morphex::python

// SPDX-License-Identifier: GPL-3.0-or-later
#include "common.h"

#include <cmath>

#include "morphex/check.h"

namespace morphex::python {
namespace {

// module.name, leaked on purpose: a static py::object would be released after the interpreter is
// finalised, at process exit.
py::handle imported(const char* module, const char* name) {
  return py::object(py::module_::import(module).attr(name)).release();
}

// What the conversions call, imported once when the module is imported (import_python_helpers).
// Not function-local statics: an import may let another thread run Python, and a second thread
// entering the same static's initialisation would wait for it while holding the GIL, which the
// first needs to finish: two threads making their first calls at once deadlocked.
struct Helpers {
  py::handle rational, real, fraction, fspath, dumps, loads;
};
Helpers helpers;

}  // namespace

void import_python_helpers() {
  helpers = {imported("numbers", "Rational"),   imported("numbers", "Real"),
             imported("fractions", "Fraction"), imported("os", "fspath"),
             imported("json", "dumps"),         imported("json", "loads")};
  // pybind11 looks numpy's C API up in a function-local static on the first array: done here.
  (void)py::array_t<double>(0);
}

std::string mesh_prefix(const PyMesh& m, const std::string& role) {
  if (!m.source.empty()) return m.source + ": ";
  return role.empty() ? std::string() : role + ": ";
}

Solid PyMesh::solid(const std::string& role, const std::string& what) const {
  if (value_.index() == 1) return std::get<Solid>(value_);
  // Not cached: a Python Mesh may be used from several threads at once.
  try {
    return check_solid(std::get<Mesh>(value_));
  } catch (const InvalidSolid& e) {
    throw InvalidSolid("", mesh_prefix(*this, role) + what + e.problem());
  }
}

FT to_exact(const py::handle& value) {
  // bool is an int in Python, but a coordinate given as True is a mistake.
  if (py::isinstance<py::bool_>(value))
    throw py::type_error("expected a number, got " + std::string(py::repr(value)));
  if (py::isinstance<py::str>(value)) return parse_exact_number(value.cast<std::string>());
  const py::handle rational = helpers.rational, real = helpers.real;
  if (py::isinstance(value, rational)) {
    // int, Fraction, numpy integers: numerator and denominator through their decimal text, so
    // that integers of any size stay exact.
    const std::string num = py::str(value.attr("numerator"));
    const std::string den = py::str(value.attr("denominator"));
    return parse_exact_number(den == "1" ? num : num + "/" + den);
  }
  if (py::isinstance(value, real)) {
    const double d = py::float_(py::reinterpret_borrow<py::object>(value));
    if (!std::isfinite(d))
      throw InputError("", "expected a finite number, got " + std::string(py::repr(value)));
    return FT(d);
  }
  throw py::type_error("expected a number (int, float, Fraction or text such as '1/3'), got " +
                       std::string(py::repr(value)));
}

Point to_exact_point(const py::handle& xyz, const char* what) {
  const py::sequence s = py::reinterpret_borrow<py::sequence>(xyz);
  if (!py::isinstance<py::sequence>(xyz) || py::isinstance<py::str>(xyz) || py::len(s) != 3)
    throw InputError(
        "", std::string(what) + ": expected three coordinates, got " + std::string(py::repr(xyz)));
  return Point(to_exact(s[0]), to_exact(s[1]), to_exact(s[2]));
}

py::object to_fraction(const FT& value) {
  return helpers.fraction(to_rational_string(value));
}

std::string to_path(const py::handle& path) {
  const py::object p = helpers.fspath(path);
  if (!py::isinstance<py::str>(p))
    throw py::type_error("expected a path as str or os.PathLike, got " + std::string(py::repr(p)));
  return p.cast<std::string>();
}

ThreadLimit::ThreadLimit(const std::optional<int>& threads) {
  if (!threads) return;
  if (*threads < 1)
    throw InputError("", "threads: expected a positive number, got " + std::to_string(*threads));
  control_.emplace(tbb::global_control::max_allowed_parallelism, std::size_t(*threads));
}

py::array_t<double> to_numpy(const std::vector<double>& values) {
  py::array_t<double> out(values.size());
  std::copy(values.begin(), values.end(), out.mutable_data());
  return out;
}

nlohmann::json to_json(const py::handle& value) {
  return nlohmann::json::parse(helpers.dumps(value).cast<std::string>());
}

py::object from_json(const nlohmann::json& value) {
  return helpers.loads(value.dump());
}

}  // namespace morphex::python

// SPDX-License-Identifier: GPL-3.0-or-later
// The Python module `morphex`: exact Booleans and mathematical morphology on triangle meshes.
#include "common.h"
#include "morphex/io.h"
#include "morphex/pipeline.h"
#include "morphex/structuring_element.h"

namespace morphex::python {
namespace {

// The Python classes of morphex/error.h's hierarchy, made once at import. Input problems are also
// ValueErrors and storage failures OSErrors, so callers that catch the built-in kinds keep working.
struct ErrorClasses {
  PyObject *error, *input, *invalid_solid, *output, *lossy_output, *storage;
};
ErrorClasses classes;

PyObject* new_class(py::module_& m, const char* name, PyObject* base, PyObject* second = nullptr) {
  const std::string qualified = std::string("morphex.") + name;
  PyObject* bases = second ? PyTuple_Pack(2, base, second) : PyTuple_Pack(1, base);
  PyObject* type = PyErr_NewException(qualified.c_str(), bases, nullptr);
  Py_DECREF(bases);
  if (!type) throw py::error_already_set();
  m.add_object(name, py::handle(type));
  return type;
}

void register_errors(py::module_& m) {
  classes.error = new_class(m, "Error", PyExc_Exception);
  classes.input = new_class(m, "InputError", classes.error, PyExc_ValueError);
  classes.invalid_solid = new_class(m, "InvalidSolid", classes.input);
  classes.output = new_class(m, "OutputError", classes.error);
  classes.lossy_output = new_class(m, "LossyOutputError", classes.output);
  classes.storage = new_class(m, "StorageError", classes.error, PyExc_OSError);
}

// Each morphex::Error as its most derived Python class, with the same message as the command line.
void translate_errors(std::exception_ptr error) {
  try {
    if (error) std::rethrow_exception(error);
  } catch (const InvalidSolid& e) {
    PyErr_SetString(classes.invalid_solid, e.what());
  } catch (const InputError& e) {
    PyErr_SetString(classes.input, e.what());
  } catch (const LossyOutputError& e) {
    PyErr_SetString(classes.lossy_output, e.what());
  } catch (const OutputError& e) {
    PyErr_SetString(classes.output, e.what());
  } catch (const StorageError& e) {
    PyErr_SetString(classes.storage, e.what());
  } catch (const Error& e) {
    PyErr_SetString(classes.error, e.what());
  }
  // Anything else keeps pybind11's mapping (std::bad_alloc: MemoryError, std::logic_error, a bug:
  // RuntimeError).
}

}  // namespace
}  // namespace morphex::python

PYBIND11_MODULE(morphex, m) {
  using namespace morphex::python;
  m.doc() = R"doc(Exact Booleans and mathematical morphology on 3D triangle meshes (morphex).

Meshes have exact rational coordinates: numpy arrays in and out are rounded only where asked
(Mesh.vertices), volumes are fractions.Fraction. Errors are the command line's (morphex/error.h): morphex.InputError
(a ValueError) for bad input, naming the file and the problem, and its subclass morphex.InvalidSolid
for a mesh that is not a valid closed solid; morphex.OutputError for a result that cannot be written
as asked (LossyOutputError: beyond the format's range); morphex.StorageError (an OSError) for a
file or index that cannot be written; all are morphex.Error. Long operations release the GIL and take threads=.)doc";
  m.attr("__version__") = MORPHEX_VERSION;
  import_python_helpers();
  register_errors(m);
  py::register_exception_translator(&translate_errors);
  register_mesh(m);
  register_operations(m);
  register_retrieval(m);
  register_index(m);
  register_plots(m);
}

// SPDX-License-Identifier: GPL-3.0-or-later
// The Python module `morphex`: exact Booleans and mathematical morphology on triangle meshes.
#include "common.h"
#include "morphex/io.h"
#include "morphex/pipeline.h"
#include "morphex/structuring_element.h"

namespace morphex::python {
namespace {

// The command line's exit code 2 ("bad input") becomes ValueError, with the same message.
void translate_errors(std::exception_ptr error) {
  try {
    if (error) std::rethrow_exception(error);
  } catch (const Error& e) {
    PyErr_SetString(PyExc_ValueError, e.what());
  }
  // Every morphex::Error (morphex/error.h) is a ValueError; anything else keeps pybind11's
  // mapping (std::invalid_argument: ValueError, std::runtime_error: RuntimeError...).
}

}  // namespace
}  // namespace morphex::python

PYBIND11_MODULE(morphex, m) {
  using namespace morphex::python;
  m.doc() = R"doc(Exact Booleans and mathematical morphology on 3D triangle meshes (morphex).

Meshes have exact rational coordinates: numpy arrays in and out are rounded only where asked
(Mesh.vertices), volumes are fractions.Fraction. Errors are the command line's: ValueError for
bad input (naming the file and the problem), morphex.InvalidSolid (a ValueError) for an operand
that is not a valid closed solid. Long operations release the GIL and take threads=.)doc";
  m.attr("__version__") = MORPHEX_VERSION;
  import_python_helpers();
  // Registered first so that it is tried last: InvalidSolid is a morphex::Error.
  py::register_exception_translator(&translate_errors);
  py::register_exception<morphex::InvalidSolid>(m, "InvalidSolid", PyExc_ValueError);
  register_mesh(m);
  register_operations(m);
  register_retrieval(m);
  register_index(m);
  register_plots(m);
}

// SPDX-License-Identifier: GPL-3.0-or-later
// Booleans, morphology, Minkowski sums and repair: each checks its operands like the command line
// (InvalidSolid naming the file or the parameter), then runs without the GIL.
#include <variant>

#include "common.h"
#include "morphex/boolean.h"
#include "morphex/check.h"
#include "morphex/json.h"
#include "morphex/morphology.h"
#include "morphex/repair.h"

namespace morphex::python {
namespace {

PyMesh boolean(const PyMesh& a, const PyMesh& b, BooleanOp op, bool merge_coplanar,
               const std::optional<int>& threads) {
  py::gil_scoped_release release;
  ThreadLimit limit(threads);
  BooleanOptions options;
  options.merge_coplanar = merge_coplanar;
  // As `morphex bool`: "FILE: first operand is not a valid solid: ..." (no file: no prefix).
  const Solid first = a.solid("", "first operand is not a valid solid: ");
  const Solid second = b.solid("", "second operand is not a valid solid: ");
  return PyMesh(compute_boolean(first, second, op, options).solid);
}

// A structuring element from its text form ("cube:r=1/10") or from a Mesh (a valid solid in its
// own coordinates, convex or not). Called without the GIL: the variant was unpacked before.
StructuringElement structuring_element(const std::string* text, const PyMesh* mesh) {
  if (text) {
    try {
      return parse_structuring_element(*text);
    } catch (const std::bad_alloc&) {
      throw;
    } catch (const std::exception& e) {
      // As the command line's "--se TEXT: ...": the text, then what is wrong with it.
      throw InputError("", "se " + *text + ": " + e.what());
    }
  }
  mesh->solid("se");  // the element must be a valid solid
  StructuringElement se;
  se.shape = "mesh";
  se.spec = mesh->source.empty() ? "mesh" : "mesh:path=" + mesh->source;
  se.mesh = mesh->mesh();
  make_exact(se.mesh);  // the morphology's pieces are built from these points many times
  se.convex = is_convex(se.mesh);
  return se;
}

using SeArg = std::variant<std::string, const PyMesh*>;

PyMesh morphology(MorphologyOp op, const PyMesh& a, const SeArg& se_arg,
                  const std::optional<int>& threads) {
  const std::string* text = std::get_if<std::string>(&se_arg);
  const PyMesh* se_mesh = text ? nullptr : std::get<const PyMesh*>(se_arg);
  py::gil_scoped_release release;
  ThreadLimit limit(threads);
  const StructuringElement se = structuring_element(text, se_mesh);
  return PyMesh(apply_morphology(op, a.solid(""), se));
}

py::object repair(const PyMesh& m, bool merge_coplanar, bool report, double budget) {
  if (!(budget >= 0)) throw InputError("", "budget: expected 0 or a positive number");
  RepairResult r;
  {
    py::gil_scoped_release release;
    RepairOptions options;
    options.merge_coplanar = merge_coplanar;
    options.budget = budget;
    try {
      r = repair_mesh(m.mesh(), options);
    } catch (const InputError& e) {
      // As `morphex repair`: the repair's message has no file name, the caller adds it.
      throw InputError("", mesh_prefix(m, "") + "cannot repair: " + e.what());
    }
  }
  PyMesh out(std::move(r.solid));
  if (!report) return py::cast(std::move(out));
  return py::make_tuple(std::move(out), from_json(r.report));
}

const char* kSeDoc =
    "se: a structuring element, as text (the command line's --se syntax: 'cube:r=1/10', "
    "'ball:r=0.05,level=1', 'box:x=1,y=2,z=1/2', 'mesh:path=se.off', offsets ox, oy, oz) or as a "
    "Mesh (a valid solid, convex or not, in its own coordinates).";

void bind_morphology(py::module_& m, const char* name, MorphologyOp op, const std::string& what) {
  m.def(
      name,
      [op](const PyMesh& a, const SeArg& se, const std::optional<int>& threads) {
        return morphology(op, a, se, threads);
      },
      py::arg("mesh"), py::arg("se"), py::kw_only(), py::arg("threads") = py::none(),
      (what + "\n\n" + kSeDoc + "\n" + kThreadsDoc +
       "\nRaises InvalidSolid when the mesh (or a Mesh se) is not a valid solid, ValueError for a "
       "bad structuring element.")
          .c_str());
}

void bind_booleans(py::module_& m) {
  const auto doc = [](const std::string& what) {
    return what +
           " of two valid closed solids, exact.\n\nmerge_coplanar: merge neighbouring coplanar "
           "result faces (no new points).\n" +
           kThreadsDoc + "\nRaises InvalidSolid when an operand is not a valid solid.";
  };
  const std::pair<const char*, BooleanOp> ops[] = {{"union", BooleanOp::Union},
                                                   {"intersection", BooleanOp::Intersection},
                                                   {"difference", BooleanOp::Difference}};
  for (const auto& [name, op] : ops) {
    const BooleanOp o = op;
    m.def(
        name,
        [o](const PyMesh& a, const PyMesh& b, bool merge, const std::optional<int>& threads) {
          return boolean(a, b, o, merge, threads);
        },
        py::arg("a"), py::arg("b"), py::kw_only(), py::arg("merge_coplanar") = true,
        py::arg("threads") = py::none(),
        doc(o == BooleanOp::Difference ? "A minus B" : std::string("The ") + name).c_str());
  }
  auto mesh = py::reinterpret_borrow<py::class_<PyMesh>>(m.attr("Mesh"));
  mesh.def("__or__", [](const PyMesh& a, const PyMesh& b) {
    return boolean(a, b, BooleanOp::Union, true, std::nullopt);
  });
  mesh.def("__and__", [](const PyMesh& a, const PyMesh& b) {
    return boolean(a, b, BooleanOp::Intersection, true, std::nullopt);
  });
  mesh.def("__sub__", [](const PyMesh& a, const PyMesh& b) {
    return boolean(a, b, BooleanOp::Difference, true, std::nullopt);
  });
}

}  // namespace

void register_operations(py::module_& m) {
  bind_booleans(m);
  bind_morphology(m, "dilate", MorphologyOp::Dilate, "Dilation mesh + se, exact.");
  bind_morphology(m, "erode", MorphologyOp::Erode, "Erosion {x : x + se inside mesh}, exact.");
  bind_morphology(m, "opening", MorphologyOp::Open, "Opening: erosion, then dilation, exact.");
  bind_morphology(m, "closing", MorphologyOp::Close, "Closing: dilation, then erosion, exact.");
  m.def(
      "minkowski_sum",
      [](const PyMesh& a, const PyMesh& b, const std::optional<int>& threads) {
        py::gil_scoped_release release;
        ThreadLimit limit(threads);
        return PyMesh(minkowski_sum(a.solid("a"), b.solid("b")));
      },
      py::arg("a"), py::arg("b"), py::kw_only(), py::arg("threads") = py::none(),
      (std::string("Exact Minkowski sum A + B of two valid solids (B convex or not).\n") +
       kThreadsDoc + "\nRaises InvalidSolid when an operand is not a valid solid.")
          .c_str());
  m.def("repair", &repair, py::arg("mesh"), py::kw_only(), py::arg("merge_coplanar") = true,
        py::arg("report") = false, py::arg("budget") = RepairOptions().budget,
        "Exact repair (as `morphex repair`): the valid solid a closed, consistently oriented mesh "
        "bounds where it crosses or touches itself, repeats vertices or faces, or has faces "
        "without area; a valid solid comes back unchanged. With report=True, returns (mesh, "
        "dict) with what was changed. ValueError says what cannot be repaired, or that the "
        "repair would exceed its work budget (budget per input face, as `morphex repair "
        "--budget`; 0: no bound; docs/index-files.md).");
  m.def(
      "structuring_element",
      [](const std::string& text) {
        py::gil_scoped_release release;
        return PyMesh{structuring_element(&text, nullptr).mesh, ""};
      },
      py::arg("text"), "The mesh of a structuring element given as text ('cube:r=1/10').");
}

}  // namespace morphex::python

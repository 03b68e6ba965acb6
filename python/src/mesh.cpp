// SPDX-License-Identifier: GPL-3.0-or-later
// morphex.Mesh (numpy and exact coordinates, files, checks) and morphex.CheckReport.

#include <cmath>
#include <sstream>

#include "common.h"
#include "morphex/check.h"
#include "morphex/io.h"
#include "morphex/json.h"
#include "morphex/rounding.h"
#include "morphex/shapes.h"

namespace morphex::python {
namespace {

// The Python view of a MeshReport: every count plus the exact volume and the first problem.
struct CheckReport {
  MeshReport report;
  std::string problems;  // describe_problems: empty for a valid solid
};

// Faces as an (M, 3) integer array, each index checked against the vertex count.
std::vector<Triangle> faces_from_numpy(const py::object& faces_like, std::size_t vertices) {
  const py::array faces = py::array::ensure(faces_like);  // lists become arrays
  if (!faces) throw py::type_error("faces: expected an (M, 3) integer array");
  if (faces.size() == 0) return {};
  const char kind = faces.dtype().kind();
  if (kind != 'i' && kind != 'u')
    throw py::type_error("faces: expected an integer array, got dtype " +
                         std::string(py::str(faces.dtype())));
  const auto f = py::array_t<long long, py::array::c_style | py::array::forcecast>::ensure(faces);
  if (f.ndim() != 2 || f.shape(1) != 3)
    throw InputError("", "faces: expected an array of shape (M, 3)");
  std::vector<Triangle> out(std::size_t(f.shape(0)));
  const auto view = f.unchecked<2>();
  for (py::ssize_t i = 0; i < f.shape(0); ++i)
    for (py::ssize_t j = 0; j < 3; ++j) {
      const long long v = view(i, j);
      if (v < 0 || std::size_t(v) >= vertices)
        throw InputError("", "faces[" + std::to_string(i) + "][" + std::to_string(j) +
                                 "]: vertex index " + std::to_string(v) + " out of range for " +
                                 std::to_string(vertices) + " vertices");
      out[std::size_t(i)][std::size_t(j)] = VertexIndex(v);
    }
  return out;
}

PyMesh mesh_from_numpy(const py::object& vertices, const py::object& faces) {
  const auto v = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(vertices);
  if (!v || (v.size() > 0 && (v.ndim() != 2 || v.shape(1) != 3)))
    throw InputError("", "vertices: expected an array of shape (N, 3)");
  DoubleMesh d;
  const std::size_t n = v.size() == 0 ? 0 : std::size_t(v.shape(0));
  d.points.resize(n);
  const double* data = v.data();
  for (std::size_t i = 0; i < 3 * n; ++i) {
    if (!std::isfinite(data[i]))
      throw InputError("", "vertices[" + std::to_string(i / 3) + "]: not a finite number");
    d.points[i / 3][i % 3] = data[i];
  }
  d.triangles = faces_from_numpy(faces, n);
  return {from_double(d), ""};  // exact: every double is a rational
}

PyMesh mesh_from_exact(const py::iterable& vertices, const py::object& faces) {
  Mesh out;
  for (const py::handle& p : vertices) out.points.push_back(to_exact_point(p, "vertices"));
  out.triangles = faces_from_numpy(faces, out.points.size());
  return PyMesh(std::move(out));
}

// The double nearest to an exact coordinate (ties to even), rounded once from the exact value
// (morphex::to_double takes the midpoint of CGAL's interval, which for 1/3 can be a neighbour).
double nearest_double(const FT& value) {
  return round_coordinate(value, RoundingGrid::Double);
}

py::array_t<double> vertices_to_numpy(const PyMesh& m) {
  py::array_t<double> out({py::ssize_t(m.mesh().points.size()), py::ssize_t(3)});
  auto view = out.mutable_unchecked<2>();
  {
    py::gil_scoped_release release;  // exact evaluation of constructed points may take a while
    for (std::size_t i = 0; i < m.mesh().points.size(); ++i)
      for (int j = 0; j < 3; ++j)
        view(py::ssize_t(i), py::ssize_t(j)) = nearest_double(m.mesh().points[i][j]);
  }
  return out;
}

py::array_t<long long> faces_to_numpy(const PyMesh& m) {
  py::array_t<long long> out({py::ssize_t(m.mesh().triangles.size()), py::ssize_t(3)});
  auto view = out.mutable_unchecked<2>();
  for (std::size_t i = 0; i < m.mesh().triangles.size(); ++i)
    for (std::size_t j = 0; j < 3; ++j)
      view(py::ssize_t(i), py::ssize_t(j)) = m.mesh().triangles[i][j];
  return out;
}

py::list exact_vertices(const PyMesh& m) {
  py::list out;
  for (const Point& p : m.mesh().points)
    out.append(py::make_tuple(to_rational_string(p.x()), to_rational_string(p.y()),
                              to_rational_string(p.z())));
  return out;
}

std::string mesh_repr(const PyMesh& m) {
  std::ostringstream out;
  out << "<morphex.Mesh " << m.mesh().num_triangles() << " faces, " << m.mesh().num_vertices()
      << " vertices" << (m.source.empty() ? "" : ", from " + m.source) << ">";
  return out.str();
}

void bind_check_report(py::module_& m) {
  using R = CheckReport;
  py::class_<R>(m, "CheckReport",
                "Validity of a mesh as the boundary of a solid (Mesh.check()). True when valid.")
      .def_property_readonly(
          "valid", [](const R& r) { return r.report.valid_solid(); },
          "True for a valid closed solid.")
      .def_property_readonly(
          "problems", [](const R& r) { return r.problems; },
          "The first problem in words, as `morphex check` prints it; '' when "
          "valid.")
      .def_property_readonly(
          "volume", [](const R& r) { return to_fraction(r.report.volume); },
          "Exact signed volume (fractions.Fraction).")
      .def_property_readonly("faces", [](const R& r) { return r.report.triangles; })
      .def_property_readonly("vertices", [](const R& r) { return r.report.vertices; })
      .def_property_readonly("components", [](const R& r) { return r.report.components; })
      .def_property_readonly(
          "genus", [](const R& r) { return r.report.genus; },
          "Sum over closed shells of (2 - chi) / 2; -1 when not a closed "
          "2-manifold.")
      .def_property_readonly("closed", [](const R& r) { return r.report.closed(); })
      .def_property_readonly("border_edges", [](const R& r) { return r.report.border_edges; })
      .def_property_readonly("non_manifold_edges",
                             [](const R& r) { return r.report.non_manifold_edges; })
      .def_property_readonly("non_manifold_vertices",
                             [](const R& r) { return r.report.non_manifold_vertices; })
      .def_property_readonly("degenerate_faces",
                             [](const R& r) { return r.report.degenerate_faces; })
      .def_property_readonly("consistently_oriented",
                             [](const R& r) { return r.report.consistently_oriented; })
      .def_property_readonly("outward", [](const R& r) { return r.report.outward; })
      .def_property_readonly("self_intersections",
                             [](const R& r) { return r.report.self_intersections; })
      .def_property_readonly(
          "bbox",
          [](const R& r) {
            const CGAL::Bbox_3& b = r.report.bbox;
            return py::make_tuple(py::make_tuple(b.xmin(), b.ymin(), b.zmin()),
                                  py::make_tuple(b.xmax(), b.ymax(), b.zmax()));
          },
          "((xmin, ymin, zmin), (xmax, ymax, zmax)), rounded outward to doubles.")
      .def(
          "to_dict", [](const R& r) { return from_json(r.report); },
          "The report as a dict, the library's JSON that `morphex check --json --exact` prints "
          "(without file and seconds): valid, faces, ..., volume (a float), volume_exact (the "
          "rational as text); genus and volumes None when the surface is not closed.")
      .def("__bool__", [](const R& r) { return r.report.valid_solid(); })
      .def("__repr__", [](const R& r) {
        return "<morphex.CheckReport " +
               (r.report.valid_solid()
                    ? std::string("valid, volume ") + to_rational_string(r.report.volume)
                    : "invalid: " + r.problems) +
               ">";
      });
}

CheckReport check(const PyMesh& m, bool self_intersections, const std::optional<int>& threads) {
  py::gil_scoped_release release;
  ThreadLimit limit(threads);
  CheckOptions options;
  options.self_intersections = self_intersections;
  CheckReport r{check_mesh(m.mesh(), options), ""};
  r.problems = describe_problems(r.report);
  return r;
}

PyMesh read(const py::object& path) {
  const std::string p = to_path(path);
  py::gil_scoped_release release;
  return {read_mesh(p), p};  // InputError names the file (ValueError)
}

// The library's report without its timings (Mesh.write's dict has always left them out).
py::dict rounding_dict(const RoundingReport& r) {
  nlohmann::json j = r;
  j.erase("phases");
  return from_json(j);
}

py::object write(const PyMesh& m, const py::object& path, bool exact) {
  const std::string p = to_path(path);
  WriteOptions options;
  options.exact = exact;
  options.measure_rounding = !exact;
  RoundingReport report;
  {
    py::gil_scoped_release release;
    report = write_mesh(m.mesh(), p, options);
  }
  if (exact) return py::none();
  return rounding_dict(report);
}

RoundingGrid grid_named(const std::string& precision) {
  if (precision == "double") return RoundingGrid::Double;
  if (precision == "float") return RoundingGrid::Float;
  throw InputError("precision", "expected 'double' or 'float', got '" + precision + "'");
}

PyMesh rounded(const PyMesh& m, const std::string& precision) {
  const RoundingGrid grid = grid_named(precision);
  py::gil_scoped_release release;
  return {from_double(round_mesh(m.mesh(), {grid}).mesh), m.source};
}

}  // namespace

void register_mesh(py::module_& m) {
  bind_check_report(m);
  py::class_<PyMesh>(m, "Mesh", R"doc(
A closed triangle mesh with exact rational coordinates.

Mesh(vertices, faces): from an (N, 3) float array and an (M, 3) integer array of vertex indices
(counter-clockwise seen from outside); every double is taken exactly. Mesh() is the empty mesh.
Operators: a | b (union), a & b (intersection), a - b (difference).)doc")
      .def(py::init<>())
      .def(py::init(&mesh_from_numpy), py::arg("vertices"), py::arg("faces"))
      .def_static("from_exact", &mesh_from_exact, py::arg("vertices"), py::arg("faces"),
                  "Mesh from exact coordinates: an iterable of 3-sequences of int, Fraction, "
                  "float or text such as '1/3', and an (M, 3) integer array of faces.")
      .def_static("read", &read, py::arg("path"),
                  "Reads OFF (plain or exact), OBJ, STL or PLY; ValueError names the file, the "
                  "problem and the line.")
      .def("write", &write, py::arg("path"), py::arg("exact") = false,
           "Writes the format of the extension, atomically; exact=True writes rational "
           "coordinates (.off only), losslessly. Plain formats round to doubles (OFF, OBJ, PLY) "
           "or floats (STL, glb, 3MF) so that the file reads back as a valid solid; returns what "
           "rounding did (a dict: moved_vertices, rounds, max_displacement, volume_change, ...), "
           "None for exact=True.")
      .def("rounded", &rounded, py::arg("precision") = "double",
           "The mesh with every coordinate a double ('double') or a 32-bit float ('float'), "
           "still a valid solid: where rounding would flatten faces or make them cross, the "
           "solid is resolved exactly and rounded again (what the plain writers do). "
           "mesh.rounded().vertices is then exact.")
      .def_property_readonly(
          "vertices", &vertices_to_numpy,
          "(N, 3) float64 array, each exact coordinate rounded to the nearest double (vertex by "
          "vertex: see rounded() for arrays that stay a valid solid).")
      .def_property_readonly("faces", &faces_to_numpy, "(M, 3) int64 array of vertex indices.")
      .def("exact_vertices", &exact_vertices,
           "Exact coordinates: a list of (x, y, z) strings such as '1/3', each accepted by "
           "fractions.Fraction.")
      .def_property_readonly("num_vertices",
                             [](const PyMesh& p) { return p.mesh().num_vertices(); })
      .def_property_readonly("num_faces", [](const PyMesh& p) { return p.mesh().num_triangles(); })
      .def_property_readonly(
          "source",
          [](const PyMesh& p) -> py::object {
            if (p.source.empty()) return py::none();
            return py::str(p.source);
          },
          "The file the mesh was read from (named in error messages), or None.")
      .def("__len__", [](const PyMesh& p) { return p.mesh().num_triangles(); })
      .def(
          "volume",
          [](const PyMesh& p) {
            FT v;
            {
              py::gil_scoped_release release;
              v = signed_volume(p.mesh());
            }
            return to_fraction(v);
          },
          "Exact signed volume (fractions.Fraction; positive when outward oriented).")
      .def("check", &check, py::kw_only(), py::arg("self_intersections") = true,
           py::arg("threads") = py::none(),
           "Validity report (CheckReport) with the exact volume, as `morphex check`.")
      .def(
          "translated",
          [](const PyMesh& p, const py::object& offset) {
            return PyMesh{translated(p.mesh(), to_exact_point(offset, "offset") - CGAL::ORIGIN),
                          ""};
          },
          py::arg("offset"), "The mesh moved by an exact (dx, dy, dz) (numbers or '1/3' text).")
      .def("__repr__", &mesh_repr)
      .def(py::pickle(
          [](const PyMesh& p) { return py::make_tuple(exact_vertices(p), faces_to_numpy(p)); },
          [](const py::tuple& t) { return mesh_from_exact(t[0].cast<py::iterable>(), t[1]); }));

  m.def(
      "box",
      [](const py::object& lo, const py::object& hi) {
        const Point a = to_exact_point(lo, "min"), b = to_exact_point(hi, "max");
        if (!(a.x() < b.x() && a.y() < b.y() && a.z() < b.z()))
          throw InputError("", "box: min must be below max on every axis");
        return PyMesh{make_box(a, b), ""};
      },
      py::arg("min"), py::arg("max"),
      "The axis-aligned box between two exact corners (numbers or text such as '1/3').");
  m.def(
      "cube",
      [](const py::object& half_side, const py::object& centre) {
        const FT r = to_exact(half_side);
        if (r <= 0)
          throw InputError(
              "", "cube: half_side: expected a positive number, got " + to_rational_string(r));
        return PyMesh{make_cube(r, to_exact_point(centre, "centre")), ""};
      },
      py::arg("half_side"), py::arg("centre") = py::make_tuple(0, 0, 0),
      "The axis-aligned cube of the given exact half side around `centre`.");
}

}  // namespace morphex::python

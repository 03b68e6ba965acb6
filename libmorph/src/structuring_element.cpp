// SPDX-License-Identifier: GPL-3.0-or-later
// Structuring elements: parameter parsing and the exact meshes behind each shape.
#include "morphex/structuring_element.h"
#include "morphex/convex_hull.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <stdexcept>

#include "minkowski_internal.h"
#include "morphex/check.h"
#include "morphex/internal/nearest.h"
#include "morphex/io.h"
#include "morphex/shapes.h"

namespace morphex {
namespace {

const SeParameterInfo kOffset[] = {
    {"ox", "number", "0", "offset of the centre along x"},
    {"oy", "number", "0", "offset of the centre along y"},
    {"oz", "number", "0", "offset of the centre along z"},
};

std::vector<SeParameterInfo> with_offset(std::vector<SeParameterInfo> params) {
  params.insert(params.end(), std::begin(kOffset), std::end(kOffset));
  return params;
}

// Reads the parameters of one shape against its declaration: unknown, duplicate and missing keys
// and malformed values are errors that name the shape and the key.
class ParameterReader {
 public:
  ParameterReader(const SeShapeInfo& info, const SeParameters& given) : info_(info) {
    for (const auto& parameter : given) {
      const std::string& key = parameter.first;
      const std::string& value = parameter.second;
      const auto known = std::find_if(info.parameters.begin(), info.parameters.end(),
                                      [&](const SeParameterInfo& p) { return p.key == key; });
      if (known == info.parameters.end()) {
        std::string list;
        for (const auto& p : info.parameters) list += (list.empty() ? "" : ", ") + p.key;
        fail(key, "unknown parameter (" + info.shape + " takes " + list + ")");
      }
      if (!values_.emplace(key, value).second) fail(key, "given twice");
    }
  }

  std::string text(const std::string& key) const {
    const auto it = values_.find(key);
    if (it != values_.end()) return it->second;
    const auto& p = declaration(key);
    if (p.default_value.empty()) fail(key, "missing (required)");
    return p.default_value;
  }

  FT number(const std::string& key, bool positive) const {
    const std::string value = text(key);
    FT x;
    try {
      x = parse_exact_number(value);
    } catch (const std::exception&) {
      fail(key, "expected a number, got " + value);
    }
    if (positive && x <= 0) fail(key, "expected a positive number, got " + value);
    // Sizes a double cannot hold have no shape morphex can build in reasonable time.
    const double d = std::abs(CGAL::to_double(x));
    if (!std::isfinite(d) || (x != 0 && d < std::numeric_limits<double>::min()))
      fail(key, value + " is outside the range of doubles (about 1e-308 to 1e308)");
    return x;
  }

  int integer(const std::string& key, int min, int max) const {
    const std::string value = text(key);
    std::size_t used = 0;
    long v = 0;
    try {
      v = std::stol(value, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != value.size() || v < min || v > max)
      fail(key, "expected an integer from " + std::to_string(min) + " to " + std::to_string(max) +
                    ", got " + value);
    return int(v);
  }

  Vector offset() const {
    return Vector(number("ox", false), number("oy", false), number("oz", false));
  }

  // "shape:key=value,..." with every given key in declaration order.
  std::string canonical() const {
    std::string out = info_.shape;
    char separator = ':';
    for (const auto& p : info_.parameters) {
      const auto it = values_.find(p.key);
      if (it == values_.end()) continue;
      out += separator + p.key + "=" + it->second;
      separator = ',';
    }
    return out;
  }

  [[noreturn]] void fail(const std::string& key, const std::string& problem) const {
    throw StructuringElementError(info_.shape, key, problem);
  }

 private:
  const SeParameterInfo& declaration(const std::string& key) const {
    for (const auto& p : info_.parameters)
      if (p.key == key) return p;
    throw std::logic_error("undeclared structuring element parameter " + key);
  }

  const SeShapeInfo& info_;
  std::map<std::string, std::string> values_;
};

// A double point in direction `unit` whose exact distance from the origin is at least r (and
// exceeds it by a few ulps at most), so that polyhedral balls and cylinders are never smaller
// than the radius at their vertices.
Point point_at_least(const std::array<double, 3>& unit, const FT& r) {
  double scale = CGAL::to_double(r);
  const FT r2 = r * r;
  for (;;) {
    const Point p(unit[0] * scale, unit[1] * scale, unit[2] * scale);
    if ((p - CGAL::ORIGIN).squared_length() >= r2) return p;
    scale = std::nextafter(scale, std::numeric_limits<double>::infinity()) * (1 + 1e-15);
  }
}

Mesh make_ball(const FT& r, int level) {
  // The subdivided icosahedron gives well-spread directions; its vertices are pushed to the sphere
  // (on or just outside it) and the SE is their exact convex hull.
  const DoubleMesh directions = to_double(make_icosphere(level, FT(1)));
  std::vector<Point> points;
  points.reserve(directions.points.size());
  for (const auto& d : directions.points) {
    const double n = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    points.push_back(point_at_least({d[0] / n, d[1] / n, d[2] / n}, r));
  }
  return convex_hull(points);
}

// A round zonohedron: a sum of segments with small integer weights, the roundest of its family.
// Level 0: along the axes (weight 9) and the body diagonals (+-1, +-1, 1) (weight 8), 7 segments,
// inradius 0.819 of the circumradius (an icosahedron's 0.796). Level 1: along the axes (9), the
// face diagonals (1, +-1, 0) and their permutations (8) and the body diagonals (5), 13 segments,
// 0.916 (the level-1 ball's 0.935). It is scaled so that its farthest vertices are on or just
// outside the sphere of radius r. Being a sum of segments, morphology by it is one sweep per
// segment (zonotope.cpp), like a box's.
Mesh make_zonoball(const FT& r, int level) {
  std::vector<Vector> unit;
  for (int k = 0; k < 3; ++k)
    unit.push_back(Vector(k == 0 ? 9 : 0, k == 1 ? 9 : 0, k == 2 ? 9 : 0));
  if (level >= 1)
    for (int k = 0; k < 3; ++k)
      for (const int s : {1, -1}) {
        int v[3] = {0, 0, 0};
        v[k] = 8;
        v[(k + 1) % 3] = 8 * s;
        unit.push_back(Vector(v[0], v[1], v[2]));
      }
  const int body = level >= 1 ? 5 : 8;
  for (const auto& [x, y] : {std::pair{1, 1}, {1, -1}, {-1, 1}, {-1, -1}})
    unit.push_back(Vector(body * x, body * y, body));
  FT far2 = 0;  // the farthest vertex's squared distance
  for (const Point& p : detail::zonotope_mesh(Point(CGAL::ORIGIN), unit).points)
    far2 = CGAL::max(far2, (p - CGAL::ORIGIN).squared_length());
  // The scale t = r q with q (a double) at least 1 / sqrt(far2), so that the farthest vertices
  // are at distance r sqrt(q^2 far2) >= r.
  double q = 1 / std::sqrt(CGAL::to_double(far2));
  while (FT(q) * FT(q) * far2 < 1) q = std::nextafter(q, std::numeric_limits<double>::infinity());
  const FT t = r * FT(q);
  for (Vector& v : unit) v = v * t;
  return detail::zonotope_mesh(Point(CGAL::ORIGIN), unit);
}

// With an even number of segments the polygon's second half is the first one negated, exactly:
// a centrally symmetric polygon is a sum of segments (its opposite edges are equal and parallel),
// so the prism is a zonotope and morphology by it takes one sweep per segment (zonotope.cpp)
// instead of convolution pieces. Rounding cos and sin separately for each vertex would break that
// symmetry by an ulp.
Mesh make_prism(const FT& r, const FT& height, int segments) {
  const FT half = height / 2;
  const bool symmetric = segments % 2 == 0;
  std::vector<Point> polygon;
  for (int i = 0; i < (symmetric ? segments / 2 : segments); ++i) {
    const double angle = 6.283185307179586 * i / segments;
    polygon.push_back(point_at_least({std::cos(angle), std::sin(angle), 0.0}, r));
  }
  if (symmetric)
    for (int i = 0; i < segments / 2; ++i)
      polygon.emplace_back(-polygon[i].x(), -polygon[i].y(), 0);
  std::vector<Point> points;
  for (const Point& p : polygon) {
    points.emplace_back(p.x(), p.y(), -half);
    points.emplace_back(p.x(), p.y(), half);
  }
  return convex_hull(points);
}

}  // namespace

const std::vector<SeShapeInfo>& structuring_element_shapes() {
  static const std::vector<SeShapeInfo> shapes = {
      {"cube", "axis-aligned cube", with_offset({{"r", "number", "", "half side"}})},
      {"box", "axis-aligned box",
       with_offset({{"x", "number", "", "half size along x"},
                    {"y", "number", "", "half size along y"},
                    {"z", "number", "", "half size along z"}})},
      {"octahedron", "regular octahedron (the L1 ball)",
       with_offset({{"r", "number", "", "distance from the centre to each vertex"}})},
      {"ball",
       "polyhedral ball: an icosahedron subdivided `level` times, vertices on or just outside the "
       "sphere of radius r (exact convex hull)",
       with_offset({{"r", "number", "", "radius"},
                    {"level", "integer", "1", "subdivisions, 0 to 5 (20 * 4^level faces)"}})},
      {"zonoball",
       "round zonohedron, a sum of segments along the axes and the body diagonals (and at level "
       "1 the face diagonals), farthest vertices on or just outside the sphere of radius r: "
       "morphology by one sweep per segment",
       with_offset({{"r", "number", "", "radius (of the farthest vertices)"},
                    {"level", "integer", "1",
                     "0: 7 segments, inradius 0.82 r; 1: 13 segments, inradius 0.92 r"}})},
      {"cylinder",
       "cylinder along z: a prism over a regular polygon whose vertices are on or just outside "
       "the circle of radius r; with an even number of segments the polygon is exactly centrally "
       "symmetric, a sum of segments, and morphology by it is one sweep per segment",
       with_offset({{"r", "number", "", "radius"},
                    {"h", "number", "", "height (the cylinder spans z = -h/2 to h/2)"},
                    {"segments", "integer", "16", "polygon sides, 3 to 1024"}})},
      {"mesh",
       "a closed mesh from a file, convex or not, in its own coordinates (the file's origin is "
       "the SE's reference point)",
       with_offset({{"path", "file", "", "OFF, OBJ, STL or PLY file"}})},
  };
  return shapes;
}

std::string structuring_element_shape_list() {
  const auto& shapes = structuring_element_shapes();
  std::string list;
  for (std::size_t i = 0; i < shapes.size(); ++i)
    list += (i == 0 ? "" : i + 1 == shapes.size() ? " or " : ", ") + shapes[i].shape;
  return list;
}

StructuringElement make_structuring_element(const std::string& shape, const SeParameters& params) {
  const auto& shapes = structuring_element_shapes();
  const auto info = std::find_if(shapes.begin(), shapes.end(),
                                 [&](const SeShapeInfo& s) { return s.shape == shape; });
  if (info == shapes.end()) {
    // Names users reach for first, then the nearest by spelling.
    static const std::vector<std::pair<std::string, std::string>> synonyms = {
        {"sphere", "ball"},    {"icosphere", "ball"},     {"cuboid", "box"},
        {"prism", "cylinder"}, {"diamond", "octahedron"}, {"file", "mesh"}};
    std::string hint;
    for (const auto& [name, meant] : synonyms)
      if (name == shape) hint = meant;
    if (hint.empty()) {
      std::vector<std::string> names;
      for (const SeShapeInfo& s : shapes) names.push_back(s.shape);
      hint = nearest_name(shape, names);
    }
    throw StructuringElementError("", "shape",
                                  "unknown structuring element shape '" + shape + "' (" +
                                      (hint.empty() ? "" : "did you mean '" + hint + "'? ") +
                                      "expected " + structuring_element_shape_list() + ")");
  }
  const ParameterReader read(*info, params);
  StructuringElement se;
  se.shape = shape;
  se.spec = read.canonical();
  if (shape == "cube") {
    se.mesh = make_cube(read.number("r", true));
  } else if (shape == "box") {
    const FT x = read.number("x", true), y = read.number("y", true), z = read.number("z", true);
    se.mesh = make_box(Point(-x, -y, -z), Point(x, y, z));
  } else if (shape == "octahedron") {
    se.mesh = make_octahedron(read.number("r", true));
  } else if (shape == "ball") {
    se.mesh = make_ball(read.number("r", true), read.integer("level", 0, 5));
  } else if (shape == "zonoball") {
    se.mesh = make_zonoball(read.number("r", true), read.integer("level", 0, 1));
  } else if (shape == "cylinder") {
    se.mesh = make_prism(read.number("r", true), read.number("h", true),
                         read.integer("segments", 3, 1024));
  } else {
    const std::string path = read.text("path");
    se.mesh = read_mesh(path);  // InputError names the file
    const MeshReport report = check_mesh(se.mesh, kValidityOnly);
    if (!report.valid_solid())
      read.fail("path", path + ": not a valid solid: " + describe_problems(report));
    se.convex = is_convex(se.mesh);
  }
  const Vector offset = read.offset();
  if (offset != CGAL::NULL_VECTOR) se.mesh = translated(se.mesh, offset);
  make_exact(se.mesh);
  return se;
}

StructuringElement parse_structuring_element(const std::string& text) {
  const auto colon = text.find(':');
  const std::string shape = text.substr(0, colon);
  SeParameters params;
  if (colon != std::string::npos) {
    std::size_t start = colon + 1;
    while (start <= text.size()) {
      const std::size_t comma = std::min(text.find(',', start), text.size());
      const std::string item = text.substr(start, comma - start);
      const auto equals = item.find('=');
      if (equals == std::string::npos || equals == 0)
        throw StructuringElementError(
            "", "", "structuring element '" + text + "': expected key=value, got '" + item + "'");
      params.emplace_back(item.substr(0, equals), item.substr(equals + 1));
      start = comma + 1;
    }
  }
  return make_structuring_element(shape, params);
}

Mesh reflected(const Mesh& mesh) {
  Mesh out;
  out.points.reserve(mesh.points.size());
  for (const Point& p : mesh.points) out.points.push_back(CGAL::ORIGIN - (p - CGAL::ORIGIN));
  // A point reflection has determinant -1: reverse every face to stay outward.
  for (const Triangle& t : mesh.triangles) out.triangles.push_back({t[0], t[2], t[1]});
  make_exact(out);
  return out;
}

void check_structuring_element_scale(const StructuringElement& se, const Mesh& a) {
  if (a.empty() || se.mesh.empty()) return;
  const auto box_of = [](const Mesh& m) {
    CGAL::Bbox_3 box;
    for (const Point& p : m.points) box += p.bbox();
    return box;
  };
  const CGAL::Bbox_3 mesh_box = box_of(a), se_box = box_of(se.mesh);
  double size = 0, smallest = std::numeric_limits<double>::infinity(), extent = 0;
  for (int i = 0; i < 3; ++i) {
    size = std::max(size, mesh_box.max(i) - mesh_box.min(i));
    smallest = std::min(smallest, se_box.max(i) - se_box.min(i));
    extent = std::max({extent, std::abs(se_box.min(i)), std::abs(se_box.max(i))});
  }
  if (!(size > 0) || !std::isfinite(size)) return;
  const auto text = [](double v) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.3g", v);
    return std::string(buffer);
  };
  if (smallest < 1e-12 * size)
    throw StructuringElementError(
        se.shape, "size",
        "a side of " + text(smallest) + " is below 1e-12 of the mesh's size (" + text(size) +
            "): exact results would need numbers (and time) out of all proportion; scale the "
            "element up or the mesh down");
  if (extent > 1e12 * size)
    throw StructuringElementError(
        se.shape, "size",
        "an extent of " + text(extent) + " is above 1e12 times the mesh's size (" + text(size) +
            "): the mesh would vanish into the element and no plain format could hold the "
            "result; scale the element down or the mesh up");
}

}  // namespace morphex

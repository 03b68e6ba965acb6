// SPDX-License-Identifier: GPL-3.0-or-later
#include "morphex/shapes.h"
#include "morphex/internal/fixtures.h"

#include <cmath>
#include <map>

namespace morphex {

Mesh make_box(const Point& lo, const Point& hi) {
  Mesh m;
  for (int i = 0; i < 8; ++i)
    m.points.emplace_back(i & 1 ? hi.x() : lo.x(), i & 2 ? hi.y() : lo.y(),
                          i & 4 ? hi.z() : lo.z());
  m.triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                 {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  return m;
}

Mesh make_cube(const FT& h, const Point& c) {
  return make_box(Point(c.x() - h, c.y() - h, c.z() - h), Point(c.x() + h, c.y() + h, c.z() + h));
}

Mesh make_tetrahedron() {
  Mesh m;
  m.points = {Point(0, 0, 0), Point(1, 0, 0), Point(0, 1, 0), Point(0, 0, 1)};
  m.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  return m;
}

Mesh make_octahedron(const FT& r) {
  Mesh m;
  m.points = {Point(r, 0, 0),  Point(-r, 0, 0), Point(0, r, 0),
              Point(0, -r, 0), Point(0, 0, r),  Point(0, 0, -r)};
  m.triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                 {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  return m;
}

Mesh make_icosahedron() {
  const FT g = FT(1618) / 1000;
  Mesh m;
  m.points = {Point(-1, g, 0), Point(1, g, 0), Point(-1, -g, 0), Point(1, -g, 0),
              Point(0, -1, g), Point(0, 1, g), Point(0, -1, -g), Point(0, 1, -g),
              Point(g, 0, -1), Point(g, 0, 1), Point(-g, 0, -1), Point(-g, 0, 1)};
  m.triangles = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                 {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                 {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                 {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  return m;
}

Mesh make_icosphere(int level, const FT& radius) {
  DoubleMesh d = to_double(make_icosahedron());
  const double r = CGAL::to_double(radius);
  auto project = [&](std::array<double, 3> p) {
    const double n = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    return std::array<double, 3>{p[0] * r / n, p[1] * r / n, p[2] * r / n};
  };
  for (auto& p : d.points) p = project(p);
  for (int l = 0; l < level; ++l) {
    std::map<std::pair<VertexIndex, VertexIndex>, VertexIndex> middle;
    auto mid = [&](VertexIndex a, VertexIndex b) {
      const auto key = std::minmax(a, b);
      auto it = middle.find(key);
      if (it != middle.end()) return it->second;
      const auto& p = d.points[a];
      const auto& q = d.points[b];
      d.points.push_back(project({p[0] + q[0], p[1] + q[1], p[2] + q[2]}));
      return middle[key] = VertexIndex(d.points.size() - 1);
    };
    std::vector<Triangle> finer;
    for (const Triangle& t : d.triangles) {
      const VertexIndex a = mid(t[0], t[1]), b = mid(t[1], t[2]), c = mid(t[2], t[0]);
      finer.insert(finer.end(), {{t[0], a, c}, {t[1], b, a}, {t[2], c, b}, {a, b, c}});
    }
    d.triangles = std::move(finer);
  }
  return from_double(d);
}

Transformation axis_rotation(int axis, const FT& c, const FT& s) {
  if (axis == 0) return Transformation(1, 0, 0, 0, c, -s, 0, s, c);
  if (axis == 1) return Transformation(c, 0, s, 0, 1, 0, -s, 0, c);
  return Transformation(c, -s, 0, s, c, 0, 0, 0, 1);
}

Transformation half_tangent_rotation(int axis, const FT& t) {
  return axis_rotation(axis, (1 - t * t) / (1 + t * t), 2 * t / (1 + t * t));
}

Transformation quaternion_rotation(const FT& a, const FT& b, const FT& c, const FT& d) {
  const FT n = a * a + b * b + c * c + d * d;
  return Transformation(
      (a * a + b * b - c * c - d * d) / n, 2 * (b * c - a * d) / n, 2 * (b * d + a * c) / n,
      2 * (b * c + a * d) / n, (a * a - b * b + c * c - d * d) / n, 2 * (c * d - a * b) / n,
      2 * (b * d - a * c) / n, 2 * (c * d + a * b) / n, (a * a - b * b - c * c + d * d) / n);
}

Mesh make_torus(int nu, int nv, double R, double r) {
  DoubleMesh d;
  const double tau = 6.283185307179586;
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const double u = tau * i / nu, v = tau * j / nv;
      d.points.push_back({(R + r * std::cos(v)) * std::cos(u), (R + r * std::cos(v)) * std::sin(u),
                          r * std::sin(v)});
    }
  auto at = [&](int i, int j) { return VertexIndex(((i + nu) % nu) * nv + (j + nv) % nv); };
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      d.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      d.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  return from_double(d);
}

Mesh make_cylinder(int segments, double radius, double h) {
  DoubleMesh d;
  const double tau = 6.283185307179586;
  for (int i = 0; i < segments; ++i) {
    const double a = tau * i / segments;
    d.points.push_back({radius * std::cos(a), radius * std::sin(a), -h});
    d.points.push_back({radius * std::cos(a), radius * std::sin(a), h});
  }
  const VertexIndex bottom = VertexIndex(d.points.size()), top = bottom + 1;
  d.points.push_back({0, 0, -h});
  d.points.push_back({0, 0, h});
  for (int i = 0; i < segments; ++i) {
    const VertexIndex b0 = 2 * i, t0 = 2 * i + 1, b1 = 2 * ((i + 1) % segments), t1 = b1 + 1;
    d.triangles.push_back({b0, b1, t1});
    d.triangles.push_back({b0, t1, t0});
    d.triangles.push_back({bottom, b1, b0});
    d.triangles.push_back({top, t0, t1});
  }
  return from_double(d);
}

Mesh make_fan_prism(int n, double radius, double height) {
  DoubleMesh d;
  const double tau = 6.283185307179586;
  for (int level = 0; level < 2; ++level)
    for (int i = 0; i < n; ++i)
      d.points.push_back(
          {radius * std::cos(tau * i / n), radius * std::sin(tau * i / n), level * height});
  const VertexIndex top = VertexIndex(n);
  for (VertexIndex i = 0; i < VertexIndex(n); ++i) {
    const VertexIndex j = (i + 1) % VertexIndex(n);
    d.triangles.push_back({i, j, top + j});
    d.triangles.push_back({i, top + j, top + i});
  }
  for (VertexIndex k = 1; k + 1 < VertexIndex(n); ++k) {
    d.triangles.push_back({0, k + 1, k});                // bottom, facing down
    d.triangles.push_back({top, top + k, top + k + 1});  // top
  }
  return from_double(d);
}

Mesh make_fan_cone(int n, double radius, double height) {
  DoubleMesh d;
  const double tau = 6.283185307179586;
  for (int i = 0; i < n; ++i)
    d.points.push_back({radius * std::cos(tau * i / n), radius * std::sin(tau * i / n), 0});
  d.points.push_back({0, 0, height});
  const VertexIndex apex = VertexIndex(n);
  for (VertexIndex i = 0; i < apex; ++i) d.triangles.push_back({i, (i + 1) % apex, apex});
  for (VertexIndex k = 1; k + 1 < apex; ++k) d.triangles.push_back({0, k + 1, k});
  return from_double(d);
}

Mesh make_tetrahedra_on_segment(int count) {
  DoubleMesh d;
  const double tau = 6.283185307179586;
  for (int k = 0; k < count; ++k) {
    const VertexIndex o = VertexIndex(d.points.size());
    const double a = tau * k / count, b = tau * (k + 0.5) / count;
    d.points.push_back({0, 0, 0});
    d.points.push_back({0, 0, 1});
    d.points.push_back({std::cos(a), std::sin(a), 0.5});
    d.points.push_back({std::cos(b), std::sin(b), 0.5});
    // Seen from outside counter-clockwise: the wedge from angle a to b lies to the left of the
    // segment's direction (0,0,1).
    d.triangles.push_back({o, o + 3, o + 2});
    d.triangles.push_back({o + 1, o + 2, o + 3});
    d.triangles.push_back({o, o + 2, o + 1});
    d.triangles.push_back({o, o + 1, o + 3});
  }
  return from_double(d);
}

namespace {
std::pair<Mesh, Mesh> unit_cube_and_shift(int dx, int dy, int dz) {
  const Mesh a = make_box(Point(0, 0, 0), Point(1, 1, 1));
  return {a, translated(a, Vector(dx, dy, dz))};
}
}  // namespace

std::pair<Mesh, Mesh> make_cubes_sharing_face() {
  return unit_cube_and_shift(1, 0, 0);
}
std::pair<Mesh, Mesh> make_cubes_sharing_edge() {
  return unit_cube_and_shift(1, 1, 0);
}
std::pair<Mesh, Mesh> make_cubes_sharing_vertex() {
  return unit_cube_and_shift(1, 1, 1);
}

Mesh concatenate(const Mesh& a, const Mesh& b) {
  Mesh m = a;
  const VertexIndex offset = VertexIndex(a.points.size());
  m.points.insert(m.points.end(), b.points.begin(), b.points.end());
  for (const Triangle& t : b.triangles)
    m.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
  return m;
}

Mesh transformed(const Mesh& mesh, const Transformation& transformation) {
  Mesh m = mesh;
  for (Point& p : m.points) p = transformation.transform(p);
  // A reflection turns the faces inside out: flip them back.
  if (transformation.is_odd())
    for (Triangle& t : m.triangles) std::swap(t[1], t[2]);
  return m;
}

Mesh translated(const Mesh& mesh, const Vector& offset) {
  Mesh m = mesh;
  for (Point& p : m.points) p = p + offset;
  return m;
}

Mesh reversed(const Mesh& mesh) {
  Mesh m = mesh;
  for (Triangle& t : m.triangles) std::swap(t[1], t[2]);
  return m;
}

}  // namespace morphex

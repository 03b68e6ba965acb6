// SPDX-License-Identifier: GPL-3.0-or-later
// Structuring elements that are zonotopes (sums of segments), recognised from their meshes, and
// morphology by them as one segment sweep per generator (segment_sweep.cpp).
//
// A convex polytope Z is a zonotope c + [-h_1, h_1] + ... + [-h_k, h_k] exactly when its edges
// fall into k classes of parallel edges, each class the translates of one edge 2 h_i. Recognition
// takes the true edges (those between non-coplanar triangles) of B's mesh, groups them by
// direction, requires every edge of a class to be +-2 h_i exactly, and then proves the guess: the
// vertices of c + sum [-h_i, h_i], built one generator at a time, must be B's vertices exactly
// (c is the mean of B's vertices, Z's centre of symmetry). Anything else (an octahedron, an
// icosphere, a mesh with vertices inside its faces) is not recognised and takes the convolution.
#include <CGAL/Kernel/global_functions.h>

#include <algorithm>
#include <map>
#include <numeric>
#include <stdexcept>

#include "minkowski_internal.h"
#include "morphex/convex_hull.h"
#include "morphex/progress.h"
#include "morphex/shapes.h"

namespace morphex::detail {
namespace {

using ExactPoint = Kernel::Exact_kernel::Point_3;
using ExactVector = Kernel::Exact_kernel::Vector_3;

// A bound on the proof's work (one hull per generator) and on the sweeps. Not a measured
// crossover: up to 33 generators (a 64-segment cylinder) the sweeps beat the convolution in 22 of
// 24 measured cases, some erosions excepted (docs/benchmarks.md, "Cylinders by sweeps").
constexpr std::size_t kMaxGenerators = 64;

bool parallel(const ExactVector& a, const ExactVector& b) {
  return CGAL::cross_product(a, b) == CGAL::NULL_VECTOR;
}

// Reorders the generators so that the first three are linearly independent; false when no three
// are.
bool independent_first(std::vector<ExactVector>& g) {
  for (std::size_t j = 1; j < g.size(); ++j)
    if (!parallel(g[0], g[j])) {
      std::swap(g[1], g[j]);
      break;
    }
  for (std::size_t j = 2; j < g.size(); ++j)
    if (CGAL::determinant(g[0], g[1], g[j]) != 0) {
      std::swap(g[2], g[j]);
      break;
    }
  return g.size() >= 3 && CGAL::determinant(g[0], g[1], g[2]) != 0;
}

// The edge vectors v - u of B's true edges, each undirected edge once; empty when an edge has not
// exactly two facets.
std::optional<std::vector<ExactVector>> true_edges(const Mesh& b) {
  const DirectedEdges edges(b);
  if (!edges.paired()) return std::nullopt;
  std::vector<ExactVector> out;
  for (std::uint32_t f = 0; f < b.triangles.size(); ++f) {
    const Triangle& t = b.triangles[f];
    for (int i = 0; i < 3; ++i) {
      const VertexIndex u = t[i], v = t[(i + 1) % 3];
      if (u > v) continue;
      const std::uint32_t g = edges.facet(v, u);
      const VertexIndex w = t[(i + 2) % 3], x = third_vertex(b.triangles[g], u, v);
      if (CGAL::orientation(b.points[u], b.points[v], b.points[w], b.points[x]) != CGAL::COPLANAR)
        out.push_back(CGAL::exact(b.points[v]) - CGAL::exact(b.points[u]));
    }
  }
  return out;
}

// The classes of parallel edges as generators h_i (half an edge), when every edge of a class is
// +-2 h_i; the first three linearly independent, so that the proof's point sets span a solid
// from the third step on.
std::optional<std::vector<ExactVector>> generators(const std::vector<ExactVector>& edges) {
  std::vector<ExactVector> full;  // 2 h_i
  std::vector<std::size_t> count;
  for (const ExactVector& e : edges) {
    std::size_t i = 0;
    while (i < full.size() && !parallel(full[i], e)) ++i;
    if (i == full.size()) {
      if (full.size() == kMaxGenerators) return std::nullopt;
      full.push_back(e);
      count.push_back(0);
    }
    if (e != full[i] && e != -full[i]) return std::nullopt;
    ++count[i];
  }
  // A zone of a 3-dimensional zonotope is a belt of at least four parallel edges.
  if (full.size() < 3 ||
      std::any_of(count.begin(), count.end(), [](std::size_t n) { return n < 4; }))
    return std::nullopt;
  if (!independent_first(full)) return std::nullopt;
  for (ExactVector& h : full) h = h / 2;
  return full;
}

// The vertices of c + sum [-h_i, h_i], exact and sorted; h's first three linearly independent.
std::vector<ExactPoint> zonotope_vertices(const ExactPoint& c, const std::vector<ExactVector>& h) {
  std::vector<ExactPoint> vertices = {c};
  for (std::size_t i = 0; i < h.size(); ++i) {
    std::vector<ExactPoint> next;
    next.reserve(2 * vertices.size());
    for (const ExactPoint& p : vertices) {
      next.push_back(p - h[i]);
      next.push_back(p + h[i]);
    }
    if (i >= 2) {  // a solid from here on: keep its hull's vertices
      std::vector<Point> points(next.begin(), next.end());
      const Mesh hull = convex_hull(points);
      next.clear();
      for (const Point& p : hull.points) next.push_back(CGAL::exact(p));
    }
    vertices = std::move(next);
  }
  std::sort(vertices.begin(), vertices.end());
  vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
  return vertices;
}

}  // namespace

Mesh zonotope_mesh(const Point& centre, const std::vector<Vector>& halves) {
  std::vector<ExactVector> h;
  for (const Vector& v : halves) h.push_back(CGAL::exact(v));
  if (!independent_first(h))
    throw std::invalid_argument("zonotope_mesh: the generators do not span 3 dimensions");
  const std::vector<ExactPoint> vertices = zonotope_vertices(CGAL::exact(centre), h);
  Mesh m = convex_hull(std::vector<Point>(vertices.begin(), vertices.end()));
  make_exact(m);
  return m;
}

std::optional<Zonotope> zonotope_of(const Mesh& b) {
  if (b.points.size() < 8 || b.triangles.empty()) return std::nullopt;
  const auto edges = true_edges(b);
  if (!edges) return std::nullopt;
  const auto h = generators(*edges);
  if (!h) return std::nullopt;
  // Z has at most k (k - 1) + 2 vertices (k generators in general position).
  if (b.points.size() > h->size() * (h->size() - 1) + 2) return std::nullopt;
  ExactVector sum = CGAL::NULL_VECTOR;
  for (const Point& p : b.points) sum = sum + (CGAL::exact(p) - CGAL::ORIGIN);
  const ExactPoint c = CGAL::ORIGIN + sum / int(b.points.size());
  std::vector<ExactPoint> mine;
  mine.reserve(b.points.size());
  for (const Point& p : b.points) mine.push_back(CGAL::exact(p));
  std::sort(mine.begin(), mine.end());
  if (zonotope_vertices(c, *h) != mine) return std::nullopt;
  Zonotope z;
  z.centre = point_from_exact(c);
  // Boxes sweep along x, y, z in that order, as they always have.
  std::vector<Vector> halves;
  for (const ExactVector& v : *h) halves.emplace_back(FT(v.x()), FT(v.y()), FT(v.z()));
  std::stable_sort(halves.begin(), halves.end(), [](const Vector& a, const Vector& b) {
    auto axis = [](const Vector& v) {
      for (int k = 0; k < 3; ++k)
        if (v[(k + 1) % 3] == 0 && v[(k + 2) % 3] == 0) return k;
      return 3;
    };
    return axis(a) < axis(b);
  });
  z.halves = std::move(halves);
  return z;
}

LabelledSolid labelled(const Mesh& m) {
  LabelledSolid out{m, std::vector<std::uint32_t>(m.triangles.size())};
  std::iota(out.plane.begin(), out.plane.end(), 0u);
  return out;
}

LabelledSolid zonotope_morphology(LabelledSolid a, const Zonotope& z, bool erode) {
  const Vector offset = z.centre - CGAL::ORIGIN;
  if (!erode && offset != CGAL::NULL_VECTOR) a.mesh = translated(a.mesh, offset);
  for (std::size_t i = 0; i < z.halves.size() && !a.mesh.empty(); ++i) {
    const ProgressPhase phase(double(i) / z.halves.size(), double(i + 1) / z.halves.size());
    a = segment_sweep(a, z.halves[i], erode);
  }
  if (erode && offset != CGAL::NULL_VECTOR) a.mesh = translated(a.mesh, -offset);
  return a;
}

Mesh zonotope_morphology(const Mesh& a, const Zonotope& z, bool erode) {
  return zonotope_morphology(labelled(a), z, erode).mesh;
}

}  // namespace morphex::detail

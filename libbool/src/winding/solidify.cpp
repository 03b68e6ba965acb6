// SPDX-License-Identifier: GPL-3.0-or-later
// solidify (morphex/solidify.h): a closed chain from a soup with CGAL's polygon-soup tools, then
// the exact repair.
#include "morphex/solidify.h"
#include "morphex/internal/solid_access.h"
#include "morphex/progress.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/repair_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/stitch_borders.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <unordered_map>

#include "exact/point_index.h"
#include "morphex/check.h"
#include "morphex/internal/union_find.h"
#include "morphex/repair.h"

namespace morphex {
namespace {

namespace PMP = CGAL::Polygon_mesh_processing;
// The soup path works on the coordinates as doubles (the files it serves store doubles): exact
// predicates on them, and hole filling adds no point.
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using SoupPoint = K::Point_3;
using Polygons = std::vector<std::vector<std::size_t>>;
using SurfaceMesh = CGAL::Surface_mesh<SoupPoint>;

// Vertices within `tolerance` (per coordinate) of an earlier one take its position: one pass
// over a hash grid of cells of that size, each vertex against the 27 cells around it.
std::size_t weld(std::vector<SoupPoint>& points, double tolerance) {
  if (!(tolerance > 0)) return 0;
  struct Key {
    long long x, y, z;
    bool operator==(const Key& o) const { return x == o.x && y == o.y && z == o.z; }
  };
  struct Hash {
    std::size_t operator()(const Key& k) const {
      return std::size_t(std::uint64_t(k.x) * 73856093u ^ std::uint64_t(k.y) * 19349663u ^
                         std::uint64_t(k.z) * 83492791u);
    }
  };
  std::unordered_map<Key, std::vector<std::size_t>, Hash> cells;
  std::size_t welded = 0;
  // Cells counted from the box's corner: at most diagonal / tolerance of them along an axis.
  CGAL::Bbox_3 box;
  for (const SoupPoint& p : points) box += p.bbox();
  const double extent =
      std::max({box.xmax() - box.xmin(), box.ymax() - box.ymin(), box.zmax() - box.zmin()});
  // Below the doubles' resolution only equal positions are one (repair_polygon_soup merges them).
  if (!(extent / tolerance < 1e15)) return 0;
  auto cell = [&](const SoupPoint& p) {
    return Key{(long long)std::floor((p.x() - box.xmin()) / tolerance),
               (long long)std::floor((p.y() - box.ymin()) / tolerance),
               (long long)std::floor((p.z() - box.zmin()) / tolerance)};
  };
  for (std::size_t v = 0; v < points.size(); ++v) {
    const Key c = cell(points[v]);
    std::size_t found = SIZE_MAX;
    for (long long dx = -1; dx <= 1 && found == SIZE_MAX; ++dx)
      for (long long dy = -1; dy <= 1 && found == SIZE_MAX; ++dy)
        for (long long dz = -1; dz <= 1 && found == SIZE_MAX; ++dz) {
          const auto it = cells.find({c.x + dx, c.y + dy, c.z + dz});
          if (it == cells.end()) continue;
          for (const std::size_t u : it->second) {
            const SoupPoint& q = points[u];
            if (std::fabs(q.x() - points[v].x()) <= tolerance &&
                std::fabs(q.y() - points[v].y()) <= tolerance &&
                std::fabs(q.z() - points[v].z()) <= tolerance) {
              found = u;
              break;
            }
          }
        }
    if (found == SIZE_MAX) {
      cells[c].push_back(v);
    } else {
      welded += points[v] != points[found];
      points[v] = points[found];
    }
  }
  return welded;
}

double diagonal(const Mesh& mesh) {
  CGAL::Bbox_3 box;
  for (const Point& p : mesh.points) box += p.bbox();
  return std::sqrt(std::pow(box.xmax() - box.xmin(), 2) + std::pow(box.ymax() - box.ymin(), 2) +
                   std::pow(box.zmax() - box.zmin(), 2));
}

// Each part's (component's) volume sign: interval sums of the faces' triple products in one pass,
// the exact sum where the interval does not decide.
std::vector<CGAL::Sign> part_signs(const Mesh& m, const std::vector<std::uint32_t>& part_of,
                                   std::size_t parts) {
  using I = CGAL::Interval_nt<false>;
  std::vector<I> sums(parts, I(0));
  {
    CGAL::Protect_FPU_rounding<true> rounding;
    for (std::uint32_t f = 0; f < m.triangles.size(); ++f) {
      const Triangle& t = m.triangles[f];
      const auto &a = CGAL::approx(m.points[t[0]]), &b = CGAL::approx(m.points[t[1]]),
                 &c = CGAL::approx(m.points[t[2]]);
      sums[part_of[f]] += a.x() * (b.y() * c.z() - b.z() * c.y()) +
                          a.y() * (b.z() * c.x() - b.x() * c.z()) +
                          a.z() * (b.x() * c.y() - b.y() * c.x());
    }
  }
  std::vector<CGAL::Sign> signs(parts, CGAL::ZERO);
  std::vector<std::uint8_t> undecided(parts, 0);
  for (std::size_t p = 0; p < parts; ++p) {
    const CGAL::Uncertain<CGAL::Sign> s = CGAL::sign(sums[p]);
    if (CGAL::is_certain(s)) signs[p] = CGAL::get_certain(s);
    undecided[p] = !CGAL::is_certain(s);
  }
  std::vector<FT> exact(parts, FT(0));
  for (std::uint32_t f = 0; f < m.triangles.size(); ++f)
    if (undecided[part_of[f]]) {
      const Triangle& t = m.triangles[f];
      exact[part_of[f]] +=
          CGAL::determinant(m.points[t[0]] - CGAL::ORIGIN, m.points[t[1]] - CGAL::ORIGIN,
                            m.points[t[2]] - CGAL::ORIGIN);
    }
  for (std::size_t p = 0; p < parts; ++p)
    if (undecided[p]) signs[p] = CGAL::sign(exact[p]);
  return signs;
}

// In a wild mesh a part is material, never a cavity: the faces of every part whose volume is
// negative are turned (an inward export, a flipped part), and parts without volume are dropped
// (a sheet closed onto itself by the hole filling, a face and its reverse): they bound nothing,
// and a soup of many would otherwise cost the repair's check a pair for every two that cross.
void orient_parts(Mesh& m, SolidifyReport& r) {
  UnionFind sets(m.points.size());
  for (const Triangle& t : m.triangles) {
    sets.join(t[0], t[1]);
    sets.join(t[0], t[2]);
  }
  std::vector<std::uint32_t> part_of_root(m.points.size(), UINT32_MAX), part_of(m.triangles.size());
  std::size_t parts = 0;
  for (std::uint32_t f = 0; f < m.triangles.size(); ++f) {
    std::uint32_t& p = part_of_root[sets.find(m.triangles[f][0])];
    if (p == UINT32_MAX) p = std::uint32_t(parts++);
    part_of[f] = p;
  }
  const std::vector<CGAL::Sign> signs = part_signs(m, part_of, parts);
  for (const CGAL::Sign s : signs) r.turned_parts += s == CGAL::NEGATIVE;
  std::vector<Triangle> kept;
  kept.reserve(m.triangles.size());
  for (std::uint32_t f = 0; f < m.triangles.size(); ++f) {
    Triangle t = m.triangles[f];
    if (signs[part_of[f]] == CGAL::ZERO) {
      ++r.dropped_faces;
      continue;
    }
    if (signs[part_of[f]] == CGAL::NEGATIVE) std::swap(t[1], t[2]);
    kept.push_back(t);
  }
  m.triangles = std::move(kept);
}

// Steps 3 of solidify.h: the soup tools, then the mesh of the closed chain they make.
Mesh closed_chain(const Mesh& mesh, const SolidifyOptions& options, SolidifyReport& r) {
  std::vector<SoupPoint> points;
  points.reserve(mesh.points.size());
  for (const Point& p : mesh.points)
    points.emplace_back(CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z()));
  Polygons polygons;
  polygons.reserve(mesh.triangles.size());
  for (const Triangle& t : mesh.triangles) polygons.push_back({t[0], t[1], t[2]});
  r.welded_vertices = weld(points, options.weld_tolerance * diagonal(mesh));
  PMP::repair_polygon_soup(points, polygons);
  r.dropped_faces = mesh.triangles.size() - std::min(mesh.triangles.size(), polygons.size());
  PMP::orient_polygon_soup(points, polygons);
  SurfaceMesh sm;
  PMP::polygon_soup_to_polygon_mesh(points, polygons, sm);
  PMP::stitch_borders(sm);
  if (options.fill_holes) {
    std::vector<SurfaceMesh::Halfedge_index> cycles;
    PMP::extract_boundary_cycles(sm, std::back_inserter(cycles));
    for (const auto h : cycles) {
      std::vector<SurfaceMesh::Face_index> patch;
      PMP::triangulate_hole(sm, h, std::back_inserter(patch));
      r.filled_holes += !patch.empty();
    }
  }
  Mesh out;
  std::vector<VertexIndex> index(sm.number_of_vertices() + sm.number_of_removed_vertices());
  for (const auto v : sm.vertices()) {
    index[v] = VertexIndex(out.points.size());
    const SoupPoint& p = sm.point(v);
    out.points.emplace_back(p.x(), p.y(), p.z());
  }
  for (const auto f : sm.faces()) {
    std::vector<VertexIndex> corners;
    for (const auto v : CGAL::vertices_around_face(sm.halfedge(f), sm)) corners.push_back(index[v]);
    for (std::size_t k = 1; k + 1 < corners.size(); ++k)  // soup polygons are triangles already
      out.triangles.push_back({corners[0], corners[k], corners[k + 1]});
  }
  orient_parts(out, r);
  if (out.empty()) throw InputError("", "mesh bounds no volume: none of its parts encloses any");
  return out;
}

// The mesh over distinct positions (equal points made one vertex), so that parts are the
// components a reader of the shape sees, not the faces of a soup.
Mesh merged_positions(const Mesh& mesh) {
  Mesh out;
  std::vector<VertexIndex> id(mesh.points.size());
  detail::PointIndex index(out.points);  // the one the repair merges positions with
  index.reserve(mesh.points.size());
  for (std::size_t v = 0; v < mesh.points.size(); ++v) id[v] = index.id(mesh.points[v]);
  for (const Triangle& t : mesh.triangles) out.triangles.push_back({id[t[0]], id[t[1]], id[t[2]]});
  return out;
}

}  // namespace

SolidifyResult solidify(const Mesh& mesh, const SolidifyOptions& options) {
  SolidifyResult out;
  SolidifyReport& r = out.report;
  r.input_faces = mesh.num_triangles();
  if (mesh.empty()) throw InputError("", "mesh bounds no volume: it has no faces");
  ProgressSteps steps;
  steps.next(0.1, "checking");
  if (check_mesh(mesh, kValidityOnly).valid_solid()) {
    r.method = "unchanged";
    out.solid = detail::trusted_solid(mesh);  // the check just said so
    r.output_faces = mesh.num_triangles();
    return out;
  }
  r.changed = true;
  RepairResult repaired;
  try {
    // A closed chain: each part taken as material (an inward part is turned, where the repair
    // alone would subtract it), then the exact repair of their union.
    r.method = "repair";
    steps.next(1, "repairing");
    Mesh chain = merged_positions(mesh);
    orient_parts(chain, r);
    if (chain.empty())
      throw InputError("", "mesh bounds no volume: none of its parts encloses any");
    repaired = repair_mesh(chain, options.repair);
  } catch (const InputError&) {  // not a closed chain: the soup tools make one
    r.method = "soup";
    r.turned_parts = r.dropped_faces = 0;  // counted again, on the soup's closed chain
    // Inside the repair's share of the bar, which moves on from where the failed attempt left it.
    ProgressSteps soup_steps;
    soup_steps.next(0.25, "closing the soup");
    const Mesh chain = closed_chain(mesh, options, r);
    soup_steps.next(1, "repairing");
    try {
      repaired = repair_mesh(chain, options.repair);
    } catch (const InputError& e) {
      // Borders the hole filling could not close (a patch whose border touches itself): the
      // surface encloses nothing that the soup tools could find.
      if (e.problem().find("not closed") == std::string::npos) throw;
      throw InputError("",
                       "mesh bounds no volume: an open surface whose borders could not be "
                       "closed (" +
                           e.problem() + ")");
    }
  }
  r.intersecting_pairs = repaired.report.intersecting_pairs;
  out.solid = std::move(repaired.solid);
  r.output_faces = out.solid.num_triangles();
  return out;
}

std::string describe(const SolidifyReport& r) {
  if (!r.changed) return "unchanged";
  std::ostringstream out;
  out << (r.method == "soup" ? "soup" : "repaired") << ":";
  const char* sep = " ";
  auto item = [&](std::size_t n, const char* what) {
    if (n == 0) return;
    out << sep << what << " " << n;
    sep = ", ";
  };
  item(r.welded_vertices, "welded vertices");
  item(r.dropped_faces, "dropped faces");
  item(r.filled_holes, "filled holes");
  item(r.turned_parts, "turned parts");
  item(r.intersecting_pairs, "intersecting pairs");
  if (*sep == ' ') out << " orientation or duplicates";
  return out.str();
}

}  // namespace morphex

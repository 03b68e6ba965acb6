// SPDX-License-Identifier: GPL-3.0-or-later
// solidify (morphex/solidify.h): a closed chain from a soup with CGAL's polygon-soup tools, then
// the exact repair.
#include "morphex/solidify.h"

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
#include <map>
#include <sstream>
#include <unordered_map>

#include "morphex/check.h"
#include "morphex/repair.h"
#include "morphex/union_find.h"

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
  const double extent = std::max({box.xmax() - box.xmin(), box.ymax() - box.ymin(),
                                  box.zmax() - box.zmin()});
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

// Faces turned in every closed part whose volume is negative: in a wild mesh a part is material,
// never a cavity (an inward export or a flipped part).
std::size_t turn_inward_parts(Mesh& m) {
  UnionFind sets(m.points.size());
  for (const Triangle& t : m.triangles) {
    sets.join(t[0], t[1]);
    sets.join(t[0], t[2]);
  }
  std::unordered_map<std::uint32_t, std::vector<std::uint32_t>> parts;
  for (std::uint32_t f = 0; f < m.triangles.size(); ++f)
    parts[sets.find(m.triangles[f][0])].push_back(f);
  std::size_t turned = 0;
  for (const auto& [root, faces] : parts) {
    Mesh part;
    part.points = m.points;
    for (const std::uint32_t f : faces) part.triangles.push_back(m.triangles[f]);
    if (signed_volume_sign(part) != CGAL::NEGATIVE) continue;
    ++turned;
    for (const std::uint32_t f : faces) std::swap(m.triangles[f][1], m.triangles[f][2]);
  }
  return turned;
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
  r.turned_parts = turn_inward_parts(out);
  return out;
}

// The mesh over distinct positions (equal points made one vertex), so that parts are the
// components a reader of the shape sees, not the faces of a soup.
Mesh merged_positions(const Mesh& mesh) {
  struct Less {
    bool operator()(const Point& a, const Point& b) const {
      return CGAL::compare_xyz(a, b) == CGAL::SMALLER;
    }
  };
  std::map<Point, VertexIndex, Less> index;
  Mesh out;
  std::vector<VertexIndex> id(mesh.points.size());
  for (std::size_t v = 0; v < mesh.points.size(); ++v) {
    const auto [it, inserted] = index.emplace(mesh.points[v], VertexIndex(out.points.size()));
    if (inserted) out.points.push_back(mesh.points[v]);
    id[v] = it->second;
  }
  for (const Triangle& t : mesh.triangles) out.triangles.push_back({id[t[0]], id[t[1]], id[t[2]]});
  return out;
}

}  // namespace

SolidifyResult solidify(const Mesh& mesh, const SolidifyOptions& options) {
  SolidifyResult out;
  SolidifyReport& r = out.report;
  r.input_faces = mesh.num_triangles();
  if (mesh.empty()) throw InputError("", "mesh bounds no volume: it has no faces");
  if (check_mesh(mesh, kValidityOnly).valid_solid()) {
    r.method = "unchanged";
    out.mesh = mesh;
    r.output_faces = mesh.num_triangles();
    return out;
  }
  r.changed = true;
  RepairResult repaired;
  try {
    // A closed chain: each part taken as material (an inward part is turned, where the repair
    // alone would subtract it), then the exact repair of their union.
    r.method = "repair";
    Mesh chain = merged_positions(mesh);
    r.turned_parts = turn_inward_parts(chain);
    repaired = repair_mesh(chain, options.repair);
  } catch (const InputError&) {  // not a closed chain: the soup tools make one
    r.method = "soup";
    const Mesh chain = closed_chain(mesh, options, r);
    try {
      repaired = repair_mesh(chain, options.repair);
    } catch (const InputError& e) {
      // Borders the hole filling could not close (a patch whose border touches itself): the
      // surface encloses nothing that the soup tools could find.
      if (e.problem().find("not closed") == std::string::npos) throw;
      throw InputError("", "mesh bounds no volume: an open surface whose borders could not be "
                           "closed (" + e.problem() + ")");
    }
  }
  r.intersecting_pairs = repaired.report.intersecting_pairs;
  out.mesh = std::move(repaired.mesh);
  r.output_faces = out.mesh.num_triangles();
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

// SPDX-License-Identifier: GPL-3.0-or-later
// Step 7, coplanar merging: after a Boolean, coplanar overlaps leave planar regions cut into many
// triangles by segments that no longer bound anything. The faces around each removable vertex
// (inside a region, or on a straight crease between two) are re-triangulated from their boundary
// without it. Only existing points are used, so the result is exact and unchanged as a set; both
// sides of a crease drop the same vertices, so no T-junction appears.
//
// The work is done on point ids of a PointTable, before output points exist: every face lies in a
// known plane (its input facet's), so coplanarity is decided on the input facets' corners (small,
// cached exact coordinates) and once per pair of planes, never on constructed points.
#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <queue>
#include <unordered_map>

#include "boolean_internal.h"
#include "flat_map.h"
#include "morphex/boolean.h"
#include "spatial.h"
#include "table_traits.h"

namespace morphex {
namespace detail {
namespace {

constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();

// The new triangles of a set of faces, from its boundary (edges over surface vertices), or nullopt
// when it must stay as it is.
template <int dropped>
std::optional<std::vector<Triangle>> triangulate_region(
    const PointTable& table, const IdMesh& surface,
    const std::vector<std::pair<VertexIndex, VertexIndex>>& boundary, const Triangle& seed) {
  using Traits = TableTraits<dropped>;
  using Vb = CGAL::Triangulation_vertex_base_with_info_2<VertexIndex, Traits>;
  using Fb = CGAL::Constrained_triangulation_face_base_2<Traits>;
  using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
  using Cdt = CGAL::Constrained_Delaunay_triangulation_2<
      Traits, Tds, CGAL::No_constraint_intersection_requiring_constructions_tag>;
  Cdt cdt{Traits(&table)};
  auto insert = [&](VertexIndex v) -> std::optional<typename Cdt::Vertex_handle> {
    const std::size_t before = cdt.number_of_vertices();
    auto h = cdt.insert(TablePoint{surface.vertex_point[v], 0});
    if (cdt.number_of_vertices() > before)
      h->info() = v;
    else if (h->info() != v)
      return std::nullopt;  // two vertices at one position: a separated non-manifold feature
    return h;
  };
  try {
    for (const auto& [u, w] : boundary) {
      const auto a = insert(u), b = insert(w);
      if (!a || !b) return std::nullopt;
      cdt.insert_constraint(*a, *b);
    }
  } catch (const std::exception&) {
    return std::nullopt;  // crossing constraints would need new points: keep the faces
  }
  // Inside = odd number of boundary crossings from the unbounded face.
  std::unordered_map<typename Cdt::Face_handle, int> depth;
  std::queue<typename Cdt::Face_handle> frontier;
  std::vector<typename Cdt::Face_handle> next_level{cdt.infinite_face()};
  for (int level = 0; !next_level.empty(); ++level) {
    std::vector<typename Cdt::Face_handle> crossing;
    for (auto f : next_level)
      if (!depth.count(f)) {
        depth[f] = level;
        frontier.push(f);
      }
    next_level.clear();
    while (!frontier.empty()) {
      auto f = frontier.front();
      frontier.pop();
      for (int i = 0; i < 3; ++i) {
        auto n = f->neighbor(i);
        if (depth.count(n)) continue;
        if (f->is_constrained(i))
          crossing.push_back(n);
        else {
          depth[n] = level;
          frontier.push(n);
        }
      }
    }
    next_level = std::move(crossing);
  }
  const auto& p = surface.vertex_point;
  const bool flip =
      table.orientation_2(dropped, p[seed[0]], p[seed[1]], p[seed[2]]) == CGAL::NEGATIVE;
  std::vector<Triangle> out;
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
    if (depth[f] % 2 == 0) continue;
    Triangle t{f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()};
    if (flip) std::swap(t[1], t[2]);
    out.push_back(t);
  }
  return out;
}

// For each vertex flagged in `of_interest`, whether another vertex has its position: the same
// point, or an equal one. Vertices are bucketed by the grid cells their interval boxes cover
// (coincident points have overlapping boxes), and only vertices sharing a cell with a flagged one
// are compared exactly.
std::vector<std::uint8_t> coincident(const PointTable& table, const IdMesh& surface,
                                     const std::vector<std::uint8_t>& of_interest) {
  const std::size_t nv = surface.vertex_point.size();
  std::vector<std::uint8_t> shared(nv, 0);
  // Double boxes: coordinates beyond float range stay finite.
  std::vector<CGAL::Bbox_3> boxes(nv);
  CGAL::Bbox_3 frame;
  for (std::size_t v = 0; v < nv; ++v) {
    boxes[v] = table.approx(surface.vertex_point[v]).bbox();
    frame += boxes[v];
  }
  // Cells about 2^-20 of the extent: far wider than any point's interval box, so that a box
  // covers one cell, rarely two along an axis.
  double cell = 0;
  for (int k = 0; k < 3; ++k) cell = std::max(cell, frame.max(k) - frame.min(k));
  cell = cell > 0 ? std::ldexp(cell, -20) : 1;
  const bool finite = std::isfinite(cell);  // else every box counts as wide
  auto cell_range = [&](const CGAL::Bbox_3& b, std::int64_t(&lo)[3], std::int64_t(&hi)[3]) {
    if (!finite) return std::numeric_limits<std::int64_t>::max();
    std::int64_t count = 1;
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::int64_t(std::floor((b.min(k) - frame.min(k)) / cell));
      hi[k] = std::int64_t(std::floor((b.max(k) - frame.min(k)) / cell));
      count *= std::min<std::int64_t>(hi[k] - lo[k] + 1, 1 << 20);
    }
    return count;
  };
  // Boxes over a few cells (constructions whose intervals are wide) are compared directly.
  constexpr std::int64_t kMaxCells = 8;
  auto for_each_cell = [&](const std::int64_t(&lo)[3], const std::int64_t(&hi)[3], auto&& visit) {
    for (std::int64_t x = lo[0]; x <= hi[0]; ++x)
      for (std::int64_t y = lo[1]; y <= hi[1]; ++y)
        for (std::int64_t z = lo[2]; z <= hi[2]; ++z)
          visit(mix64(std::uint64_t(x) * 0x9e3779b97f4a7c15ull ^ std::uint64_t(y) << 21 ^
                      std::uint64_t(z) << 42));
  };
  auto compare = [&](VertexIndex u, VertexIndex v) {
    if (v != u && CGAL::do_overlap(boxes[u], boxes[v]) &&
        table.equal(surface.vertex_point[u], surface.vertex_point[v]))
      shared[v] = 1;
  };
  std::unordered_map<std::uint64_t, std::vector<VertexIndex>> cells;
  std::vector<VertexIndex> flagged, wide_flagged;
  for (VertexIndex v = 0; v < nv; ++v) {
    if (!of_interest[v]) continue;
    flagged.push_back(v);
    std::int64_t lo[3], hi[3];
    if (cell_range(boxes[v], lo, hi) > kMaxCells)
      wide_flagged.push_back(v);
    else
      for_each_cell(lo, hi, [&](std::uint64_t key) { cells[key].push_back(v); });
  }
  if (flagged.empty()) return shared;
  for (VertexIndex u = 0; u < nv; ++u) {
    for (const VertexIndex v : wide_flagged) compare(u, v);
    std::int64_t lo[3], hi[3];
    if (cell_range(boxes[u], lo, hi) > kMaxCells) {
      for (const VertexIndex v : flagged) compare(u, v);
      continue;
    }
    for_each_cell(lo, hi, [&](std::uint64_t key) {
      const auto it = cells.find(key);
      if (it == cells.end()) return;
      for (const VertexIndex v : it->second) compare(u, v);
    });
  }
  return shared;
}

}  // namespace

void merge_coplanar(const PointTable& table, IdMesh& surface,
                    const std::vector<std::array<PointId, 3>>& planes,
                    std::vector<std::uint32_t>& plane_of) {
  const std::size_t nf = surface.triangles.size(), nv = surface.vertex_point.size();
  if (nf == 0) return;
  const auto& tri = surface.triangles;
  const auto& point = surface.vertex_point;
  // The face across each edge: edge k of face f runs tri[f][k] -> tri[f][k + 1], and its twin is
  // the face around tri[f][k + 1] that runs back. Faces around each vertex are listed
  // contiguously, so the search stays in cache (a hash table of all edges did not).
  std::vector<std::uint32_t> twin(3 * nf, kNone);
  {
    std::vector<std::uint32_t> start(nv + 1, 0);
    for (const Triangle& t : tri)
      for (VertexIndex v : t) ++start[v + 1];
    for (std::size_t v = 0; v < nv; ++v) start[v + 1] += start[v];
    std::vector<std::uint32_t> faces_at(3 * nf), fill(start.begin(), start.end() - 1);
    for (std::uint32_t f = 0; f < nf; ++f)
      for (VertexIndex v : tri[f]) faces_at[fill[v]++] = f;
    for (std::uint32_t f = 0; f < nf; ++f)
      for (int k = 0; k < 3; ++k) {
        const VertexIndex u = tri[f][k], v = tri[f][(k + 1) % 3];
        for (std::uint32_t i = start[v]; i < start[v + 1]; ++i) {
          const Triangle& g = tri[faces_at[i]];
          if ((g[0] == v && g[1] == u) || (g[1] == v && g[2] == u) || (g[2] == v && g[0] == u)) {
            twin[3 * f + k] = faces_at[i];
            break;
          }
        }
      }
  }
  auto twin_face = [&](std::uint32_t f, int k) { return twin[3 * f + k]; };
  // Two planes are one when each corner of the second is on the first and the normals agree;
  // decided once per pair of planes.
  FlatMap<std::uint64_t, std::uint8_t, Hash64> same_plane_cache;
  std::vector<std::unique_ptr<PointTable::Plane>> equation(planes.size());
  auto same_plane = [&](std::uint32_t a, std::uint32_t b) {
    if (a == b) return true;
    const std::uint64_t key = edge_key(std::min(a, b), std::max(a, b));
    if (const std::uint8_t* known = same_plane_cache.find(key)) return *known != 0;
    const auto &pa = planes[a], &pb = planes[b];
    // Intervals first; the planes that meet here are mostly one plane, so the exact test is
    // against the plane's equation, computed once.
    auto on_plane = [&](PointId q) {
      const CGAL::Uncertain<CGAL::Sign> s = table.orientation_filter(pa[0], pa[1], pa[2], q);
      if (s.is_certain()) return s.make_certain() == CGAL::ZERO;
      if (!equation[a])
        equation[a] = std::make_unique<PointTable::Plane>(table.exact_plane(pa[0], pa[1], pa[2]));
      return table.plane_side(*equation[a], q) == CGAL::ZERO;
    };
    const bool same =
        std::all_of(pb.begin(), pb.end(), on_plane) && table.normal_dot(pa, pb) == CGAL::POSITIVE;
    same_plane_cache.emplace(key, same);
    return same;
  };

  // Regions: flood fill across edges whose two faces lie in one plane, alike oriented.
  std::vector<std::uint32_t> region(nf, kNone);
  std::vector<std::uint32_t> region_seed;
  std::vector<std::uint32_t> stack;
  for (std::uint32_t start = 0; start < nf; ++start) {
    if (region[start] != kNone) continue;
    const auto r = std::uint32_t(region_seed.size());
    region_seed.push_back(start);
    region[start] = r;
    stack.push_back(start);
    while (!stack.empty()) {
      const std::uint32_t f = stack.back();
      stack.pop_back();
      for (int i = 0; i < 3; ++i) {
        const std::uint32_t g = twin_face(f, i);
        if (g == kNone || region[g] != kNone || !same_plane(plane_of[f], plane_of[g])) continue;
        region[g] = r;
        stack.push_back(g);
      }
    }
  }
  if (region_seed.size() == nf) return;  // nothing coplanar to merge

  // Removable vertices: inside one region, or on a straight crease between exactly two. Both
  // regions need two faces or more (a corner of a lone triangle stays), which leaves few
  // candidates; only those are examined further.
  std::vector<std::uint32_t> region_size(region_seed.size(), 0);
  for (std::uint32_t f = 0; f < nf; ++f) ++region_size[region[f]];
  std::vector<std::uint32_t> first_region(nv, kNone), second_region(nv, kNone);
  std::vector<std::uint8_t> many_regions(nv, 0);
  for (std::uint32_t f = 0; f < nf; ++f)
    for (VertexIndex v : tri[f]) {
      const std::uint32_t r = region[f];
      if (first_region[v] == kNone || first_region[v] == r)
        first_region[v] = r;
      else if (second_region[v] == kNone || second_region[v] == r)
        second_region[v] = r;
      else
        many_regions[v] = 1;
    }
  std::vector<VertexIndex> candidates;
  std::vector<std::uint8_t> is_candidate(nv, 0);
  for (VertexIndex v = 0; v < nv; ++v) {
    if (first_region[v] == kNone || many_regions[v] || region_size[first_region[v]] < 2) continue;
    if (second_region[v] != kNone && region_size[second_region[v]] < 2) continue;
    candidates.push_back(v);
    is_candidate[v] = 1;
  }
  if (candidates.empty()) return;

  // A region holding a candidate whose position another vertex shares (a separated non-manifold
  // feature or a contact) keeps all its triangles and vertices: its edges may be needed to keep
  // the touching parts meeting only at common vertices and edges.
  std::vector<std::uint8_t> frozen_region(region_seed.size(), 0);
  {
    const std::vector<std::uint8_t> shared = coincident(table, surface, is_candidate);
    for (std::uint32_t f = 0; f < nf; ++f)
      for (VertexIndex v : tri[f])
        if (shared[v]) frozen_region[region[f]] = 1;
  }

  // The crease neighbours of the candidates: the other ends of their edges between two regions.
  std::vector<std::uint32_t> crease_count(nv, 0);
  std::vector<std::array<VertexIndex, 2>> crease(nv);
  std::vector<std::uint32_t> face_at(nv, kNone);  // a face of each candidate, for its plane
  for (std::uint32_t f = 0; f < nf; ++f)
    for (int i = 0; i < 3; ++i) {
      const VertexIndex u = tri[f][i], v = tri[f][(i + 1) % 3];
      if (!is_candidate[u]) continue;
      face_at[u] = f;
      const std::uint32_t g = twin_face(f, i);
      if (g != kNone && region[g] == region[f]) continue;
      if (crease_count[u] < 2) crease[u][crease_count[u]] = v;
      ++crease_count[u];
    }
  // a, v, b collinear (all three in the plane of v's face) with v strictly between a and b.
  auto strictly_between = [&](VertexIndex a, VertexIndex v, VertexIndex b) {
    const auto& plane = planes[plane_of[face_at[v]]];
    const int dropped = table.dominant_axis(plane[0], plane[1], plane[2]);
    if (table.orientation_2(dropped, point[a], point[v], point[b]) != CGAL::ZERO) return false;
    for (int axis = 0; axis < 3; ++axis) {
      const CGAL::Comparison_result ab = table.compare(axis, point[a], point[b]);
      if (ab == CGAL::EQUAL) continue;
      return table.compare(axis, point[a], point[v]) == ab &&
             table.compare(axis, point[v], point[b]) == ab;
    }
    return false;
  };
  std::vector<std::uint8_t> removable(nv, 0);
  std::vector<std::uint8_t> region_changes(region_seed.size(), 0);
  for (const VertexIndex v : candidates) {
    if (frozen_region[first_region[v]] ||
        (second_region[v] != kNone && frozen_region[second_region[v]]))
      continue;
    bool remove = false;
    if (second_region[v] == kNone)
      remove = crease_count[v] == 0;
    else if (crease_count[v] == 2)
      remove = strictly_between(crease[v][0], v, crease[v][1]);
    if (!remove) continue;
    removable[v] = 1;
    region_changes[first_region[v]] = 1;
    if (second_region[v] != kNone) region_changes[second_region[v]] = 1;
  }

  // Only the faces around removable vertices change: per region, their union is re-triangulated
  // from its boundary, with runs of removable vertices skipped (a large planar face that loses
  // two vertices keeps the rest of its triangles).
  std::vector<std::vector<std::uint32_t>> faces_of(region_seed.size());
  std::vector<std::uint8_t> changes(nf, 0);
  for (std::uint32_t f = 0; f < nf; ++f) {
    const Triangle& t = tri[f];
    if (!removable[t[0]] && !removable[t[1]] && !removable[t[2]]) continue;
    changes[f] = 1;
    faces_of[region[f]].push_back(f);
  }
  std::vector<Triangle> out;
  std::vector<std::uint32_t> out_plane;
  out.reserve(nf);
  out_plane.reserve(nf);
  std::unordered_map<VertexIndex, VertexIndex> next;  // along one region's boundary
  for (std::uint32_t r = 0; r < region_seed.size(); ++r) {
    if (!region_changes[r]) continue;
    std::vector<std::pair<VertexIndex, VertexIndex>> directed;
    next.clear();
    for (std::uint32_t f : faces_of[r])
      for (int i = 0; i < 3; ++i) {
        const VertexIndex u = tri[f][i], v = tri[f][(i + 1) % 3];
        const std::uint32_t g = twin_face(f, i);
        if (g != kNone && region[g] == r && changes[g]) continue;
        directed.emplace_back(u, v);
        if (removable[u]) next[u] = v;  // a removable crease vertex has one way on
      }
    std::vector<std::pair<VertexIndex, VertexIndex>> boundary;
    bool ok = true;
    for (const auto& [u, v] : directed) {
      if (removable[u]) continue;
      VertexIndex w = v;
      for (std::size_t steps = 0; removable[w] && ok; ++steps) {
        const auto it = next.find(w);
        ok = it != next.end() && steps < directed.size();
        if (ok) w = it->second;
      }
      boundary.emplace_back(u, w);
    }
    const Triangle& seed = tri[faces_of[r].front()];
    const auto& plane = planes[plane_of[faces_of[r].front()]];
    std::optional<std::vector<Triangle>> merged;
    if (ok) switch (table.dominant_axis(plane[0], plane[1], plane[2])) {
        case 0:
          merged = triangulate_region<0>(table, surface, boundary, seed);
          break;
        case 1:
          merged = triangulate_region<1>(table, surface, boundary, seed);
          break;
        default:
          merged = triangulate_region<2>(table, surface, boundary, seed);
      }
    // Rare (coincident vertices in the region): a neighbour may already have dropped a shared
    // crease vertex, so the only safe answer is the unmerged surface, which is always valid.
    if (!merged) return;
    out.insert(out.end(), merged->begin(), merged->end());
    out_plane.resize(out.size(), plane_of[faces_of[r].front()]);
  }
  for (std::uint32_t f = 0; f < nf; ++f)
    if (!changes[f]) {
      out.push_back(tri[f]);
      out_plane.push_back(plane_of[f]);
    }

  // Compact: keep referenced vertices in their original order.
  std::vector<VertexIndex> new_index(nv, kNone);
  for (const Triangle& t : out)
    for (VertexIndex v : t) new_index[v] = 0;
  IdMesh result;
  for (VertexIndex v = 0; v < nv; ++v)
    if (new_index[v] != kNone) {
      new_index[v] = VertexIndex(result.vertex_point.size());
      result.vertex_point.push_back(point[v]);
    }
  result.triangles.reserve(out.size());
  for (const Triangle& t : out)
    result.triangles.push_back({new_index[t[0]], new_index[t[1]], new_index[t[2]]});
  surface = std::move(result);
  plane_of = std::move(out_plane);
}

Mesh materialize(const PointTable& table, const IdMesh& surface) {
  Mesh out;
  out.points.resize(surface.vertex_point.size());
  tbb::parallel_for(std::size_t(0), out.points.size(),
                    [&](std::size_t v) { out.points[v] = table.point(surface.vertex_point[v]); });
  out.triangles = surface.triangles;
  return out;
}

}  // namespace detail

Mesh merge_coplanar_faces(const Mesh& solid) {
  if (solid.empty()) return solid;
  // The mesh as its own point table: vertex v is point v, and each face is its own plane.
  const detail::PointTable table(solid, solid, true);
  detail::IdMesh surface;
  surface.vertex_point.resize(solid.num_vertices());
  for (VertexIndex v = 0; v < solid.num_vertices(); ++v) surface.vertex_point[v] = v;
  surface.triangles = solid.triangles;
  std::vector<std::array<detail::PointId, 3>> planes(solid.triangles.begin(),
                                                     solid.triangles.end());
  std::vector<std::uint32_t> plane_of(solid.num_triangles());
  for (std::uint32_t f = 0; f < plane_of.size(); ++f) plane_of[f] = f;
  detail::merge_coplanar(table, surface, planes, plane_of);
  return detail::materialize(table, surface);
}

}  // namespace morphex

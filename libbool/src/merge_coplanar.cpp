// SPDX-License-Identifier: GPL-3.0-or-later
// Coplanar merging: after a Boolean, coplanar overlaps leave planar regions cut into many
// triangles by segments that no longer bound anything. Each region is re-triangulated from its
// boundary alone, without the vertices that are not corners of the solid. Only existing points are
// used, so the result is exact and unchanged as a set; both sides of a crease drop the same
// vertices, so no T-junction appears.
#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>
#include <queue>
#include <unordered_map>

#include "boolean_internal.h"
#include "filtered.h"
#include "flat_map.h"
#include "morphex/boolean.h"
#include "morphex/spatial.h"
#include "point_index.h"
#include "projection_traits.h"

namespace morphex {
namespace {

constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();

// The region's new triangles, or nullopt when the region must stay as it is.
template <class Traits>
std::optional<std::vector<Triangle>> triangulate_region(
    const Mesh& mesh, const std::vector<std::pair<VertexIndex, VertexIndex>>& boundary,
    const Triangle& seed) {
  using Vb = CGAL::Triangulation_vertex_base_with_info_2<VertexIndex, Traits>;
  using Fb = CGAL::Constrained_triangulation_face_base_2<Traits>;
  using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
  using Cdt = CGAL::Constrained_Delaunay_triangulation_2<
      Traits, Tds, CGAL::No_constraint_intersection_requiring_constructions_tag>;
  Cdt cdt;
  auto insert = [&](VertexIndex v) -> std::optional<typename Cdt::Vertex_handle> {
    const std::size_t before = cdt.number_of_vertices();
    auto h = cdt.insert(mesh.points[v]);
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
    return std::nullopt;  // crossing constraints would need new points: keep the region
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
  const auto orient = Traits().orientation_2_object();
  const bool flip =
      orient(mesh.points[seed[0]], mesh.points[seed[1]], mesh.points[seed[2]]) == CGAL::NEGATIVE;
  std::vector<Triangle> out;
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
    if (depth[f] % 2 == 0) continue;
    Triangle t{f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()};
    if (flip) std::swap(t[1], t[2]);
    out.push_back(t);
  }
  return out;
}

// For each vertex flagged in `of_interest`, whether another vertex of the mesh has its position.
// Vertices are bucketed by the grid cells their interval boxes cover (coincident points have
// overlapping boxes), and only vertices sharing a cell with a flagged one are compared exactly.
std::vector<std::uint8_t> coincident(const Mesh& mesh,
                                     const std::vector<std::uint8_t>& of_interest) {
  const std::size_t nv = mesh.num_vertices();
  std::vector<std::uint8_t> shared(nv, 0);
  std::vector<FloatBox> boxes(nv);
  FloatBox frame;
  for (std::size_t v = 0; v < nv; ++v) {
    boxes[v] = FloatBox::of(mesh.points[v]);
    frame += boxes[v];
  }
  // Cells about 2^-20 of the extent: far wider than any point's interval box, so that a box
  // covers one cell, rarely two along an axis.
  double cell = 0;
  for (int k = 0; k < 3; ++k) cell = std::max(cell, double(frame.hi[k]) - double(frame.lo[k]));
  cell = cell > 0 ? std::ldexp(cell, -20) : 1;
  auto for_each_cell = [&](const FloatBox& b, auto&& visit) {
    std::int64_t lo[3], hi[3];
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::int64_t(std::floor((double(b.lo[k]) - double(frame.lo[k])) / cell));
      hi[k] = std::int64_t(std::floor((double(b.hi[k]) - double(frame.lo[k])) / cell));
    }
    for (std::int64_t x = lo[0]; x <= hi[0]; ++x)
      for (std::int64_t y = lo[1]; y <= hi[1]; ++y)
        for (std::int64_t z = lo[2]; z <= hi[2]; ++z)
          visit(detail::mix64(std::uint64_t(x) * 0x9e3779b97f4a7c15ull ^ std::uint64_t(y) << 21 ^
                              std::uint64_t(z) << 42));
  };
  std::unordered_map<std::uint64_t, std::vector<VertexIndex>> cells;
  for (VertexIndex v = 0; v < nv; ++v)
    if (of_interest[v])
      for_each_cell(boxes[v], [&](std::uint64_t key) { cells[key].push_back(v); });
  for (VertexIndex u = 0; u < nv; ++u)
    for_each_cell(boxes[u], [&](std::uint64_t key) {
      const auto it = cells.find(key);
      if (it == cells.end()) return;
      for (const VertexIndex v : it->second)
        if (v != u && boxes[u].overlaps(boxes[v]) && mesh.points[u] == mesh.points[v])
          shared[v] = 1;
    });
  return shared;
}

}  // namespace

Mesh merge_coplanar_faces(const Mesh& solid) {
  return detail::merge_coplanar_faces(solid, nullptr);
}

namespace detail {

Mesh merge_coplanar_faces(const Mesh& solid, const std::vector<FaceOrigin>* origin) {
  const std::size_t nf = solid.triangles.size(), nv = solid.points.size();
  if (nf == 0) return solid;
  FlatMap<std::uint64_t, std::uint32_t, Hash64> face_of_edge(3 * nf);
  for (std::uint32_t f = 0; f < nf; ++f)
    for (int i = 0; i < 3; ++i)
      face_of_edge.emplace(detail::edge_key(solid.triangles[f][i], solid.triangles[f][(i + 1) % 3]),
                           f);
  auto twin_face = [&](VertexIndex u, VertexIndex v) {
    const std::uint32_t* face = face_of_edge.find(detail::edge_key(v, u));
    return face ? *face : kNone;
  };
  const auto& p = solid.points;

  // Regions: flood fill across edges whose two faces are coplanar with agreeing normals.
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
      const std::uint32_t stack_face = stack.back();
      const Triangle& t = solid.triangles[stack_face];
      stack.pop_back();
      for (int i = 0; i < 3; ++i) {
        const VertexIndex u = t[i], v = t[(i + 1) % 3], w = t[(i + 2) % 3];
        const std::uint32_t g = twin_face(u, v);
        if (g == kNone || region[g] != kNone) continue;
        // Pieces of one input facet are coplanar and alike oriented: no predicate needed.
        const bool same_facet = origin && (*origin)[g].mesh == (*origin)[stack_face].mesh &&
                                (*origin)[g].face == (*origin)[stack_face].face;
        const Triangle& s = solid.triangles[g];
        if (same_facet) {
          region[g] = r;
          stack.push_back(g);
          continue;
        }
        const VertexIndex x = s[0] != u && s[0] != v ? s[0] : s[1] != u && s[1] != v ? s[1] : s[2];
        if (detail::orient3d(p[u], p[v], p[w], p[x]) != CGAL::COPLANAR ||
            CGAL::coplanar_orientation(p[u], p[v], p[w], p[x]) != CGAL::NEGATIVE)
          continue;
        region[g] = r;
        stack.push_back(g);
      }
    }
  }
  if (region_seed.size() == nf) return solid;  // nothing coplanar to merge

  // Removable vertices: inside one region, or on a straight crease between exactly two. Both
  // regions need two faces or more (a corner of a lone triangle stays), which leaves few
  // candidates; only those are examined further.
  std::vector<std::uint32_t> region_size(region_seed.size(), 0);
  for (std::uint32_t f = 0; f < nf; ++f) ++region_size[region[f]];
  std::vector<std::uint32_t> first_region(nv, kNone), second_region(nv, kNone);
  std::vector<std::uint8_t> many_regions(nv, 0);
  for (std::uint32_t f = 0; f < nf; ++f)
    for (VertexIndex v : solid.triangles[f]) {
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
  if (candidates.empty()) return solid;

  // A region holding a candidate whose position another vertex shares (a separated non-manifold
  // feature or a contact) keeps all its triangles and vertices: its edges may be needed to keep
  // the touching parts meeting only at common vertices and edges.
  std::vector<std::uint8_t> frozen_region(region_seed.size(), 0);
  {
    const std::vector<std::uint8_t> shared = coincident(solid, is_candidate);
    for (std::uint32_t f = 0; f < nf; ++f)
      for (VertexIndex v : solid.triangles[f])
        if (shared[v]) frozen_region[region[f]] = 1;
  }

  // The crease neighbours of the candidates: the other ends of their edges between two regions.
  std::vector<std::uint32_t> crease_count(nv, 0);
  std::vector<std::array<VertexIndex, 2>> crease(nv);
  for (std::uint32_t f = 0; f < nf; ++f)
    for (int i = 0; i < 3; ++i) {
      const VertexIndex u = solid.triangles[f][i], v = solid.triangles[f][(i + 1) % 3];
      if (!is_candidate[u]) continue;
      const std::uint32_t g = twin_face(u, v);
      if (g != kNone && region[g] == region[f]) continue;
      if (crease_count[u] < 2) crease[u][crease_count[u]] = v;
      ++crease_count[u];
    }
  std::vector<std::uint8_t> removable(nv, 0);
  std::vector<std::uint8_t> region_changes(region_seed.size(), 0);
  for (const VertexIndex v : candidates) {
    if (frozen_region[first_region[v]] ||
        (second_region[v] != kNone && frozen_region[second_region[v]]))
      continue;
    bool remove = false;
    if (second_region[v] == kNone)
      remove = crease_count[v] == 0;
    else if (crease_count[v] == 2) {
      const Point& a = p[crease[v][0]];
      const Point& b = p[crease[v][1]];
      remove = detail::collinear3d(a, p[v], b) &&
               CGAL::collinear_are_strictly_ordered_along_line(a, p[v], b);
    }
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
    const Triangle& t = solid.triangles[f];
    if (!removable[t[0]] && !removable[t[1]] && !removable[t[2]]) continue;
    changes[f] = 1;
    faces_of[region[f]].push_back(f);
  }
  std::vector<Triangle> out;
  out.reserve(nf);
  std::unordered_map<VertexIndex, VertexIndex> next;  // along one region's boundary
  for (std::uint32_t r = 0; r < region_seed.size(); ++r) {
    if (!region_changes[r]) continue;
    std::vector<std::pair<VertexIndex, VertexIndex>> directed;
    next.clear();
    for (std::uint32_t f : faces_of[r])
      for (int i = 0; i < 3; ++i) {
        const VertexIndex u = solid.triangles[f][i], v = solid.triangles[f][(i + 1) % 3];
        const std::uint32_t g = twin_face(u, v);
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
    const Triangle& seed = solid.triangles[faces_of[r].front()];
    std::optional<std::vector<Triangle>> merged;
    if (ok) switch (detail::dominant_axis(p[seed[0]], p[seed[1]], p[seed[2]])) {
        case 0:
          merged = triangulate_region<detail::FilteredProjectionTraits<0>>(solid, boundary, seed);
          break;
        case 1:
          merged = triangulate_region<detail::FilteredProjectionTraits<1>>(solid, boundary, seed);
          break;
        default:
          merged = triangulate_region<detail::FilteredProjectionTraits<2>>(solid, boundary, seed);
      }
    // Rare (coincident vertices in the region): a neighbour may already have dropped a shared
    // crease vertex, so the only safe answer is the unmerged solid, which is always valid.
    if (!merged) return solid;
    out.insert(out.end(), merged->begin(), merged->end());
  }
  for (std::uint32_t f = 0; f < nf; ++f)
    if (!changes[f]) out.push_back(solid.triangles[f]);

  // Compact: keep referenced vertices in their original order.
  std::vector<VertexIndex> new_index(nv, kNone);
  for (const Triangle& t : out)
    for (VertexIndex v : t) new_index[v] = 0;
  Mesh result;
  for (VertexIndex v = 0; v < nv; ++v)
    if (new_index[v] != kNone) {
      new_index[v] = VertexIndex(result.points.size());
      result.points.push_back(p[v]);
    }
  result.triangles.reserve(out.size());
  for (const Triangle& t : out)
    result.triangles.push_back({new_index[t[0]], new_index[t[1]], new_index[t[2]]});
  return result;
}

}  // namespace detail
}  // namespace morphex

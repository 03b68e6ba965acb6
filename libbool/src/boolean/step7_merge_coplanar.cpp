// SPDX-License-Identifier: GPL-3.0-or-later
// Step 7, coplanar merging: after a Boolean, coplanar overlaps leave planar regions cut into many
// triangles by segments that no longer bound anything. The faces around each removable vertex
// (inside a region, or on a straight crease between two) are re-triangulated from their boundary
// without it. Only existing points are used, so the result is exact and unchanged as a set; both
// sides of a crease drop the same vertices, so no T-junction appears.
//
// The work is done on point ids of a PointTable, before output points exist: every face lies in a
// known plane (its input facet's), so coplanarity is decided on the input facets' corners (small,
// cached exact coordinates) and once per plane and region, never on constructed points.
//
// After a Boolean, only vertices of faces the Boolean cut may go: the other faces are input
// facets kept whole, around the inputs' own vertices, which the result keeps as they were. The
// merge then looks only at the regions around those vertices: its cost follows the size of the
// cut, not of the output (a coarse part cut into a fine one has a large output and a few
// removable vertices near the cut; docs/benchmarks.md has the measurement).

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <unordered_map>

#include "boolean/boolean_internal.h"
#include "boolean/merge_adjacency.h"
#include "boolean/merge_triangulate.h"
#include "exact/double_plane.h"
#include "morphex/boolean.h"
#include "morphex/internal/parallel_points.h"
#include "morphex/internal/solid_access.h"
#include "tree/box_tree.h"

namespace morphex {
namespace detail {
namespace {

constexpr std::uint32_t kNone = kNoFace;  // no face, no region

// The surface being merged with what every later step reads: its adjacency and its coplanar
// regions (merging never crosses a region's border).
struct Regions {
  const PointTable& table;
  const IdMesh& surface;
  const std::vector<std::array<PointId, 3>>& planes;
  const std::vector<std::uint32_t>& plane_of;
  VertexEdges edges;
  std::vector<std::uint32_t> twin;    // VertexEdges::all_twins, or empty: edges.twin on demand
  std::vector<std::uint32_t> region;  // of each face
  std::uint32_t count = 0;            // regions

  std::uint32_t twin_face(std::uint32_t f, int k) const {
    return twin.empty() ? edges.twin(f, k) : twin[3 * f + k];
  }
};

// What the doubles say of an edge between two faces, at 3 f + k for edge k of face f < its twin.
enum EdgePlanes : std::uint8_t {
  kApart,      // the faces' planes differ (a corner of one is certainly off the other), or no twin
  kOnePlane,   // both faces lie in one input facet's plane
  kUndecided,  // distinct planes that may be one: the exact stage decides
};

// Face f's plane against the planes of the faces across its edges, in doubles. Most edges of a
// curved surface join two planes that a side test tells apart: f's plane is computed once for
// its three edges, and only the corners of the other plane not on it are read, which is cheaper
// than an orientation filter per edge (each would recompute the plane from its corners).
class FaceScreen {
 public:
  FaceScreen(const Regions& s, std::uint32_t f)
      : s_(s), xyz_(s.table.input_near_doubles()), a_(s.plane_of[f]) {
    const std::array<PointId, 3>& pa = s.planes[a_];
    doubles_ = !xyz_.empty() && s.table.is_input(pa[0]) && s.table.is_input(pa[1]) &&
               s.table.is_input(pa[2]);
  }
  // The EdgePlanes of f's edge to face g.
  EdgePlanes against(std::uint32_t g) {
    const std::uint32_t b = s_.plane_of[g];
    return a_ == b ? kOnePlane : apart(b) ? kApart : kUndecided;
  }

 private:
  bool apart(std::uint32_t b) {
    if (!doubles_) return false;
    const std::array<PointId, 3>& pa = s_.planes[a_];
    if (!plane_) plane_ = DoublePlane::through(xyz_[pa[0]], xyz_[pa[1]], xyz_[pa[2]]);
    for (const PointId c : s_.planes[b]) {
      if (c == pa[0] || c == pa[1] || c == pa[2] || !s_.table.is_input(c)) continue;
      const std::optional<int> side = plane_->side(xyz_[pa[0]], xyz_[c], s_.table.input_error());
      if (side && *side != 0) return true;
    }
    return false;
  }
  const Regions& s_;
  const std::vector<std::array<double, 3>>& xyz_;
  const std::uint32_t a_;
  bool doubles_;
  std::optional<DoublePlane> plane_;  // a_'s, once an edge needs it
};

// The EdgePlanes of face f's edges to higher faces, into kind[3 f + k].
void screen_face(const Regions& s, std::uint32_t f, std::vector<std::uint8_t>& kind) {
  FaceScreen screen(s, f);
  for (int k = 0; k < 3; ++k) {
    const std::uint32_t g = s.twin_face(f, k);
    if (g != kNone && g > f) kind[3 * f + k] = screen.against(g);
  }
}

// Each edge's EdgePlanes, in parallel.
std::vector<std::uint8_t> screen_edges(const Regions& s) {
  const std::size_t nf = s.surface.triangles.size();
  std::vector<std::uint8_t> kind(3 * nf, kApart);
  tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, std::uint32_t(nf), 1024),
                    [&](const tbb::blocked_range<std::uint32_t>& range) {
                      for (std::uint32_t f = range.begin(); f < range.end(); ++f)
                        screen_face(s, f, kind);
                    });
  return kind;
}

// Numbers the coplanar regions: flood fill across edges whose two faces lie in one plane, alike
// oriented. That relation between planes is an equivalence, so a face joins a region exactly when
// its plane is the region's: each other plane is tested once per region, and the exact tests are
// of points against the seed's plane by its linear form, computed once (PlaneSides). Testing each
// edge's two planes instead costs a 4x4 determinant per pair of planes, which dominated the merge
// on CAD meshes with large flat faces; the linear form costs four products per point.
//
// Given `active` vertices (those a Boolean may have made removable), only the regions of the faces
// around them are filled, and every other face is a region of its own: none of their vertices
// is a candidate, and no filled region reaches them. The edges are then screened as the fill
// reaches them; for the whole surface, all at once in parallel.
void find_regions(Regions& s, const std::vector<VertexIndex>* active) {
  const std::size_t nf = s.surface.triangles.size();
  const std::vector<std::uint8_t> kind = active ? std::vector<std::uint8_t>() : screen_edges(s);
  // The entry of the edge f -> g, kept at the lower face.
  auto kind_across = [&](std::uint32_t f, int k, std::uint32_t g) -> std::uint8_t {
    if (f < g) return kind[3 * f + k];
    for (int j = 0; j < 3; ++j)
      if (s.twin_face(g, j) == f) return kind[3 * g + j];
    return kApart;
  };
  // By plane: the last region it was tested against, and the answer.
  std::vector<std::uint32_t> tested_for(s.planes.size(), kNone);
  std::vector<std::uint8_t> joins(s.planes.size(), 0);
  s.region.assign(nf, kNone);
  std::vector<std::uint32_t> stack;
  // The seed's plane sides, made when a region first needs an exact test. Declared once: the
  // object is large, and most regions are one face that never needs it.
  std::optional<PointTable::PlaneSides> sides;
  auto fill = [&](std::uint32_t start) {
    if (s.region[start] != kNone) return;
    const std::uint32_t r = s.count++;
    const std::array<PointId, 3>& seed = s.planes[s.plane_of[start]];
    sides.reset();
    // Whether plane b, across an edge from a face of the region in plane a, is the seed's plane
    // (a's, the region's planes being one): b's corners that are a's lie on it already, the
    // filters may put another off it, and the exact stage decides the rest.
    auto same_as_seed = [&](std::uint32_t a, std::uint32_t b) {
      if (tested_for[b] == r) return joins[b] != 0;
      const std::array<PointId, 3>&pa = s.planes[a], &pb = s.planes[b];
      bool undecided[3], same = true;
      for (int k = 0; k < 3 && same; ++k) {
        const CGAL::Uncertain<CGAL::Sign> o =
            s.table.orientation_filter(pa[0], pa[1], pa[2], pb[k]);
        same = !o.is_certain() || o.make_certain() == CGAL::ZERO;
        undecided[k] = !o.is_certain();
      }
      for (int k = 0; k < 3 && same; ++k) {
        if (!undecided[k]) continue;
        if (!sides) sides.emplace(s.table, seed);
        same = sides->exact(pb[k]) == CGAL::ZERO;
      }
      same = same && s.table.normal_dot(pa, pb) == CGAL::POSITIVE;
      tested_for[b] = r;
      joins[b] = same;
      return same;
    };
    s.region[start] = r;
    stack.push_back(start);
    while (!stack.empty()) {
      const std::uint32_t f = stack.back();
      stack.pop_back();
      FaceScreen screen(s, f);
      for (int i = 0; i < 3; ++i) {
        const std::uint32_t g = s.twin_face(f, i);
        if (g == kNone || s.region[g] != kNone) continue;
        const std::uint8_t across = kind.empty() ? screen.against(g) : kind_across(f, i, g);
        if (across == kApart ||
            (across == kUndecided && !same_as_seed(s.plane_of[f], s.plane_of[g])))
          continue;
        s.region[g] = r;
        stack.push_back(g);
      }
    }
  };
  if (!active) {
    for (std::uint32_t f = 0; f < nf; ++f) fill(f);
    return;
  }
  for (const VertexIndex v : *active)
    for (const std::uint32_t* f = s.edges.faces_begin(v); f != s.edges.faces_end(v); ++f) fill(*f);
  for (std::uint32_t f = 0; f < nf; ++f)
    if (s.region[f] == kNone) s.region[f] = s.count++;
}

// Vertices that may be removable: inside one region, or between exactly two (first_region and
// second_region; kNone where a vertex has fewer).
struct Candidates {
  std::vector<std::uint32_t> first_region, second_region;  // of each vertex
  std::vector<VertexIndex> list;
  std::vector<std::uint8_t> flag;  // of each vertex: in `list`
};

// Both regions of a candidate need two faces or more (a corner of a lone triangle stays), which
// leaves few candidates; only those are examined further.
// Only `active` vertices, when given, are considered (see find_regions).
Candidates find_candidates(const Regions& s, const std::vector<VertexIndex>* active) {
  const auto& tri = s.surface.triangles;
  const std::size_t nf = tri.size(), nv = s.surface.vertex_point.size();
  std::vector<std::uint32_t> region_size(s.count, 0);
  for (std::uint32_t f = 0; f < nf; ++f) ++region_size[s.region[f]];
  Candidates c;
  c.first_region.assign(nv, kNone);
  c.second_region.assign(nv, kNone);
  std::vector<std::uint8_t> many_regions(nv, 0);
  auto note = [&](VertexIndex v, std::uint32_t f) {  // face f is around v
    const std::uint32_t r = s.region[f];
    if (c.first_region[v] == kNone || c.first_region[v] == r)
      c.first_region[v] = r;
    else if (c.second_region[v] == kNone || c.second_region[v] == r)
      c.second_region[v] = r;
    else
      many_regions[v] = 1;
  };
  auto consider = [&](VertexIndex v) {
    if (c.first_region[v] == kNone || many_regions[v] || region_size[c.first_region[v]] < 2) return;
    if (c.second_region[v] != kNone && region_size[c.second_region[v]] < 2) return;
    c.list.push_back(v);
    c.flag[v] = 1;
  };
  c.flag.assign(nv, 0);
  if (active) {
    for (const VertexIndex v : *active)
      for (const std::uint32_t* f = s.edges.faces_begin(v); f != s.edges.faces_end(v); ++f)
        note(v, *f);
    for (const VertexIndex v : *active) consider(v);
    return c;
  }
  for (std::uint32_t f = 0; f < nf; ++f)
    for (VertexIndex v : tri[f]) note(v, f);
  for (VertexIndex v = 0; v < nv; ++v) consider(v);
  return c;
}

// A region holding a candidate and a vertex whose position another vertex shares (a separated
// non-manifold feature or a contact) keeps all its triangles and vertices: its edges may be
// needed to keep the touching parts meeting only at common vertices and edges. The shared vertex
// need not be the candidate: where two sheets touch along a segment, one end of it has a copy
// per sheet, and a candidate beside the segment would take the segment's edge with it.
std::vector<std::uint8_t> frozen_regions(const Regions& s, const Candidates& c) {
  const auto& tri = s.surface.triangles;
  std::vector<std::uint8_t> with_candidate(s.count, 0);
  for (std::uint32_t f = 0; f < tri.size(); ++f)
    for (VertexIndex v : tri[f])
      if (c.flag[v]) with_candidate[s.region[f]] = 1;
  std::vector<std::uint8_t> in_such_region(s.surface.vertex_point.size(), 0);
  for (std::uint32_t f = 0; f < tri.size(); ++f)
    if (with_candidate[s.region[f]])
      for (VertexIndex v : tri[f]) in_such_region[v] = 1;
  std::vector<std::uint8_t> frozen(s.count, 0);
  const std::vector<std::uint8_t> shared = coincident(s.table, s.surface, in_such_region);
  for (std::uint32_t f = 0; f < tri.size(); ++f)
    for (VertexIndex v : tri[f])
      if (shared[v]) frozen[s.region[f]] = 1;
  return frozen;
}

// The crease neighbours of the candidates: the other ends of their edges between two regions.
// A candidate on a straight crease has exactly two; `ends` keeps the first two, `count` all.
struct Creases {
  std::vector<std::uint32_t> count;
  std::vector<std::array<VertexIndex, 2>> ends;
  std::vector<std::uint32_t> face_at;  // a face of each candidate, for its plane
  // Of each candidate: the faces on both sides of its first crease edge (kNone, kNone if none),
  // and whether a crease edge of it has no face across.
  std::vector<std::array<std::uint32_t, 2>> across;
  std::vector<std::uint8_t> open;
};

Creases find_creases(const Regions& s, const Candidates& c) {
  const auto& tri = s.surface.triangles;
  const std::size_t nv = s.surface.vertex_point.size();
  Creases creases{std::vector<std::uint32_t>(nv, 0), std::vector<std::array<VertexIndex, 2>>(nv),
                  std::vector<std::uint32_t>(nv, kNone),
                  std::vector<std::array<std::uint32_t, 2>>(nv, {kNone, kNone}),
                  std::vector<std::uint8_t>(nv, 0)};
  for (std::uint32_t f = 0; f < tri.size(); ++f)
    for (int i = 0; i < 3; ++i) {
      const VertexIndex u = tri[f][i], v = tri[f][(i + 1) % 3];
      if (!c.flag[u]) continue;
      creases.face_at[u] = f;
      const std::uint32_t g = s.twin_face(f, i);
      if (g != kNone && s.region[g] == s.region[f]) continue;
      if (creases.count[u] < 2) creases.ends[u][creases.count[u]] = v;
      ++creases.count[u];
      if (g == kNone)
        creases.open[u] = 1;
      else if (creases.across[u][0] == kNone)
        creases.across[u] = {f, g};
    }
  return creases;
}

// Whether faces f and g lie in two distinct planes. Every face of a region lies in its plane, and
// the faces around a candidate lie in two regions: a crease edge with faces on both sides then
// lies in both regions' planes, and when those are distinct, so do the candidate and both crease
// neighbours, on the planes' common line. They are then collinear without evaluating their
// orientation, which for cut points would need their exact coordinates (a flat face of many
// facets crossing another makes whole rows of them).
bool distinct_planes(const Regions& s, std::uint32_t f, std::uint32_t g) {
  const std::uint32_t a = s.plane_of[f], b = s.plane_of[g];
  if (a == b) return false;
  const std::array<PointId, 3>&pa = s.planes[a], &pb = s.planes[b];
  for (const PointId c : pb)
    if (s.table.orientation(pa[0], pa[1], pa[2], c) != CGAL::ZERO) return true;
  return false;
}

// a, v, b collinear (all three in the plane of `face`, a face of v; known to be when `collinear`)
// with v strictly between a and b: only then does dropping v leave the crease straight, with no
// T-junction.
bool strictly_between(const Regions& s, std::uint32_t face, VertexIndex a, VertexIndex v,
                      VertexIndex b, bool collinear) {
  const PointTable& table = s.table;
  const auto& point = s.surface.vertex_point;
  if (!collinear) {
    const auto& plane = s.planes[s.plane_of[face]];
    const int dropped = table.dominant_axis(plane[0], plane[1], plane[2]);
    if (table.orientation_2(dropped, point[a], point[v], point[b]) != CGAL::ZERO) return false;
  }
  // Along any axis on which a and b differ; the one they differ most on first, where intervals
  // tell the order apart (on another, a crease parallel to a coordinate plane would need the
  // points' exact coordinates to find them equal).
  const ApproxPoint &pa = table.approx(point[a]), &pb = table.approx(point[b]);
  std::array<int, 3> axes = {0, 1, 2};
  std::array<double, 3> extent;
  for (int axis = 0; axis < 3; ++axis)
    extent[axis] = std::abs(pb.cartesian(axis).inf() - pa.cartesian(axis).inf());
  std::sort(axes.begin(), axes.end(), [&](int i, int j) { return extent[i] > extent[j]; });
  for (const int axis : axes) {
    const CGAL::Comparison_result ab = table.compare(axis, point[a], point[b]);
    if (ab == CGAL::EQUAL) continue;
    return table.compare(axis, point[a], point[v]) == ab &&
           table.compare(axis, point[v], point[b]) == ab;
  }
  return false;
}

// The vertices merging drops, and the regions that lose one (only those are re-triangulated).
struct Removal {
  std::vector<std::uint8_t> vertex;          // of each vertex: removed
  std::vector<std::uint8_t> region_changes;  // of each region: loses a vertex
};

// The candidates actually removed: those of unfrozen regions that lie inside one region with no
// crease, or on a straight crease between two.
Removal find_removable(const Regions& s, const Candidates& c,
                       const std::vector<std::uint8_t>& frozen) {
  const Creases creases = find_creases(s, c);
  Removal removal{std::vector<std::uint8_t>(s.surface.vertex_point.size(), 0),
                  std::vector<std::uint8_t>(s.count, 0)};
  for (const VertexIndex v : c.list) {
    const std::uint32_t first = c.first_region[v], second = c.second_region[v];
    if (frozen[first] || (second != kNone && frozen[second])) continue;
    bool remove = false;
    if (second == kNone)
      remove = creases.count[v] == 0;
    else if (creases.count[v] == 2) {
      const auto [f, g] = creases.across[v];
      const bool on_line = !creases.open[v] && f != kNone && distinct_planes(s, f, g);
      remove = strictly_between(s, creases.face_at[v], creases.ends[v][0], v, creases.ends[v][1],
                                on_line);
    }
    if (!remove) continue;
    removal.vertex[v] = 1;
    removal.region_changes[first] = 1;
    if (second != kNone) removal.region_changes[second] = 1;
  }
  return removal;
}

// The faces that change: those around removable vertices.
struct Changes {
  std::vector<std::vector<std::uint32_t>> faces_of;  // of each region
  std::vector<std::uint8_t> face;                    // of each face: changes
};

Changes changing_faces(const Regions& s, const Removal& removal) {
  const auto& tri = s.surface.triangles;
  Changes changes{std::vector<std::vector<std::uint32_t>>(s.count),
                  std::vector<std::uint8_t>(tri.size(), 0)};
  for (std::uint32_t f = 0; f < tri.size(); ++f) {
    const Triangle& t = tri[f];
    if (!removal.vertex[t[0]] && !removal.vertex[t[1]] && !removal.vertex[t[2]]) continue;
    changes.face[f] = 1;
    changes.faces_of[s.region[f]].push_back(f);
  }
  return changes;
}

// The boundary of region r's changing faces with each run of removable vertices skipped, or
// nullopt when a run does not lead on to a kept vertex. `next` is scratch space, kept by the
// caller so that its buckets are reused from region to region.
std::optional<Boundary> boundary_without_removable(
    const Regions& s, const Removal& removal, const Changes& changes, std::uint32_t r,
    std::unordered_map<VertexIndex, VertexIndex>& next) {
  const auto& tri = s.surface.triangles;
  const auto& removable = removal.vertex;
  Boundary directed;
  next.clear();
  for (std::uint32_t f : changes.faces_of[r])
    for (int i = 0; i < 3; ++i) {
      const VertexIndex u = tri[f][i], v = tri[f][(i + 1) % 3];
      const std::uint32_t g = s.twin_face(f, i);
      if (g != kNone && s.region[g] == r && changes.face[g]) continue;
      directed.emplace_back(u, v);
      if (removable[u]) next[u] = v;  // a removable crease vertex has one way on
    }
  Boundary boundary;
  for (const auto& [u, v] : directed) {
    if (removable[u]) continue;
    VertexIndex w = v;
    for (std::size_t steps = 0; removable[w]; ++steps) {
      const auto it = next.find(w);
      if (it == next.end() || steps >= directed.size()) return std::nullopt;
      w = it->second;
    }
    boundary.emplace_back(u, w);
  }
  return boundary;
}

// The faces of the merged surface, each with the index of its plane.
struct Faces {
  std::vector<Triangle> triangles;
  std::vector<std::uint32_t> plane_of;
};

// The merged surface's faces: per region, the union of the changing faces re-triangulated from
// its boundary (a large planar face that loses two vertices keeps the rest of its triangles),
// then the unchanged faces in order. Nullopt when a region cannot be re-triangulated.
std::optional<Faces> retriangulate(const Regions& s, const Removal& removal) {
  const auto& tri = s.surface.triangles;
  const std::size_t nf = tri.size();
  const Changes changes = changing_faces(s, removal);
  Faces out;
  out.triangles.reserve(nf);
  out.plane_of.reserve(nf);
  std::unordered_map<VertexIndex, VertexIndex> next;  // along one region's boundary
  for (std::uint32_t r = 0; r < s.count; ++r) {
    if (!removal.region_changes[r]) continue;
    const std::uint32_t seed = changes.faces_of[r].front();
    const std::optional<Boundary> boundary =
        boundary_without_removable(s, removal, changes, r, next);
    std::optional<std::vector<Triangle>> merged;
    if (boundary)
      merged = triangulate_in_plane(s.table, s.surface, s.planes[s.plane_of[seed]], *boundary,
                                    tri[seed]);
    // Rare (coincident vertices in the region): a neighbour may already have dropped a shared
    // crease vertex, so the only safe answer is the unmerged surface, which is always valid.
    if (!merged) return std::nullopt;
    out.triangles.insert(out.triangles.end(), merged->begin(), merged->end());
    out.plane_of.resize(out.triangles.size(), s.plane_of[seed]);
  }
  for (std::uint32_t f = 0; f < nf; ++f)
    if (!changes.face[f]) {
      out.triangles.push_back(tri[f]);
      out.plane_of.push_back(s.plane_of[f]);
    }
  return out;
}

// The surface of `faces` over the referenced vertices only, kept in their original order.
IdMesh compacted(const std::vector<PointId>& point, const std::vector<Triangle>& faces) {
  const std::size_t nv = point.size();
  std::vector<VertexIndex> new_index(nv, kNone);
  for (const Triangle& t : faces)
    for (VertexIndex v : t) new_index[v] = 0;
  IdMesh result;
  for (VertexIndex v = 0; v < nv; ++v)
    if (new_index[v] != kNone) {
      new_index[v] = VertexIndex(result.vertex_point.size());
      result.vertex_point.push_back(point[v]);
    }
  result.triangles.reserve(faces.size());
  for (const Triangle& t : faces)
    result.triangles.push_back({new_index[t[0]], new_index[t[1]], new_index[t[2]]});
  return result;
}

}  // namespace

// Each step narrows the work: coplanar regions, then the few vertices that may go, then those
// that do, and only their faces are re-triangulated.
void merge_coplanar(const PointTable& table, IdMesh& surface,
                    const std::vector<std::array<PointId, 3>>& planes,
                    std::vector<std::uint32_t>& plane_of,
                    const std::vector<std::uint8_t>* touched) {
  const std::size_t nf = surface.triangles.size(), nv = surface.vertex_point.size();
  if (nf == 0) return;
  Regions s{table, surface, planes, plane_of, VertexEdges(surface.triangles, nv)};
  // The vertices that may go: those of the touched faces, or all.
  std::vector<VertexIndex> active;
  if (touched) {
    std::vector<std::uint8_t> seen(nv, 0);
    for (std::uint32_t f = 0; f < nf; ++f)
      if ((*touched)[f])
        for (const VertexIndex v : surface.triangles[f])
          if (!seen[v]) {
            seen[v] = 1;
            active.push_back(v);
          }
    if (active.empty()) return;
  } else {
    s.twin = s.edges.all_twins();
  }
  find_regions(s, touched ? &active : nullptr);
  if (s.count == nf) return;  // nothing coplanar to merge
  const Candidates candidates = find_candidates(s, touched ? &active : nullptr);
  if (candidates.list.empty()) return;
  const Removal removal = find_removable(s, candidates, frozen_regions(s, candidates));
  std::optional<Faces> merged = retriangulate(s, removal);
  if (!merged) return;
  surface = compacted(surface.vertex_point, merged->triangles);
  plane_of = std::move(merged->plane_of);
}

Mesh materialize(const PointTable& table, const IdMesh& surface) {
  Mesh out;
  out.points = parallel_points(surface.vertex_point.size(),
                               [&](std::size_t v) { return table.point(surface.vertex_point[v]); });
  out.triangles = surface.triangles;
  return out;
}

}  // namespace detail

Solid merge_coplanar_faces(const Solid& input) {
  const Mesh& solid = input.mesh();
  if (solid.empty()) return input;
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
  // The same solid as a set, exactly: still valid.
  return detail::trusted_solid(detail::materialize(table, surface));
}

}  // namespace morphex

// SPDX-License-Identifier: GPL-3.0-or-later
// Validity of a mesh as the boundary of a solid. Linear passes over sorted edge records and per
// vertex corner lists; self-intersections by one traversal of the mesh's tree against itself and
// exact tests on a point table (intervals first), where neighbouring triangles are told apart by
// the positions they share.
#include "morphex/check.h"
#include "morphex/progress.h"

#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <optional>
#include <sstream>

#include "check/check_edge_fans.h"
#include "check/check_internal.h"
#include "check/check_nesting.h"
#include "check/check_planar.h"
#include "check/check_planes.h"
#include "check/check_stars.h"
#include "exact/point_index.h"
#include "exact/point_table.h"
#include "exact/static_filter.h"
#include "exact/triangle_overlap.h"
#include "mesh/volume_internal.h"
#include "morphex/internal/union_find.h"
#include "tree/box_frame.h"
#include "tree/box_tree.h"

namespace morphex {

namespace {
using detail::inside_2;
using detail::PointId;
using detail::PointTable;
using detail::segments_meet_2;

using EdgeKey = std::uint64_t;
EdgeKey key(VertexIndex a, VertexIndex b) {
  return (std::uint64_t(std::min(a, b)) << 32) | std::max(a, b);
}

// Exact tests between two triangles of one mesh, on ids of positions (coincident vertices share
// one id, so that triangles touching at separated features meet "at a common vertex").
class TrianglePairs {
 public:
  TrianglePairs(const PointTable& table, const std::vector<PointId>& position)
      : table_(table), position_(position), overlap_(table) {}

  // What a caller knows of a triangle's plane: `sides` over corners that turn as the triangle's
  // (orientation against it, with its signs), built once for many pairs, and points known to lie
  // in it (a flat patch's own vertices, proved coplanar). Points in the plane are where the exact
  // stage is slow: the filter cannot say zero, and off doubles (a rotated part, any Boolean's
  // result) an orientation is a determinant of long integers.
  struct KnownPlane {
    const PointTable::PlaneSides* sides;
    const std::vector<PointId>* in_plane = nullptr;  // sorted
  };

  // True when the closed triangles meet in anything other than nothing, one common vertex or one
  // common edge, "common" by position. `kf`, `kg`: what is known of f's and g's planes, if any.
  bool improper(const Triangle& f, const Triangle& g, const KnownPlane* kf = nullptr,
                const KnownPlane* kg = nullptr) const {
    const std::array<PointId, 3> a = ids(f), b = ids(g);
    int shared = 0, sa = -1, sb = -1, sa2 = -1, sb2 = -1;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        if (a[i] == b[j]) {
          (shared == 0 ? sa : sa2) = i;
          (shared == 0 ? sb : sb2) = j;
          ++shared;
        }
    if (shared >= 3) return true;  // the same triangle twice
    if (shared == 2) {
      // A common edge: improper only when the triangles fold onto each other.
      const PointId p = a[sa], q = a[sa2], rf = a[3 - sa - sa2], rg = b[3 - sb - sb2];
      if (side(a, kf, rg) != CGAL::ZERO) return false;
      const int dropped = table_.dominant_axis(p, q, rf);
      return table_.orientation_2(dropped, p, q, rf) == table_.orientation_2(dropped, p, q, rg);
    }
    if (shared == 1) return improper_at_vertex(a, sa, b, sb, kf, kg);
    return triangles_meet(a, b, kf, kg);
  }

 private:
  std::array<PointId, 3> ids(const Triangle& t) const {
    return {position_[t[0]], position_[t[1]], position_[t[2]]};
  }

  // orientation(t[0], t[1], t[2], x), through what is known of t's plane when `k` is given.
  CGAL::Sign side(const std::array<PointId, 3>& t, const KnownPlane* k, PointId x) const {
    if (!k) return table_.orientation(t[0], t[1], t[2], x);
    if (k->in_plane && std::binary_search(k->in_plane->begin(), k->in_plane->end(), x))
      return CGAL::ZERO;
    return (*k->sides)(x);
  }

  // Triangles a and b with one common position, a[sa] = b[sb], meet beyond it.
  bool improper_at_vertex(const std::array<PointId, 3>& a, int sa, const std::array<PointId, 3>& b,
                          int sb, const KnownPlane* ka, const KnownPlane* kb) const {
    const PointId v = a[sa], a1 = a[(sa + 1) % 3], a2 = a[(sa + 2) % 3], b1 = b[(sb + 1) % 3],
                  b2 = b[(sb + 2) % 3];
    const CGAL::Sign o1 = side(b, kb, a1), o2 = side(b, kb, a2);
    // a meets b's plane at v alone: nothing more of a can be in b.
    if (o1 != CGAL::ZERO && o1 == o2) return false;
    if (o1 == CGAL::ZERO && o2 == CGAL::ZERO) return coplanar_wedges_overlap(v, a1, a2, b1, b2);
    // Anything beyond the common vertex reaches the edge opposite it in one of the triangles.
    return segment_meets_triangle(a1, a2, b, kb) || segment_meets_triangle(b1, b2, a, ka);
  }

  // Coplanar triangles (v, a1, a2) and (v, b1, b2), both proper, meet beyond v exactly when their
  // angles at v overlap: near v each triangle is its angle, and two convex angles that share
  // more than their apex share a side ray of one of them. A few orientations instead of nine
  // segment tests, which matters in fans of long thin facets (every pair shares the apex).
  bool coplanar_wedges_overlap(PointId v, PointId a1, PointId a2, PointId b1, PointId b2) const {
    const int d = table_.dominant_axis(v, a1, a2);
    const CGAL::Sign turn_a = table_.orientation_2(d, v, a1, a2),
                     turn_b = table_.orientation_2(d, v, b1, b2);
    // The ray from v through x lies in the closed angle p v q (turning `turn` from p to q).
    auto in_angle = [&](PointId p, PointId q, CGAL::Sign turn, PointId x) {
      return table_.orientation_2(d, v, p, x) != -turn && table_.orientation_2(d, v, x, q) != -turn;
    };
    return in_angle(a1, a2, turn_a, b1) || in_angle(a1, a2, turn_a, b2) ||
           in_angle(b1, b2, turn_b, a1) || in_angle(b1, b2, turn_b, a2);
  }

  // All of x's corners lie strictly on one side of t's plane, by the filter alone.
  bool certainly_beside(const std::array<PointId, 3>& x, const std::array<PointId, 3>& t) const {
    const CGAL::Uncertain<CGAL::Sign> s0 = table_.orientation_filter(t[0], t[1], t[2], x[0]);
    if (!s0.is_certain() || s0.make_certain() == CGAL::ZERO) return false;
    for (int i = 1; i < 3; ++i) {
      const CGAL::Uncertain<CGAL::Sign> si = table_.orientation_filter(t[0], t[1], t[2], x[i]);
      if (!si.is_certain() || si.make_certain() != s0.make_certain()) return false;
    }
    return true;
  }

  // Closed triangles a and b (no common position) meet.
  bool triangles_meet(const std::array<PointId, 3>& a, const std::array<PointId, 3>& b,
                      const KnownPlane* ka, const KnownPlane* kb) const {
    // Either triangle beside the other's plane settles it. Near-coplanar pairs (a nearly flat
    // face against a wall that ends on it) often have one way that the filter decides and one
    // that needs exact arithmetic, so both ways are tried by the filter first.
    if (certainly_beside(a, b) || certainly_beside(b, a)) return false;
    std::int8_t sa[3], sb[3];
    for (int i = 0; i < 3; ++i) sa[i] = std::int8_t(side(b, kb, a[i]));
    if (sa[0] != 0 && sa[0] == sa[1] && sa[1] == sa[2]) return false;
    for (int i = 0; i < 3; ++i) sb[i] = std::int8_t(side(a, ka, b[i]));
    if (sb[0] != 0 && sb[0] == sb[1] && sb[1] == sb[2]) return false;
    if (sa[0] == 0 && sa[1] == 0 && sa[2] == 0) return coplanar_meet(a, b);
    return overlap_(a, b, sa, sb);
  }

  // Coplanar closed triangles meet: an edge of one crosses or touches an edge of the other, or
  // one holds a vertex of the other.
  bool coplanar_meet(const std::array<PointId, 3>& a, const std::array<PointId, 3>& b) const {
    const int d = table_.dominant_axis(a[0], a[1], a[2]);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        if (segments_meet_2(table_, d, a[i], a[(i + 1) % 3], b[j], b[(j + 1) % 3])) return true;
    return inside_2(table_, d, a, b[0]) || inside_2(table_, d, b, a[0]);
  }

  // The closed segment ab meets the closed triangle t (a, b not corners of t by position).
  bool segment_meets_triangle(PointId a, PointId b, const std::array<PointId, 3>& t,
                              const KnownPlane* kt) const {
    const CGAL::Sign oa = side(t, kt, a), ob = side(t, kt, b);
    if (oa != CGAL::ZERO && oa == ob) return false;
    if (oa == CGAL::ZERO && ob == CGAL::ZERO) {
      const int d = table_.dominant_axis(t[0], t[1], t[2]);
      for (int j = 0; j < 3; ++j)
        if (segments_meet_2(table_, d, a, b, t[j], t[(j + 1) % 3])) return true;
      return inside_2(table_, d, t, a);
    }
    // ab crosses or touches the plane: the point is in t when ab sees t's edges all one way.
    const CGAL::Sign s0 = table_.orientation(a, b, t[0], t[1]),
                     s1 = table_.orientation(a, b, t[1], t[2]),
                     s2 = table_.orientation(a, b, t[2], t[0]);
    const bool no_positive = s0 != CGAL::POSITIVE && s1 != CGAL::POSITIVE && s2 != CGAL::POSITIVE;
    const bool no_negative = s0 != CGAL::NEGATIVE && s1 != CGAL::NEGATIVE && s2 != CGAL::NEGATIVE;
    return no_positive || no_negative;
  }

  const PointTable& table_;
  const std::vector<PointId>& position_;
  detail::TriangleOverlap overlap_;
};

// Degenerate faces: repeated corners, or collinear ones (every projection of the triangle flat).
// The face planes' filter settles nearly every proper face as they are computed.
std::vector<std::uint8_t> find_degenerate_faces(const Mesh& mesh, const PointTable& table,
                                                const detail::FacePlanes& planes, MeshReport& r) {
  const std::size_t nf = mesh.num_triangles();
  std::vector<std::uint8_t> degenerate(nf, 0);
  detail::for_each_upward(nf, [&](std::size_t f) {
    const Triangle& t = mesh.triangles[f];
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) {
      degenerate[f] = 1;
      return;
    }
    if (planes.proper(std::uint32_t(f))) return;
    degenerate[f] = table.orientation_2(0, t[0], t[1], t[2]) == CGAL::ZERO &&
                    table.orientation_2(1, t[0], t[1], t[2]) == CGAL::ZERO &&
                    table.orientation_2(2, t[0], t[1], t[2]) == CGAL::ZERO;
  });
  for (std::uint32_t f = 0; f < nf; ++f)
    if (degenerate[f]) {
      if (!r.first_degenerate_face) r.first_degenerate_face = f;
      ++r.degenerate_faces;
    }
  return degenerate;
}

// For each manifold edge (two uses), its two faces, sorted by edge key.
using detail::ManifoldEdges;

// Edges by vertex index: sorted records (edge, face, direction), one run per edge. Counts border
// and non-manifold edges and misoriented pairs, and joins the faces of every edge in `components`.
ManifoldEdges check_edges(const Mesh& mesh, UnionFind& components, MeshReport& r) {
  struct EdgeRecord {
    EdgeKey edge;
    std::uint32_t face;
    bool forward;  // min -> max
    bool operator<(const EdgeRecord& o) const {
      return edge != o.edge ? edge < o.edge : face < o.face;
    }
  };
  const std::size_t nf = mesh.num_triangles();
  std::vector<EdgeRecord> records(3 * nf);
  tbb::parallel_for(std::uint32_t(0), std::uint32_t(nf), [&](std::uint32_t f) {
    for (int k = 0; k < 3; ++k) {
      const VertexIndex a = mesh.triangles[f][k], b = mesh.triangles[f][(k + 1) % 3];
      records[3 * f + k] = {key(a, b), f, a < b};
    }
  });
  tbb::parallel_sort(records.begin(), records.end());
  ManifoldEdges manifold;
  manifold.reserve(3 * nf / 2);
  for (std::size_t i = 0; i < records.size();) {
    std::size_t j = i + 1;
    while (j < records.size() && records[j].edge == records[i].edge) ++j;
    const std::size_t count = j - i;
    for (std::size_t k = i + 1; k < j; ++k) components.join(records[k].face, records[i].face);
    if (count == 1) {
      ++r.border_edges;
      const VertexIndex v = VertexIndex(records[i].edge >> 32);
      if (!r.first_border_vertex || v < *r.first_border_vertex) r.first_border_vertex = v;
    } else if (count > 2) {
      ++r.non_manifold_edges;
    } else {
      if (records[i].forward == records[i + 1].forward) {
        r.consistently_oriented = false;
        if (!r.first_misoriented_face || records[i].face < *r.first_misoriented_face)
          r.first_misoriented_face = records[i].face;
      }
      manifold.push_back({records[i].edge, {records[i].face, records[i + 1].face}});
    }
    i = j;
  }
  return manifold;
}

// Non-manifold vertices: the faces around a vertex must form one fan through manifold edges.
void check_vertex_fans(const Mesh& mesh, const ManifoldEdges& manifold, MeshReport& r) {
  const std::size_t nf = mesh.num_triangles(), nv = mesh.num_vertices();
  // Corners 3 f + k, joined across every manifold edge at their vertex: one set per fan. (A
  // corner repeated in a degenerate face is joined through its first occurrence only.)
  auto corner = [&](std::uint32_t f, VertexIndex v) {
    const Triangle& t = mesh.triangles[f];
    return std::uint32_t(3 * f + (t[0] == v ? 0 : t[1] == v ? 1 : 2));
  };
  UnionFind fans(3 * nf);
  for (const auto& [edge, faces] : manifold) {
    for (const VertexIndex v : {VertexIndex(edge >> 32), VertexIndex(edge & 0xffffffffu)})
      fans.join(corner(faces[0], v), corner(faces[1], v));
  }
  std::vector<std::uint32_t> fan_of(nv, UINT32_MAX);
  std::vector<std::uint8_t> bad(nv, 0);
  for (std::uint32_t c = 0; c < 3 * nf; ++c) {
    const VertexIndex v = mesh.triangles[c / 3][c % 3];
    const std::uint32_t fan = fans.find(c);
    if (fan_of[v] == UINT32_MAX)
      fan_of[v] = fan;
    else if (fan_of[v] != fan)
      bad[v] = 1;
  }
  for (VertexIndex v = 0; v < nv; ++v)
    if (bad[v]) {
      ++r.non_manifold_vertices;
      if (!r.first_non_manifold_vertex) r.first_non_manifold_vertex = v;
    }
}

// Edges, fans and the local proofs of the stars in one pass by vertex (check_stars.h), or, when
// some face repeats a vertex, by sorted edge records and fans over corners. Joins the faces of
// every edge in `components`; `proved` gets the vertices whose stars are proved embedded.
ManifoldEdges check_topology(const Mesh& mesh, const PointTable& table, bool prove,
                             UnionFind& components, std::vector<std::uint8_t>& proved,
                             MeshReport& r) {
  for (const Triangle& t : mesh.triangles)
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) {
      ManifoldEdges manifold = check_edges(mesh, components, r);
      check_vertex_fans(mesh, manifold, r);
      return manifold;
    }
  detail::VertexStars stars = detail::examine_vertex_stars(mesh, table, prove);
  for (const auto& [edge, faces] : stars.manifold) components.join(faces[1], faces[0]);
  for (const auto& [f, g] : stars.other_joins) components.join(f, g);
  r.border_edges = stars.border_edges;
  r.first_border_vertex = stars.first_border_vertex;
  r.non_manifold_edges = stars.non_manifold_edges;
  r.consistently_oriented = !stars.first_misoriented_face;
  r.first_misoriented_face = stars.first_misoriented_face;
  r.non_manifold_vertices = stars.non_manifold_vertices;
  r.first_non_manifold_vertex = stars.first_non_manifold_vertex;
  proved = std::move(stars.embedded);
  return std::move(stars.manifold);
}

// Each face's component, numbered 0.. in face order; sets r.components.
std::vector<std::uint32_t> number_components(UnionFind& components, std::size_t nf, MeshReport& r) {
  std::vector<std::uint32_t> component_of(nf), index(nf, UINT32_MAX);
  std::uint32_t count = 0;
  for (std::uint32_t f = 0; f < nf; ++f) {
    std::uint32_t& c = index[components.find(f)];
    if (c == UINT32_MAX) c = count++;
    component_of[f] = c;
  }
  r.components = count;
  return component_of;
}

// The genus summed over shells, from chi = V - E + F per shell (a vertex of a manifold surface
// is in one shell); -1 when the surface is not a closed 2-manifold.
long total_genus(const Mesh& mesh, const std::vector<std::uint32_t>& component_of,
                 const MeshReport& r) {
  if (!r.closed() || r.non_manifold_edges != 0 || r.non_manifold_vertices != 0) return -1;
  std::vector<long> vertices(r.components, 0), faces(r.components, 0);
  std::vector<std::uint8_t> counted(mesh.num_vertices(), 0);
  for (std::uint32_t f = 0; f < mesh.num_triangles(); ++f) {
    ++faces[component_of[f]];
    for (VertexIndex v : mesh.triangles[f])
      if (!counted[v]) {
        counted[v] = 1;
        ++vertices[component_of[f]];
      }
  }
  long genus = 0;
  for (std::size_t c = 0; c < r.components; ++c)
    genus += (2 - (vertices[c] - faces[c] * 3 / 2 + faces[c])) / 2;
  return genus;
}

// Improper pairs found by one task: how many, the first (smallest (i, j)) and, when listed, all.
struct Found {
  std::size_t count = 0;
  std::pair<std::uint32_t, std::uint32_t> first{UINT32_MAX, UINT32_MAX};
  std::vector<std::pair<std::uint32_t, std::uint32_t>> all;
  void add(std::uint32_t i, std::uint32_t j, bool list) {
    const auto pair = std::make_pair(std::min(i, j), std::max(i, j));
    ++count;
    first = std::min(first, pair);
    if (list) all.push_back(pair);
  }
};

void report(const std::vector<Found>& found, MeshReport& r) {
  for (const Found& f : found) {
    r.self_intersections += f.count;
    if (f.count > 0 && (!r.first_self_intersection || f.first < *r.first_self_intersection))
      r.first_self_intersection = f.first;
    r.self_intersecting_pairs.insert(r.self_intersecting_pairs.end(), f.all.begin(), f.all.end());
  }
  std::sort(r.self_intersecting_pairs.begin(), r.self_intersecting_pairs.end());
}

// Patches of at least this many triangles are proved embedded as a whole (check_planar.h);
// smaller flat regions are cheaper to test pair by pair.
constexpr std::size_t kMinPlanarPatch = 16;
// Vertex stars of at least this many triangles (a cone's apex, a fan over a curved cap) are
// proved as a whole, the same way.
constexpr std::size_t kMinStar = 32;

// The triangles that may meet patch `p` improperly: those near its box that meet its plane
// elsewhere than in its vertices and edges (a flat patch) or reach into its slab (a nearly flat
// one), outside it and outside the patches before it (whose own candidates included p's
// triangles). For a slab, `parts` gets the box of each candidate's part in it.
std::vector<std::uint32_t> patch_candidates(const Mesh& mesh, const PointTable& table,
                                            const std::vector<PointId>& position,
                                            const detail::PlanarPatches& planar,
                                            const TriangleTree& rest, const TriangleTree& patched,
                                            const detail::BoxFrame& frame,
                                            const std::vector<FloatBox>& vertex_boxes,
                                            std::size_t p, std::vector<CGAL::Bbox_3>& parts) {
  const detail::PlanarPatch& patch = planar.patches[p];
  std::vector<std::uint32_t> out;
  const PointTable::PlaneSides plane_side(table, patch.plane);
  auto consider = [&](std::uint32_t t) {
    const Triangle& f = mesh.triangles[t];
    const std::array<PointId, 3> corners = {position[f[0]], position[f[1]], position[f[2]]};
    if (patch.kind == detail::PlanarPatch::Kind::NearlyFlat) {
      if (const auto part = detail::part_in_slab(table, patch, corners, frame)) {
        out.push_back(t);
        parts.push_back(*part);
      }
    } else if (patch.kind == detail::PlanarPatch::Kind::Star ||
               !detail::meets_patch_only_at_its_features(plane_side, patch, corners))
      out.push_back(t);
  };
  const detail::UpwardRounding rounding;
  // The patch's box as the trees box triangles (in their frame), from its corners.
  FloatBox box;
  for (const std::uint32_t t : patch.triangles)
    for (const VertexIndex v : mesh.triangles[t]) box += vertex_boxes[v];
  rest.for_each_overlap(box, consider);
  patched.for_each_overlap(box, [&](std::uint32_t t) {
    if (std::size_t(planar.patch_of[t]) > p) consider(t);
  });
  return out;
}

// The pairs of a nearly flat patch's triangles and its candidates that may meet, for
// test(i, j): the patch's triangles (boxed piece by piece: they are often long and thin) near a
// candidate's part in its slab, and of those only the ones that its projection does not clear.
template <class Test>
void slab_pairs(const Mesh& mesh, const PointTable& table, const std::vector<PointId>& position,
                const detail::BoxFrame& frame, const detail::PlanarPatch& slab,
                const std::vector<std::uint32_t>& candidates,
                const std::vector<CGAL::Bbox_3>& parts, Test&& test) {
  auto corners = [&](std::uint32_t t) {
    const Triangle& f = mesh.triangles[t];
    return std::array<PointId, 3>{position[f[0]], position[f[1]], position[f[2]]};
  };
  // The tree reports the slab's triangles by their place in slab.triangles, whose edge lines are
  // computed once: each is tested against many candidates.
  std::vector<CGAL::Bbox_3> pieces;
  std::vector<FloatBox> boxes;
  std::vector<std::uint32_t> ids;
  std::vector<detail::EdgeLines> lines(slab.triangles.size());
  const int dropped = detail::dropped_in(frame, slab);
  for (std::uint32_t k = 0; k < slab.triangles.size(); ++k) {
    pieces.clear();
    const detail::ApproxCorners c = detail::corners_in(table, frame, corners(slab.triangles[k]));
    lines[k] = detail::edge_lines(c, dropped);
    detail::add_pieces(c, detail::pieces_for(c), pieces);
    for (const CGAL::Bbox_3& b : pieces) {
      boxes.push_back(FloatBox::of(b));
      ids.push_back(k);
    }
  }
  const TriangleTree tree(std::move(boxes), ids);
  // A triangle whose pieces meet a candidate's part more than once is tested once: `seen` holds,
  // by slab triangle, the last candidate it was met with.
  std::vector<std::uint32_t> seen(slab.triangles.size(), UINT32_MAX);
  for (std::uint32_t c = 0; c < candidates.size(); ++c)
    tree.for_each_overlap(parts[c], [&](std::uint32_t k) {
      if (seen[k] == c) return;
      seen[k] = c;
      if (!detail::apart_along_axis(lines[k], parts[c])) test(slab.triangles[k], candidates[c]);
    });
}

// Vertices by position: coincident ones (separated features) are one position. From the
// table's contiguous copy of the coordinates when they are all doubles.
std::vector<PointId> positions(const Mesh& mesh, const PointTable& table) {
  std::vector<PointId> position(mesh.num_vertices());
  detail::PositionIndex index;
  index.reserve(mesh.num_vertices());
  const auto& doubles = table.input_doubles();
  for (VertexIndex v = 0; v < mesh.num_vertices(); ++v)
    position[v] = doubles.empty() ? index.find_or_insert(mesh.points[v], v)
                                  : index.find_or_insert(doubles[v], v);
  return position;
}

// Self-intersections: flat patches proved embedded, the other triangles by their tree against
// itself, and each patch against the triangles that reach its plane; each pair is tested
// exactly, once (i < j).
// `kept` gets a tree over every triangle when the trees are along the coordinate axes.
void find_self_intersections(const Mesh& mesh, const PointTable& table,
                             const detail::FacePlanes& planes,
                             const std::vector<std::uint8_t>& degenerate,
                             const ManifoldEdges& manifold, const std::vector<std::uint8_t>& proved,
                             const CheckOptions& options, MeshReport& r,
                             std::optional<TriangleTree>* kept) {
  const std::vector<PointId> position = positions(mesh, table);
  detail::PlanarPatches planar = detail::verified_planar_patches(
      mesh, table, planes, position, degenerate, manifold, kMinPlanarPatch);
  detail::add_near_flat_patches(mesh, table, planes, position, degenerate, manifold,
                                kMinPlanarPatch, planar);
  detail::add_proved_stars(mesh, table, position, degenerate, kMinStar, planar);
  std::vector<std::uint32_t> others, in_patches;
  for (std::uint32_t t = 0; t < mesh.num_triangles(); ++t) {
    if (planar.patch_of[t] >= 0) in_patches.push_back(t);
    if (planar.patch_of[t] < 0 && !degenerate[t]) others.push_back(t);
  }
  // The triangles of the patches, for each patch's candidates among the later patches.
  // The vertices' boxes from the table's copy of their intervals (contiguous), for every tree,
  // along the axes of the mesh itself when it lies turned off the coordinate axes.
  const detail::BoxFrame frame = detail::choose_box_frame(mesh, table.input_near_doubles());
  const std::vector<FloatBox> vertex_boxes =
      detail::boxes_in_frame(frame, table, 0, mesh.num_vertices());
  const TriangleTree patched(mesh, vertex_boxes, in_patches);
  TriangleTree tree = planar.patches.empty() ? TriangleTree(mesh, vertex_boxes)
                                             : TriangleTree(mesh, vertex_boxes, others);
  const TrianglePairs test(table, position);
  const bool list = options.list_self_intersections;
  // Triangles with a common vertex whose star is proved embedded near it meet properly (the
  // neighbours of every triangle: most of the pairs the traversal meets); the traversal drops
  // them by these keys.
  TriangleTree::TriangleKeys proved_corners;
  if (!proved.empty()) {
    proved_corners.resize(mesh.num_triangles());
    tbb::parallel_for(std::size_t(0), mesh.num_triangles(), [&](std::size_t t) {
      for (int k = 0; k < 3; ++k) {
        const VertexIndex v = mesh.triangles[t][k];
        proved_corners[t][k] = proved[v] ? v : TriangleTree::kNoKey;
      }
    });
  }
  // The last slot: faces crossing along a segment that several edges share (no pair of
  // triangles meets improperly there).
  std::vector<Found> found(tree.self_pair_tasks() + planar.patches.size() + 1);
  for (const auto& [i, j] : detail::interleaved_edge_fans(mesh, table, position))
    found.back().add(i, j, options.list_self_intersections);
  tree.for_each_self_pair<detail::UpwardRounding>(
      [&](std::size_t task, std::uint32_t i, std::uint32_t j) {
        // Degenerate faces are reported on their own (the tree over all faces holds them).
        if (degenerate[i] || degenerate[j]) return;
        if (planes.beside(i, j) || planes.beside(j, i)) return;
        if (test.improper(mesh.triangles[i], mesh.triangles[j])) found[task].add(i, j, list);
      },
      proved.empty() ? nullptr : &proved_corners);
  tbb::parallel_for(std::size_t(0), planar.patches.size(), [&](std::size_t p) {
    std::vector<CGAL::Bbox_3> parts;
    const std::vector<std::uint32_t> candidates = patch_candidates(
        mesh, table, position, planar, tree, patched, frame, vertex_boxes, p, parts);
    if (candidates.empty()) return;
    const detail::UpwardRounding rounding;
    Found& f = found[tree.self_pair_tasks() + p];
    auto test_pair = [&](std::uint32_t i, std::uint32_t j,
                         const TrianglePairs::KnownPlane* ki = nullptr,
                         const TrianglePairs::KnownPlane* kj = nullptr) {
      // As in the traversal: a common vertex whose star is proved embedded settles the pair.
      if (!proved.empty())
        for (const VertexIndex v : mesh.triangles[i])
          if (proved[v] &&
              (v == mesh.triangles[j][0] || v == mesh.triangles[j][1] || v == mesh.triangles[j][2]))
            return;
      if (planes.beside(i, j) || planes.beside(j, i)) return;
      if (test.improper(mesh.triangles[i], mesh.triangles[j], ki, kj)) f.add(i, j, list);
    };
    const detail::PlanarPatch& patch = planar.patches[p];
    if (patch.kind == detail::PlanarPatch::Kind::NearlyFlat) {
      slab_pairs(mesh, table, position, frame, patch, candidates, parts,
                 [&](std::uint32_t i, std::uint32_t j) { test_pair(i, j); });
      return;
    }
    auto pairs = TriangleTree::overlapping_pairs(TriangleTree(mesh, vertex_boxes, patch.triangles),
                                                 TriangleTree(mesh, vertex_boxes, candidates));
    if (patch.kind != detail::PlanarPatch::Kind::Flat) {
      for (const auto& [i, j] : pairs) test_pair(i, j);
      return;
    }
    // A flat patch's triangles all turn as the triangle spanning its plane (they were joined so)
    // and its vertices lie in that plane: orientation against any of them is the plane's, built
    // once. A candidate meets several of the patch's triangles: its plane is built once per group.
    const PointTable::PlaneSides patch_sides(table, patch.plane);
    const TrianglePairs::KnownPlane in_patch{&patch_sides, &patch.vertices};
    std::sort(pairs.begin(), pairs.end(),
              [](const auto& x, const auto& y) { return x.second < y.second; });
    for (std::size_t k = 0; k < pairs.size();) {
      const std::uint32_t j = pairs[k].second;
      const Triangle& g = mesh.triangles[j];
      const PointTable::PlaneSides candidate_sides(
          table, {position[g[0]], position[g[1]], position[g[2]]});
      const TrianglePairs::KnownPlane candidate{&candidate_sides};
      for (; k < pairs.size() && pairs[k].second == j; ++k)
        test_pair(pairs[k].first, j, &in_patch, &candidate);
    }
  });
  report(found, r);
  // The Boolean's trees are along the coordinate axes (it boxes the other operand so). With
  // patches, the two trees joined hold every triangle unless some are degenerate (then the
  // mesh is refused anyway).
  if (!kept || !frame.world) return;
  if (planar.patches.empty())
    kept->emplace(std::move(tree));
  else if (others.size() + in_patches.size() == mesh.num_triangles())
    kept->emplace(std::move(tree), patched, mesh.num_triangles());
}

// Outward: one shell's volume is positive; several shells nest as check_nesting.h asks. Only
// meaningful for closed, consistently oriented meshes.
bool is_outward(const Mesh& mesh, const PointTable& table,
                const std::vector<std::uint32_t>& component_of, const CheckOptions& options,
                const MeshReport& r) {
  if (mesh.num_triangles() == 0) return true;
  if (!r.closed() || !r.consistently_oriented) return false;
  if (r.self_intersections != 0 || r.degenerate_faces != 0 || r.components <= 1)
    return (options.volume ? CGAL::sign(r.volume)
                           : detail::signed_volume_sign(mesh, table.input_near_doubles(),
                                                        table.input_error())) == CGAL::POSITIVE;
  return detail::shells_nest_outward(mesh, positions(mesh, table), component_of, r.components);
}

}  // namespace

namespace {

// The check; `tree` (when given) gets the tree check_mesh_keeping_tree describes.
MeshReport run_check(const Mesh& mesh, const CheckOptions& options,
                     std::optional<TriangleTree>* tree) {
  if (tree) tree->reset();
  MeshReport r;
  r.vertices = mesh.num_vertices();
  r.triangles = mesh.num_triangles();
  // Each pass's share of the bar, about its share of a smooth mesh's check.
  ProgressSteps steps;
  steps.next(0.15, "points and faces");
  const PointTable table(mesh, mesh, true);
  // From the table's copy of the points' intervals: contiguous, where each point is a pointer.
  for (VertexIndex v = 0; v < mesh.num_vertices(); ++v) r.bbox += table.approx(v).bbox();
  // Each face's normal in doubles (its plane record when a pass asks for it).
  const detail::FacePlanes planes(mesh, table.input_near_doubles(), table.input_error());
  const std::vector<std::uint8_t> degenerate = find_degenerate_faces(mesh, table, planes, r);
  steps.next(0.4, "edges and vertex stars");
  UnionFind components(mesh.num_triangles());
  std::vector<std::uint8_t> proved;
  const ManifoldEdges manifold =
      check_topology(mesh, table, options.self_intersections, components, proved, r);
  const std::vector<std::uint32_t> component_of =
      number_components(components, mesh.num_triangles(), r);
  steps.next(0.5, "volume");
  // Every edge used once each way: the faces form a cycle, whose volume takes fewer products.
  const bool cycle = r.closed() && r.non_manifold_edges == 0 && r.consistently_oriented;
  if (options.volume) r.volume = cycle ? detail::signed_volume_of_cycle(mesh) : signed_volume(mesh);
  r.genus = total_genus(mesh, component_of, r);
  steps.next(0.95, "self-intersections");
  if (options.self_intersections && mesh.num_triangles() > 1)
    find_self_intersections(mesh, table, planes, degenerate, manifold, proved, options, r, tree);
  steps.next(1, "outward");
  r.outward = is_outward(mesh, table, component_of, options, r);
  return r;
}

}  // namespace

MeshReport check_mesh(const Mesh& mesh, const CheckOptions& options) {
  return run_check(mesh, options, nullptr);
}

std::vector<std::pair<std::uint32_t, std::uint32_t>> detail::improper_pairs(
    const Mesh& mesh, const std::vector<std::pair<std::uint32_t, std::uint32_t>>& candidates) {
  const PointTable table(mesh, mesh, true);
  const std::vector<PointId> position = positions(mesh, table);
  const TrianglePairs test(table, position);
  std::vector<std::uint8_t> improper(candidates.size(), 0);
  tbb::parallel_for(std::size_t(0), candidates.size(), [&](std::size_t k) {
    const auto [i, j] = candidates[k];
    improper[k] = test.improper(mesh.triangles[i], mesh.triangles[j]);
  });
  std::vector<std::pair<std::uint32_t, std::uint32_t>> out;
  for (std::size_t k = 0; k < candidates.size(); ++k)
    if (improper[k]) out.push_back(candidates[k]);
  return out;
}

MeshReport detail::check_mesh_keeping_tree(const Mesh& mesh, const CheckOptions& options,
                                           std::optional<TriangleTree>& tree) {
  return run_check(mesh, options, &tree);
}

std::string describe_problems(const MeshReport& r) {
  std::ostringstream out;
  if (r.border_edges > 0)
    out << "mesh is not closed: " << r.border_edges << " border edges, first at vertex "
        << *r.first_border_vertex;
  else if (r.non_manifold_edges > 0)
    out << "mesh has " << r.non_manifold_edges << " non-manifold edges";
  else if (r.degenerate_faces > 0)
    out << "mesh has " << r.degenerate_faces << " degenerate faces, first is face "
        << *r.first_degenerate_face;
  else if (!r.consistently_oriented)
    out << "mesh is not consistently oriented, first at face " << *r.first_misoriented_face;
  else if (r.non_manifold_vertices > 0)
    out << "mesh has " << r.non_manifold_vertices << " non-manifold vertices, first is vertex "
        << *r.first_non_manifold_vertex;
  else if (r.self_intersections > 0)
    out << "mesh self-intersects: " << r.self_intersections << " pairs of faces, first faces "
        << r.first_self_intersection->first << " and " << r.first_self_intersection->second;
  else if (!r.outward)
    out << "mesh is oriented inward (its faces must be counter-clockwise seen from outside)";
  return out.str();
}

}  // namespace morphex

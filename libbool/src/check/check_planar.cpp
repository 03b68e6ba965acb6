// SPDX-License-Identifier: GPL-3.0-or-later
// Coplanar patches proved embedded in their plane (see check_planar.h for the argument).
#include "check/check_planar.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>

#include "exact/static_filter.h"
#include "morphex/internal/union_find.h"

namespace morphex::detail {
namespace {

std::uint64_t edge_key(PointId a, PointId b) {
  return (std::uint64_t(std::min(a, b)) << 32) | std::max(a, b);
}

std::array<PointId, 3> corners(const Mesh& mesh, const std::vector<PointId>& position,
                               std::uint32_t f) {
  const Triangle& t = mesh.triangles[f];
  return {position[t[0]], position[t[1]], position[t[2]]};
}

// The two faces of a manifold edge lie in one plane on either side of the edge (the same turn
// seen along the plane's dominant axis).
bool coplanar_across(const Mesh& mesh, const PointTable& table, const FacePlanes& planes,
                     const std::vector<PointId>& position,
                     const std::vector<std::uint8_t>& degenerate,
                     const std::pair<std::uint64_t, std::array<std::uint32_t, 2>>& link) {
  const auto [fi, gi] = link.second;
  if (degenerate[fi] || degenerate[gi]) return false;
  // Faces bent apart are not worth the tests below (a missed pair of coplanar faces only leaves
  // them to the pair tests: patches are a speed-up).
  if (planes.bent(fi, gi)) return false;
  // Most edges of a curved surface are not flat: f's plane in doubles says so without the
  // positions. Only a certain nonzero side is taken; a vertex coincident with one of f's gives
  // zero and goes on below.
  const Triangle &tf = mesh.triangles[fi], &tg = mesh.triangles[gi];
  for (const VertexIndex w : tg)
    if (w != tf[0] && w != tf[1] && w != tf[2]) {
      if (const auto side = planes.side(fi, w); side && *side != 0) return false;
      break;
    }
  const auto f = corners(mesh, position, fi), g = corners(mesh, position, gi);
  for (int k = 0; k < 3; ++k) {
    const PointId x = g[k];
    if (x == f[0] || x == f[1] || x == f[2]) continue;
    if (table.orientation(f[0], f[1], f[2], x) != CGAL::ZERO) return false;
    const int d = table.dominant_axis(f[0], f[1], f[2]);
    return table.orientation_2(d, f[0], f[1], f[2]) == table.orientation_2(d, g[0], g[1], g[2]);
  }
  return false;
}

// Faces joined across manifold edges when they lie in one plane on either side of the edge.
UnionFind coplanar_neighbours(const Mesh& mesh, const PointTable& table, const FacePlanes& planes,
                              const std::vector<PointId>& position,
                              const std::vector<std::uint8_t>& degenerate,
                              const ManifoldEdges& links) {
  std::vector<std::uint8_t> join(links.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, links.size(), 1024),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      const UpwardRounding rounding;  // once per range: setting it costs
                      for (std::size_t l = range.begin(); l != range.end(); ++l)
                        join[l] =
                            coplanar_across(mesh, table, planes, position, degenerate, links[l]);
                    });
  UnionFind patches(mesh.num_triangles());
  for (std::size_t l = 0; l < links.size(); ++l)
    if (join[l]) patches.join(links[l].second[0], links[l].second[1]);
  return patches;
}

// What one patch's proof needs: its plane's projection and turn.
struct Projection {
  const PointTable& table;
  int dropped;
  CGAL::Sign turn;  // of every triangle, seen along `dropped`
  CGAL::Sign orient(PointId p, PointId q, PointId r) const {
    return CGAL::Sign(turn * table.orientation_2(dropped, p, q, r));
  }
};

// The corner of a triangle at `apex`: the angle from the ray to `start` to the ray to `end`.
struct Wedge {
  PointId apex, start, end;
  // One comparison of 64-bit keys: patches sort three corners per triangle.
  std::uint64_t key() const { return (std::uint64_t(apex) << 32) | start; }
  bool operator<(const Wedge& o) const { return key() < o.key(); }
};

// The ray apex -> x lies in the half-open angle [start, end) of w.
bool in_wedge(const Projection& p, const Wedge& w, PointId x) {
  return p.orient(w.apex, w.start, x) != CGAL::NEGATIVE &&
         p.orient(w.apex, x, w.end) == CGAL::POSITIVE;
}

// The rays apex -> p and apex -> q point the same way.
bool same_direction(const Projection& p, PointId apex, PointId a, PointId b) {
  if (p.orient(apex, a, b) != CGAL::ZERO) return false;
  for (int axis = 0; axis < 3; ++axis) {
    if (axis == p.dropped) continue;
    const auto ca = p.table.compare(axis, apex, a);
    if (ca != CGAL::EQUAL) return ca == p.table.compare(axis, apex, b);
  }
  return false;
}

// The corners at one vertex (sorted by start) chain into one fan that wraps exactly once
// (a cycle: an interior vertex) or less than once (a chain: a border vertex). `ends` gets their
// end rays' far vertices, sorted (the caller's buffer, reused from vertex to vertex).
bool star_wraps_at_most_once(const Projection& p, const Wedge* begin, const Wedge* end,
                             std::vector<PointId>& ends) {
  const std::size_t m = std::size_t(end - begin);
  auto by_start = [&](PointId s) -> const Wedge* {
    const Wedge key{begin->apex, s, 0};
    const Wedge* w = std::lower_bound(begin, end, key);
    return w != end && w->start == s ? w : nullptr;
  };
  for (const Wedge* w = begin; w + 1 < end; ++w)
    if (w->start == (w + 1)->start) return false;  // two corners on one side of an edge
  // A chain starts at the corner whose start ray ends no other corner.
  ends.clear();
  for (const Wedge* w = begin; w != end; ++w) ends.push_back(w->end);
  std::sort(ends.begin(), ends.end());
  // Two corners ending on one ray: each corner then has at most one successor and predecessor.
  if (std::adjacent_find(ends.begin(), ends.end()) != ends.end()) return false;
  const Wedge* first = begin;
  int chain_starts = 0;
  for (const Wedge* w = begin; w != end; ++w)
    if (!std::binary_search(ends.begin(), ends.end(), w->start)) {
      first = w;
      ++chain_starts;
    }
  if (chain_starts > 1) return false;
  const bool cycle = chain_starts == 0;
  const Wedge* w = first;
  for (std::size_t visited = 1;; ++visited) {
    const Wedge* next = by_start(w->end);
    if (!next || next == first) {
      if (visited != m || (cycle && next != first)) return false;  // several fans
      if (!cycle && same_direction(p, first->apex, w->end, first->start)) return false;
      return true;
    }
    // Past the first corner, no corner may hold the first ray: the fan would wrap again.
    if (in_wedge(p, *next, first->start)) return false;
    w = next;
  }
}
}  // namespace

bool segments_meet_2(const PointTable& table, int d, PointId p, PointId q, PointId r, PointId s) {
  const CGAL::Sign o1 = table.orientation_2(d, p, q, r), o2 = table.orientation_2(d, p, q, s);
  const CGAL::Sign o3 = table.orientation_2(d, r, s, p), o4 = table.orientation_2(d, r, s, q);
  if (o1 * o2 < 0 && o3 * o4 < 0) return true;              // a proper crossing
  auto on_segment = [&](PointId a, PointId b, PointId x) {  // x collinear with ab
    for (int axis = 0; axis < 3; ++axis) {
      const auto ab = table.compare(axis, a, b);
      if (ab == CGAL::EQUAL) continue;
      const auto ax = table.compare(axis, a, x), xb = table.compare(axis, x, b);
      return (ax == CGAL::EQUAL || ax == ab) && (xb == CGAL::EQUAL || xb == ab);
    }
    return table.equal(a, x);
  };
  return (o1 == CGAL::ZERO && on_segment(p, q, r)) || (o2 == CGAL::ZERO && on_segment(p, q, s)) ||
         (o3 == CGAL::ZERO && on_segment(r, s, p)) || (o4 == CGAL::ZERO && on_segment(r, s, q));
}

bool inside_2(const PointTable& table, int d, const std::array<PointId, 3>& t, PointId x) {
  const CGAL::Sign turn = table.orientation_2(d, t[0], t[1], t[2]);
  for (int i = 0; i < 3; ++i)
    if (table.orientation_2(d, t[i], t[(i + 1) % 3], x) == -turn) return false;
  return true;
}

namespace {

// The border's cycles (vertex sequences), when every border vertex has one border edge out and
// they chain into closed polygons.
std::optional<std::vector<std::vector<PointId>>> border_cycles(
    std::vector<std::array<PointId, 2>>& border) {
  std::sort(border.begin(), border.end());
  for (std::size_t i = 0; i + 1 < border.size(); ++i)
    if (border[i][0] == border[i + 1][0]) return std::nullopt;  // two border edges leave a vertex
  std::vector<std::uint8_t> used(border.size(), 0);
  std::vector<std::vector<PointId>> cycles;
  for (std::size_t start = 0; start < border.size(); ++start) {
    if (used[start]) continue;
    std::vector<PointId> cycle;
    std::size_t e = start;
    while (!used[e]) {
      used[e] = 1;
      cycle.push_back(border[e][0]);
      const auto next =
          std::lower_bound(border.begin(), border.end(), std::array<PointId, 2>{border[e][1], 0});
      if (next == border.end() || (*next)[0] != border[e][1]) return std::nullopt;
      e = std::size_t(next - border.begin());
    }
    if (e != start || cycle.size() < 3) return std::nullopt;  // ran into another cycle
    cycles.push_back(std::move(cycle));
  }
  return cycles;
}

// No two border edges meet, except consecutive ones at their common vertex (which the star
// proof covers): a sweep over their boxes along one axis.
bool border_edges_disjoint(const Projection& p, const std::vector<std::array<PointId, 2>>& border) {
  const int u = p.dropped == 0 ? 1 : 0, v = p.dropped == 2 ? 1 : 2;
  struct Extent {
    double lo[2], hi[2];
    std::size_t edge;
  };
  std::vector<Extent> extents;
  extents.reserve(border.size());
  for (std::size_t e = 0; e < border.size(); ++e) {
    const auto& a = p.table.approx(border[e][0]);
    const auto& b = p.table.approx(border[e][1]);
    Extent x{};
    x.edge = e;
    for (int k = 0; k < 2; ++k) {
      const int axis = k == 0 ? u : v;
      x.lo[k] = std::min(a.cartesian(axis).inf(), b.cartesian(axis).inf());
      x.hi[k] = std::max(a.cartesian(axis).sup(), b.cartesian(axis).sup());
    }
    extents.push_back(x);
  }
  std::sort(extents.begin(), extents.end(),
            [](const Extent& a, const Extent& b) { return a.lo[0] < b.lo[0]; });
  for (std::size_t i = 0; i < extents.size(); ++i)
    for (std::size_t j = i + 1; j < extents.size() && extents[j].lo[0] <= extents[i].hi[0]; ++j) {
      if (extents[j].lo[1] > extents[i].hi[1] || extents[i].lo[1] > extents[j].hi[1]) continue;
      const auto& e = border[extents[i].edge];
      const auto& f = border[extents[j].edge];
      if (e[0] == f[1] || e[1] == f[0]) continue;  // consecutive: the star proof covers them
      if (segments_meet_2(p.table, p.dropped, e[0], e[1], f[0], f[1])) return false;
    }
  return true;
}

// +1 when the cycle turns as the patch's triangles do, -1 the other way: the turn at its
// lowest vertex (by the two projected coordinates), which for a simple polygon is its own.
int cycle_turn(const Projection& p, const std::vector<PointId>& cycle) {
  const int u = p.dropped == 0 ? 1 : 0, v = p.dropped == 2 ? 1 : 2;
  std::size_t low = 0;
  for (std::size_t i = 1; i < cycle.size(); ++i) {
    CGAL::Comparison_result c = p.table.compare(u, cycle[i], cycle[low]);
    if (c == CGAL::EQUAL) c = p.table.compare(v, cycle[i], cycle[low]);
    if (c == CGAL::SMALLER) low = i;
  }
  const std::size_t n = cycle.size();
  return p.orient(cycle[(low + n - 1) % n], cycle[low], cycle[(low + 1) % n]);
}

// x (not on the cycle) lies inside it: the ray from x along +u crosses it an odd number of times.
bool inside_cycle(const Projection& p, const std::vector<PointId>& cycle, PointId x) {
  const int v = p.dropped == 2 ? 1 : 2;
  bool inside = false;
  for (std::size_t i = 0; i < cycle.size(); ++i) {
    const PointId a = cycle[i], b = cycle[(i + 1) % cycle.size()];
    const bool a_above = p.table.compare(v, a, x) == CGAL::LARGER,
               b_above = p.table.compare(v, b, x) == CGAL::LARGER;
    if (a_above == b_above) continue;
    // The edge crosses the ray's line, to the right of x when x is on the left of an upward
    // edge or on the right of a downward one (orientation_2 turns in the (u, v) plane).
    const CGAL::Sign side = p.table.orientation_2(p.dropped, a, b, x);
    if (b_above ? side == CGAL::POSITIVE : side == CGAL::NEGATIVE) inside = !inside;
  }
  return inside;
}

// The border is pairwise disjoint simple polygons whose windings add up to at most one
// everywhere: the number of preimages of a locally injective map is that sum, so the patch is
// embedded. One polygon turning with the triangles is the disc; holes turn the other way inside.
bool border_bounds_an_embedded_patch(const Projection& p,
                                     std::vector<std::array<PointId, 2>> border) {
  constexpr std::size_t kMaxCycles = 64;  // nesting is tested cycle against cycle
  if (border.size() < 3) return false;
  const auto cycles = border_cycles(border);
  if (!cycles || cycles->size() > kMaxCycles || !border_edges_disjoint(p, border)) return false;
  std::vector<int> turn(cycles->size());
  for (std::size_t i = 0; i < cycles->size(); ++i) {
    turn[i] = cycle_turn(p, (*cycles)[i]);
    if (turn[i] == 0) return false;
  }
  // Just inside cycle i the count is its own turn plus those of the cycles around it.
  for (std::size_t i = 0; i < cycles->size(); ++i) {
    int count = turn[i];
    for (std::size_t j = 0; j < cycles->size(); ++j)
      if (j != i && inside_cycle(p, (*cycles)[j], (*cycles)[i][0])) count += turn[j];
    if (count < 0 || count > 1) return false;
  }
  return true;
}

// The corners of a patch's triangles grouped by apex, each group sorted by start: a counting
// sort over the patch's own vertices (a sort of all corners costs a tenth of a CAD mesh's check),
// through `slot`, a scratch array over all positions that holds kNoSlot outside each call.
class CornersByApex {
 public:
  static constexpr std::uint32_t kNoSlot = 0xffffffffu;
  CornersByApex(std::vector<std::uint32_t>& slot, const std::vector<Wedge>& corners) : slot_(slot) {
    for (const Wedge& w : corners) {
      std::uint32_t& s = slot_[w.apex];
      if (s == kNoSlot) {
        s = std::uint32_t(apexes_.size());
        apexes_.push_back(w.apex);
        first_.push_back(0);
      }
      ++first_[s];
    }
    std::uint32_t sum = 0;
    for (std::uint32_t& f : first_) sum += std::exchange(f, sum);
    first_.push_back(sum);
    grouped_.resize(corners.size());
    std::vector<std::uint32_t> next(first_.begin(), first_.end() - 1);
    for (const Wedge& w : corners) grouped_[next[slot_[w.apex]]++] = w;
    for (std::size_t g = 0; g + 1 < first_.size(); ++g)
      std::sort(grouped_.begin() + first_[g], grouped_.begin() + first_[g + 1]);
  }
  ~CornersByApex() {
    for (const PointId a : apexes_) slot_[a] = kNoSlot;
  }
  CornersByApex(const CornersByApex&) = delete;
  CornersByApex& operator=(const CornersByApex&) = delete;

  std::size_t groups() const { return apexes_.size(); }
  const Wedge* begin(std::size_t g) const { return grouped_.data() + first_[g]; }
  const Wedge* end(std::size_t g) const { return grouped_.data() + first_[g + 1]; }

 private:
  std::vector<std::uint32_t>& slot_;
  std::vector<PointId> apexes_;
  std::vector<std::uint32_t> first_;  // group g: grouped_[first_[g], first_[g + 1])
  std::vector<Wedge> grouped_;
};

// The proof of check_planar.h for one patch, and its vertex and edge lists when it holds. `slot`
// is CornersByApex's scratch array.
std::optional<PlanarPatch> prove_embedded(const Mesh& mesh, const PointTable& table,
                                          const std::vector<PointId>& position,
                                          std::vector<std::uint32_t> triangles,
                                          std::vector<std::uint32_t>& slot) {
  PlanarPatch patch;
  patch.plane = corners(mesh, position, triangles[0]);
  const auto& s = patch.plane;
  const int dropped = table.dominant_axis(s[0], s[1], s[2]);
  const Projection p{table, dropped, table.orientation_2(dropped, s[0], s[1], s[2])};
  if (p.turn == CGAL::ZERO) return std::nullopt;
  // Each triangle's corners: wedge (a, s, e) is triangle a, s, e, which uses the edge a -> s.
  std::vector<Wedge> wedges;
  wedges.reserve(3 * triangles.size());
  for (const std::uint32_t f : triangles) {
    const auto c = corners(mesh, position, f);
    if (p.orient(c[0], c[1], c[2]) != CGAL::POSITIVE) return std::nullopt;
    for (int k = 0; k < 3; ++k) wedges.push_back({c[k], c[(k + 1) % 3], c[(k + 2) % 3]});
  }
  const CornersByApex by_apex(slot, wedges);
  // Once the corners at a pass (each edge a -> s used once at most), the edge s -> a is used
  // exactly when a corner at a ends at s: a -> s is then inside the patch, else on its border.
  // Each edge is listed once: from its smaller end when inside, from the end it leaves when on
  // the border (one use only).
  std::vector<std::array<PointId, 2>> border;
  std::vector<PointId> ends;
  for (std::size_t g = 0; g < by_apex.groups(); ++g) {
    if (!star_wraps_at_most_once(p, by_apex.begin(g), by_apex.end(g), ends)) return std::nullopt;
    const PointId a = by_apex.begin(g)->apex;
    patch.vertices.push_back(a);
    for (const Wedge* w = by_apex.begin(g); w != by_apex.end(g); ++w) {
      const bool inside = std::binary_search(ends.begin(), ends.end(), w->start);
      if (!inside) border.push_back({a, w->start});
      if (!inside || a < w->start) patch.edges.push_back(edge_key(a, w->start));
    }
  }
  std::sort(patch.vertices.begin(), patch.vertices.end());
  std::sort(patch.edges.begin(), patch.edges.end());
  if (!border_bounds_an_embedded_patch(p, std::move(border))) return std::nullopt;
  for (const PointId v : patch.vertices) patch.box += table.approx(v).bbox();
  patch.triangles = std::move(triangles);
  return patch;
}

// The groups of `joined` with at least min_triangles eligible triangles, each proved embedded
// (in parallel); the proved ones, their triangles in increasing order.
std::vector<PlanarPatch> proved_groups(const Mesh& mesh, const PointTable& table,
                                       const std::vector<PointId>& position, UnionFind& joined,
                                       const std::vector<std::uint8_t>& eligible,
                                       std::size_t min_triangles) {
  const std::uint32_t nf = std::uint32_t(mesh.num_triangles());
  std::vector<std::uint32_t> root(nf), size(nf, 0);
  for (std::uint32_t f = 0; f < nf; ++f) {
    root[f] = std::uint32_t(joined.find(f));
    size[root[f]] += eligible[f];
  }
  std::vector<std::vector<std::uint32_t>> groups;
  std::vector<std::int32_t> group_of_root(nf, -1);
  for (std::uint32_t f = 0; f < nf; ++f) {
    if (!eligible[f] || size[root[f]] < min_triangles) continue;
    if (group_of_root[root[f]] < 0) {
      group_of_root[root[f]] = std::int32_t(groups.size());
      groups.emplace_back();
    }
    groups[std::size_t(group_of_root[root[f]])].push_back(f);
  }
  std::vector<std::optional<PlanarPatch>> proved(groups.size());
  // prove_embedded's scratch, one per thread, over every position.
  const std::size_t positions =
      position.empty() ? 0 : std::size_t(*std::max_element(position.begin(), position.end())) + 1;
  tbb::enumerable_thread_specific<std::vector<std::uint32_t>> slots(
      [&] { return std::vector<std::uint32_t>(positions, CornersByApex::kNoSlot); });
  tbb::parallel_for(std::size_t(0), groups.size(), [&](std::size_t g) {
    const UpwardRounding rounding;
    proved[g] = prove_embedded(mesh, table, position, std::move(groups[g]), slots.local());
  });
  std::vector<PlanarPatch> out;
  for (auto& patch : proved)
    if (patch) out.push_back(std::move(*patch));
  return out;
}

void append(std::vector<PlanarPatch>&& patches, PlanarPatches& out) {
  for (auto& patch : patches) {
    for (const std::uint32_t f : patch.triangles)
      out.patch_of[f] = std::int32_t(out.patches.size());
    out.patches.push_back(std::move(patch));
  }
}

using Normal = std::array<double, 3>;

// Face f's normal in doubles, of unit length (zero for a face too thin to tell): only to group
// faces, never to decide anything.
Normal rough_normal(const Mesh& mesh, const PointTable& table, const std::vector<PointId>& position,
                    std::uint32_t f) {
  Normal n = rough_cross(table, corners(mesh, position, f));
  const double length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  if (!(length > 0) || !std::isfinite(length)) return {0, 0, 0};
  for (double& x : n) x /= length;
  return n;
}

// The slab of a proved near-flat patch: its normal the sum of its faces', its bounds those of
// its vertices' heights in interval arithmetic (the caller rounds upward).
void set_slab(const PointTable& table, const std::vector<Normal>& normal, PlanarPatch& patch) {
  Normal n = {0, 0, 0};
  for (const std::uint32_t f : patch.triangles)
    for (int a = 0; a < 3; ++a) n[a] += normal[f][a];
  patch.normal = n;
  patch.dropped = 0;
  for (int a = 1; a < 3; ++a)
    if (std::abs(n[a]) > std::abs(n[patch.dropped])) patch.dropped = a;
  patch.low = std::numeric_limits<double>::infinity();
  patch.high = -patch.low;
  for (const PointId v : patch.vertices) {
    const ApproxPoint& x = table.approx(v);
    const auto h = n[0] * x.x() + n[1] * x.y() + n[2] * x.z();
    patch.low = std::min(patch.low, h.inf());
    patch.high = std::max(patch.high, h.sup());
  }
}

}  // namespace

PlanarPatches verified_planar_patches(const Mesh& mesh, const PointTable& table,
                                      const FacePlanes& planes,
                                      const std::vector<PointId>& position,
                                      const std::vector<std::uint8_t>& degenerate,
                                      const ManifoldEdges& manifold, std::size_t min_triangles) {
  PlanarPatches out;
  out.patch_of.assign(mesh.num_triangles(), -1);
  UnionFind joined = coplanar_neighbours(mesh, table, planes, position, degenerate, manifold);
  std::vector<std::uint8_t> eligible(mesh.num_triangles());
  for (std::size_t f = 0; f < eligible.size(); ++f) eligible[f] = !degenerate[f];
  append(proved_groups(mesh, table, position, joined, eligible, min_triangles), out);
  return out;
}

void add_near_flat_patches(const Mesh& mesh, const PointTable& table, const FacePlanes& planes,
                           const std::vector<PointId>& position,
                           const std::vector<std::uint8_t>& degenerate,
                           const ManifoldEdges& manifold, std::size_t min_triangles,
                           PlanarPatches& groups) {
  // Normals within about 1.4e-3 radians: 1 - cos(angle) below 1e-6.
  constexpr double kBend = 1e-6;
  const std::size_t nf = mesh.num_triangles();
  std::vector<std::uint8_t> eligible(nf);
  std::vector<Normal> normal(nf);
  tbb::parallel_for(std::size_t(0), nf, [&](std::size_t f) {
    eligible[f] = !degenerate[f] && groups.patch_of[f] < 0;
    if (!eligible[f]) return;
    normal[f] = planes.empty() ? rough_normal(mesh, table, position, std::uint32_t(f))
                               : planes.unit_normal(std::uint32_t(f));
  });
  std::vector<std::uint8_t> join(manifold.size());
  tbb::parallel_for(std::size_t(0), manifold.size(), [&](std::size_t l) {
    const auto [f, g] = manifold[l].second;
    const Normal &a = normal[f], &b = normal[g];
    join[l] = eligible[f] && eligible[g] && a[0] * b[0] + a[1] * b[1] + a[2] * b[2] >= 1 - kBend;
  });
  UnionFind joined(nf);
  std::size_t joins = 0;
  for (std::size_t l = 0; l < manifold.size(); ++l)
    if (join[l]) {
      joined.join(manifold[l].second[0], manifold[l].second[1]);
      ++joins;
    }
  if (joins + 1 < min_triangles) return;  // no group can be large enough
  std::vector<PlanarPatch> proved =
      proved_groups(mesh, table, position, joined, eligible, min_triangles);
  tbb::parallel_for(std::size_t(0), proved.size(), [&](std::size_t p) {
    const UpwardRounding rounding;
    proved[p].kind = PlanarPatch::Kind::NearlyFlat;
    set_slab(table, normal, proved[p]);
  });
  append(std::move(proved), groups);
}

namespace {

// The corners at one vertex, by start ray, if some coordinate projection turns them all one way
// and wraps them at most once around it.
bool star_is_embedded(const PointTable& table, std::vector<Wedge>& wedges) {
  std::sort(wedges.begin(), wedges.end());
  for (int dropped = 0; dropped < 3; ++dropped) {
    const Wedge& w = wedges.front();
    const CGAL::Sign turn = table.orientation_2(dropped, w.apex, w.start, w.end);
    if (turn == CGAL::ZERO) continue;
    const Projection p{table, dropped, turn};
    const bool one_way = std::all_of(wedges.begin(), wedges.end(), [&](const Wedge& x) {
      return p.orient(x.apex, x.start, x.end) == CGAL::POSITIVE;
    });
    std::vector<PointId> ends;
    if (one_way)
      return star_wraps_at_most_once(p, wedges.data(), wedges.data() + wedges.size(), ends);
  }
  return false;
}

}  // namespace

void add_proved_stars(const Mesh& mesh, const PointTable& table,
                      const std::vector<PointId>& position,
                      const std::vector<std::uint8_t>& degenerate, std::size_t min_triangles,
                      PlanarPatches& groups) {
  // The corners of every proper triangle, by vertex position.
  struct Corner {
    PointId apex;
    std::uint32_t face;
    bool operator<(const Corner& o) const { return apex != o.apex ? apex < o.apex : face < o.face; }
  };
  // Most meshes have no vertex of that many triangles: a count by position settles it at once.
  {
    std::vector<std::uint32_t> degree(mesh.num_vertices(), 0);
    bool any = false;
    for (std::uint32_t f = 0; f < mesh.num_triangles() && !any; ++f)
      if (!degenerate[f] && groups.patch_of[f] < 0)
        for (const VertexIndex v : mesh.triangles[f]) any |= ++degree[position[v]] >= min_triangles;
    if (!any) return;
  }
  std::vector<Corner> corners_at;
  corners_at.reserve(3 * mesh.num_triangles());
  for (std::uint32_t f = 0; f < mesh.num_triangles(); ++f)
    if (!degenerate[f])
      for (const VertexIndex v : mesh.triangles[f]) corners_at.push_back({position[v], f});
  tbb::parallel_sort(corners_at.begin(), corners_at.end());
  // Stars with at least min_triangles triangles outside the groups.
  std::vector<std::pair<std::size_t, std::size_t>> stars;
  for (std::size_t i = 0; i < corners_at.size();) {
    std::size_t j = i + 1, outside = 0;
    while (j < corners_at.size() && corners_at[j].apex == corners_at[i].apex) ++j;
    for (std::size_t k = i; k < j; ++k) outside += groups.patch_of[corners_at[k].face] < 0;
    if (outside >= min_triangles) stars.emplace_back(i, j);
    i = j;
  }
  // Each star is proved whole (its triangles in groups too); any subset of it is then embedded.
  std::vector<std::uint8_t> proved(stars.size(), 0);
  tbb::parallel_for(std::size_t(0), stars.size(), [&](std::size_t s) {
    const UpwardRounding rounding;
    std::vector<Wedge> wedges;
    for (std::size_t k = stars[s].first; k < stars[s].second; ++k) {
      const auto c = corners(mesh, position, corners_at[k].face);
      const int at = c[0] == corners_at[k].apex ? 0 : c[1] == corners_at[k].apex ? 1 : 2;
      wedges.push_back({c[at], c[(at + 1) % 3], c[(at + 2) % 3]});
    }
    proved[s] = star_is_embedded(table, wedges);
  });
  for (std::size_t s = 0; s < stars.size(); ++s) {
    if (!proved[s]) continue;
    PlanarPatch group;
    group.kind = PlanarPatch::Kind::Star;
    for (std::size_t k = stars[s].first; k < stars[s].second; ++k) {
      const std::uint32_t f = corners_at[k].face;
      if (groups.patch_of[f] >= 0) continue;  // claimed by an earlier group
      group.triangles.push_back(f);
      for (const VertexIndex v : mesh.triangles[f]) group.box += table.approx(position[v]).bbox();
    }
    if (group.triangles.size() < min_triangles) continue;
    for (const std::uint32_t f : group.triangles)
      groups.patch_of[f] = std::int32_t(groups.patches.size());
    groups.patches.push_back(std::move(group));
  }
}

bool meets_patch_only_at_its_features(const PointTable::PlaneSides& plane_side,
                                      const PlanarPatch& patch, const std::array<PointId, 3>& t) {
  bool above = false, below = false;
  PointId on[3];
  int count = 0;
  for (const PointId x : t) {
    const CGAL::Sign o = plane_side(x);
    above |= o == CGAL::POSITIVE;
    below |= o == CGAL::NEGATIVE;
    if (o == CGAL::ZERO) on[count++] = x;
  }
  if (above && below) return false;  // t crosses the plane
  if (count == 3) return false;      // t lies in the plane
  for (int k = 0; k < count; ++k)
    if (!std::binary_search(patch.vertices.begin(), patch.vertices.end(), on[k])) return false;
  return count < 2 ||
         std::binary_search(patch.edges.begin(), patch.edges.end(), edge_key(on[0], on[1]));
}

}  // namespace morphex::detail

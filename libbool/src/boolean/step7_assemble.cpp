// SPDX-License-Identifier: GPL-3.0-or-later
// Step 7: keep the facets and sub-triangles the operation selects, share the points of the two
// inputs, and separate non-manifold features so the result is a closed 2-manifold the next
// Boolean accepts.
//
// Selection (coplanar patches are kept once, from A, or dropped):
//   | op           | from A'   | from B'            | coplanar same | coplanar opposite |
//   | union        | outside B | outside A          | A's copy      | none              |
//   | intersection | inside B  | inside A           | A's copy      | none              |
//   | A minus B    | outside B | inside A, reversed | none          | A's copy          |
//
// Only special points (on both surfaces, or where coincident input vertices met) can be
// non-manifold: every other vertex keeps the fan it had in its input. So only the corners at
// special points are examined, and the work is proportional to the intersection, not the meshes.
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <limits>
#include <memory>
#include <numeric>
#include <stdexcept>
#include <tuple>
#include <unordered_map>
#include <vector>

#include "boolean/boolean_internal.h"
#include "containers/block_offsets.h"
#include "containers/flat_map.h"
#include "containers/id_pairs.h"
#include "exact/around_edge.h"
#include "exact/filtered.h"

namespace morphex::detail {

namespace {

bool keep(BooleanOp op, int side, Label label) {
  switch (op) {
    case BooleanOp::Union:
      return label == Label::Outside || (side == 0 && label == Label::CoplanarSame);
    case BooleanOp::Intersection:
      return label == Label::Inside || (side == 0 && label == Label::CoplanarSame);
    case BooleanOp::Difference:
      if (side == 0) return label == Label::Outside || label == Label::CoplanarOpposite;
      return label == Label::Inside;
  }
  return false;
}

constexpr std::uint32_t kUnset = 0xffffffffu;  // no vertex or face assigned yet

// A corner (f, k), numbered 3 f + k, sits at faces[f][k]; half-edge (f, k) leaves it for
// faces[f][k + 1], and half-edge (f, k - 1) arrives at it from faces[f][k - 1].
struct FaceCorners {
  const std::vector<Triangle>& faces;
  PointId at(std::uint32_t corner) const { return faces[corner / 3][corner % 3]; }
  PointId next(std::uint32_t corner) const { return faces[corner / 3][(corner % 3 + 1) % 3]; }
  PointId previous(std::uint32_t corner) const { return faces[corner / 3][(corner % 3 + 2) % 3]; }
};

// A pair of faces along the non-manifold edge (lo, hi) that the radial order put together.
struct WedgePair {
  PointId lo, hi;
  std::uint32_t faces[2];
};

// The fans of attached corners at the special points: at each point, each corner is joined to
// the corner whose arriving half-edge is the mate of its leaving one; the faces of a non-manifold
// edge are paired by the solid wedges between them.
class Fans {
 public:
  Fans(const PointTable& points, const std::vector<Triangle>& faces,
       std::vector<std::pair<PointId, std::uint32_t>> corners)
      : points_(points),
        faces_{faces},
        corners_(std::move(corners)),
        sets_(corners_.size()),
        slot_of_corner_(corners_.size()) {
    for (std::uint32_t i = 0; i < corners_.size(); ++i)
      slot_of_corner_.emplace(corners_[i].second, i);
  }

  // Joins the fans at every special point, in the order of the points.
  void join_all() {
    for (std::size_t begin = 0; begin < corners_.size();) {
      std::size_t end = begin + 1;
      while (end < corners_.size() && corners_[end].first == corners_[begin].first) ++end;
      join_at(begin, end);
      begin = end;
    }
  }

  std::size_t size() const { return corners_.size(); }
  // The fan of a corner at a special point: the same number for all the corners of one fan.
  std::uint32_t fan_of(std::uint64_t corner) const {
    return sets_.root(*slot_of_corner_.find(corner));
  }
  const std::vector<WedgePair>& wedge_pairs() const { return wedge_pairs_; }

 private:
  using Slots = std::vector<std::pair<PointId, std::uint32_t>>;  // (w, slot) at one point

  // The corners [begin, end) of `corners_`, all at one point v. Half-edges v -> w leave the
  // corner (f, k); half-edges w -> v arrive at it from (f, k - 1). Edges vw with one of each
  // join their two corners; edges with several are paired radially.
  void join_at(std::size_t begin, std::size_t end) {
    const PointId v = corners_[begin].first;
    leaving_.clear();
    arriving_.clear();
    for (std::size_t i = begin; i < end; ++i) {
      leaving_.emplace_back(faces_.next(corners_[i].second), std::uint32_t(i));
      arriving_.emplace_back(faces_.previous(corners_[i].second), std::uint32_t(i));
    }
    std::sort(leaving_.begin(), leaving_.end());
    std::sort(arriving_.begin(), arriving_.end());
    for (std::size_t i = 0, j = 0; i < leaving_.size();) {
      const PointId w = leaving_[i].first;
      std::size_t i_end = i;
      while (i_end < leaving_.size() && leaving_[i_end].first == w) ++i_end;
      while (j < arriving_.size() && arriving_[j].first < w) ++j;
      std::size_t j_end = j;
      while (j_end < arriving_.size() && arriving_[j_end].first == w) ++j_end;
      if (i_end - i == 1 && j_end - j == 1)
        sets_.join(leaving_[i].second, arriving_[j].second);
      else if (i_end - i == j_end - j && i_end > i)
        join_around_edge(v, w, i, i_end, j, j_end);
      // Otherwise the edge is not closed (not possible for selected patches of valid inputs);
      // its corners keep their own fans.
      i = i_end;
      j = j_end;
    }
  }

  // Several solids meet along the edge vw, whose half-edges at v are leaving_[i, i_end) and
  // arriving_[j, j_end): sort its faces around the axis u->v with u < v (the same order seen
  // from both ends) and pair each face that runs u->v with the one just before it (the wedge
  // between them is inside the solid).
  void join_around_edge(PointId v, PointId w, std::size_t i, std::size_t i_end, std::size_t j,
                        std::size_t j_end) {
    struct HalfEdge {
      std::uint32_t corner;  // the face's corner at v
      bool leaves_v;
    };
    std::vector<HalfEdge> hs;
    for (std::size_t t = i; t < i_end; ++t)
      hs.push_back({corners_[leaving_[t].second].second, true});
    for (std::size_t t = j; t < j_end; ++t)
      hs.push_back({corners_[arriving_[t].second].second, false});
    const PointId lo = std::min(v, w), hi = std::max(v, w);
    auto third = [&](const HalfEdge& h) {
      return h.leaves_v ? faces_.previous(h.corner) : faces_.next(h.corner);
    };
    auto face_of = [](const HalfEdge& h) { return h.corner / 3; };
    std::sort(hs.begin(), hs.end(),
              [&](const HalfEdge& x, const HalfEdge& y) { return face_of(x) < face_of(y); });
    const AroundEdge order{points_, lo, hi, third(hs[0])};
    std::sort(hs.begin(), hs.end(),
              [&](const HalfEdge& x, const HalfEdge& y) { return order(third(x), third(y)); });
    for (std::size_t t = 0; t < hs.size(); ++t) {
      const bool runs_lo_hi = hs[t].leaves_v == (v == lo);
      if (!runs_lo_hi) continue;
      const HalfEdge& before = hs[(t + hs.size() - 1) % hs.size()];
      // One of the two leaves v and the other arrives at it: their corners at v share a fan.
      sets_.join(*slot_of_corner_.find(hs[t].corner), *slot_of_corner_.find(before.corner));
      // Each pair once, from the lower end (both ends of the edge are examined).
      if (v == lo) wedge_pairs_.push_back({lo, hi, {face_of(hs[t]), face_of(before)}});
    }
  }

  const PointTable& points_;
  const FaceCorners faces_;
  const std::vector<std::pair<PointId, std::uint32_t>> corners_;  // see special_corners
  UnionFind sets_;  // over the special corners, by their index in `corners_`
  FlatMap<std::uint64_t, std::uint32_t, Hash64> slot_of_corner_;
  std::vector<WedgePair> wedge_pairs_;
  Slots leaving_, arriving_;  // scratch for join_at, reused from point to point
};

// Output vertices: one per non-special point, one per fan of a special point (its key: the point
// id, or the number of points plus the fan), numbered in the order of their keys so that the
// output does not depend on the thread count: in parallel, the keys in use are marked, ranked by
// blocks, and each corner takes its key's rank. In that order the result's points are read from
// the table in order too.
IdMesh number_vertices(const PointTable& points, const std::vector<Triangle>& faces,
                       const std::vector<std::uint8_t>& special, const Fans& fans) {
  const std::size_t nf = faces.size(), np = points.size(), keys = np + fans.size();
  auto key_of = [&](std::size_t c) {
    const PointId p = faces[c / 3][c % 3];
    return special[p] ? np + fans.fan_of(std::uint32_t(c)) : std::size_t(p);
  };
  // Keys are kept per corner, and ranked into vertex indices, in 32 bits.
  if (keys > std::numeric_limits<VertexIndex>::max())
    throw std::length_error("Boolean: more points and fans than vertex indices");
  const auto used = std::make_unique<std::atomic<std::uint8_t>[]>(keys);
  const auto fan_point = std::make_unique<std::atomic<PointId>[]>(fans.size());
  // Each corner's key, taken once: a special corner's is a lookup of its fan.
  std::unique_ptr<VertexIndex[]> key_at(new VertexIndex[3 * nf]);
  tbb::parallel_for(std::size_t(0), 3 * nf, [&](std::size_t c) {
    const std::size_t key = key_of(c);
    key_at[c] = VertexIndex(key);
    used[key].store(1, std::memory_order_relaxed);
    // Every corner of a fan is at its point: they all store the same id.
    if (key >= np) fan_point[key - np].store(faces[c / 3][c % 3], std::memory_order_relaxed);
  });
  constexpr std::size_t kBlock = 1 << 14;
  const std::vector<std::size_t> first =
      block_offsets(keys, kBlock, [&](std::size_t begin, std::size_t end) {
        std::size_t n = 0;
        for (std::size_t k = begin; k < end; ++k) n += used[k].load(std::memory_order_relaxed);
        return n;
      });
  IdMesh out;
  out.vertex_point.resize(first.back());
  std::vector<VertexIndex> vertex_of_key(keys, kUnset);
  tbb::parallel_for(std::size_t(0), first.size() - 1, [&](std::size_t b) {
    auto v = VertexIndex(first[b]);
    for (std::size_t k = b * kBlock; k < std::min(keys, (b + 1) * kBlock); ++k)
      if (used[k].load(std::memory_order_relaxed)) {
        out.vertex_point[v] =
            k < np ? PointId(k) : fan_point[k - np].load(std::memory_order_relaxed);
        vertex_of_key[k] = v++;
      }
  });
  out.triangles.resize(nf);
  tbb::parallel_for(std::size_t(0), 3 * nf,
                    [&](std::size_t c) { out.triangles[c / 3][c % 3] = vertex_of_key[key_at[c]]; });
  return out;
}

// The face among f and the halves split off it that holds the edge (a, b), and the edge's place
// in it. A face can belong to pairs of two of its edges: after the first split, the second edge
// may have moved to the appended half.
std::pair<std::uint32_t, int> face_holding(
    const IdMesh& out, const std::unordered_map<std::uint32_t, std::vector<std::uint32_t>>& halves,
    std::uint32_t f, VertexIndex a, VertexIndex b) {
  std::vector<std::uint32_t> todo{f};
  while (!todo.empty()) {
    const std::uint32_t g = todo.back();
    todo.pop_back();
    const Triangle& t = out.triangles[g];
    for (int k = 0; k < 3; ++k)
      if ((t[k] == a && t[(k + 1) % 3] == b) || (t[k] == b && t[(k + 1) % 3] == a)) return {g, k};
    if (const auto it = halves.find(g); it != halves.end())
      todo.insert(todo.end(), it->second.begin(), it->second.end());
  }
  throw std::logic_error("Boolean: a face of a non-manifold edge lost the edge");
}

// Non-manifold edges where two pairs still share both vertex copies: every pair of such an edge
// is split at its own copy of the midpoint, so that the halves of different pairs meet only at
// common edges. All pairs of the edge are split, not only those sharing: where three solids meet
// along it, an unsplit pair's edge would hold the others' midpoints in its interior. The split
// faces' second halves are appended to `out` (and their origins to `origin`).
void split_shared_pairs(PointTable& points, const std::vector<Triangle>& faces,
                        const std::vector<WedgePair>& wedge_pairs, IdMesh& out,
                        std::vector<FaceOrigin>* origin) {
  struct Copy {
    std::uint64_t edge, copies;  // (lo, hi) as point ids, and as the pair's output vertices
    std::size_t pair;
    bool operator<(const Copy& o) const {
      return std::tie(edge, copies, pair) < std::tie(o.edge, o.copies, o.pair);
    }
  };
  std::vector<Copy> copies;
  for (std::size_t i = 0; i < wedge_pairs.size(); ++i) {
    const WedgePair& w = wedge_pairs[i];
    const Triangle& t = out.triangles[w.faces[0]];
    const Triangle& input = faces[w.faces[0]];
    VertexIndex a = kUnset, b = kUnset;
    for (int k = 0; k < 3; ++k) {
      if (input[k] == w.lo) a = t[k];
      if (input[k] == w.hi) b = t[k];
    }
    copies.push_back({(std::uint64_t(w.lo) << 32) | w.hi, (std::uint64_t(a) << 32) | b, i});
  }
  std::sort(copies.begin(), copies.end());
  std::unordered_map<std::uint32_t, std::vector<std::uint32_t>> halves;
  for (std::size_t begin = 0; begin < copies.size();) {
    std::size_t end = begin + 1;
    bool shared = false;
    for (; end < copies.size() && copies[end].edge == copies[begin].edge; ++end)
      shared = shared || copies[end].copies == copies[end - 1].copies;
    for (std::size_t i = begin; shared && i < end; ++i) {
      const auto a = VertexIndex(copies[i].copies >> 32), b = VertexIndex(copies[i].copies);
      const auto m = VertexIndex(out.vertex_point.size());
      out.vertex_point.push_back(points.add_explicit(
          CGAL::midpoint(points.point(out.vertex_point[a]), points.point(out.vertex_point[b]))));
      for (const std::uint32_t face : wedge_pairs[copies[i].pair].faces) {
        const auto [f, k] = face_holding(out, halves, face, a, b);
        const Triangle t = out.triangles[f];
        out.triangles[f] = {t[k], m, t[(k + 2) % 3]};
        halves[f].push_back(std::uint32_t(out.triangles.size()));
        out.triangles.push_back({m, t[(k + 1) % 3], t[(k + 2) % 3]});
        if (origin) origin->push_back((*origin)[f]);
      }
    }
    begin = end;
  }
}

}  // namespace

// Sorted so that each point's corners are contiguous. Gathered in parallel blocks of faces: the
// faces are many, the special corners few.
SpecialCorners special_corners(const std::vector<Triangle>& faces,
                               const std::vector<std::uint8_t>& special) {
  constexpr std::size_t kBlock = 4096;
  const std::vector<std::size_t> first =
      block_offsets(faces.size(), kBlock, [&](std::size_t begin, std::size_t end) {
        std::size_t n = 0;
        for (std::size_t f = begin; f < end; ++f)
          for (const PointId p : faces[f]) n += special[p] != 0;
        return n;
      });
  SpecialCorners corners(first.back());
  tbb::parallel_for(std::size_t(0), first.size() - 1, [&](std::size_t b) {
    std::size_t slot = first[b];
    for (std::size_t f = b * kBlock; f < std::min(faces.size(), (b + 1) * kBlock); ++f)
      for (std::uint32_t i = 0; i < 3; ++i)
        if (special[faces[f][i]]) corners[slot++] = {faces[f][i], std::uint32_t(3 * f + i)};
  });
  sort_id_pairs(corners.begin(), corners.end());
  return corners;
}

// The points that are not special but end a non-manifold edge at a special point: an input
// vertex whose fan runs through a doubled edge of its input (two pairs of faces on one segment,
// told apart there by a copy of the other end). The operation may pair that edge's faces
// otherwise than the input did (a difference pairs each face with one of the other wedge, whose
// faces the input kept apart), which splits or joins the vertex's fan, so it must be examined
// too. The faces of edge vw are the corners at v whose next or previous point is w.
namespace {

std::vector<PointId> unexamined_ends(const std::vector<Triangle>& faces,
                                     const std::vector<std::uint8_t>& special,
                                     const SpecialCorners& corners) {
  const FaceCorners at{faces};
  std::vector<PointId> ends, around;
  for (std::size_t begin = 0; begin < corners.size();) {
    std::size_t end = begin + 1;
    while (end < corners.size() && corners[end].first == corners[begin].first) ++end;
    around.clear();
    for (std::size_t i = begin; i < end; ++i) {
      around.push_back(at.next(corners[i].second));
      around.push_back(at.previous(corners[i].second));
    }
    std::sort(around.begin(), around.end());
    for (std::size_t i = 0, j; i < around.size(); i = j) {
      for (j = i + 1; j < around.size() && around[j] == around[i];) ++j;
      if (j - i > 2 && !special[around[i]]) ends.push_back(around[i]);
    }
    begin = end;
  }
  std::sort(ends.begin(), ends.end());
  ends.erase(std::unique(ends.begin(), ends.end()), ends.end());
  return ends;
}

}  // namespace

// At a special point, each corner is attached to the corner of the face across each of its two
// edges there; a non-manifold edge pairs its faces by the solid wedges between them. Each fan of
// attached corners becomes one vertex.
//
// Fans do not always tell the pairs of a non-manifold edge apart: where the solid is two opposite
// wedges along the edge but one piece around each end (a solid minus two boxes sharing an edge),
// each end is a single fan, and both pairs of faces would share one edge. Each such extra pair is
// split at the edge's midpoint, a vertex of its own (coincident midpoints only touch).
IdMesh separate_non_manifold(PointTable& points, const std::vector<Triangle>& faces,
                             const std::vector<std::uint8_t>& special,
                             std::vector<FaceOrigin>* origin) {
  return separate_non_manifold(points, faces, special, special_corners(faces, special), origin);
}

IdMesh separate_non_manifold(PointTable& points, const std::vector<Triangle>& faces,
                             const std::vector<std::uint8_t>& special, SpecialCorners corners,
                             std::vector<FaceOrigin>* origin) {
  // Rare: the far ends of non-manifold edges join the special points, with their corners.
  std::vector<std::uint8_t> extended;
  for (std::vector<PointId> ends = unexamined_ends(faces, special, corners); !ends.empty();
       ends = unexamined_ends(faces, extended, corners)) {
    if (extended.empty()) extended = special;
    std::vector<std::uint8_t> added(special.size(), 0);
    for (const PointId p : ends) extended[p] = added[p] = 1;
    const SpecialCorners more = special_corners(faces, added);
    corners.insert(corners.end(), more.begin(), more.end());
    sort_id_pairs(corners.begin(), corners.end());
  }
  const std::vector<std::uint8_t>& examined = extended.empty() ? special : extended;
  Fans fans(points, faces, std::move(corners));
  fans.join_all();
  IdMesh out = number_vertices(points, faces, examined, fans);
  split_shared_pairs(points, faces, fans.wedge_pairs(), out, origin);
  return out;
}

Mesh assemble(const Mesh& a, const Mesh& b, Intersection& x, const Refined refined[2],
              const Labels labels[2], BooleanOp op, bool merge,
              std::vector<FaceOrigin>* provenance) {
  // The kept faces of both sides, in facet order, gathered in parallel blocks of facets.
  std::vector<Triangle> faces;
  std::vector<FaceOrigin> origin;
  const Mesh* meshes[2] = {&a, &b};
  for (int side = 0; side < 2; ++side) {
    const Mesh& mesh = *meshes[side];
    const bool reverse = op == BooleanOp::Difference && side == 1;
    const Refined& r = refined[side];
    // Sub-triangles of the i-th cut facet: [sub_begin[i], sub_begin[i + 1]).
    std::vector<std::uint32_t> sub_begin(r.facets.size() + 1, 0);
    for (std::size_t i = 0, t = 0; i < r.facets.size(); ++i) {
      sub_begin[i] = std::uint32_t(t);
      while (t < r.triangles.size() && r.triangles[t].facet == r.facets[i]) ++t;
      sub_begin[i + 1] = std::uint32_t(t);
    }
    constexpr std::uint32_t kBlock = 4096;
    const auto nf = std::uint32_t(mesh.num_triangles());
    const std::uint32_t blocks = (nf + kBlock - 1) / kBlock;
    // Visits the faces block k keeps, in facet order.
    auto for_each_kept = [&](std::uint32_t k, auto&& visit) {
      const std::uint32_t begin = k * kBlock, end = std::min(nf, begin + kBlock);
      std::size_t cut =
          std::lower_bound(r.facets.begin(), r.facets.end(), begin) - r.facets.begin();
      for (std::uint32_t f = begin; f < end; ++f) {
        if (cut < r.facets.size() && r.facets[cut] == f) {
          for (std::uint32_t t = sub_begin[cut]; t < sub_begin[cut + 1]; ++t)
            if (keep(op, side, labels[side].sub[t])) visit(r.triangles[t].v, f);
          ++cut;
          continue;
        }
        if (!keep(op, side, labels[side].facet[f])) continue;
        const Triangle& t = mesh.triangles[f];
        visit(std::array<PointId, 3>{x.vertex_id(side, t[0]), x.vertex_id(side, t[1]),
                                     x.vertex_id(side, t[2])},
              f);
      }
    };
    const std::vector<std::size_t> first =
        block_offsets(nf, kBlock, [&](std::size_t begin, std::size_t) {
          std::size_t n = 0;
          for_each_kept(std::uint32_t(begin / kBlock),
                        [&](const std::array<PointId, 3>&, std::uint32_t) { ++n; });
          return n;
        });
    const std::size_t base = faces.size();
    faces.resize(base + first.back());
    origin.resize(base + first.back());
    tbb::parallel_for(std::uint32_t(0), blocks, [&](std::uint32_t k) {
      std::size_t slot = base + first[k];
      for_each_kept(k, [&](const std::array<PointId, 3>& v, std::uint32_t f) {
        faces[slot] = reverse ? Triangle{v[0], v[2], v[1]} : Triangle{v[0], v[1], v[2]};
        origin[slot++] = {std::uint8_t(side), f};
      });
    });
  }

  // A vertex can only become removable by merging coplanar faces when the faces around it lie in
  // at most two planes: a special point where A's and B's facets meet transversally stays (three
  // planes or more, usually found among its first faces), one on a flat face or a straight crease
  // of what remains (coplanar facets overlapped, or the other mesh touched a face or an edge only)
  // may go.
  SpecialCorners around = special_corners(faces, x.flags);  // (point, 3 face + k)
  bool may_merge = merge && x.coplanar_overlaps;
  if (merge && !may_merge) {
    auto corners_of = [&](const FaceOrigin& o) {
      const Triangle& t = meshes[o.mesh]->triangles[o.face];
      return std::array<PointId, 3>{x.points.vertex(o.mesh, t[0]), x.points.vertex(o.mesh, t[1]),
                                    x.points.vertex(o.mesh, t[2])};
    };
    auto coplanar = [&](const FaceOrigin& f, const FaceOrigin& g) {
      if (f.mesh == g.mesh && f.face == g.face) return true;
      const auto a = corners_of(f), b = corners_of(g);
      return std::all_of(b.begin(), b.end(), [&](PointId p) {
        return x.points.orientation(a[0], a[1], a[2], p) == CGAL::ZERO;
      });
    };
    for (std::size_t i = 0; i < around.size() && !may_merge;) {
      std::size_t j = i;
      while (j < around.size() && around[j].first == around[i].first) ++j;
      const FaceOrigin* plane[2] = {nullptr, nullptr};  // a face in each plane met so far
      bool few = true;                                  // at most two planes
      for (std::size_t k = i; k < j && few; ++k) {
        const FaceOrigin& o = origin[around[k].second / 3];
        if ((plane[0] && coplanar(*plane[0], o)) || (plane[1] && coplanar(*plane[1], o))) continue;
        if (plane[1]) few = false;
        (plane[0] ? plane[1] : plane[0]) = &o;
      }
      may_merge = few;
      i = j;
    }
  }

  IdMesh surface = separate_non_manifold(x.points, faces, x.flags, std::move(around), &origin);
  if (may_merge) {
    // Each face lies in its input facet's plane (oriented as the face: B's facets are reversed in
    // a difference), one plane per facet.
    std::vector<std::array<PointId, 3>> planes;
    std::vector<std::uint32_t> plane_of(origin.size());
    std::vector<std::uint32_t> plane_of_facet[2] = {
        std::vector<std::uint32_t>(a.num_triangles(), kUnset),
        std::vector<std::uint32_t>(b.num_triangles(), kUnset)};
    // Faces of facets the other mesh touches (cut, or split at a point) may hold removable
    // vertices; the others are input facets kept whole, around their inputs' own vertices.
    std::vector<std::uint8_t> cut_facet[2] = {std::vector<std::uint8_t>(a.num_triangles(), 0),
                                              std::vector<std::uint8_t>(b.num_triangles(), 0)};
    for (int side = 0; side < 2; ++side)
      for (const auto& entry : x.cuts[side]) cut_facet[side][entry.first] = 1;
    std::vector<std::uint8_t> touched(origin.size());
    for (std::size_t f = 0; f < origin.size(); ++f) {
      const FaceOrigin& o = origin[f];
      touched[f] = cut_facet[o.mesh][o.face];
      std::uint32_t& plane = plane_of_facet[o.mesh][o.face];
      if (plane == kUnset) {
        const Triangle& t = meshes[o.mesh]->triangles[o.face];
        plane = std::uint32_t(planes.size());
        std::array<PointId, 3> corners = {x.points.vertex(o.mesh, t[0]),
                                          x.points.vertex(o.mesh, t[1]),
                                          x.points.vertex(o.mesh, t[2])};
        if (op == BooleanOp::Difference && o.mesh == 1) std::swap(corners[1], corners[2]);
        planes.push_back(corners);
      }
      plane_of[f] = plane;
    }
    merge_coplanar(x.points, surface, planes, plane_of, &touched);
  } else if (provenance) {
    *provenance = std::move(origin);
  }
  return materialize(x.points, surface);
}

}  // namespace morphex::detail

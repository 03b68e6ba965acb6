// SPDX-License-Identifier: GPL-3.0-or-later
#include "check/check_stars.h"

#include <CGAL/FPU.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>

#include "exact/static_filter.h"

namespace morphex::detail {

namespace {

// One use of an edge {v, other} by a face of v's star.
struct Use {
  VertexIndex other;
  std::uint32_t face;
  std::uint32_t corner;  // the face's place in the star
  bool outgoing;         // the face runs v -> other
  bool operator<(const Use& o) const { return other != o.other ? other < o.other : face < o.face; }
};

// The angle of a face at v: from the vertex after v to the one before it.
struct Angle {
  VertexIndex from, to;
  std::uint32_t face;
};

// The angles of every face grouped by vertex (a counting sort, faces read in order):
// angles[first[v] .. first[v + 1]) is the star of v.
struct StarsByVertex {
  std::vector<std::uint32_t> first;
  std::vector<Angle> angles;
  explicit StarsByVertex(const Mesh& mesh) : first(mesh.num_vertices() + 1, 0) {
    for (const Triangle& t : mesh.triangles)
      for (const VertexIndex v : t) ++first[v + 1];
    std::partial_sum(first.begin(), first.end(), first.begin());
    angles.resize(3 * mesh.num_triangles());
    std::vector<std::uint32_t> next(first.begin(), first.end() - 1);
    for (std::uint32_t f = 0; f < mesh.num_triangles(); ++f) {
      const Triangle& t = mesh.triangles[f];
      angles[next[t[0]]++] = {t[1], t[2], f};
      angles[next[t[1]]++] = {t[2], t[0], f};
      angles[next[t[2]]++] = {t[0], t[1], f};
    }
  }
};

// Stars of up to this many faces are paired by comparing every angle with every other; larger
// ones (a cone's apex) sort their edge uses instead.
constexpr std::size_t kSmallStar = 32;

class StarExaminer {
 public:
  StarExaminer(const PointTable& table, bool prove) : table_(table), prove_(prove) {}

  // Examines the star of v (its angles) into `out`; true when proved embedded near v.
  bool examine(VertexIndex v, const Angle* angles, std::size_t n, VertexStars& out) {
    star_.assign(angles, angles + n);
    const bool paired =
        n <= kSmallStar && pair_angles() ? record_paired(v, out) : record_uses(v, out);
    if (!prove_ || !paired || n < 3) return false;
    const std::array<double, 3> normal = mean_normal(v);
    // A coordinate axis suits smooth surfaces; where faces meet at sharp angles (CAD models:
    // a face perpendicular to every axis that suits the others) a diagonal may.
    return covers_once(v, closest_axis(normal)) || covers_once_along_diagonal(v, normal) ||
           covers_once_along_normal(v, normal);
  }

 private:
  // The common case: every neighbour is where one angle ends and exactly one other begins
  // (each edge at v used twice in opposite directions). next_[i] is the angle after angle i
  // around v; false when the angles do not pair up so.
  bool pair_angles() {
    const std::size_t n = star_.size();
    next_.assign(n, 0);
    before_.assign(n, UINT32_MAX);
    for (std::size_t i = 0; i < n; ++i) {
      const VertexIndex to = star_[i].to;
      std::uint32_t matches = 0, next = 0;
      for (std::uint32_t j = 0; j < n; ++j) {
        const bool match = star_[j].from == to;
        matches += match;
        next = match ? j : next;
      }
      if (matches != 1 || before_[next] != UINT32_MAX) return false;
      next_[i] = next;
      before_[next] = std::uint32_t(i);
    }
    return true;
  }

  // The edges of a paired star (all manifold and consistently oriented) and its fans (the cycles
  // of next_) into `out`; true.
  bool record_paired(VertexIndex v, VertexStars& out) {
    const std::size_t first = out.manifold.size();
    for (std::size_t i = 0; i < star_.size(); ++i) {
      const VertexIndex other = star_[i].from;
      if (other < v) continue;
      const std::uint32_t f = star_[i].face, g = star_[before_[i]].face;
      out.manifold.push_back({(std::uint64_t(v) << 32) | other, {std::min(f, g), std::max(f, g)}});
    }
    std::sort(out.manifold.begin() + std::ptrdiff_t(first), out.manifold.end());
    std::size_t cycle = 1;
    for (std::uint32_t i = next_[0]; i != 0; i = next_[i]) ++cycle;
    if (cycle != star_.size()) non_manifold_vertex(v, out);
    return true;
  }

  void non_manifold_vertex(VertexIndex v, VertexStars& out) const {
    ++out.non_manifold_vertices;
    if (!out.first_non_manifold_vertex) out.first_non_manifold_vertex = v;
  }

  // Any star: its edge uses sorted by neighbour. The edges {v, other} with other > v (each edge
  // is counted at its smaller end) and whether the faces form one fan into `out`; true when
  // every edge at v is used twice in opposite directions.
  bool record_uses(VertexIndex v, VertexStars& out) {
    uses_.clear();
    for (std::size_t i = 0; i < star_.size(); ++i) {
      uses_.push_back({star_[i].from, star_[i].face, std::uint32_t(i), true});
      uses_.push_back({star_[i].to, star_[i].face, std::uint32_t(i), false});
    }
    std::sort(uses_.begin(), uses_.end());
    if (!one_fan()) non_manifold_vertex(v, out);
    return count_edges(v, out);
  }

  bool count_edges(VertexIndex v, VertexStars& out) const {
    bool paired = true;
    for (std::size_t i = 0; i < uses_.size();) {
      std::size_t j = i + 1;
      while (j < uses_.size() && uses_[j].other == uses_[i].other) ++j;
      const bool opposite = j - i == 2 && uses_[i].outgoing != uses_[i + 1].outgoing;
      paired = paired && opposite;
      if (uses_[i].other > v) record_edge(v, i, j, opposite, out);
      i = j;
    }
    return paired;
  }

  void record_edge(VertexIndex v, std::size_t i, std::size_t j, bool opposite,
                   VertexStars& out) const {
    const std::uint64_t key = (std::uint64_t(v) << 32) | uses_[i].other;
    if (j - i == 1) {
      ++out.border_edges;
      if (!out.first_border_vertex) out.first_border_vertex = v;
    } else if (j - i > 2) {
      ++out.non_manifold_edges;
      for (std::size_t k = i + 1; k < j; ++k)
        out.other_joins.emplace_back(uses_[k].face, uses_[i].face);
    } else {
      if (!opposite && (!out.first_misoriented_face || uses_[i].face < *out.first_misoriented_face))
        out.first_misoriented_face = uses_[i].face;
      out.manifold.push_back({key, {uses_[i].face, uses_[i + 1].face}});
    }
  }

  // The faces of the star form one fan: joined across the edges at v used by exactly two faces.
  bool one_fan() {
    parent_.resize(star_.size());
    std::iota(parent_.begin(), parent_.end(), 0u);
    auto find = [&](std::uint32_t x) {
      while (parent_[x] != x) x = parent_[x] = parent_[parent_[x]];
      return x;
    };
    std::size_t sets = star_.size();
    for (std::size_t i = 0; i < uses_.size();) {
      std::size_t j = i + 1;
      while (j < uses_.size() && uses_[j].other == uses_[i].other) ++j;
      if (j - i == 2) {
        const std::uint32_t a = find(uses_[i].corner), b = find(uses_[i + 1].corner);
        if (a != b) parent_[a] = b, --sets;
      }
      i = j;
    }
    return sets <= 1;
  }

  // The star's mean normal, in doubles (a poor one only makes the proofs fail, never wrong).
  std::array<double, 3> mean_normal(VertexIndex v) const {
    const auto& doubles = table_.input_near_doubles();
    auto xyz = [&](VertexIndex p) {
      if (!doubles.empty()) return doubles[p];
      const ApproxPoint& a = table_.approx(p);
      return std::array<double, 3>{a.x().inf(), a.y().inf(), a.z().inf()};
    };
    const std::array<double, 3> o = xyz(v);
    std::array<double, 3> n{0, 0, 0};
    for (const Angle& a : star_) {
      std::array<double, 3> p = xyz(a.from), q = xyz(a.to);
      for (int i = 0; i < 3; ++i) p[i] -= o[i], q[i] -= o[i];
      n[0] += p[1] * q[2] - p[2] * q[1];
      n[1] += p[2] * q[0] - p[0] * q[2];
      n[2] += p[0] * q[1] - p[1] * q[0];
    }
    return n;
  }

  static int closest_axis(const std::array<double, 3>& n) {
    const double x = std::fabs(n[0]), y = std::fabs(n[1]), z = std::fabs(n[2]);
    return x >= y && x >= z ? 0 : y >= z ? 1 : 2;
  }

  // The same proof along the diagonal d = (sx, sy, 1) (sx, sy = +-1) closest to the normal,
  // double inputs only. The plane across d gets the frame f1 = d x e_z = (sy, -sx, 0) and
  // f2 = d x f1 = (sx, sy, -2), whose integer entries make each coordinate of a direction a sum
  // of a few doubles, with an exact sign; f1 x f2 = 2 d, so the turn in that frame is the sign
  // of det [p - v, q - v, d] (the static filter: undecided makes the proof fail).
  bool covers_once_along_diagonal(VertexIndex v, const std::array<double, 3>& normal) const {
    const auto& doubles = table_.input_doubles();
    if (doubles.empty()) return false;
    const CGAL::Protect_FPU_rounding<true> nearest(CGAL_FE_TONEAREST);  // for sign_of_sum
    const double sx = normal[0] * normal[2] < 0 ? -1 : 1, sy = normal[1] * normal[2] < 0 ? -1 : 1;
    const std::array<double, 3>& o = doubles[v];
    // The quadrant of p - v in the frame, from the exact signs of its two coordinates.
    auto quadrant_of = [&](const std::array<double, 3>& p) {
      for (int k = 0; k < 3; ++k)  // sums of a few coordinates must not overflow
        if (!(std::fabs(p[k]) < 1e300 && std::fabs(o[k]) < 1e300)) return 5;
      const int u = sign_of_sum({sy * p[0], -sy * o[0], -sx * p[1], sx * o[1]});
      const int w =
          sign_of_sum({sx * p[0], sy * p[1], -2 * p[2], -sx * o[0], -sy * o[1], 2 * o[2]});
      return quadrant(u, w);
    };
    int turn = 0, quarters = 0;
    for (const Angle& a : star_) {
      const std::array<double, 3>&p = doubles[a.from], &q = doubles[a.to];
      const std::optional<int> s = static_orientation_of_differences(
          p[0] - o[0], p[1] - o[1], p[2] - o[2], q[0] - o[0], q[1] - o[1], q[2] - o[2], sx, sy, 1);
      if (!s || *s == 0 || *s == -turn) return false;
      turn = *s;
      const int from = quadrant_of(p), to = quadrant_of(q);
      if (from > 3 || to > 3) return false;
      quarters += quarters_turned(turn, from, to);
    }
    return quarters == 4;
  }

  // The same proof along the star's mean normal d itself, by the doubles within their errors: a
  // ridge or a tip whose faces no axis or diagonal sees all from one side (a model turned off the
  // axes has many). The winding is counted by the angles that a ray r from v across d meets,
  // half-open at their first side: each turns less than half a turn, all the same way, so r
  // meets one angle per winding.
  bool covers_once_along_normal(VertexIndex v, const std::array<double, 3>& normal) const {
    const auto& doubles = table_.input_near_doubles();
    if (doubles.empty()) return false;
    const double error = table_.input_error();
    // Any direction near the normal serves: d scaled to entries of at most 1, r = e_k x d for
    // the axis k least along d (exact: entries of d moved and negated).
    const double scale =
        std::max({std::fabs(normal[0]), std::fabs(normal[1]), std::fabs(normal[2])});
    if (!(scale > 0) || !std::isfinite(scale)) return false;
    const Xyz d = {normal[0] / scale, normal[1] / scale, normal[2] / scale};
    const int k = std::fabs(d[0]) <= std::fabs(d[1]) && std::fabs(d[0]) <= std::fabs(d[2]) ? 0
                  : std::fabs(d[1]) <= std::fabs(d[2])                                     ? 1
                                                                                           : 2;
    const Xyz r = k == 0 ? Xyz{0, -d[2], d[1]} : k == 1 ? Xyz{d[2], 0, -d[0]} : Xyz{-d[1], d[0], 0};
    const Xyz& o = doubles[v];
    auto from_v = [&](VertexIndex p) {
      return Xyz{doubles[p][0] - o[0], doubles[p][1] - o[1], doubles[p][2] - o[2]};
    };
    int turn = 0, crossings = 0;
    for (const Angle& a : star_) {
      const Xyz p = from_v(a.from), q = from_v(a.to);
      const std::optional<int> s = static_turn_along(p, q, d, error);
      if (!s || *s == 0 || *s == -turn) return false;
      turn = *s;
      // r in [p, q): from p to r turns the angle's way or not at all, from r to q strictly.
      const std::optional<int> pr = static_turn_along(p, r, d, error),
                               rq = static_turn_along(r, q, d, error);
      if (!pr || !rq) return false;  // no exact zeros here: the proof just fails
      crossings += *pr == turn && *rq == turn;
    }
    return crossings == 1;
  }

  // Every angle turns one way seen along `axis` and, together, they wind once around v.
  //
  // The winding is counted in quarter turns: a direction's quadrant (half-open, so that every
  // nonzero direction has one) is exact from the signs of its differences from v, and an angle
  // that turns less than half a turn one way crosses exactly (q(end) - q(start)) mod 4 quadrant
  // boundaries (0, 1 or 2; 3 is impossible). Around a closed loop they add up to 4 per winding.
  bool covers_once(VertexIndex v, int axis) const {
    const auto& doubles = table_.input_near_doubles();
    if (doubles.empty()) return covers_once_exactly(v, axis);
    const double error = table_.input_error();
    const int u = axis == 0 ? 1 : 0, w = axis == 2 ? 1 : 2;
    const double ou = doubles[v][u], ow = doubles[v][w];
    // A difference's sign: the doubles' one when the points are doubles (rounding keeps it),
    // else when it clears the two points' errors (and its own rounding); else exactly.
    const double margin = 2 * error * (1 + 0x1p-40);
    auto sign = [&](double d, VertexIndex p, int k) {
      if (error == 0 || std::fabs(d) > margin) return d;
      return exact_sign(p, v, k);
    };
    int turn = 0, quarters = 0;
    for (const Angle& a : star_) {
      const double fu = doubles[a.from][u] - ou, fw = doubles[a.from][w] - ow,
                   tu = doubles[a.to][u] - ou, tw = doubles[a.to][w] - ow;
      const std::optional<int> f =
          error == 0
              ? static_orientation_2_of_differences(fu, fw, tu, tw)
              : static_orientation_2_near(u, w, doubles[v], doubles[a.from], doubles[a.to], error);
      const int s = f ? *f : int(table_.orientation_2(axis, v, a.from, a.to));
      if (s == 0 || s == -turn) return false;
      turn = s;
      quarters += quarters_turned(s, quadrant(sign(fu, a.from, u), sign(fw, a.from, w)),
                                  quadrant(sign(tu, a.to, u), sign(tw, a.to, w)));
    }
    return quarters == 4;
  }

  // The sign of p - v along k: by the intervals when they are apart, else exactly (from the
  // table's homogeneous points, computed once per point: comparing the mesh's lazy coordinates
  // built and evaluated two lazy numbers per comparison).
  double exact_sign(VertexIndex p, VertexIndex v, int k) const {
    return double(table_.compare(k, p, v));
  }

  // The same without doubles: exact coordinate comparisons and orientations.
  bool covers_once_exactly(VertexIndex v, int axis) const {
    const int u = axis == 0 ? 1 : 0, w = axis == 2 ? 1 : 2;
    auto sign = [&](VertexIndex p, int k) { return exact_sign(p, v, k); };
    int turn = 0, quarters = 0;
    for (const Angle& a : star_) {
      const int s = int(table_.orientation_2(axis, v, a.from, a.to));
      if (s == 0 || s == -turn) return false;
      turn = s;
      quarters += quarters_turned(s, quadrant(sign(a.from, u), sign(a.from, w)),
                                  quadrant(sign(a.to, u), sign(a.to, w)));
    }
    return quarters == 4;
  }

  // The half-open quadrant of a nonzero direction (exact: only signs are compared).
  // Without branches: directions around a vertex fall in any quadrant, and a mispredicted
  // branch costs more than these comparisons.
  static int quadrant(double du, double dw) {
    const int u_pos = du > 0, w_pos = dw > 0, u_neg = du < 0, w_neg = dw < 0;
    return (1 - u_pos) * w_pos + 2 * (u_neg * (1 - w_pos)) + 3 * ((1 - u_neg) * w_neg);
  }
  // Quadrant boundaries crossed by an angle turning `turn` (less than half a turn) from
  // quadrant `from` to `to`: 0, 1 or 2 (3 cannot happen; 5 makes the sum fail if it did).
  static int quarters_turned(int turn, int from, int to) {
    const int q = (turn > 0 ? to - from : from - to) & 3;
    return q == 3 ? 5 : q;
  }

  const PointTable& table_;
  const bool prove_;
  std::vector<Angle> star_;
  std::vector<Use> uses_;
  std::vector<std::uint32_t> parent_, next_, before_;
};

// The chunks' findings, in vertex order (manifold edges stay sorted by key).
void append(VertexStars& all, VertexStars& chunk) {
  all.manifold.insert(all.manifold.end(), chunk.manifold.begin(), chunk.manifold.end());
  all.other_joins.insert(all.other_joins.end(), chunk.other_joins.begin(), chunk.other_joins.end());
  all.border_edges += chunk.border_edges;
  all.non_manifold_edges += chunk.non_manifold_edges;
  all.non_manifold_vertices += chunk.non_manifold_vertices;
  if (!all.first_border_vertex) all.first_border_vertex = chunk.first_border_vertex;
  if (!all.first_non_manifold_vertex)
    all.first_non_manifold_vertex = chunk.first_non_manifold_vertex;
  if (chunk.first_misoriented_face &&
      (!all.first_misoriented_face || *chunk.first_misoriented_face < *all.first_misoriented_face))
    all.first_misoriented_face = chunk.first_misoriented_face;
}

}  // namespace

VertexStars examine_vertex_stars(const Mesh& mesh, const PointTable& table, bool prove) {
  const StarsByVertex by_vertex(mesh);
  const std::size_t nv = mesh.num_vertices(), chunk_size = 2048;
  std::vector<VertexStars> chunks((nv + chunk_size - 1) / chunk_size);
  VertexStars all;
  all.embedded.assign(prove ? nv : 0, 0);
  tbb::parallel_for(std::size_t(0), chunks.size(), [&](std::size_t c) {
    StarExaminer examiner(table, prove);
    chunks[c].manifold.reserve(3 * chunk_size);
    for (std::size_t v = c * chunk_size; v < std::min(nv, (c + 1) * chunk_size); ++v) {
      const std::uint32_t begin = by_vertex.first[v], end = by_vertex.first[v + 1];
      if (begin == end) continue;
      const bool embedded =
          examiner.examine(VertexIndex(v), &by_vertex.angles[begin], end - begin, chunks[c]);
      if (prove) all.embedded[v] = embedded;
    }
  });
  all.manifold.reserve(3 * mesh.num_triangles() / 2);
  for (VertexStars& chunk : chunks) append(all, chunk);
  return all;
}

}  // namespace morphex::detail

// SPDX-License-Identifier: GPL-3.0-or-later
// Which pieces of a cut soup bound {w >= threshold}: winding numbers on both sides of each patch.
//
// No sheet crosses a member (crossings are constraints of the cuts), so the winding number is
// constant just in front of it, w_front, and just behind it, w_back:
//   w_back   w_front plus the jump across the member's plane: the weights of the facets of its
//            coplanar stack (the facets of the soup in its plane that contain it), each signed
//            by whether its normal agrees.
//   regions  the sides of members that are one region of space: across an edge that exactly two
//            members share, one each way, their fronts and their backs; around any other edge
//            (where sheets cross or several meet), the sides facing one wedge between
//            consecutive half-planes, in exact angular order.
//   w_front  one exact ray cast per connected set of regions, from a point inside one member (its
//            centroid, an exact construction) to a far point on the front side: the signed
//            weights of the facets the segment crosses (facets whose plane holds the start are
//            never crossed; a segment that grazes an edge or a corner is replaced by one to
//            another far point). Every other region follows along the members, w_back = w_front +
//            jump, and a region reached twice must get one value (checked).
// A member is kept when the threshold lies between the two, oriented so that {w >= threshold} is
// behind it; of a stack only the facet with the least index speaks for all.
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <climits>
#include <cmath>
#include <stdexcept>

#include "winding/winding_internal.h"

namespace morphex::detail {
namespace {

// Generic directions (not along an axis, a diagonal or a box's diagonal plane), both ways.
constexpr double kDirections[6][3] = {{1.0, 0.5773502691896257, 0.3119047619047619},
                                      {-0.2718281828459045, 1.0, 0.7071067811865476},
                                      {0.4142135623730951, -0.8660254037844386, 1.0},
                                      {-1.0, -0.3183098861837907, 0.6931471805599453},
                                      {0.1414213562373095, 0.7320508075688772, -1.0},
                                      {0.9, -0.1234567890123457, -0.4567891234567891}};

// Far points around the soup, outside every facet's box: the ends of the rays.
std::vector<PointId> far_points(PointTable& table, std::size_t num_vertices) {
  double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  for (PointId v = 0; v < num_vertices; ++v)
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], table.approx(v).cartesian(k).inf());
      hi[k] = std::max(hi[k], table.approx(v).cartesian(k).sup());
    }
  double extent = 0, centre[3];
  for (int k = 0; k < 3; ++k) {
    extent = std::max(extent, hi[k] - lo[k]);
    centre[k] = 0.5 * (lo[k] + hi[k]);
  }
  const double reach = 4 * extent + 1;
  std::vector<PointId> out;
  for (int sign : {1, -1})
    for (const auto& d : kDirections)
      out.push_back(
          table.add_explicit(Point(centre[0] + sign * reach * d[0], centre[1] + sign * reach * d[1],
                                   centre[2] + sign * reach * d[2])));
  return out;
}

class WindingProbe {
 public:
  WindingProbe(const Chain& chain, const TriangleTree& tree, const Intersection& x,
               std::vector<PointId> far)
      : chain_(chain), tree_(tree), x_(x), table_(x.points), far_(std::move(far)) {}

  Corners3 corners(std::uint32_t facet) const {
    const Triangle& t = chain_.soup.triangles[facet];
    return {x_.vertex_id(0, t[0]), x_.vertex_id(0, t[1]), x_.vertex_id(0, t[2])};
  }

  // The winding number just in front of `facet` at its point q (not on any other sheet).
  int in_front(std::uint32_t facet, PointId q) const {
    const Corners3 t = corners(facet);
    for (PointId z : far_) {
      if (table_.orientation(t[0], t[1], t[2], z) != CGAL::POSITIVE) continue;
      int winding = 0;
      if (cast(q, z, winding)) return winding;
    }
    throw std::logic_error("winding number: every ray from a sample point was degenerate");
  }

  // Whether the member of `facet` with centroid q lies inside the closed coplanar facet g.
  bool inside_coplanar(int dropped, PointId q, std::uint32_t g) const {
    const Corners3 c = corners(g);
    const CGAL::Sign turn = table_.orientation_2(dropped, c[0], c[1], c[2]);
    for (int k = 0; k < 3; ++k)
      if (table_.orientation_2(dropped, c[k], c[(k + 1) % 3], q) == -turn) return false;
    return true;
  }

 private:
  // Sum over the facets crossed by the segment q -> z of their weights, signed + where the
  // segment leaves through the front. False when it passes through an edge or a corner.
  bool cast(PointId q, PointId z, int& winding) const {
    const ApproxPoint& aq = table_.approx(q);
    const ApproxPoint& az = table_.approx(z);
    const CGAL::Bbox_3 origin(aq.x().inf(), aq.y().inf(), aq.z().inf(), aq.x().sup(), aq.y().sup(),
                              aq.z().sup());
    const std::array<double, 3> direction = {CGAL::to_double(az.x()) - CGAL::to_double(aq.x()),
                                             CGAL::to_double(az.y()) - CGAL::to_double(aq.y()),
                                             CGAL::to_double(az.z()) - CGAL::to_double(aq.z())};
    bool degenerate = false;
    tree_.for_each_on_ray(origin, direction, [&](std::uint32_t u) {
      if (degenerate) return;
      const Corners3 c = corners(u);
      const CGAL::Sign sq = table_.orientation(c[0], c[1], c[2], q);
      if (sq == CGAL::ZERO) return;  // its plane holds q: the segment leaves it at once
      const CGAL::Sign sz = table_.orientation(c[0], c[1], c[2], z);
      if (sz == CGAL::ZERO || sz == sq) return;  // z is beyond every facet
      bool positive = false, negative = false, zero = false;
      for (int k = 0; k < 3; ++k) {
        const CGAL::Sign s = table_.orientation(q, z, c[k], c[(k + 1) % 3]);
        positive |= s == CGAL::POSITIVE;
        negative |= s == CGAL::NEGATIVE;
        zero |= s == CGAL::ZERO;
      }
      if (positive && negative) return;
      if (zero) {
        degenerate = true;
        return;
      }
      winding += sz == CGAL::POSITIVE ? chain_.weight[u] : -chain_.weight[u];
    });
    return !degenerate;
  }

  const Chain& chain_;
  const TriangleTree& tree_;
  const Intersection& x_;
  const PointTable& table_;
  std::vector<PointId> far_;
};

PointId add_centroid(PointTable& table, const Member& m) {
  Recipe r;
  r.kind = Recipe::Kind::Centroid;
  r.p = m.v[0], r.q = m.v[1], r.a = m.v[2], r.b = m.v[2], r.c = m.v[2];
  return table.add(r);
}

// A member at an edge lo - hi: its vertex off the edge, its facet, and whether it runs lo -> hi.
struct Leaf {
  PointId third;
  std::uint32_t member, facet;
  bool along;  // runs lo -> hi: its normal faces increasing angle
};

// Right-handed angle order of the leaves' half-planes around the axis lo -> hi, from `ref`'s. Two
// leaves of one facet lie in one plane through the axis, on opposite sides (the facet's sub-
// triangles on both sides of the edge run it both ways): that is known without a predicate, and
// is the degenerate question every crossing would otherwise ask exactly.
struct AroundAxis {
  const PointTable& table;
  PointId lo, hi;
  Leaf ref;
  int half(const Leaf& w) const {  // 0: angle in [0, pi), 1: [pi, 2 pi)
    if (w.facet == ref.facet) return w.along == ref.along ? 0 : 1;
    const CGAL::Sign s = table.orientation(lo, hi, ref.third, w.third);
    if (s != CGAL::ZERO) return s == CGAL::POSITIVE ? 0 : 1;
    // In the plane of the axis and ref: angle 0 on ref's side of the axis (the triangles
    // (lo, hi, ref) and (lo, hi, w) alike oriented), else pi.
    return table.normal_dot({lo, hi, ref.third}, {lo, hi, w.third}) == CGAL::POSITIVE ? 0 : 1;
  }
  bool operator()(const Leaf& p, const Leaf& q) const {
    const int hp = half(p), hq = half(q);
    if (hp != hq) return hp < hq;
    if (p.facet == q.facet) return false;  // one half-plane
    return table.orientation(lo, hi, p.third, q.third) == CGAL::POSITIVE;
  }
};

// The sides of the members as nodes (2 m in front of member m, 2 m + 1 behind it), joined where
// they are one region of space: across an edge that exactly two members share, one each way, the
// fronts of both and the backs of both; around any other edge, the sides that face one wedge
// between consecutive half-planes (members in one half-plane form one layer).
UnionFind join_sides(const PointTable& table, const std::vector<Member>& members) {
  const std::size_t n = members.size();
  std::vector<std::pair<std::uint64_t, std::uint32_t>> edges(3 * n);  // (edge, member * 2 + dir)
  tbb::parallel_for(std::size_t(0), n, [&](std::size_t i) {
    for (int k = 0; k < 3; ++k) {
      const PointId a = members[i].v[k], b = members[i].v[(k + 1) % 3];
      edges[3 * i + k] = {edge_key(undirected(a, b)), std::uint32_t(2 * i + (a > b))};
    }
  });
  tbb::parallel_sort(edges.begin(), edges.end());
  UnionFind sides(2 * n);
  std::vector<std::size_t> fans;  // first slot of each edge shared otherwise
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i + 1;
    while (j < edges.size() && edges[j].first == edges[i].first) ++j;
    const std::uint32_t m0 = edges[i].second >> 1;
    if (j - i == 2 && (edges[i].second & 1) != (edges[i + 1].second & 1)) {
      const std::uint32_t m1 = edges[i + 1].second >> 1;
      sides.join(2 * m0, 2 * m1);
      sides.join(2 * m0 + 1, 2 * m1 + 1);
    } else if (j - i >= 2) {
      fans.push_back(i);
    }
    i = j;
  }
  // Around the other edges, in parallel: each fan's wedges as pairs of sides to join.
  std::vector<std::vector<std::pair<std::uint32_t, std::uint32_t>>> wedges(fans.size());
  for_each_upward(fans.size(), [&](std::size_t f) {
    std::size_t j = fans[f] + 1;
    while (j < edges.size() && edges[j].first == edges[fans[f]].first) ++j;
    const PointId lo = PointId(edges[fans[f]].first >> 32), hi = PointId(edges[fans[f]].first);
    std::vector<Leaf> leaves;
    for (std::size_t k = fans[f]; k < j; ++k) {
      const Member& m = members[edges[k].second >> 1];
      PointId third = m.v[0];
      for (PointId p : m.v)
        if (p != lo && p != hi) third = p;
      leaves.push_back({third, edges[k].second >> 1, m.facet, (edges[k].second & 1) == 0});
    }
    const AroundAxis order{table, lo, hi, leaves[0]};
    std::sort(leaves.begin(), leaves.end(), order);
    auto up = [&](const Leaf& l) { return 2 * l.member + (l.along ? 0 : 1); };    // +angle side
    auto down = [&](const Leaf& l) { return 2 * l.member + (l.along ? 1 : 0); };  // -angle side
    // Layers: runs of leaves at one angle. Each wedge joins the +angle sides of a layer with the
    // -angle sides of the next.
    std::vector<std::size_t> layer;
    for (std::size_t k = 0; k < leaves.size(); ++k)
      if (k == 0 || order(leaves[k - 1], leaves[k])) layer.push_back(k);
    layer.push_back(leaves.size());
    const std::size_t count = layer.size() - 1;
    for (std::size_t l = 0; l < count; ++l) {
      const std::size_t next = (l + 1) % count;
      const std::uint32_t wedge = up(leaves[layer[l]]);
      for (std::size_t k = layer[l]; k < layer[l + 1]; ++k)
        wedges[f].emplace_back(wedge, up(leaves[k]));
      for (std::size_t k = layer[next]; k < layer[next + 1]; ++k)
        wedges[f].emplace_back(wedge, down(leaves[k]));
    }
  });
  for (const auto& list : wedges)
    for (const auto& [a, b] : list) sides.join(a, b);
  return sides;
}
}  // namespace

std::vector<std::int8_t> select_by_winding(const Chain& chain, const TriangleTree& tree,
                                           const std::vector<Member>& members, Intersection& x,
                                           int threshold, WindingStats& stats) {
  const std::size_t n = members.size();
  PointTable& table = x.points;
  UnionFind sides = join_sides(table, members);

  // Samples of the members of facets with coplanar neighbours, for their stacks.
  std::vector<PointId> sample(n, 0);
  std::vector<std::uint8_t> stacked(n, 0);
  for (std::uint32_t i = 0; i < n; ++i) {
    const FacetCut* cut = x.cut(0, members[i].facet);
    stacked[i] = cut && !cut->coplanar_facets.empty();
    if (stacked[i]) sample[i] = add_centroid(table, members[i]);
  }
  std::vector<PointId> far = far_points(table, table.num_inputs());
  const WindingProbe probe(chain, tree, x, std::move(far));

  // The jump w_back - w_front across each member's plane, and whether it speaks for its stack.
  std::vector<int> jump(n);
  std::vector<std::uint8_t> speaks(n, 1);
  for_each_upward(n, [&](std::size_t i) {
    const std::uint32_t facet = members[i].facet;
    jump[i] = chain.weight[facet];
    if (!stacked[i]) return;
    const Corners3 t = probe.corners(facet);
    const int dropped = table.dominant_axis(t[0], t[1], t[2]);
    for (std::uint32_t g : x.cut(0, facet)->coplanar_facets) {
      if (!probe.inside_coplanar(dropped, sample[i], g)) continue;
      if (g < facet) speaks[i] = 0;  // the stack's least facet speaks for it
      const bool alike = table.normal_dot(t, probe.corners(g)) == CGAL::POSITIVE;
      jump[i] += alike ? chain.weight[g] : -chain.weight[g];
    }
  });

  // Regions (classes of sides) linked by members: w(back) = w(front) + jump. One ray cast per
  // connected set of regions, the rest follows along the links.
  std::vector<std::uint32_t> region(2 * n);
  for (std::uint32_t k = 0; k < 2 * n; ++k) region[k] = sides.find(k);
  std::vector<std::vector<std::uint32_t>> linked(2 * n);  // region -> members touching it
  for (std::uint32_t i = 0; i < n; ++i) {
    linked[region[2 * i]].push_back(i);
    if (region[2 * i + 1] != region[2 * i]) linked[region[2 * i + 1]].push_back(i);
  }
  constexpr int kUnknown = INT32_MIN;
  std::vector<int> winding(2 * n, kUnknown);
  std::vector<std::uint32_t> queue;
  for (std::uint32_t start = 0; start < n; ++start) {
    if (winding[region[2 * start]] != kUnknown) continue;
    const PointId q = sample[start] ? sample[start] : add_centroid(table, members[start]);
    winding[region[2 * start]] = probe.in_front(members[start].facet, q);
    ++stats.patches;
    queue.assign(1, region[2 * start]);
    while (!queue.empty()) {
      const std::uint32_t r = queue.back();
      queue.pop_back();
      for (std::uint32_t i : linked[r]) {
        const std::uint32_t front = region[2 * i], back = region[2 * i + 1];
        const bool from_front = front == r;
        const std::uint32_t other = from_front ? back : front;
        const int value = from_front ? winding[r] + jump[i] : winding[r] - jump[i];
        if (winding[other] == kUnknown) {
          winding[other] = value;
          queue.push_back(other);
        } else if (winding[other] != value) {
          throw std::logic_error("winding numbers: inconsistent regions around the arrangement");
        }
      }
    }
  }

  std::vector<std::int8_t> keep(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    if (!speaks[i]) continue;
    const int w_front = winding[region[2 * i]], w_back = w_front + jump[i];
    const bool in_front = w_front >= threshold, in_back = w_back >= threshold;
    keep[i] = in_back && !in_front ? 1 : in_front && !in_back ? -1 : 0;
  }
  return keep;
}

}  // namespace morphex::detail

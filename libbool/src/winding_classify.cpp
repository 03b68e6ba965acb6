// SPDX-License-Identifier: GPL-3.0-or-later
// Which pieces of a cut soup bound {w >= threshold}: winding numbers on both sides of each patch.
//
// A patch is a set of members (uncut facets and sub-triangles) joined across edges that exactly
// two members share, one in each direction: around such an edge nothing else passes, so the
// space in front of both members is one region, and so is the space behind. No sheet crosses a
// patch (crossings are constraints of the cuts), so the winding number is constant in front of
// it, w_front, and behind it, w_back.
//
//   w_front  one exact ray cast from a point inside one member (its centroid, an exact
//            construction) to a far point on the front side: the signed weights of the facets
//            the segment crosses. Facets whose plane holds the start are never crossed; a segment
//            that grazes an edge or a corner is replaced by one to another far point.
//   w_back   w_front plus the jump across the member's plane: the weights of the facets of its
//            coplanar stack (the facets of the soup in its plane that contain it), each signed
//            by whether its normal agrees.
// A member is kept when the threshold lies between the two, oriented so that {w >= threshold} is
// behind it; of a stack only the facet with the least index speaks for all.
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <cmath>
#include <stdexcept>

#include "winding_internal.h"

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
      out.push_back(table.add_explicit(Point(centre[0] + sign * reach * d[0],
                                             centre[1] + sign * reach * d[1],
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
    const CGAL::Bbox_3 origin(aq.x().inf(), aq.y().inf(), aq.z().inf(), aq.x().sup(),
                              aq.y().sup(), aq.z().sup());
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

// Members joined across edges that exactly two of them share, one in each direction.
UnionFind patches_of(const std::vector<Member>& members) {
  const std::size_t n = members.size();
  std::vector<std::pair<std::uint64_t, std::uint32_t>> edges(3 * n);  // (edge, member * 2 + dir)
  tbb::parallel_for(std::size_t(0), n, [&](std::size_t i) {
    for (int k = 0; k < 3; ++k) {
      const PointId a = members[i].v[k], b = members[i].v[(k + 1) % 3];
      edges[3 * i + k] = {edge_key(undirected(a, b)), std::uint32_t(2 * i + (a > b))};
    }
  });
  tbb::parallel_sort(edges.begin(), edges.end());
  UnionFind patches(n);
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i + 1;
    while (j < edges.size() && edges[j].first == edges[i].first) ++j;
    if (j - i == 2 && (edges[i].second & 1) != (edges[i + 1].second & 1))
      patches.join(edges[i].second >> 1, edges[i + 1].second >> 1);
    i = j;
  }
  return patches;
}

PointId add_centroid(PointTable& table, const Member& m) {
  Recipe r;
  r.kind = Recipe::Kind::Centroid;
  r.p = m.v[0], r.q = m.v[1], r.a = m.v[2], r.b = m.v[2], r.c = m.v[2];
  return table.add(r);
}

}  // namespace

std::vector<std::int8_t> select_by_winding(const Chain& chain, const TriangleTree& tree,
                                           const std::vector<Member>& members, Intersection& x,
                                           int threshold, WindingStats& stats) {
  const std::size_t n = members.size();
  UnionFind patches = patches_of(members);
  std::vector<std::uint32_t> patch_of(n), representative;
  {
    std::vector<std::uint32_t> index(n, UINT32_MAX);
    for (std::uint32_t i = 0; i < n; ++i) {
      std::uint32_t& p = index[patches.find(i)];
      if (p == UINT32_MAX) {
        p = std::uint32_t(representative.size());
        representative.push_back(i);
      }
      patch_of[i] = p;
    }
  }
  stats.patches = representative.size();

  // Sample points (sequential: the table grows): one per patch, one per member of a facet with
  // coplanar neighbours.
  PointTable& table = x.points;
  std::vector<PointId> far = far_points(table, table.num_inputs());
  std::vector<PointId> sample(n, 0);
  std::vector<std::uint8_t> stacked(n, 0);
  for (std::uint32_t p = 0; p < representative.size(); ++p) {
    const std::uint32_t i = representative[p];
    sample[i] = add_centroid(table, members[i]);
  }
  for (std::uint32_t i = 0; i < n; ++i) {
    const FacetCut* cut = x.cut(0, members[i].facet);
    stacked[i] = cut && !cut->coplanar_facets.empty();
    if (stacked[i] && sample[i] == 0) sample[i] = add_centroid(table, members[i]);
  }
  const WindingProbe probe(chain, tree, x, std::move(far));

  std::vector<int> front(representative.size());
  for_each_upward(representative.size(), [&](std::size_t p) {
    const std::uint32_t i = representative[p];
    front[p] = probe.in_front(members[i].facet, sample[i]);
  });

  std::vector<std::int8_t> keep(n, 0);
  for_each_upward(n, [&](std::size_t i) {
    const std::uint32_t facet = members[i].facet;
    int jump = chain.weight[facet];
    if (stacked[i]) {
      const Corners3 t = probe.corners(facet);
      const int dropped = table.dominant_axis(t[0], t[1], t[2]);
      for (std::uint32_t g : x.cut(0, facet)->coplanar_facets) {
        if (!probe.inside_coplanar(dropped, sample[i], g)) continue;
        if (g < facet) return;  // the stack's least facet speaks for it
        const bool alike = table.normal_dot(t, probe.corners(g)) == CGAL::POSITIVE;
        jump += alike ? chain.weight[g] : -chain.weight[g];
      }
    }
    const int w_front = front[patch_of[i]], w_back = w_front + jump;
    const bool in_front = w_front >= threshold, in_back = w_back >= threshold;
    keep[i] = in_back && !in_front ? 1 : in_front && !in_back ? -1 : 0;
  });
  return keep;
}

}  // namespace morphex::detail

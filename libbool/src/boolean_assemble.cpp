// SPDX-License-Identifier: GPL-3.0-or-later
// Step 7: keep the sub-triangles the operation selects, share the points of the two inputs, and
// separate non-manifold features so the result is a closed 2-manifold the next Boolean accepts.
//
// Selection (coplanar patches are kept once, from A, or dropped):
//   | op           | from A'   | from B'            | coplanar same | coplanar opposite |
//   | union        | outside B | outside A          | A's copy      | none              |
//   | intersection | inside B  | inside A           | A's copy      | none              |
//   | A minus B    | outside B | inside A, reversed | none          | A's copy          |
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <numeric>
#include <vector>

#include "boolean_internal.h"
#include "union_find.h"

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

// Angle order of the faces around the directed axis u->v: true when face third vertex `p` comes
// before `q` counter-clockwise, starting from `ref`. Exact orientation predicates only.
struct AroundEdge {
  const Point &u, &v, &ref;
  int half(const Point& w) const {  // 0: angle in [0, pi), 1: [pi, 2 pi)
    const auto s = CGAL::orientation(u, v, ref, w);
    if (s == CGAL::POSITIVE) return 0;
    if (s == CGAL::NEGATIVE) return 1;
    // In the plane of ref: angle 0 when on the same side of the axis as ref, else pi.
    return CGAL::coplanar_orientation(u, v, ref, w) == CGAL::POSITIVE ? 0 : 1;
  }
  bool operator()(const Point& p, const Point& q) const {
    const int hp = half(p), hq = half(q);
    if (hp != hq) return hp < hq;
    return CGAL::orientation(u, v, p, q) == CGAL::POSITIVE;
  }
};

}  // namespace

// Faces are corners of vertices; a corner (face f, slot k) is "attached" to the corner of the
// face across each of its two edges at that vertex. Non-manifold edges first pair their faces by
// the solid wedges between them; then each vertex gets one copy per fan of attached corners.
Mesh separate_non_manifold(const std::vector<Point>& points, std::vector<Triangle>& faces) {
  const std::size_t nf = faces.size();
  // half-edge (f, k) goes faces[f][k] -> faces[f][k+1]; mate[f*3+k] is the opposite half-edge.
  std::vector<std::uint32_t> mate(nf * 3, UINT32_MAX);
  // Half-edges sorted by their undirected edge: each run is one edge of the result.
  std::vector<std::pair<std::uint64_t, std::uint32_t>> half_edges(nf * 3);
  tbb::parallel_for(std::uint32_t(0), std::uint32_t(nf), [&](std::uint32_t f) {
    for (int k = 0; k < 3; ++k) {
      const Edge e = undirected(faces[f][k], faces[f][(k + 1) % 3]);
      half_edges[f * 3 + k] = {edge_key(e.first, e.second), f * 3 + k};
    }
  });
  tbb::parallel_sort(half_edges.begin(), half_edges.end());
  std::vector<std::uint32_t> hs;
  for (std::size_t begin = 0; begin < half_edges.size();) {
    std::size_t end = begin + 1;
    while (end < half_edges.size() && half_edges[end].first == half_edges[begin].first) ++end;
    const Edge edge{PointId(half_edges[begin].first >> 32), PointId(half_edges[begin].first)};
    hs.clear();
    for (std::size_t i = begin; i < end; ++i) hs.push_back(half_edges[i].second);
    begin = end;
    if (hs.size() == 2) {
      mate[hs[0]] = hs[1];
      mate[hs[1]] = hs[0];
      continue;
    }
    // Several solids meet along this edge: sort the faces around u->v and pair each face that
    // runs u->v with the one just before it (the wedge between them is inside the solid).
    const Point& u = points[edge.first];
    const Point& v = points[edge.second];
    auto third = [&](std::uint32_t h) -> const Point& {
      return points[faces[h / 3][(h % 3 + 2) % 3]];
    };
    const AroundEdge order{u, v, third(hs[0])};
    std::sort(hs.begin(), hs.end(),
              [&](std::uint32_t a, std::uint32_t b) { return order(third(a), third(b)); });
    for (std::size_t i = 0; i < hs.size(); ++i) {
      const std::uint32_t h = hs[i];
      if (faces[h / 3][h % 3] != edge.first) continue;  // runs v->u
      const std::uint32_t before = hs[(i + hs.size() - 1) % hs.size()];
      mate[h] = before;
      mate[before] = h;
    }
  }

  // Corner c = f*3+k sits at vertex faces[f][k]. Half-edge (f,k) leaves that corner; its mate
  // (g,l) arrives at the same vertex from face g, whose corner there is (g, l+1).
  UnionFind fans(nf * 3);
  for (std::uint32_t h = 0; h < nf * 3; ++h) {
    if (mate[h] == UINT32_MAX) continue;
    const std::uint32_t g = mate[h] / 3, l = mate[h] % 3;
    fans.join(h, g * 3 + (l + 1) % 3);
  }
  Mesh out;
  std::vector<VertexIndex> vertex_of_fan(nf * 3, UINT32_MAX);  // fan root -> output vertex
  out.triangles.resize(nf);
  for (std::uint32_t c = 0; c < nf * 3; ++c) {
    VertexIndex& v = vertex_of_fan[fans.find(c)];
    if (v == UINT32_MAX) {
      v = VertexIndex(out.points.size());
      out.points.push_back(points[faces[c / 3][c % 3]]);
    }
    out.triangles[c / 3][c % 3] = v;
  }
  return out;
}

Mesh assemble(const Intersection& x, const Refined refined[2], const std::vector<Label> labels[2],
              BooleanOp op, std::vector<FaceOrigin>* provenance) {
  std::vector<Triangle> faces;
  std::vector<FaceOrigin> origin;
  for (int side = 0; side < 2; ++side) {
    const bool reverse = op == BooleanOp::Difference && side == 1;
    for (std::size_t i = 0; i < refined[side].triangles.size(); ++i) {
      if (!keep(op, side, labels[side][i])) continue;
      const SubTriangle& s = refined[side].triangles[i];
      faces.push_back(reverse ? Triangle{s.v[0], s.v[2], s.v[1]}
                              : Triangle{s.v[0], s.v[1], s.v[2]});
      origin.push_back({std::uint8_t(side), s.facet});
    }
  }
  Mesh out = separate_non_manifold(x.points, faces);
  if (provenance) *provenance = std::move(origin);
  return out;
}

}  // namespace morphex::detail

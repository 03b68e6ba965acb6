// SPDX-License-Identifier: GPL-3.0-or-later
// The convex pieces of a reduced convolution: A + B for a solid A and a convex B, from far fewer
// and far thinner pieces than the hulls conv(f + B) of every facet.
//
// Notation. A is bounded by `surface`, facets f with outward normals n_f, edges e, vertices v. B is
// convex with a point c in its interior; S(m) is the face of B maximal in direction m (a vertex, an
// edge or a facet); S(K) is the union of S(m) over a cone K of directions. Then
//
//   A + B = (A + c)  u  U_f  f + conv(c u S(n_f))          prisms when S(n_f) is a vertex, else f +
//   B
//                    u  U_e  e + conv(c u S(cone(n1, n2)))  convex edges whose facets' S differ
//                    u  U_v  v + conv(c u S(cone(n_f)))    vertices whose facets' S differ
//
// Every piece lies in A + B, so only covering needs an argument (docs/morphology-design.md has it
// in full). Let x be in A + B but not in A + c, and t* <= 1 the least t with x in A + c + tB'
// (B' = B - c holds the origin inside). Then K = x - c - t*B' meets A, but its interior does not.
// Where K touches A at a point a of a facet f, K lies on the outer side of f's plane, so
// x - a is in c + t*(S(n_f) - c), inside f's prism. At an edge, if the edge is convex a plane
// separates K from A's wedge, with normal in cone(n1, n2): the edge piece; if it is reflex, K lies
// in the wedge's complement, on the outer side of both facet planes: the prism of either facet. At
// a vertex v, any normal m of a plane supporting K at v has x - v in c + t*(S(m) - c). If no such m
// were in cone(n_f), a direction d strictly inside K's cone would lie strictly below every facet
// plane at v, and such a d is strictly inside A's tangent cone (the link of v winds around d),
// which K's interior cannot meet. Selections of S are therefore supersets: a piece too large is
// harmless, a piece missing is not.
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <vector>

#include "convolution_internal.h"
#include "morphex/internal/union_find.h"
#include "morphex/structuring_element.h"

namespace morphex::detail {
namespace {

using Vector = Kernel::Vector_3;

bool same_direction(const Vector& a, const Vector& b) {
  return CGAL::cross_product(a, b) == CGAL::NULL_VECTOR && CGAL::is_positive(a * b);
}

// A closed convex cone of directions from its generators. `arcs` are the generator pairs spanning
// its facets, each with the cone on its positive side (det(arc.first, arc.second, inside) > 0); a
// cone with two generators has their minor arc. `everything` marks a cone that is not pointed (or
// whose shape was not decided): it is taken as all directions, which only makes pieces larger.
struct DirectionCone {
  std::vector<Vector> generators;
  std::vector<std::pair<int, int>> arcs;
  bool everything = false;
};

DirectionCone make_cone(const std::vector<Vector>& directions) {
  DirectionCone cone;
  for (const Vector& d : directions)
    if (std::none_of(cone.generators.begin(), cone.generators.end(),
                     [&](const Vector& g) { return same_direction(g, d); }))
      cone.generators.push_back(d);
  const auto& g = cone.generators;
  const int k = int(g.size());
  if (k == 2) {
    if (CGAL::cross_product(g[0], g[1]) == CGAL::NULL_VECTOR)
      cone.everything = true;  // opposite directions
    else
      cone.arcs.emplace_back(0, 1);
  } else if (k >= 3) {
    for (int i = 0; i < k; ++i)
      for (int j = 0; j < k; ++j) {
        if (i == j) continue;
        bool facet = true, strict = false;
        for (int l = 0; l < k && facet; ++l) {
          if (l == i || l == j) continue;
          const CGAL::Sign s = CGAL::orientation(g[i], g[j], g[l]);
          facet = s != CGAL::NEGATIVE;
          strict = strict || s == CGAL::POSITIVE;
        }
        if (facet && strict) cone.arcs.emplace_back(i, j);
      }
    // Pointed: the sum of the generators is strictly inside every facet.
    Vector sum = CGAL::NULL_VECTOR;
    for (const Vector& d : g) sum = sum + d;
    cone.everything =
        cone.arcs.size() < 3 ||
        std::any_of(cone.arcs.begin(), cone.arcs.end(), [&](const std::pair<int, int>& a) {
          return CGAL::orientation(g[a.first], g[a.second], sum) != CGAL::POSITIVE;
        });
    if (cone.everything) cone.arcs.clear();
  }
  return cone;
}

bool contains(const DirectionCone& cone, const Vector& d) {
  const auto& g = cone.generators;
  if (cone.everything) return true;
  if (g.size() == 1) return same_direction(g[0], d);
  if (g.size() == 2) {
    const Vector normal = CGAL::cross_product(g[0], g[1]);
    return CGAL::orientation(g[0], g[1], d) == CGAL::ZERO &&
           !CGAL::is_negative(CGAL::cross_product(g[0], d) * normal) &&
           !CGAL::is_negative(CGAL::cross_product(d, g[1]) * normal);
  }
  return std::all_of(cone.arcs.begin(), cone.arcs.end(), [&](const std::pair<int, int>& a) {
    return CGAL::orientation(g[a.first], g[a.second], d) != CGAL::NEGATIVE;
  });
}

// Whether the minor arcs ab and cd cross or touch: exact. Arcs on one great circle answer no
// (where they overlap, an end of one lies inside the other).
bool arcs_cross(const Vector& a, const Vector& b, const Vector& c, const Vector& d) {
  const CGAL::Sign sa = CGAL::orientation(c, d, a), sb = CGAL::orientation(c, d, b);
  if (sa * sb == CGAL::POSITIVE || (sa == CGAL::ZERO && sb == CGAL::ZERO)) return false;
  const CGAL::Sign sc = CGAL::orientation(a, b, c), sd = CGAL::orientation(a, b, d);
  if (sc * sd == CGAL::POSITIVE) return false;
  // The great circles meet at +-x; x, taken on arc ab (a non-negative combination of a and b),
  // must also lie on arc cd.
  const FT alpha = CGAL::determinant(c, d, a), beta = CGAL::determinant(c, d, b);
  const Vector x =
      sa == CGAL::NEGATIVE || sb == CGAL::POSITIVE ? beta * a - alpha * b : alpha * b - beta * a;
  const Vector normal = CGAL::cross_product(c, d);
  return !CGAL::is_negative(CGAL::cross_product(c, x) * normal) &&
         !CGAL::is_negative(CGAL::cross_product(x, d) * normal);
}

// Whether two cones share a direction other than 0: a generator of one inside the other, or two
// facet arcs crossing. Exact, touching included.
bool may_meet(const DirectionCone& p, const DirectionCone& q) {
  if (p.everything || q.everything) return true;
  for (const Vector& d : p.generators)
    if (contains(q, d)) return true;
  for (const Vector& d : q.generators)
    if (contains(p, d)) return true;
  for (const auto& [i, j] : p.arcs)
    for (const auto& [k, l] : q.arcs) {
      if (arcs_cross(p.generators[i], p.generators[j], q.generators[k], q.generators[l]))
        return true;
    }
  return false;
}

// The sign of m . (p - q), in intervals first (no lazy construction), exactly when they cannot
// tell.
CGAL::Sign climb_sign(const Vector& m, const Point& p, const Point& q) {
  {
    CGAL::Protect_FPU_rounding<true> rounding;
    const auto& am = CGAL::approx(m);
    const auto &ap = CGAL::approx(p), &aq = CGAL::approx(q);
    const auto dot =
        am.x() * (ap.x() - aq.x()) + am.y() * (ap.y() - aq.y()) + am.z() * (ap.z() - aq.z());
    const CGAL::Uncertain<CGAL::Sign> s = CGAL::sign(dot);
    if (CGAL::is_certain(s)) return CGAL::get_certain(s);
  }
  const auto& em = CGAL::exact(m);
  const auto &ep = CGAL::exact(p), &eq = CGAL::exact(q);
  return CGAL::sign(em.x() * (ep.x() - eq.x()) + em.y() * (ep.y() - eq.y()) +
                    em.z() * (ep.z() - eq.z()));
}

// B with its vertex graph and the normal cone at each vertex, for exact support queries.
class ConvexBody {
 public:
  explicit ConvexBody(const Mesh& b) : mesh_(b), neighbours_(b.points.size()) {
    std::vector<std::vector<Vector>> normals(b.points.size());
    for (const Triangle& t : b.triangles) {
      const Vector n =
          CGAL::cross_product(b.points[t[1]] - b.points[t[0]], b.points[t[2]] - b.points[t[0]]);
      for (int i = 0; i < 3; ++i) {
        neighbours_[t[i]].push_back(t[(i + 1) % 3]);
        normals[t[i]].push_back(n);
      }
    }
    cones_.reserve(b.points.size());
    for (const auto& n : normals) cones_.push_back(make_cone(n));
    for (const Point& p : b.points)
      approx_.push_back({CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())});
  }

  std::size_t size() const { return mesh_.points.size(); }
  const Point& point(VertexIndex i) const { return mesh_.points[i]; }

  // S(m), sorted: a local maximum of m over the vertex graph, plateaus walked (a convex polytope
  // has no other local maxima), the start guessed in doubles.
  std::vector<VertexIndex> support(const Vector& m) const {
    const std::array<double, 3> md = {CGAL::to_double(m.x()), CGAL::to_double(m.y()),
                                      CGAL::to_double(m.z())};
    VertexIndex best = 0;
    double best_value = -HUGE_VAL;
    for (VertexIndex i = 0; i < approx_.size(); ++i) {
      const double value = md[0] * approx_[i][0] + md[1] * approx_[i][1] + md[2] * approx_[i][2];
      if (value > best_value) best_value = value, best = i;
    }
    std::vector<VertexIndex> plateau;
    for (;;) {
      plateau.assign(1, best);
      bool climbed = false;
      for (std::size_t k = 0; k < plateau.size() && !climbed; ++k)
        for (VertexIndex w : neighbours_[plateau[k]]) {
          if (std::find(plateau.begin(), plateau.end(), w) != plateau.end()) continue;
          const CGAL::Sign s = climb_sign(m, mesh_.points[w], mesh_.points[plateau[k]]);
          if (s == CGAL::POSITIVE) {
            best = w, climbed = true;
            break;
          }
          if (s == CGAL::ZERO) plateau.push_back(w);
        }
      if (!climbed) break;
    }
    std::sort(plateau.begin(), plateau.end());
    return plateau;
  }

  // S(cone) (a superset, see may_meet), grown from the supports of its generators: S of a
  // connected set of directions is connected in the vertex graph.
  std::vector<VertexIndex> support(const DirectionCone& cone,
                                   const std::vector<VertexIndex>& seeds) const {
    if (cone.everything) {
      std::vector<VertexIndex> all(size());
      for (VertexIndex i = 0; i < all.size(); ++i) all[i] = i;
      return all;
    }
    std::vector<VertexIndex> found = seeds;
    std::sort(found.begin(), found.end());
    found.erase(std::unique(found.begin(), found.end()), found.end());
    for (std::size_t k = 0; k < found.size(); ++k)
      for (VertexIndex w : neighbours_[found[k]])
        if (std::find(found.begin(), found.end(), w) == found.end() && may_meet(cone, cones_[w]))
          found.push_back(w);
    std::sort(found.begin(), found.end());
    return found;
  }

 private:
  const Mesh& mesh_;
  std::vector<std::vector<VertexIndex>> neighbours_;
  std::vector<DirectionCone> cones_;
  std::vector<std::array<double, 3>> approx_;
};

// conv(X + ({c} u S)) for the vertices X of a facet, an edge or a vertex of A (c left out when
// null: S is then all of B, which holds it).
Mesh hull_of_sums(const std::vector<Point>& x, const ConvexBody& b,
                  const std::vector<VertexIndex>& s, const Point* c) {
  std::vector<Point> points;
  points.reserve(x.size() * (s.size() + 1));
  for (const Point& p : x) {
    if (c) points.push_back(sum_point(p, *c));
    for (VertexIndex i : s) points.push_back(sum_point(p, b.point(i)));
  }
  Mesh hull = convex_hull(points);
  make_exact(hull);
  return hull;
}

// v + conv({c} u S) for a vertex v of A: a tetrahedron built directly when S has three vertices
// (the common case: the hull itself without the cost of a hull of exact points), else the hull.
Mesh vertex_piece(const Point& v, const ConvexBody& b, const std::vector<VertexIndex>& s,
                  const Point& c) {
  if (s.size() == 3)
    return tetrahedron({sum_point(v, c), sum_point(v, b.point(s[0])), sum_point(v, b.point(s[1])),
                        sum_point(v, b.point(s[2]))});
  return hull_of_sums({v}, b, s, &c);
}

}  // namespace

bool convex_by_edges(const Mesh& solid) {
  // A connected, closed, embedded surface whose dihedral angles are all at most pi bounds a convex
  // solid: for valid solids this replaces a hull and two volumes by one sign per edge.
  const std::size_t nf = solid.triangles.size();
  const DirectedEdges edges(solid);
  if (nf == 0 || !edges.paired()) return false;
  UnionFind parts(solid.points.size());
  for (const Triangle& t : solid.triangles) {
    parts.join(t[0], t[1]);
    parts.join(t[0], t[2]);
  }
  const std::size_t root = parts.find(solid.triangles[0][0]);
  const auto& p = solid.points;
  for (std::uint32_t f = 0; f < nf; ++f) {
    const Triangle& t = solid.triangles[f];
    if (parts.find(t[0]) != root) return false;
    for (int i = 0; i < 3; ++i) {
      const VertexIndex u = t[i], v = t[(i + 1) % 3], w = t[(i + 2) % 3];
      const VertexIndex x = third_vertex(solid.triangles[edges.facet(v, u)], u, v);
      if (CGAL::orientation(p[u], p[v], p[w], p[x]) == CGAL::POSITIVE) return false;  // reflex
    }
  }
  return true;
}

Point interior_point(const Mesh& convex) {
  const Point origin(CGAL::ORIGIN);
  if (std::all_of(convex.triangles.begin(), convex.triangles.end(), [&](const Triangle& t) {
        return CGAL::orientation(convex.points[t[0]], convex.points[t[1]], convex.points[t[2]],
                                 origin) == CGAL::NEGATIVE;
      }))
    return origin;
  // The vertex centroid of a solid convex polytope is strictly inside it.
  FT x = 0, y = 0, z = 0;
  for (const Point& p : convex.points) x += p.x(), y += p.y(), z += p.z();
  const FT n(int(convex.points.size()));
  return point_from_exact(CGAL::exact(Point(x / n, y / n, z / n)));
}

namespace {

// What the pieces are chosen from: A's facet normals and the supporting vertices of B.
struct Supports {
  std::vector<Vector> normal;
  std::vector<std::vector<VertexIndex>> of_facet;  // S(n_f), sorted
  // Where S(n_f) is an edge or a facet of B (a facet of A parallel to one of B's), the piece is
  // the hull f + conv(c u S(n_f)) (with the facet coplanar with f, see convex_facet_groups), not
  // a prism, and edges and vertices at f get their pieces as anywhere else. (f + B, which holds
  // those pieces, was used before: on an eroded surface, where many facets are parallel to B's,
  // its pieces overlap each other many layers deep.)
  std::vector<std::uint8_t> whole;
};

Supports supports_of(const Mesh& surface, const ConvexBody& body) {
  const std::size_t nf = surface.triangles.size();
  const auto& p = surface.points;
  Supports s;
  s.normal.resize(nf);
  s.of_facet.resize(nf);
  s.whole.resize(nf);
  tbb::parallel_for(std::size_t(0), nf, [&](std::size_t f) {
    const Triangle& t = surface.triangles[f];
    s.normal[f] = CGAL::cross_product(p[t[1]] - p[t[0]], p[t[2]] - p[t[0]]);
    s.of_facet[f] = body.support(s.normal[f]);
    s.whole[f] = s.of_facet[f].size() > 1;
  });
  return s;
}

// The edge pieces: convex edges whose facets' supports differ. Edges whose cone meets two
// vertices of B go to `triangles` (chained into swept triangles), the others are built here.
void edge_pieces(const Mesh& surface, const DirectedEdges& edges, const Supports& s,
                 const ConvexBody& body, const Point& c, std::vector<TriangleEdge>& triangles,
                 std::vector<Mesh>& out) {
  struct Edge {
    VertexIndex u, v;
    DirectionCone cone;
    std::vector<VertexIndex> seeds, support;
  };
  std::vector<Edge> found;
  const auto& p = surface.points;
  for (std::uint32_t f = 0; f < surface.triangles.size(); ++f)
    for (int i = 0; i < 3; ++i) {
      const Triangle& t = surface.triangles[f];
      const VertexIndex u = t[i], v = t[(i + 1) % 3], w = t[(i + 2) % 3];
      if (u > v) continue;  // each edge once
      const std::uint32_t g = edges.facet(v, u);
      if (s.of_facet[f] == s.of_facet[g]) continue;
      const VertexIndex x = third_vertex(surface.triangles[g], u, v);
      if (CGAL::orientation(p[u], p[v], p[w], p[x]) != CGAL::NEGATIVE) continue;  // not convex
      Edge e{u, v, make_cone({s.normal[f], s.normal[g]}), s.of_facet[f], {}};
      e.seeds.insert(e.seeds.end(), s.of_facet[g].begin(), s.of_facet[g].end());
      found.push_back(std::move(e));
    }
  tbb::parallel_for(std::size_t(0), found.size(), [&](std::size_t i) {
    found[i].support = body.support(found[i].cone, found[i].seeds);
  });
  std::vector<std::size_t> hulls;
  for (std::size_t i = 0; i < found.size(); ++i) {
    const auto& support = found[i].support;
    if (support.size() == 2)
      triangles.push_back({found[i].u, found[i].v, support[0], support[1]});
    else
      hulls.push_back(i);
  }
  std::vector<Mesh> built(hulls.size());
  tbb::parallel_for(std::size_t(0), hulls.size(), [&](std::size_t k) {
    const Edge& e = found[hulls[k]];
    built[k] = hull_of_sums({p[e.u], p[e.v]}, body, e.support, &c);
  });
  for (Mesh& m : built) out.push_back(std::move(m));
}

// The vertex pieces: vertices around which the facets' supports differ.
void vertex_pieces(const Mesh& surface, const Supports& s, const ConvexBody& body, const Point& c,
                   std::vector<Mesh>& out) {
  const auto& p = surface.points;
  std::vector<std::vector<std::uint32_t>> facets_at(p.size());
  for (std::uint32_t f = 0; f < surface.triangles.size(); ++f)
    for (VertexIndex v : surface.triangles[f]) facets_at[v].push_back(f);
  std::vector<VertexIndex> corners;
  for (VertexIndex v = 0; v < p.size(); ++v) {
    const auto& around = facets_at[v];
    if (!around.empty() && std::any_of(around.begin(), around.end(), [&](std::uint32_t f) {
          return s.of_facet[f] != s.of_facet[around.front()];
        }))
      corners.push_back(v);
  }
  std::vector<Mesh> built(corners.size());
  tbb::parallel_for(std::size_t(0), corners.size(), [&](std::size_t k) {
    std::vector<Vector> normals;
    std::vector<VertexIndex> seeds;
    for (std::uint32_t f : facets_at[corners[k]]) {
      normals.push_back(s.normal[f]);
      seeds.insert(seeds.end(), s.of_facet[f].begin(), s.of_facet[f].end());
    }
    std::sort(seeds.begin(), seeds.end());
    seeds.erase(std::unique(seeds.begin(), seeds.end()), seeds.end());
    const auto support = body.support(make_cone(normals), seeds);
    // A cone meeting two vertices of B gives the flat hull of three points: no piece.
    if (support.size() > 2) built[k] = vertex_piece(p[corners[k]], body, support, c);
  });
  for (Mesh& m : built)
    if (!m.empty()) out.push_back(std::move(m));
}

}  // namespace

std::optional<std::vector<Mesh>> convolution_pieces(const Mesh& surface, const Mesh& b,
                                                    const Point& c, bool solids,
                                                    std::vector<std::size_t>* unchecked) {
  // Every edge must have exactly two facets, one each way, for edges and vertices to be read.
  const DirectedEdges edges(surface);
  if (!edges.paired()) return std::nullopt;

  // Lazy coordinates are evaluated here, once: CGAL's lazy evaluation of a shared point is not
  // safe from several threads, and the parallel loops below read every point exactly.
  for (const Point& q : surface.points) CGAL::exact(q);
  for (const Point& q : b.points) CGAL::exact(q);
  CGAL::exact(c);
  const ConvexBody body(b);
  const Supports s = supports_of(surface, body);
  const auto& p = surface.points;

  std::vector<Mesh> pieces;
  // Facet pieces: the prisms of each patch with one supporting vertex, glued into sweeps.
  const auto patches = same_support_patches(surface, edges, s.of_facet, s.whole);
  std::vector<std::vector<Mesh>> swept(patches.size());
  tbb::parallel_for(std::size_t(0), patches.size(), [&](std::size_t i) {
    patch_pieces(surface, edges, patches[i], body.point(s.of_facet[patches[i][0]][0]), c, solids,
                 swept[i]);
  });
  for (std::size_t i = 0; i < swept.size(); ++i)
    for (Mesh& m : swept[i]) {
      if (!solids && unchecked && patches[i].size() > 1) unchecked->push_back(pieces.size());
      pieces.push_back(std::move(m));
    }
  // f + conv(c u S(n_f)) where S(n_f) is an edge or a facet of B; coplanar pairs share one piece.
  std::vector<std::vector<VertexIndex>> whole_groups;
  std::vector<std::uint32_t> whole_facet;  // a facet of each group
  for (const FacetGroup& group : convex_facet_groups(surface))
    if (s.whole[group.facets.front()]) {
      whole_groups.push_back(group.vertices);
      whole_facet.push_back(group.facets.front());
    }
  std::vector<Mesh> whole(whole_groups.size());
  tbb::parallel_for(std::size_t(0), whole_groups.size(), [&](std::size_t i) {
    std::vector<Point> corners;
    for (VertexIndex v : whole_groups[i]) corners.push_back(p[v]);
    whole[i] = hull_of_sums(corners, body, s.of_facet[whole_facet[i]], &c);
  });
  for (Mesh& m : whole) pieces.push_back(std::move(m));
  // Edge and vertex pieces.
  std::vector<TriangleEdge> triangle_edges;
  edge_pieces(surface, edges, s, body, c, triangle_edges, pieces);
  triangle_edge_pieces(surface, triangle_edges, b.points, c, pieces);
  vertex_pieces(surface, s, body, c, pieces);
  split_shared_quads_alike(pieces, surface, c);
  return pieces;
}

}  // namespace morphex::detail

// SPDX-License-Identifier: GPL-3.0-or-later
// Minkowski sums as unions of convex pieces (see minkowski.h for the decomposition).
#include "morphex/minkowski.h"
#include "morphex/internal/solid_access.h"
#include "morphex/internal/stopwatch.h"
#include "morphex/internal/valid_operations.h"
#include "morphex/progress.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>
#include <optional>
#include <stdexcept>
#include <vector>

#include "minkowski_internal.h"
#include "morphex/boolean.h"
#include "morphex/check.h"
#include "morphex/convex_hull.h"
#include "morphex/internal/union_find.h"
#include "morphex/shapes.h"
#include "morphex/winding.h"

namespace morphex {
namespace {

// conv(g + B) for a convex planar group g of facets and a convex B.
Mesh facet_sum_convex(const Mesh& surface, const std::vector<VertexIndex>& group, const Mesh& b) {
  std::vector<Point> points;
  points.reserve(group.size() * b.points.size());
  // The sums are evaluated exactly here, once: the hull's many exact fallbacks (its faces often
  // hold four coplanar sums) then read stored values instead of walking construction graphs.
  for (VertexIndex v : group) {
    const auto& offset = CGAL::exact(surface.points[v]);
    for (const Point& q : b.points) {
      const auto& e = CGAL::exact(q);
      points.push_back(
          point_from_exact({e.x() + offset.x(), e.y() + offset.y(), e.z() + offset.z()}));
    }
  }
  Mesh piece = convex_hull(points);
  make_exact(piece);
  return piece;
}

// conv(f + g) for two triangles: the hull of their nine vertex sums (empty when they are coplanar
// and the sum is flat: a flat piece bounds no volume and other pieces cover its surface).
Mesh triangle_pair_sum(const Mesh& surface, const Triangle& f, const Mesh& b, const Triangle& g) {
  std::vector<Point> points;
  points.reserve(9);
  for (VertexIndex v : f)
    for (VertexIndex w : g) {
      const auto &p = CGAL::exact(surface.points[v]), &q = CGAL::exact(b.points[w]);
      points.push_back(point_from_exact({p.x() + q.x(), p.y() + q.y(), p.z() + q.z()}));
    }
  Mesh piece = convex_hull(points);
  make_exact(piece);
  return piece;
}

}  // namespace

namespace detail {

// The surface's facets in convex planar groups: a triangle with its neighbour across one edge
// when the two are coplanar, alike oriented and make a strictly convex quadrilateral, else alone.
// For convex B, (f1 u f2) + B = (f1 + B) u (f2 + B), and the sum of a convex quadrilateral with B
// is convex, so each group is one convex piece: half as many pieces on meshes whose planar faces
// are split in triangles (CAD models, boxes). Greedy in facet order, so the grouping depends only
// on the input.
DirectedEdges::DirectedEdges(const Mesh& mesh) {
  facet_.reserve(3 * mesh.triangles.size());
  for (std::uint32_t f = 0; f < mesh.triangles.size(); ++f)
    for (int i = 0; i < 3; ++i) {
      const Triangle& t = mesh.triangles[f];
      paired_ = facet_.emplace(key(t[i], t[(i + 1) % 3]), f).second && paired_;
    }
  for (const auto& entry : facet_)
    paired_ = paired_ && facet_.count((entry.first << 32) | (entry.first >> 32));
}

std::vector<FacetGroup> convex_facet_groups(const Mesh& surface) {
  const std::size_t nf = surface.triangles.size();
  const DirectedEdges edges(surface);
  const auto& p = surface.points;
  std::vector<std::uint8_t> grouped(nf, 0);
  std::vector<FacetGroup> groups;
  groups.reserve(nf);
  for (std::uint32_t f = 0; f < nf; ++f) {
    if (grouped[f]) continue;
    grouped[f] = 1;
    const Triangle& t = surface.triangles[f];
    FacetGroup group{{f}, {t.begin(), t.end()}};
    for (int i = 0; i < 3; ++i) {
      const VertexIndex u = t[i], v = t[(i + 1) % 3], w = t[(i + 2) % 3];
      const std::uint32_t twin = edges.facet(v, u);
      if (twin == DirectedEdges::kNone || grouped[twin]) continue;
      const VertexIndex x = third_vertex(surface.triangles[twin], u, v);
      // Coplanar, x across uv from w, and u, v across wx from each other: a convex quadrilateral.
      if (CGAL::orientation(p[u], p[v], p[w], p[x]) != CGAL::COPLANAR ||
          CGAL::coplanar_orientation(p[u], p[v], p[w], p[x]) != CGAL::NEGATIVE ||
          // (u on the line wx: a flat angle, and coplanar_orientation's precondition fails)
          CGAL::collinear(p[w], p[x], p[u]) ||
          CGAL::coplanar_orientation(p[w], p[x], p[u], p[v]) != CGAL::NEGATIVE)
        continue;
      grouped[twin] = 1;
      group.vertices.push_back(x);
      group.facets.push_back(twin);
      break;
    }
    groups.push_back(std::move(group));
  }
  return groups;
}

std::vector<Mesh> connected_components(const Mesh& mesh) {
  UnionFind sets(mesh.points.size());
  for (const Triangle& t : mesh.triangles) {
    sets.join(t[0], t[1]);
    sets.join(t[0], t[2]);
  }
  std::vector<std::int64_t> component_of_root(mesh.points.size(), -1);
  std::vector<Mesh> components;
  std::vector<std::vector<std::int64_t>> local;  // per component: global vertex -> local index
  for (const Triangle& t : mesh.triangles) {
    const std::size_t root = sets.find(t[0]);
    if (component_of_root[root] < 0) {
      component_of_root[root] = std::int64_t(components.size());
      components.emplace_back();
      local.emplace_back(mesh.points.size(), -1);
    }
    const std::size_t c = std::size_t(component_of_root[root]);
    Triangle mapped;
    for (int k = 0; k < 3; ++k) {
      std::int64_t& index = local[c][t[k]];
      if (index < 0) {
        index = std::int64_t(components[c].points.size());
        components[c].points.push_back(mesh.points[t[k]]);
      }
      mapped[k] = VertexIndex(index);
    }
    components[c].triangles.push_back(mapped);
  }
  return components;
}

bool convex_contains_origin(const Mesh& convex) {
  for (const Triangle& t : convex.triangles)
    if (CGAL::orientation(convex.points[t[0]], convex.points[t[1]], convex.points[t[2]],
                          Point(CGAL::ORIGIN)) == CGAL::POSITIVE)
      return false;
  return true;
}

std::optional<std::vector<Mesh>> timed_convolution_pieces(const Mesh& surface, const Mesh& b,
                                                          const Point& c, bool solids,
                                                          std::vector<std::size_t>* unchecked,
                                                          MinkowskiStats* stats) {
  const Stopwatch start;
  // The pieces are a small part of a Minkowski sum's time; their union, the rest.
  const ProgressPhase phase(0, 0.15, "Minkowski pieces");
  auto pieces = convolution_pieces(surface, b, c, solids, unchecked);
  if (pieces && stats) {
    stats->seconds_pieces += start.seconds();
    stats->pieces += pieces->size();
    for (const Mesh& piece : *pieces) stats->piece_triangles += piece.triangles.size();
  }
  return pieces;
}

Mesh timed_union(std::vector<Mesh> solids, MinkowskiStats* stats) {
  const Stopwatch start;
  UnionStats union_stats;
  Mesh united = detail::union_of_valid(std::move(solids), &union_stats);
  if (stats) {
    stats->seconds_union += start.seconds();
    stats->binary_unions += union_stats.binary_unions;
  }
  return united;
}

bool small_beside_facets(const Mesh& surface, const Mesh& b, const Point& c) {
  if (surface.triangles.empty()) return true;
  std::vector<double> lengths;
  lengths.reserve(surface.triangles.size());
  for (const Triangle& t : surface.triangles)  // one edge per facet is a fair sample
    lengths.push_back(std::sqrt(
        CGAL::to_double(CGAL::squared_distance(surface.points[t[0]], surface.points[t[1]]))));
  const auto middle = lengths.begin() + std::ptrdiff_t(lengths.size() / 2);
  std::nth_element(lengths.begin(), middle, lengths.end());
  double radius = 0;
  for (const Point& q : b.points)
    radius = std::max(radius, std::sqrt(CGAL::to_double(CGAL::squared_distance(q, c))));
  return radius <= kShallowRatio * *middle;
}

std::optional<Mesh> pieces_arrangement(const Mesh& moved_a, const std::vector<Mesh>& pieces,
                                       bool subtract, double max_pairs_per_triangle,
                                       MinkowskiStats* stats) {
  const Stopwatch start;
  std::size_t points = moved_a.points.size(), triangles = moved_a.triangles.size();
  for (const Mesh& p : pieces) points += p.points.size(), triangles += p.triangles.size();
  Mesh chain;
  chain.points.reserve(points);
  chain.triangles.reserve(triangles);
  chain.points = moved_a.points;
  chain.triangles = moved_a.triangles;
  for (const Mesh& p : pieces) {
    const auto offset = VertexIndex(chain.points.size());
    chain.points.insert(chain.points.end(), p.points.begin(), p.points.end());
    for (const Triangle& t : p.triangles)
      chain.triangles.push_back(subtract ? Triangle{t[0] + offset, t[2] + offset, t[1] + offset}
                                         : Triangle{t[0] + offset, t[1] + offset, t[2] + offset});
  }
  std::optional<Mesh> result = winding_solid_within(max_pairs_per_triangle, chain);
  if (!result) return std::nullopt;
  if (stats) {
    stats->seconds_union += start.seconds();
    ++stats->arrangements;
  }
  return result;
}

std::optional<Mesh> convolution_union(const Mesh& surface, const Mesh& b, const Point& c,
                                      const Mesh& moved_a, bool subtract, PieceRoute route,
                                      MinkowskiStats* stats, double max_pairs_per_triangle) {
  std::optional<std::vector<Mesh>> pieces;
  if (route != PieceRoute::Tree &&
      (route == PieceRoute::Arrangement || small_beside_facets(surface, b, c))) {
    // Pieces for a chain: the patches' sweeps as they are, neither checked nor split.
    std::vector<std::size_t> unchecked;
    pieces = timed_convolution_pieces(surface, b, c, false, &unchecked, stats);
    if (!pieces) return std::nullopt;
    {
      const ProgressPhase phase(0.15, 1, subtract ? "subtracting pieces" : "uniting pieces");
      const double budget = route == PieceRoute::Arrangement ? 0 : max_pairs_per_triangle;
      if (auto result = pieces_arrangement(moved_a, *pieces, subtract, budget, stats))
        return result;
    }
    // Too deep: the tree needs valid solids. A sweep that overlaps itself is replaced by the
    // region its chain winds around at least once, the union of its prisms.
    tbb::parallel_for(std::size_t(0), unchecked.size(), [&](std::size_t k) {
      Mesh& sweep = (*pieces)[unchecked[k]];
      if (!check_mesh(sweep, kValidityOnly).valid_solid()) sweep = winding_solid(sweep);
    });
  } else {
    pieces = timed_convolution_pieces(surface, b, c, true, nullptr, stats);
    if (!pieces) return std::nullopt;
  }
  // The pieces first: A + c spans them all and would be carried through every level.
  Mesh shell;
  {
    const ProgressPhase phase(0.15, 0.85, "uniting pieces");
    shell = timed_union(std::move(*pieces), stats);
  }
  const ProgressPhase phase(0.85, 1, subtract ? "subtracting the shell" : "uniting with the input");
  if (subtract) {
    if (stats) ++stats->binary_unions;
    return detail::boolean_of_valid(moved_a, shell, BooleanOp::Difference).mesh;
  }
  return timed_union({std::move(shell), moved_a}, stats);
}

Mesh sum_with_component(const Mesh& a, const Mesh& b, bool b_convex, MinkowskiStats* stats) {
  if (b_convex && convex_by_edges(a)) {
    std::vector<Point> sums;
    sums.reserve(a.points.size() * b.points.size());
    for (const Point& p : a.points)
      for (const Point& q : b.points) sums.push_back(p + (q - CGAL::ORIGIN));
    Mesh hull = convex_hull(sums);
    make_exact(hull);
    return hull;
  }
  if (b_convex)
    if (const auto z = zonotope_of(b)) return zonotope_morphology(a, *z, false);
  if (b_convex) {
    const Point c = interior_point(b);
    const Mesh moved = c == Point(CGAL::ORIGIN) ? a : translated(a, c - CGAL::ORIGIN);
    if (auto sum = convolution_union(a, b, c, moved, false, PieceRoute::Automatic, stats))
      return std::move(*sum);
  }
  Mesh shell = boundary_sum(a, b, b_convex, stats);
  // A + b0 for a point b0 of B; when B is convex and holds the origin, A itself.
  const bool origin_inside = b_convex && convex_contains_origin(b);
  Mesh moved = origin_inside ? a : translated(a, b.points.front() - CGAL::ORIGIN);
  const Stopwatch start;
  Mesh sum = detail::union_of_valid({std::move(shell), std::move(moved)});
  if (stats) {
    stats->seconds_union += start.seconds();
    ++stats->binary_unions;
  }
  return sum;
}

}  // namespace detail

Mesh boundary_sum(const Mesh& surface, const Mesh& b, bool b_convex, MinkowskiStats* stats,
                  PieceUnion method) {
  const Stopwatch start;
  std::vector<Mesh> pieces, copies;  // convex pieces; translated copies of a non-convex B
  if (b_convex) {
    const std::vector<detail::FacetGroup> groups = detail::convex_facet_groups(surface);
    pieces.resize(groups.size());
    tbb::parallel_for(std::size_t(0), pieces.size(), [&](std::size_t i) {
      pieces[i] = facet_sum_convex(surface, groups[i].vertices, b);
    });
  } else {
    // f + B = (f + dB) u (p_f + B): pairs of triangles, plus B at every vertex of the surface.
    const std::size_t pairs = surface.triangles.size() * b.triangles.size();
    pieces.resize(pairs);
    tbb::parallel_for(std::size_t(0), pairs, [&](std::size_t i) {
      pieces[i] = triangle_pair_sum(surface, surface.triangles[i / b.triangles.size()], b,
                                    b.triangles[i % b.triangles.size()]);
    });
    copies.resize(surface.points.size());
    tbb::parallel_for(std::size_t(0), surface.points.size(), [&](std::size_t v) {
      copies[v] = translated(b, surface.points[v] - CGAL::ORIGIN);
      make_exact(copies[v]);
    });
  }
  const double seconds_pieces = start.seconds();
  std::size_t triangles = 0;
  for (const Mesh& p : pieces) triangles += p.triangles.size();
  for (const Mesh& p : copies) triangles += p.triangles.size();
  const std::size_t count = pieces.size() + copies.size();

  const Stopwatch union_start;
  UnionStats union_stats;
  Mesh shell;
  for (Mesh& c : copies) pieces.push_back(std::move(c));
  if (method == PieceUnion::Arrangement) {
    // Every piece is a valid solid, so the sum of their boundaries is a closed chain whose
    // winding number counts the pieces holding a point: their union is where it is >= 1.
    Mesh chain;
    for (const Mesh& p : pieces) {
      const auto offset = VertexIndex(chain.points.size());
      chain.points.insert(chain.points.end(), p.points.begin(), p.points.end());
      for (const Triangle& t : p.triangles)
        chain.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
    }
    shell = winding_solid(chain);
  } else {
    shell = detail::union_of_valid(std::move(pieces), &union_stats);
  }
  if (stats) {
    stats->pieces += count;
    stats->piece_triangles += triangles;
    stats->binary_unions += union_stats.binary_unions;
    stats->seconds_pieces += seconds_pieces;
    stats->seconds_union += union_start.seconds();
  }
  return shell;
}

Solid minkowski_sum(const Solid& a, const Solid& b, MinkowskiStats* stats) {
  if (a.empty() || b.empty()) return {};
  std::vector<Mesh> sums;
  for (const Mesh& component : detail::connected_components(b))
    sums.push_back(detail::sum_with_component(a, component, is_convex(component), stats));
  return detail::trusted_solid(sums.size() == 1 ? std::move(sums.front())
                                                : detail::union_of_valid(std::move(sums)));
}

}  // namespace morphex

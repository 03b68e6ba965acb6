// SPDX-License-Identifier: GPL-3.0-or-later
// n-ary union of convex solids: the Boolean's phases once over the soup of all pieces.
//   pairs          triangles of different pieces whose boxes overlap (one tree over the soup)
//   segments       detail::intersect on (soup, soup), every point named by exact position
//   retriangulate  one CDT per cut facet with the constraints from every other piece
//   classify       patches (sub-triangles of one piece joined across unconstrained edges), each
//                  labelled by exact orientation tests against the planes of the pieces whose box
//                  holds the patch's representative point
//   assemble       kept patches, non-manifold features separated, coplanar faces merged
#include <tbb/parallel_for.h>

#include <algorithm>
#include <map>
#include <unordered_map>

#include "boolean_internal.h"
#include "filtered.h"
#include "morphex/spatial.h"
#include "point_index.h"

namespace morphex {
namespace {

enum class Containment { Outside, Inside, BoundarySame, BoundaryOpposite };

// Where q lies with respect to the convex solid `piece` (triangles [first, last) of the soup).
// `facet` is the soup triangle q was taken from, to tell a shared face's orientation.
Containment locate(const Mesh& soup, std::uint32_t first, std::uint32_t last, const Point& q,
                   std::uint32_t facet) {
  std::uint32_t on_plane = UINT32_MAX;
  for (std::uint32_t t = first; t < last; ++t) {
    const Triangle& f = soup.triangles[t];
    switch (detail::orient3d(soup.points[f[0]], soup.points[f[1]], soup.points[f[2]], q)) {
      case CGAL::POSITIVE:
        return Containment::Outside;
      case CGAL::ZERO:
        on_plane = t;
        break;
      default:
        break;
    }
  }
  if (on_plane == UINT32_MAX) return Containment::Inside;
  // q is on the piece's boundary, so the patch lies in that face's plane: compare the normals.
  const Triangle& f = soup.triangles[on_plane];
  const Triangle& g = soup.triangles[facet];
  const auto nf = CGAL::cross_product(soup.points[f[1]] - soup.points[f[0]],
                                      soup.points[f[2]] - soup.points[f[0]]);
  const auto ng = CGAL::cross_product(soup.points[g[1]] - soup.points[g[0]],
                                      soup.points[g[2]] - soup.points[g[0]]);
  return CGAL::is_positive(nf * ng) ? Containment::BoundarySame : Containment::BoundaryOpposite;
}

// Segments left on one facet by two other pieces may cross: the crossing is a point where three
// surfaces meet. It is constructed exactly from the two 3D segments, so every facet through it
// finds the same point and, through its exact position, the same point id; both segments are split
// there.
void split_crossing_segments(detail::Intersection& x) {
  detail::PointTable& table = x.points;
  detail::PositionIndex positions;
  for (const auto& [facet, cut] : x.cuts[0])
    for (const detail::CutPoint& p : cut.points) positions.find_or_insert(table.point(p.id), p.id);
  auto id_of = [&](const Point& p) {
    const detail::PointId next = detail::PointId(table.size());
    const detail::PointId id = positions.find_or_insert(p, next);
    if (id == next) {
      table.add_explicit(p);
      ++x.constructed_points;
    }
    return id;
  };
  for (auto& [facet, cut] : x.cuts[0]) {
    auto& segments = cut.segments;
    std::sort(segments.begin(), segments.end());
    segments.erase(std::unique(segments.begin(), segments.end()), segments.end());
    if (segments.size() < 2) continue;
    std::vector<CGAL::Bbox_3> boxes;
    for (const auto& [a, b] : segments)
      boxes.push_back(table.point(a).bbox() + table.point(b).bbox());
    std::vector<std::vector<detail::PointId>> splits(segments.size());
    for (std::size_t i = 0; i < segments.size(); ++i)
      for (std::size_t j = i + 1; j < segments.size(); ++j) {
        const auto [a, b] = segments[i];
        const auto [c, d] = segments[j];
        if (a == c || a == d || b == c || b == d || !CGAL::do_overlap(boxes[i], boxes[j])) continue;
        const Kernel::Segment_3 s(table.point(a), table.point(b)),
            t(table.point(c), table.point(d));
        if (!CGAL::do_intersect(s, t)) continue;
        const auto result = CGAL::intersection(s, t);
        const Point* p = result ? boost::get<Point>(&*result) : nullptr;
        if (!p) continue;  // collinear overlap: the CDT splits it at the existing vertices
        const detail::PointId id = id_of(point_from_exact(CGAL::exact(*p)));
        if (id != a && id != b) splits[i].push_back(id);
        if (id != c && id != d) splits[j].push_back(id);
        cut.points.push_back({id, 0});
      }
    std::vector<detail::Edge> out;
    for (std::size_t i = 0; i < segments.size(); ++i) {
      auto [a, b] = segments[i];
      auto& inner = splits[i];
      if (inner.empty()) {
        out.push_back(segments[i]);
        continue;
      }
      const Point pa = table.point(a);
      std::sort(inner.begin(), inner.end(), [&](detail::PointId u, detail::PointId v) {
        return CGAL::compare_distance_to_point(pa, table.point(u), table.point(v)) == CGAL::SMALLER;
      });
      inner.erase(std::unique(inner.begin(), inner.end()), inner.end());
      detail::PointId from = a;
      for (detail::PointId m : inner) {
        out.push_back(detail::undirected(from, m));
        from = m;
      }
      out.push_back(detail::undirected(from, b));
    }
    segments = std::move(out);
  }
  x.flags.resize(table.size(), detail::kOnSurface);
}

}  // namespace

Mesh compute_union_of_convex(std::vector<Mesh> convex_solids, UnionStats* stats) {
  // The soup: all pieces side by side; piece k owns triangles [first[k], first[k+1]).
  Mesh soup;
  std::vector<std::uint32_t> first{0};
  std::vector<std::uint32_t> piece_of;
  for (Mesh& m : convex_solids) {
    if (m.empty()) continue;
    const auto offset = VertexIndex(soup.points.size());
    soup.points.insert(soup.points.end(), m.points.begin(), m.points.end());
    for (const Triangle& t : m.triangles) {
      soup.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
      piece_of.push_back(std::uint32_t(first.size() - 1));
    }
    first.push_back(std::uint32_t(soup.triangles.size()));
  }
  const std::size_t pieces = first.size() - 1;
  if (pieces <= 1) return soup;

  // Pairs of triangles from different pieces whose boxes overlap, each once (t < u).
  const TriangleTree tree(soup);
  std::vector<std::vector<std::pair<std::uint32_t, std::uint32_t>>> per_triangle(
      soup.triangles.size());
  tbb::parallel_for(std::uint32_t(0), std::uint32_t(soup.triangles.size()), [&](std::uint32_t t) {
    tree.for_each_overlap(tree.box(t), [&](std::uint32_t u) {
      if (u > t && piece_of[u] != piece_of[t]) per_triangle[t].emplace_back(t, u);
    });
  });
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
  for (auto& list : per_triangle) pairs.insert(pairs.end(), list.begin(), list.end());
  per_triangle = {};

  // Segments: the soup against itself. A facet's cuts from both roles are merged into one.
  detail::IntersectOptions soup_options;
  soup_options.soup = true;
  detail::Intersection x = detail::intersect(soup, soup, pairs, soup_options);
  {
    std::vector<std::pair<std::uint32_t, detail::FacetCut>> merged;
    std::size_t i = 0, j = 0;
    auto& first = x.cuts[0];
    auto& second = x.cuts[1];
    while (i < first.size() || j < second.size()) {
      if (j == second.size() || (i < first.size() && first[i].first < second[j].first)) {
        merged.push_back(std::move(first[i++]));
      } else if (i == first.size() || second[j].first < first[i].first) {
        merged.push_back(std::move(second[j++]));
      } else {
        detail::FacetCut& into = first[i].second;
        const detail::FacetCut& cut = second[j++].second;
        into.points.insert(into.points.end(), cut.points.begin(), cut.points.end());
        into.segments.insert(into.segments.end(), cut.segments.begin(), cut.segments.end());
        merged.push_back(std::move(first[i++]));
      }
    }
    x.cuts[0] = std::move(merged);
    x.cuts[1].clear();
  }
  split_crossing_segments(x);
  const detail::Refined refined = detail::retriangulate(soup, 0, x);

  // Patches of one piece: its uncut facets and sub-triangles joined without crossing a segment.
  const std::size_t nf = soup.num_triangles(), n = refined.triangles.size();
  UnionFind patches = detail::connect_patches(soup, 0, refined, x, &piece_of);
  std::vector<std::uint8_t> cut(nf, 0);
  for (std::uint32_t f : refined.facets) cut[f] = 1;
  // A node and the triangle it stands for: an uncut facet or a sub-triangle.
  struct Member {
    std::uint32_t node, facet;
    std::array<detail::PointId, 3> v;
  };
  std::vector<Member> members;
  for (std::uint32_t f = 0; f < nf; ++f)
    if (!cut[f]) {
      const Triangle& t = soup.triangles[f];
      members.push_back({f, f, {x.vertex_id(0, t[0]), x.vertex_id(0, t[1]), x.vertex_id(0, t[2])}});
    }
  for (std::uint32_t i = 0; i < n; ++i)
    members.push_back({std::uint32_t(nf + i), refined.triangles[i].facet, refined.triangles[i].v});
  std::vector<std::uint32_t> representative;  // one member per patch
  std::vector<std::uint32_t> patch_of(members.size());
  std::unordered_map<std::uint32_t, std::uint32_t> patch_index;
  for (std::uint32_t i = 0; i < members.size(); ++i) {
    const auto [it, inserted] =
        patch_index.emplace(patches.find(members[i].node), std::uint32_t(representative.size()));
    if (inserted) representative.push_back(i);
    patch_of[i] = it->second;
  }

  // Piece boxes, looked up through a tree of "box proxies": one triangle per piece spanning its
  // box (min corner, max corner, max corner), so that TriangleTree's boxes are the piece boxes.
  Mesh proxies;
  for (std::size_t k = 0; k < pieces; ++k) {
    CGAL::Bbox_3 box;
    for (std::uint32_t t = first[k]; t < first[k + 1]; ++t) box += tree.box(t);
    proxies.points.emplace_back(box.xmin(), box.ymin(), box.zmin());
    proxies.points.emplace_back(box.xmax(), box.ymax(), box.zmax());
    const auto v = VertexIndex(2 * k);
    proxies.triangles.push_back({v, v + 1, v + 1});
  }
  const TriangleTree piece_tree(proxies);

  std::vector<std::uint8_t> keep(representative.size(), 1);
  tbb::parallel_for(std::size_t(0), representative.size(), [&](std::size_t p) {
    const Member& s = members[representative[p]];
    const std::uint32_t own = piece_of[s.facet];
    const Point q =
        CGAL::centroid(x.points.point(s.v[0]), x.points.point(s.v[1]), x.points.point(s.v[2]));
    piece_tree.for_each_overlap(q.bbox(), [&](std::uint32_t k) {
      if (!keep[p] || k == own) return;
      switch (locate(soup, first[k], first[k + 1], q, s.facet)) {
        case Containment::Outside:
          break;
        case Containment::BoundarySame:
          if (k < own) keep[p] = 0;  // the lowest piece keeps the shared face
          break;
        default:
          keep[p] = 0;
      }
    });
  });

  std::vector<Triangle> faces;
  std::vector<FaceOrigin> origin;
  for (std::uint32_t i = 0; i < members.size(); ++i)
    if (keep[patch_of[i]]) {
      faces.push_back(members[i].v);
      origin.push_back({0, members[i].facet});
    }
  detail::IdMesh surface = detail::separate_non_manifold(
      x.points, faces, std::vector<std::uint8_t>(x.points.size(), 1), &origin);
  // Each face lies in the plane of its soup facet.
  std::vector<std::array<detail::PointId, 3>> planes;
  std::vector<std::uint32_t> plane_of;
  for (const FaceOrigin& o : origin) {
    const Triangle& t = soup.triangles[o.face];
    plane_of.push_back(std::uint32_t(planes.size()));
    planes.push_back({x.vertex_id(0, t[0]), x.vertex_id(0, t[1]), x.vertex_id(0, t[2])});
  }
  detail::merge_coplanar(x.points, surface, planes, plane_of);
  Mesh out = detail::materialize(x.points, surface);
  make_exact(out);
  if (stats) {
    stats->candidate_pairs += pairs.size();
    stats->patches += representative.size();
  }
  return out;
}

}  // namespace morphex

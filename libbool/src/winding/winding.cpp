// SPDX-License-Identifier: GPL-3.0-or-later
// winding_solid: the chain, the pairs, the driver and the assembly (morphex/winding.h).
#include "morphex/winding.h"
#include "morphex/internal/stopwatch.h"
#include "morphex/progress.h"

#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <chrono>
#include <numeric>
#include <optional>
#include <unordered_map>

#include "exact/point_index.h"
#include "winding/winding_internal.h"

namespace morphex::detail {

Chain prepare_chain(const Mesh& surface, const std::vector<int>& weights,
                    const std::vector<std::uint32_t>* planes, WindingStats& stats) {
  Chain chain;
  stats.input_faces = surface.triangles.size();
  // Distinct positions: one vertex each.
  std::vector<VertexIndex> id(surface.points.size());
  {
    PointIndex index(chain.soup.points);
    index.reserve(surface.points.size());
    for (std::size_t v = 0; v < surface.points.size(); ++v) id[v] = index.id(surface.points[v]);
  }
  stats.merged_vertices = surface.points.size() - chain.soup.points.size();
  // Each triangle by its corners in increasing order and the parity of its orientation: a
  // triangle and its reverse have one key and opposite signs, so their weights cancel.
  struct Keyed {
    std::array<VertexIndex, 3> sorted;
    int weight;
    std::uint32_t face;
  };
  std::vector<Keyed> keyed(surface.triangles.size(), Keyed{{0, 0, 0}, 0, 0});
  std::vector<std::uint8_t> degenerate(surface.triangles.size(), 0);
  const auto& p = chain.soup.points;
  tbb::parallel_for(std::size_t(0), surface.triangles.size(), [&](std::size_t f) {
    const int w = weights.empty() ? 1 : weights[f];
    if (w == 0) return;
    std::array<VertexIndex, 3> t = {id[surface.triangles[f][0]], id[surface.triangles[f][1]],
                                    id[surface.triangles[f][2]]};
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2] ||
        CGAL::collinear(p[t[0]], p[t[1]], p[t[2]])) {
      degenerate[f] = 1;
      return;
    }
    std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
    keyed[f] = t[1] < t[2] ? Keyed{t, w, std::uint32_t(f)}
                           : Keyed{{t[0], t[2], t[1]}, -w, std::uint32_t(f)};
  });
  stats.degenerate_faces = std::size_t(std::count(degenerate.begin(), degenerate.end(), 1));
  keyed.erase(
      std::remove_if(keyed.begin(), keyed.end(), [](const Keyed& k) { return k.weight == 0; }),
      keyed.end());
  const std::size_t kept = keyed.size();
  tbb::parallel_sort(keyed.begin(), keyed.end(),
                     [](const Keyed& a, const Keyed& b) { return a.sorted < b.sorted; });
  chain.face_of.assign(surface.triangles.size(), Chain::kNoFace);
  for (std::size_t i = 0; i < keyed.size();) {
    std::size_t j = i;
    int sum = 0;
    for (; j < keyed.size() && keyed[j].sorted == keyed[i].sorted; ++j) sum += keyed[j].weight;
    if (sum != 0) {
      for (std::size_t k = i; k < j; ++k)
        chain.face_of[keyed[k].face] = std::uint32_t(chain.soup.triangles.size());
      chain.plane.push_back(planes ? (*planes)[keyed[i].face]
                                   : std::uint32_t(chain.soup.triangles.size()));
      const auto& t = keyed[i].sorted;
      chain.soup.triangles.push_back(sum > 0 ? Triangle{t[0], t[1], t[2]}
                                             : Triangle{t[0], t[2], t[1]});
      chain.weight.push_back(std::abs(sum));
    }
    i = j;
  }
  stats.cancelled_faces = kept - chain.soup.triangles.size();
  return chain;
}

Pairs self_pairs(const TriangleTree& tree, const TriangleTree::TriangleKeys* keys) {
  std::vector<Pairs> per_task(tree.self_pair_tasks());
  tree.for_each_self_pair([&](std::size_t task, std::uint32_t i,
                              std::uint32_t j) { per_task[task].emplace_back(i, j); },
                          keys);
  Pairs pairs;
  std::size_t total = 0;
  for (const Pairs& p : per_task) total += p.size();
  pairs.reserve(total);
  for (const Pairs& p : per_task) pairs.insert(pairs.end(), p.begin(), p.end());
  return pairs;
}

TriangleTree::TriangleKeys group_keys(const Chain& chain,
                                      const std::vector<std::uint32_t>& groups) {
  // A soup triangle keeps its input triangles' group when they all have the same one.
  constexpr std::uint32_t kNone = TriangleTree::kNoKey;
  TriangleTree::TriangleKeys keys(chain.soup.triangles.size(), {kNone, kNone, kNone});
  std::vector<std::uint8_t> seen(chain.soup.triangles.size(), 0);
  for (std::size_t f = 0; f < chain.face_of.size(); ++f) {
    const std::uint32_t s = chain.face_of[f];
    if (s == Chain::kNoFace) continue;
    if (!seen[s]) {
      seen[s] = 1;
      keys[s][0] = groups[f];
    } else if (keys[s][0] != groups[f]) {
      keys[s][0] = kNone;
    }
  }
  return keys;
}

Pairs known_pairs(const Chain& chain,
                  const std::vector<std::pair<std::uint32_t, std::uint32_t>>& of_input) {
  Pairs pairs;
  pairs.reserve(of_input.size());
  for (const auto& [i, j] : of_input) {
    if (i >= chain.face_of.size() || j >= chain.face_of.size())
      throw InputError("", "winding_solid: a listed pair names a triangle that is not there");
    const std::uint32_t a = chain.face_of[i], b = chain.face_of[j];
    if (a != Chain::kNoFace && b != Chain::kNoFace && a != b)
      pairs.emplace_back(std::min(a, b), std::max(a, b));
  }
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  return pairs;
}

std::vector<Member> members_of(const Mesh& soup, const Refined& refined, const Intersection& x) {
  std::vector<Member> members;
  members.reserve(soup.triangles.size() + refined.triangles.size());
  std::size_t cut = 0;
  for (std::uint32_t f = 0; f < soup.triangles.size(); ++f) {
    if (cut < refined.facets.size() && refined.facets[cut] == f) {
      ++cut;
      continue;
    }
    const Triangle& t = soup.triangles[f];
    members.push_back({{x.vertex_id(0, t[0]), x.vertex_id(0, t[1]), x.vertex_id(0, t[2])}, f});
  }
  for (const SubTriangle& s : refined.triangles) members.push_back({s.v, s.facet});
  return members;
}

namespace {

// The kept members as a closed surface: non-manifold features separated, coplanar faces merged.
// `labels` receives each face's plane label.
Mesh assemble_kept(const Chain& chain, Intersection& x, const std::vector<Member>& members,
                   const std::vector<std::int8_t>& keep, bool merge,
                   std::vector<std::uint32_t>* labels) {
  // Planes: one per label and orientation, from the first facet with the label; a face's
  // orientation is its facet's against that one, turned when the face is reversed.
  const std::size_t nf = chain.soup.triangles.size();
  auto corners = [&](std::uint32_t f) {
    const Triangle& t = chain.soup.triangles[f];
    return std::array<PointId, 3>{x.vertex_id(0, t[0]), x.vertex_id(0, t[1]), x.vertex_id(0, t[2])};
  };
  std::unordered_map<std::uint32_t, std::uint32_t> label_index;  // label -> its slot
  std::vector<std::uint32_t> first_facet;                        // per slot
  std::vector<std::uint32_t> slot_of(nf);
  for (std::uint32_t f = 0; f < nf; ++f) {
    const auto [it, added] = label_index.emplace(chain.plane[f], std::uint32_t(first_facet.size()));
    if (added) first_facet.push_back(f);
    slot_of[f] = it->second;
  }
  std::vector<std::uint8_t> turned(nf, 0);  // against its label's first facet
  for_each_upward(nf, [&](std::size_t f) {
    const std::uint32_t first = first_facet[slot_of[f]];
    if (first != f)
      turned[f] = x.points.normal_dot(corners(first), corners(std::uint32_t(f))) == CGAL::NEGATIVE;
  });
  std::vector<Triangle> faces;
  std::vector<FaceOrigin> origin;  // `mesh`: the face's plane is its label's turned over
  for (std::size_t i = 0; i < members.size(); ++i) {
    if (keep[i] == 0) continue;
    const auto& v = members[i].v;
    faces.push_back(keep[i] > 0 ? Triangle{v[0], v[1], v[2]} : Triangle{v[0], v[2], v[1]});
    origin.push_back(
        {std::uint8_t((keep[i] < 0) != bool(turned[members[i].facet])), members[i].facet});
  }
  if (faces.empty()) return {};
  // Any point of a soup may be where the result is not a 2-manifold.
  IdMesh surface = separate_non_manifold(x.points, faces,
                                         std::vector<std::uint8_t>(x.points.size(), 1), &origin);
  std::vector<std::array<PointId, 3>> planes(2 * first_facet.size());
  for (std::size_t k = 0; k < first_facet.size(); ++k) {
    planes[2 * k] = planes[2 * k + 1] = corners(first_facet[k]);
    std::swap(planes[2 * k + 1][1], planes[2 * k + 1][2]);
  }
  std::vector<std::uint32_t> plane_of(origin.size());
  for (std::size_t f = 0; f < origin.size(); ++f)
    plane_of[f] = 2 * slot_of[origin[f].face] + origin[f].mesh;
  if (merge) merge_coplanar(x.points, surface, planes, plane_of);
  if (labels) {
    labels->resize(plane_of.size());
    for (std::size_t f = 0; f < plane_of.size(); ++f)
      (*labels)[f] = chain.plane[first_facet[plane_of[f] / 2]];
  }
  return materialize(x.points, surface);
}

}  // namespace
}  // namespace morphex::detail

namespace morphex {

Mesh winding_solid(const Mesh& surface, const std::vector<int>& weights,
                   const WindingOptions& options, WindingStats* stats_out) {
  return *winding_solid_within(0, surface, weights, options, stats_out);
}

std::optional<Mesh> winding_solid_within(double max_pairs_per_triangle, const Mesh& surface,
                                         const std::vector<int>& weights,
                                         const WindingOptions& options, WindingStats* stats_out) {
  using namespace detail;
  if (!weights.empty() && weights.size() != surface.triangles.size())
    throw InputError("", "winding_solid: one weight per triangle expected");
  WindingStats stats;
  Stopwatch clock;
  if (options.planes && options.planes->size() != surface.triangles.size())
    throw InputError("", "winding_solid: one plane label per triangle expected");
  // Each step's share of the bar, about its share of a repair's or a sweep's time.
  ProgressSteps steps;
  steps.next(0.05, "preparing the surface");
  const Chain chain = prepare_chain(surface, weights, options.planes, stats);
  stats.seconds_chain = clock.lap();
  Mesh result;
  if (!chain.soup.triangles.empty()) {
    steps.next(0.15, "pairing triangles");
    const TriangleTree tree(chain.soup);
    if (options.groups && options.groups->size() != surface.triangles.size())
      throw InputError("", "winding_solid: one group per triangle expected");
    std::optional<TriangleTree::TriangleKeys> keys;
    if (options.groups && !options.pairs) keys = group_keys(chain, *options.groups);
    const Pairs pairs = options.pairs ? known_pairs(chain, *options.pairs)
                                      : self_pairs(tree, keys ? &*keys : nullptr);
    stats.candidate_pairs = pairs.size();
    stats.seconds_pairs = clock.lap();
    if (max_pairs_per_triangle > 0 &&
        double(pairs.size()) > max_pairs_per_triangle * double(chain.soup.triangles.size())) {
      if (stats_out) *stats_out = stats;
      return std::nullopt;
    }

    steps.next(0.55, "intersecting");
    IntersectOptions soup;
    soup.soup = true;
    soup.planes = &chain.plane;
    Intersection x = orient_segments(intersect(chain.soup, chain.soup, pairs, soup));
    stats.intersecting_pairs = x.intersecting_pairs;
    stats.triple_points = merge_soup_cuts(chain.soup, x);
    stats.cut_facets = x.cuts[0].size();
    stats.seconds_segments = clock.lap();

    steps.next(0.75, "retriangulating");
    const Refined refined = retriangulate(chain.soup, 0, x);
    const std::vector<Member> members = members_of(chain.soup, refined, x);
    stats.seconds_cuts = clock.lap();

    steps.next(0.9, "winding numbers");
    const std::vector<std::int8_t> keep =
        select_by_winding(chain, tree, members, x, options.threshold, stats);
    stats.seconds_winding = clock.lap();

    steps.next(1, "assembling");
    result = assemble_kept(chain, x, members, keep, options.merge_coplanar, options.result_planes);
    stats.seconds_assembly = clock.lap();
  }
  if (options.result_planes && result.empty()) options.result_planes->clear();
  if (stats_out) *stats_out = stats;
  return result;
}

}  // namespace morphex

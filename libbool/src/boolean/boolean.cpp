// SPDX-License-Identifier: GPL-3.0-or-later
// The Boolean driver: the steps of docs/boolean-design.md in order, each timed (step 1 ran when
// the operands were read: boolean/step1_triangulate.h).
#include "morphex/boolean.h"

#include <tbb/parallel_invoke.h>

#include "boolean/boolean_internal.h"
#include "boolean/segments_internal.h"
#include "morphex/internal/solid_access.h"
#include "morphex/internal/stopwatch.h"
#include "morphex/internal/valid_operations.h"
#include "morphex/progress.h"

namespace morphex {

BooleanOp parse_boolean_op(const std::string& name) {
  if (name == "union") return BooleanOp::Union;
  if (name == "intersection") return BooleanOp::Intersection;
  if (name == "difference") return BooleanOp::Difference;
  throw InputError(
      "", "unknown Boolean operation '" + name + "' (expected union, intersection or difference)");
}

const char* to_string(BooleanOp op) {
  switch (op) {
    case BooleanOp::Union:
      return "union";
    case BooleanOp::Intersection:
      return "intersection";
    case BooleanOp::Difference:
      return "difference";
  }
  return "?";
}

namespace detail {

MeshBoolean boolean_of_valid(const Mesh& a, const Mesh& b, BooleanOp op,
                             const BooleanOptions& options,
                             std::shared_ptr<const TriangleTree> tree_a,
                             std::shared_ptr<const TriangleTree> tree_b) {
  MeshBoolean result;
  Stopwatch clock;
  // The input check's trees, when it built them over whole meshes, serve step 2 and step 6.
  OperandTrees trees;
  trees.adopt(0, std::move(tree_a));
  trees.adopt(1, std::move(tree_b));
  // Each step's share of the bar, roughly its share of a Boolean's time on bench_bool's real
  // pairs, so that the bar moves evenly.
  ProgressSteps step;
  BooleanStats& stats = result.stats;
  step.next(0.1, "pairing triangles");

  // Step 2. The exact point table of both operands (step 3's) comes first: the trees step 2
  // builds box the vertices from its contiguous copy of their intervals.
  PointTable points(a, b);
  trees.use_points(&points);
  // Turned CAD parts are paired along their own axes, where their long thin facets' boxes are
  // tight (box_frame.h).
  if (const auto& xyz = points.input_near_doubles(); !xyz.empty())
    trees.use_frame(choose_box_frame(a, xyz.data(), b, xyz.data() + points.vertex(1, 0)));
  const Pairs pairs = candidate_pairs(a, b, trees);
  stats.candidate_pairs = pairs.size();
  stats.seconds.pairs = clock.lap();
  step.next(0.45, "intersecting");

  // Steps 3 and 4: the segments, then oriented and gathered per facet.
  IntersectOptions intersect_options;
  intersect_options.points = &points;
  Intersection x = orient_segments(intersect(a, b, pairs, intersect_options));
  trees.use_points(&x.points);  // the table moved; step 6 may build the tree step 2 did not
  stats.intersecting_pairs = x.intersecting_pairs;
  stats.intersection_points = x.constructed_points;
  stats.cut_facets_a = x.cuts[0].size();
  stats.cut_facets_b = x.cuts[1].size();
  for (int side = 0; side < 2; ++side)
    for (const auto& [facet, cut] : x.cuts[side]) stats.segments += cut.segments.size();
  stats.seconds.segments = clock.lap();
  step.next(0.7, "retriangulating");

  // Step 5.
  const Refined refined[2] = {retriangulate(a, 0, x), retriangulate(b, 1, x)};
  stats.seconds.retriangulate = clock.lap();
  step.next(0.8, "classifying");

  // Step 6, the two sides at once: a side's patch flood fill is sequential.
  ClassifyCounts counts[2];
  Labels labels[2];
  tbb::parallel_invoke([&] { labels[0] = classify(a, b, 0, refined[0], x, trees, counts[0]); },
                       [&] { labels[1] = classify(b, a, 1, refined[1], x, trees, counts[1]); });
  stats.patches = counts[0].patches + counts[1].patches;
  stats.patches_by_orientation_rule = counts[0].by_orientation_rule + counts[1].by_orientation_rule;
  stats.patches_by_ray_cast = counts[0].by_ray_cast + counts[1].by_ray_cast;
  stats.orientation_conflicts = counts[0].rule_conflicts + counts[1].rule_conflicts;
  stats.seconds.classify = clock.lap();
  step.next(1, "assembling");

  // Step 7.
  result.mesh =
      assemble(a, b, x, refined, labels, op, options.merge_coplanar && !options.provenance,
               options.provenance ? &result.provenance : nullptr);
  if (options.exact_output) make_exact(result.mesh);
  stats.seconds.assemble = clock.lap();
  return result;
}

}  // namespace detail

BooleanResult compute_boolean(const Solid& a, const Solid& b, BooleanOp op,
                              const BooleanOptions& options) {
  detail::MeshBoolean r = detail::boolean_of_valid(
      a.mesh(), b.mesh(), op, options, detail::SolidAccess::tree(a), detail::SolidAccess::tree(b));
  return {detail::trusted_solid(std::move(r.mesh)), r.stats, std::move(r.provenance)};
}

}  // namespace morphex

// SPDX-License-Identifier: GPL-3.0-or-later
// The Boolean driver: validation, then the phases in order, each timed.
#include "morphex/boolean.h"

#include <tbb/parallel_invoke.h>

#include <chrono>
#include <stdexcept>

#include "boolean/boolean_internal.h"
#include "check/check_internal.h"
#include "morphex/check.h"
#include "morphex/progress.h"
#include "morphex/internal/stopwatch.h"

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

BooleanResult compute_boolean(const Mesh& a, const Mesh& b, BooleanOp op,
                              const BooleanOptions& options) {
  BooleanResult result;
  Stopwatch clock;
  // The input check's trees, when it built them over whole meshes, serve step 2 and step 6.
  detail::OperandTrees trees;
  // Each step's share of the bar, roughly its share of a Boolean's time on bench_bool's real
  // pairs, so that the bar moves evenly; the check takes the first part when it runs.
  const double checked = options.validate_inputs ? 0.4 : 0;
  ProgressSteps steps;
  const auto step = [&](double end, const char* name) {
    steps.next(checked + (1 - checked) * end, name);
  };
  steps.next(checked, "checking inputs");
  if (options.validate_inputs) {
    // Both operands at once: each check is parallel inside, but its sequential parts (edge
    // records, patch proofs) leave threads idle that the other check can use.
    MeshReport reports[2];
    std::optional<TriangleTree> checked[2];
    tbb::parallel_invoke(
        [&] { reports[0] = detail::check_mesh_keeping_tree(a, kValidityOnly, checked[0]); },
        [&] { reports[1] = detail::check_mesh_keeping_tree(b, kValidityOnly, checked[1]); });
    for (int side = 0; side < 2; ++side) trees.adopt(side, std::move(checked[side]));
    for (int side = 0; side < 2; ++side) {
      const MeshReport& report = reports[side];
      if (!report.valid_solid()) {
        result.status = side == 0 ? BooleanStatus::InvalidInputA : BooleanStatus::InvalidInputB;
        result.message = std::string(side == 0 ? "first" : "second") +
                         " operand is not a valid solid: " + describe_problems(report);
        return result;
      }
    }
  }
  BooleanStats& stats = result.stats;
  stats.seconds.validate = clock.lap();
  step(0.1, "pairing triangles");

  // The exact point table of both operands (step 3's), first: the trees step 2 builds box the
  // vertices from its contiguous copy of their intervals.
  detail::PointTable points(a, b);
  trees.use_points(&points);
  // Turned CAD parts are paired along their own axes, where their long thin facets' boxes are
  // tight (box_frame.h).
  if (const auto& xyz = points.input_near_doubles(); !xyz.empty())
    trees.use_frame(detail::choose_box_frame(a, xyz.data(), b, xyz.data() + points.vertex(1, 0)));
  const auto pairs = detail::candidate_pairs(a, b, trees);
  stats.candidate_pairs = pairs.size();
  stats.seconds.pairs = clock.lap();
  step(0.45, "intersecting");

  detail::IntersectOptions intersect_options;
  intersect_options.points = &points;
  detail::Intersection x = detail::intersect(a, b, pairs, intersect_options);
  trees.use_points(&x.points);  // the table moved; step 6 may build the tree step 2 did not
  stats.intersecting_pairs = x.intersecting_pairs;
  stats.intersection_points = x.constructed_points;
  stats.cut_facets_a = x.cuts[0].size();
  stats.cut_facets_b = x.cuts[1].size();
  for (int side = 0; side < 2; ++side)
    for (const auto& [facet, cut] : x.cuts[side]) stats.segments += cut.segments.size();
  stats.seconds.segments = clock.lap();
  step(0.7, "retriangulating");

  const detail::Refined refined[2] = {detail::retriangulate(a, 0, x),
                                      detail::retriangulate(b, 1, x)};
  stats.seconds.retriangulate = clock.lap();
  step(0.8, "classifying");

  detail::ClassifyCounts counts[2];
  // The two sides at once: a side's patch flood fill is sequential.
  detail::Labels labels[2];
  tbb::parallel_invoke(
      [&] { labels[0] = detail::classify(a, b, 0, refined[0], x, trees, counts[0]); },
      [&] { labels[1] = detail::classify(b, a, 1, refined[1], x, trees, counts[1]); });
  stats.patches = counts[0].patches + counts[1].patches;
  stats.patches_by_orientation_rule = counts[0].by_orientation_rule + counts[1].by_orientation_rule;
  stats.patches_by_ray_cast = counts[0].by_ray_cast + counts[1].by_ray_cast;
  stats.orientation_conflicts = counts[0].rule_conflicts + counts[1].rule_conflicts;
  stats.seconds.classify = clock.lap();
  step(1, "assembling");

  result.mesh =
      detail::assemble(a, b, x, refined, labels, op, options.merge_coplanar && !options.provenance,
                       options.provenance ? &result.provenance : nullptr);
  if (options.exact_output) make_exact(result.mesh);
  stats.seconds.assemble = clock.lap();
  return result;
}

}  // namespace morphex

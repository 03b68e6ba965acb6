// SPDX-License-Identifier: GPL-3.0-or-later
// libbool's result structs as JSON, the one format the command line, the pipelines' reports, the
// Python module and the web server share. nlohmann's convention: `nlohmann::json j = report;`
// (found by argument-dependent lookup), or to_json(j, report).
//
// Keys are the struct's fields under the names scripts already read (RoundingReport::broken_pairs
// is "resolved_pairs"); numbers the library computes exactly are given twice where readers need
// both, the exact rational as a string and the nearest double. What is not the struct's (a file
// name, the caller's timing) is the caller's to add around the object.
#pragma once

#include <nlohmann/json.hpp>

#include "morphex/boolean.h"
#include "morphex/check.h"
#include "morphex/repair.h"
#include "morphex/rounding.h"
#include "morphex/solidify.h"

namespace morphex {

// valid, faces, vertices, components, border_edges, non_manifold_edges, non_manifold_vertices,
// degenerate_faces, closed, consistently_oriented, outward, self_intersecting,
// self_intersections, first_self_intersection (when one was found), genus, bbox {min, max},
// volume (the nearest double), volume_approx (the same: the name older scripts read) and
// volume_exact (the exact rational, which can run to thousands of digits). Genus and the volumes
// are null for a surface that is not closed (they mean nothing there).
void to_json(nlohmann::json& j, const MeshReport& report);
// candidate_pairs, intersecting_pairs, cut_facets_a, cut_facets_b, intersected_facets (their
// sum), segments, intersection_points, patches, patches_by_orientation_rule, patches_by_ray_cast,
// orientation_conflicts, phases {pairs, segments, retriangulate, classify, assemble} (the operands
// were checked where their Solids were made: `morphex bool` adds that check's time as
// phases.validate).
void to_json(nlohmann::json& j, const BooleanStats& stats);
// binary_unions, disjoint_merges.
void to_json(nlohmann::json& j, const UnionStats& stats);
// changed, reversed, merged_vertices, duplicate_faces, degenerate_faces, cancelled_faces,
// intersecting_pairs, components_in, components_out.
void to_json(nlohmann::json& j, const RepairReport& report);
// method, changed, summary (describe(report)), welded_vertices, dropped_faces, filled_holes,
// turned_parts, intersecting_pairs.
void to_json(nlohmann::json& j, const SolidifyReport& report);
// moved_vertices, rounds, resolved_pairs, flattened_faces, max_displacement, collapsed,
// not_a_solid, phases {round, check, resolve}, and volume_change, relative_volume_change when
// the volume was measured.
void to_json(nlohmann::json& j, const RoundingReport& report);

}  // namespace morphex

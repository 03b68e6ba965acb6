// SPDX-License-Identifier: GPL-3.0-or-later
// libbool's result structs as JSON (morphex/json.h has the keys).
#include "morphex/json.h"

namespace morphex {

void to_json(nlohmann::json& j, const MeshReport& r) {
  j = nlohmann::json::object();
  j["valid"] = r.valid_solid();
  j["faces"] = r.triangles;
  j["vertices"] = r.vertices;
  j["components"] = r.components;
  j["border_edges"] = r.border_edges;
  j["non_manifold_edges"] = r.non_manifold_edges;
  j["non_manifold_vertices"] = r.non_manifold_vertices;
  j["degenerate_faces"] = r.degenerate_faces;
  j["closed"] = r.closed();
  j["consistently_oriented"] = r.consistently_oriented;
  j["outward"] = r.outward;
  j["self_intersecting"] = r.self_intersections > 0;
  j["self_intersections"] = r.self_intersections;
  if (r.first_self_intersection)
    j["first_self_intersection"] = {r.first_self_intersection->first,
                                    r.first_self_intersection->second};
  // Genus and volume mean something for a closed surface only (an open one has genus -1).
  const bool closed = r.closed();
  j["genus"] = closed ? nlohmann::json(r.genus) : nlohmann::json();
  j["bbox"] = {{"min", {r.bbox.xmin(), r.bbox.ymin(), r.bbox.zmin()}},
               {"max", {r.bbox.xmax(), r.bbox.ymax(), r.bbox.zmax()}}};
  j["volume"] = closed ? nlohmann::json(CGAL::to_double(r.volume)) : nlohmann::json();
  j["volume_approx"] = j["volume"];
  j["volume_exact"] = closed ? nlohmann::json(to_rational_string(r.volume)) : nlohmann::json();
}

void to_json(nlohmann::json& j, const BooleanStats& s) {
  j = {{"candidate_pairs", s.candidate_pairs},
       {"intersecting_pairs", s.intersecting_pairs},
       {"cut_facets_a", s.cut_facets_a},
       {"cut_facets_b", s.cut_facets_b},
       {"intersected_facets", s.cut_facets_a + s.cut_facets_b},
       {"segments", s.segments},
       {"intersection_points", s.intersection_points},
       {"patches", s.patches},
       {"patches_by_orientation_rule", s.patches_by_orientation_rule},
       {"patches_by_ray_cast", s.patches_by_ray_cast},
       {"orientation_conflicts", s.orientation_conflicts},
       {"phases",
        {{"pairs", s.seconds.pairs},
         {"segments", s.seconds.segments},
         {"retriangulate", s.seconds.retriangulate},
         {"classify", s.seconds.classify},
         {"assemble", s.seconds.assemble}}}};
}

void to_json(nlohmann::json& j, const UnionStats& s) {
  j = {{"binary_unions", s.binary_unions}, {"disjoint_merges", s.disjoint_merges}};
}

void to_json(nlohmann::json& j, const RepairReport& r) {
  j = {{"changed", r.changed},
       {"reversed", r.reversed},
       {"merged_vertices", r.merged_vertices},
       {"duplicate_faces", r.duplicate_faces},
       {"degenerate_faces", r.degenerate_faces},
       {"cancelled_faces", r.cancelled_faces},
       {"intersecting_pairs", r.intersecting_pairs},
       {"components_in", r.components_in},
       {"components_out", r.components_out}};
}

void to_json(nlohmann::json& j, const SolidifyReport& r) {
  j = {{"method", r.method},
       {"changed", r.changed},
       {"summary", describe(r)},
       {"welded_vertices", r.welded_vertices},
       {"dropped_faces", r.dropped_faces},
       {"filled_holes", r.filled_holes},
       {"turned_parts", r.turned_parts},
       {"intersecting_pairs", r.intersecting_pairs}};
}

void to_json(nlohmann::json& j, const RoundingReport& r) {
  j = {{"moved_vertices", r.moved_vertices},
       {"rounds", r.rounds},
       {"resolved_pairs", r.broken_pairs},
       {"flattened_faces", r.flattened_faces},
       {"max_displacement", r.max_displacement},
       {"collapsed", r.collapsed},
       {"not_a_solid", r.not_a_solid},
       {"phases",
        {{"round", r.seconds_round}, {"check", r.seconds_check}, {"resolve", r.seconds_resolve}}}};
  if (r.volume_measured) {
    j["volume_change"] = r.volume_change;
    j["relative_volume_change"] = r.relative_volume_change;
  }
}

}  // namespace morphex

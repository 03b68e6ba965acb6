// SPDX-License-Identifier: GPL-3.0-or-later
// libmorph's result structs as JSON (morphex/morph_json.h has the keys).
#include "morphex/morph_json.h"

#include "morphex/error.h"

namespace morphex {

void to_json(nlohmann::json& j, const MorphologyStats& s) {
  j = {{"pieces", s.pieces},
       {"binary_unions", s.binary_unions},
       {"arrangements", s.arrangements},
       {"seconds", s.seconds}};
}

void to_json(nlohmann::json& j, const MinkowskiStats& s) {
  j = {{"pieces", s.pieces},
       {"piece_triangles", s.piece_triangles},
       {"binary_unions", s.binary_unions},
       {"arrangements", s.arrangements},
       {"phases", {{"pieces", s.seconds_pieces}, {"union", s.seconds_union}}}};
}

void to_json(nlohmann::json& j, const Descriptors& d) {
  j = {{"scale_length", d.scale_length},
       {"thickness", d.thickness},
       {"filtered_facets", d.facets},
       {"simplified", d.simplified},
       {"open_radii", d.open_radii},
       {"close_radii", d.close_radii},
       {"granulometry", d.granulometry},
       {"pattern_spectrum", d.pattern_spectrum},
       {"anti_granulometry", d.anti_granulometry},
       {"opening_residue", d.opening_residue},
       {"closing_residue", d.closing_residue},
       {"components", d.components},
       {"d2", d.d2},
       {"seconds_morphology", d.seconds_morphology}};
  for (const std::string& kind : descriptor_kinds())
    j["vectors"][kind] = descriptor_vector(d, kind);
}

void from_json(const nlohmann::json& j, Descriptors& d) {
  const auto read = [&](const char* key, auto& field) {
    if (!j.contains(key)) return;
    try {
      j.at(key).get_to(field);
    } catch (const nlohmann::json::exception&) {
      throw InputError(key, "a value of the wrong type: " + j.at(key).dump());
    }
  };
  read("scale_length", d.scale_length);
  read("thickness", d.thickness);
  read("filtered_facets", d.facets);
  read("simplified", d.simplified);
  read("open_radii", d.open_radii);
  read("close_radii", d.close_radii);
  read("granulometry", d.granulometry);
  read("pattern_spectrum", d.pattern_spectrum);
  read("anti_granulometry", d.anti_granulometry);
  read("opening_residue", d.opening_residue);
  read("closing_residue", d.closing_residue);
  read("components", d.components);
  read("d2", d.d2);
  read("seconds_morphology", d.seconds_morphology);
}

}  // namespace morphex

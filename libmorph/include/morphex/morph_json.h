// SPDX-License-Identifier: GPL-3.0-or-later
// libmorph's result structs as JSON (nlohmann's convention, as morphex/json.h for libbool): what
// `morphex describe --json`, the pipelines' reports, the Python module and the web server print.
#pragma once

#include <nlohmann/json.hpp>

#include "morphex/descriptor_settings.h"  // to_json and from_json of DescriptorSettings
#include "morphex/descriptors.h"
#include "morphex/minkowski.h"
#include "morphex/morphology.h"

namespace morphex {

// pieces, binary_unions, arrangements, seconds.
void to_json(nlohmann::json& j, const MorphologyStats& stats);
// pieces, piece_triangles, binary_unions, arrangements, phases {pieces, union}.
void to_json(nlohmann::json& j, const MinkowskiStats& stats);
// scale_length, thickness, filtered_facets, simplified, the curves open_radii, close_radii,
// granulometry, pattern_spectrum, anti_granulometry, opening_residue, closing_residue,
// components, d2, seconds_morphology, and vectors {kind: descriptor_vector(d, kind)} for every
// descriptor_kinds() (what an index stores and compares).
void to_json(nlohmann::json& j, const Descriptors& descriptors);
// The same keys read back (vectors are computed from the rest, so they are not read); keys left
// out keep the defaults. Throws InputError naming a key whose value has the wrong type.
void from_json(const nlohmann::json& j, Descriptors& descriptors);

}  // namespace morphex

// SPDX-License-Identifier: GPL-3.0-or-later
// Conversions shared by validation and execution.
#pragma once

#include <nlohmann/json.hpp>

#include "morphex/descriptors.h"
#include "morphex/shapes.h"
#include "morphex/structuring_element.h"

namespace morphex::pipeline::detail {

// A JSON number, or a string holding one ("1/20"), as an exact number; throws on anything else.
FT exact_number(const nlohmann::json& value);

// The JSON form {"shape": "ball", "r": 0.05, "level": 1} or the text form "ball:r=0.05,level=1".
// Throws StructuringElementError (its key() names the member at fault).
StructuringElement structuring_element(const nlohmann::json& value);

// Rotation about a coordinate axis by an angle in degrees, exactly orthogonal: multiples of 90
// degrees are exact, other angles use the rational half-tangent nearest to a 1e-9 grid.
Transformation rotation(const std::string& axis, const FT& degrees);

}  // namespace morphex::pipeline::detail

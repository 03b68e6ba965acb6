// SPDX-License-Identifier: GPL-3.0-or-later
// The morphology on a mesh libmorph knows to be a valid solid (the descriptor's posed copy and its
// filtered results), without wrapping each in a Solid.
#pragma once

#include "morphex/morphology.h"

namespace morphex::detail {

// apply_morphology's work, without the structuring element's scale check.
Mesh morphology_of_valid(MorphologyOp op, const Mesh& a, const StructuringElement& se,
                         MorphologyStats* stats = nullptr);

}  // namespace morphex::detail

// SPDX-License-Identifier: GPL-3.0-or-later
// Mathematical morphology of solids by a structuring element B, exactly:
//   dilation  A + B
//   erosion   {x : x + B inside A} = (A - b0) minus (dA + (-B))   for B connected, b0 in B
//   opening   dilation(erosion(A)),  closing  erosion(dilation(A))
// An erosion that removes everything gives a valid empty mesh. Results are exact valid solids
// that can feed the next operation directly.
#pragma once

#include <string>

#include "morphex/minkowski.h"
#include "morphex/solid.h"
#include "morphex/structuring_element.h"

namespace morphex {

enum class MorphologyOp { Dilate, Erode, Open, Close };

// "dilate", "erode", "open", "close"; throws InputError otherwise.
MorphologyOp parse_morphology_op(const std::string& name);
const char* to_string(MorphologyOp op);

struct MorphologyStats {
  std::size_t pieces = 0;  // Minkowski pieces united, over every step
  std::size_t binary_unions = 0;
  std::size_t arrangements = 0;  // pieces closed by one winding arrangement (no binary unions)
  double seconds = 0;
};

// The operations on a valid solid (morphex/solid.h), whose result is one again: chains feed each
// result to the next operation without checking it again. Each refuses a structuring element out
// of proportion with `a` (check_structuring_element_scale) before any work.
Solid apply_morphology(MorphologyOp op, const Solid& a, const StructuringElement& se,
                       MorphologyStats* stats = nullptr);
Solid dilation(const Solid& a, const StructuringElement& se, MorphologyStats* stats = nullptr);
Solid erosion(const Solid& a, const StructuringElement& se, MorphologyStats* stats = nullptr);
Solid opening(const Solid& a, const StructuringElement& se, MorphologyStats* stats = nullptr);
Solid closing(const Solid& a, const StructuringElement& se, MorphologyStats* stats = nullptr);

}  // namespace morphex

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
#include "morphex/structuring_element.h"

namespace morphex {

enum class MorphologyOp { Dilate, Erode, Open, Close };

// "dilate", "erode", "open", "close"; throws InputError otherwise.
MorphologyOp parse_morphology_op(const std::string& name);
const char* to_string(MorphologyOp op);

struct MorphologyStats {
  std::size_t pieces = 0;  // Minkowski pieces united, over every step
  std::size_t binary_unions = 0;
  double seconds = 0;
};

// Throw std::invalid_argument if `a` is not a valid solid.
Mesh dilation(const Mesh& a, const StructuringElement& se, MorphologyStats* stats = nullptr);
Mesh erosion(const Mesh& a, const StructuringElement& se, MorphologyStats* stats = nullptr);
// The same for an `a` already known to be a valid solid (the result of an exact morphex operation
// or of a check): the input check, which costs as much as a small operation, is skipped. Chains
// such as the descriptor's granulometry validate once at the start.
Mesh dilation_of_valid(const Mesh& a, const StructuringElement& se,
                       MorphologyStats* stats = nullptr);
Mesh erosion_of_valid(const Mesh& a, const StructuringElement& se,
                      MorphologyStats* stats = nullptr);
Mesh opening_of_valid(const Mesh& a, const StructuringElement& se,
                      MorphologyStats* stats = nullptr);
Mesh closing_of_valid(const Mesh& a, const StructuringElement& se,
                      MorphologyStats* stats = nullptr);
Mesh opening(const Mesh& a, const StructuringElement& se, MorphologyStats* stats = nullptr);
Mesh closing(const Mesh& a, const StructuringElement& se, MorphologyStats* stats = nullptr);
Mesh apply_morphology(MorphologyOp op, const Mesh& a, const StructuringElement& se,
                      MorphologyStats* stats = nullptr);
Mesh apply_morphology_of_valid(MorphologyOp op, const Mesh& a, const StructuringElement& se,
                               MorphologyStats* stats = nullptr);

}  // namespace morphex

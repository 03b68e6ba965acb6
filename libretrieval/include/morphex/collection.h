// SPDX-License-Identifier: GPL-3.0-or-later
// A procedural labelled collection for retrieval tests: shape families built from exact boxes,
// with random proportions, poses (exact rational rotations), scales and positions.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "morphex/mesh.h"

namespace morphex {

struct LabelledMesh {
  std::string name;   // "<family>-<k>", the file stem
  std::string label;  // the family
  Mesh mesh;          // a valid closed solid with exact rational coordinates
};

// Families: bar, ell, tee, plus, frame (genus 1), steps. Deterministic for a seed.
std::vector<std::string> collection_families();
std::vector<LabelledMesh> make_collection(int per_family, std::uint64_t seed,
                                          const std::vector<std::string>& families = {});

// The Princeton .cla text labelling `meshes` by family.
std::string to_cla(const std::vector<LabelledMesh>& meshes);

}  // namespace morphex

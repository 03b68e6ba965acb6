// SPDX-License-Identifier: GPL-3.0-or-later
// Structuring elements (SE): the probe shapes of morphology, as exact closed meshes.
//
// Text form  shape:key=value,...   e.g. "cube:r=1/20", "ball:r=0.05,level=1", "mesh:path=se.off"
// JSON form  {"shape": "ball", "r": 0.05, "level": 1}  (pipelines convert it to the same pairs)
// Numbers are exact: "1/20" is one twentieth, a decimal such as 0.05 is the nearest double.
// Every SE is centred on the origin unless an offset ox, oy, oz is given.
#pragma once

#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "morphex/convex_hull.h"
#include "morphex/mesh.h"

namespace morphex {

struct StructuringElement {
  std::string shape;   // cube, box, octahedron, ball, zonoball, cylinder or mesh
  std::string spec;    // the text form it was made from, normalised (for reports)
  Mesh mesh;           // closed, outward oriented, exact
  bool convex = true;  // decided exactly (the hull has the same volume)
};

using SeParameters = std::vector<std::pair<std::string, std::string>>;  // key, value text

// A bad structuring element (a morphex::InputError, morphex/error.h): what() reads "ball: r:
// expected a positive number, got -1"; key() is the parameter at fault ("shape" for the shape
// itself) and problem() the rest, so callers can point at their own location (a JSON path, an
// option).
class StructuringElementError : public InputError {
 public:
  StructuringElementError(const std::string& shape, std::string key, std::string problem)
      : InputError(shape.empty() ? "" : shape + ": " + key, std::move(problem)),
        key_(std::move(key)) {}
  const std::string& key() const { return key_; }

 private:
  std::string key_;
};

// Builds a structuring element; throws StructuringElementError.
StructuringElement make_structuring_element(const std::string& shape, const SeParameters& params);
// Parses the text form, then make_structuring_element.
StructuringElement parse_structuring_element(const std::string& text);

// Refuses (StructuringElementError, key "size") an element whose size is out of proportion with
// the mesh `a` it is applied to: a side below 1e-12 or an extent above 1e12 times the largest side
// of a's bounding box. Exact arithmetic would carry such sizes, but at a cost that grows with the
// ratio (a ball of radius 1e-300 on a unit cube runs for minutes) and into results no plain
// format can hold (a unit cube dilated by 1e300 rounds to a degenerate one). Nothing for an empty
// `a`. Called by the morphological operations that validate their input.
void check_structuring_element_scale(const StructuringElement& se, const Mesh& a);

// What each shape accepts, for --help, `morphex stages` and error messages.
struct SeParameterInfo {
  std::string key, type, default_value, description;  // default empty when required
};
struct SeShapeInfo {
  std::string shape, description;
  std::vector<SeParameterInfo> parameters;
};
const std::vector<SeShapeInfo>& structuring_element_shapes();
// Their names for messages: "cube, box, ..., cylinder or mesh".
std::string structuring_element_shape_list();

// -B: every point negated (faces re-oriented so that the mesh stays outward).
Mesh reflected(const Mesh& mesh);

}  // namespace morphex

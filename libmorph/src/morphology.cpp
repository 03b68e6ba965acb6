// SPDX-License-Identifier: GPL-3.0-or-later
// Dilation, erosion, opening and closing from Minkowski shells and exact Booleans.
#include "morphex/morphology.h"
#include "morphex/internal/solid_access.h"
#include "morphex/internal/valid_operations.h"
#include "morphology_internal.h"

#include <chrono>
#include <optional>
#include <stdexcept>

#include "minkowski_internal.h"
#include "morphex/boolean.h"
#include "morphex/progress.h"
#include "morphex/shapes.h"

namespace morphex {

MorphologyOp parse_morphology_op(const std::string& name) {
  if (name == "dilate") return MorphologyOp::Dilate;
  if (name == "erode") return MorphologyOp::Erode;
  if (name == "open") return MorphologyOp::Open;
  if (name == "close") return MorphologyOp::Close;
  throw InputError(
      "", "unknown morphological operation '" + name + "' (expected dilate, erode, open or close)");
}

const char* to_string(MorphologyOp op) {
  switch (op) {
    case MorphologyOp::Dilate:
      return "dilate";
    case MorphologyOp::Erode:
      return "erode";
    case MorphologyOp::Open:
      return "open";
    case MorphologyOp::Close:
      return "close";
  }
  return "?";
}

namespace {

// One connected part of the SE with its convexity, decided once per SE.
struct SePart {
  Mesh mesh;
  bool convex;
};

std::vector<SePart> parts_of(const StructuringElement& se) {
  if (se.convex) return {{se.mesh, true}};
  std::vector<SePart> parts;
  for (Mesh& c : detail::connected_components(se.mesh)) {
    const bool convex = is_convex(c);
    parts.push_back({std::move(c), convex});
  }
  return parts;
}

// Both operands are results of exact operations, valid by construction.
Mesh binary(const Mesh& a, const Mesh& b, BooleanOp op) {
  return detail::boolean_of_valid(a, b, op).mesh;
}

Mesh dilate_valid(const Mesh& a, const std::vector<SePart>& parts, MinkowskiStats& stats) {
  if (a.empty()) return {};
  Mesh result;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    const double n = double(parts.size());
    const ProgressPhase phase(i / n, (i + 1) / n);
    Mesh sum = detail::sum_with_component(a, parts[i].mesh, parts[i].convex, &stats);
    result = i == 0 ? std::move(sum) : binary(result, sum, BooleanOp::Union);
  }
  return result;
}

// {x : x + B inside A} for connected B: (A + c) minus the pieces of A's complement dilated by -B
// (its surface is A's, reversed; c strictly inside -B) when B is convex, else (A - b0) minus
// the shell dA + (-B) of the facet-hull formula.
Mesh erode_by_part(const Mesh& a, const SePart& b, MinkowskiStats& stats) {
  if (b.convex)
    if (const auto z = detail::zonotope_of(b.mesh)) return detail::zonotope_morphology(a, *z, true);
  const Mesh minus_b = reflected(b.mesh);
  if (b.convex) {
    const Point c = detail::interior_point(minus_b);
    const Mesh surface = reversed(a);
    const Mesh moved = c == Point(CGAL::ORIGIN) ? a : translated(a, c - CGAL::ORIGIN);
    if (auto eroded = detail::convolution_union(surface, minus_b, c, moved, true,
                                                detail::PieceRoute::Automatic, &stats))
      return std::move(*eroded);
  }
  Mesh shell = boundary_sum(a, minus_b, b.convex, &stats);
  const bool origin_inside = b.convex && detail::convex_contains_origin(b.mesh);
  const Mesh moved = origin_inside ? a : translated(a, CGAL::ORIGIN - b.mesh.points.front());
  ++stats.binary_unions;
  const ProgressPhase phase(0.8, 1, "subtracting the shell");
  return binary(moved, shell, BooleanOp::Difference);
}

// For several components, the intersection of the erosions by each.
Mesh erode_valid(const Mesh& a, const std::vector<SePart>& parts, MinkowskiStats& stats) {
  if (a.empty()) return {};
  Mesh result;
  for (std::size_t i = 0; i < parts.size() && !(i > 0 && result.empty()); ++i) {
    const double n = double(parts.size());
    const ProgressPhase phase(i / n, (i + 1) / n);
    Mesh eroded = erode_by_part(a, parts[i], stats);
    result = i == 0 ? std::move(eroded) : binary(result, eroded, BooleanOp::Intersection);
  }
  return result;
}

// An opening or closing by one zonotope (a box among them): its two halves as one sweep per
// generator each, the plane labels of the first half passed on to the second. Empty optional for
// any other SE.
std::optional<Mesh> zonotope_round_trip(const Mesh& a, const std::vector<SePart>& parts,
                                        bool open) {
  if (parts.size() != 1 || !parts[0].convex) return std::nullopt;
  const auto z = detail::zonotope_of(parts[0].mesh);
  if (!z) return std::nullopt;
  detail::LabelledSolid s;
  {
    const ProgressPhase phase(0, 0.5, open ? "erosion" : "dilation");
    s = detail::zonotope_morphology(detail::labelled(a), *z, open);
  }
  if (s.mesh.empty()) return Mesh{};
  const ProgressPhase phase(0.5, 1, open ? "dilation" : "erosion");
  return detail::zonotope_morphology(std::move(s), *z, !open).mesh;
}

Mesh open_valid(const Mesh& a, const std::vector<SePart>& parts, MinkowskiStats& s) {
  if (auto round_trip = zonotope_round_trip(a, parts, true)) return std::move(*round_trip);
  Mesh eroded;
  {
    const ProgressPhase phase(0, 0.5, "erosion");
    eroded = erode_valid(a, parts, s);
  }
  const ProgressPhase phase(0.5, 1, "dilation");
  return dilate_valid(eroded, parts, s);
}

Mesh close_valid(const Mesh& a, const std::vector<SePart>& parts, MinkowskiStats& s) {
  if (auto round_trip = zonotope_round_trip(a, parts, false)) return std::move(*round_trip);
  Mesh dilated;
  {
    const ProgressPhase phase(0, 0.5, "dilation");
    dilated = dilate_valid(a, parts, s);
  }
  const ProgressPhase phase(0.5, 1, "erosion");
  return erode_valid(dilated, parts, s);
}

Mesh dispatch(MorphologyOp op, const Mesh& a, const std::vector<SePart>& parts, MinkowskiStats& s) {
  switch (op) {
    case MorphologyOp::Dilate:
      return dilate_valid(a, parts, s);
    case MorphologyOp::Erode:
      return erode_valid(a, parts, s);
    case MorphologyOp::Open:
      return open_valid(a, parts, s);
    case MorphologyOp::Close:
      return close_valid(a, parts, s);
  }
  throw std::logic_error("unknown morphological operation");
}

}  // namespace

Mesh detail::morphology_of_valid(MorphologyOp op, const Mesh& a, const StructuringElement& se,
                                 MorphologyStats* stats) {
  const auto start = std::chrono::steady_clock::now();
  MinkowskiStats minkowski;
  Mesh result = dispatch(op, a, parts_of(se), minkowski);
  make_exact(result);  // chains of operations would otherwise grow lazy-evaluation graphs
  if (stats) {
    stats->pieces += minkowski.pieces;
    stats->binary_unions += minkowski.binary_unions;
    stats->arrangements += minkowski.arrangements;
    stats->seconds +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  return result;
}

Solid apply_morphology(MorphologyOp op, const Solid& a, const StructuringElement& se,
                       MorphologyStats* stats) {
  check_structuring_element_scale(se, a);
  return detail::trusted_solid(detail::morphology_of_valid(op, a, se, stats));
}

Solid dilation(const Solid& a, const StructuringElement& se, MorphologyStats* stats) {
  return apply_morphology(MorphologyOp::Dilate, a, se, stats);
}

Solid erosion(const Solid& a, const StructuringElement& se, MorphologyStats* stats) {
  return apply_morphology(MorphologyOp::Erode, a, se, stats);
}

Solid opening(const Solid& a, const StructuringElement& se, MorphologyStats* stats) {
  return apply_morphology(MorphologyOp::Open, a, se, stats);
}

Solid closing(const Solid& a, const StructuringElement& se, MorphologyStats* stats) {
  return apply_morphology(MorphologyOp::Close, a, se, stats);
}

}  // namespace morphex

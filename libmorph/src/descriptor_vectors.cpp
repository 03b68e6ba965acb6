// SPDX-License-Identifier: GPL-3.0-or-later
// Descriptor vectors by kind, and the distances between them.
#include <cmath>
#include <stdexcept>

#include "morphex/descriptors.h"

namespace morphex {
namespace {

// Block weights of the morphology and combined vectors: each block's weight divided by its mean
// L1 spread between two meshes of the SHREC 2007 watertight tuning split (granulometry 0.79,
// anti-granulometry 0.50, opening residue 2.54, closing residue 0.75, components 3.40, T/L 0.096,
// D2 0.26), so that no block drowns the others by its units alone. The weights before that
// division (openings 1 and 1.5, closings 0.5 and 0.5, components 0.2, T/L 0.5, D2 2) were the best
// of the variants tried on that split (README "Retrieval benchmark").
struct Block {
  const std::vector<double> Descriptors::*values;
  double weight;
};
constexpr Block kMorphology[] = {
    {&Descriptors::granulometry, 1.25},   {&Descriptors::anti_granulometry, 1.0},
    {&Descriptors::opening_residue, 0.6}, {&Descriptors::closing_residue, 0.65},
    {&Descriptors::components, 0.06},
};
constexpr double kThicknessWeight = 5.0;  // T / L
constexpr double kD2Weight = 7.5;         // D2 in the combined vector

void append(std::vector<double>& out, const std::vector<double>& v, double weight) {
  for (double x : v) out.push_back(weight * x);
}

std::vector<double> morphology_vector(const Descriptors& d) {
  std::vector<double> out;
  for (const Block& b : kMorphology) append(out, d.*b.values, b.weight);
  out.push_back(kThicknessWeight * d.thickness);
  return out;
}

}  // namespace

std::vector<std::string> descriptor_kinds() {
  return {"combined", "morphology", "granulometry", "pattern_spectrum", "spatial", "d2"};
}

const char* default_descriptor_kind() {
  return "combined";
}

// 1: three cube radii relative to cbrt(volume); 2: per-mesh scales, residue placements, D2 64.
const char* descriptor_version() {
  return "4";
}

std::vector<double> descriptor_vector(const Descriptors& d, const std::string& kind) {
  if (kind == "morphology") return morphology_vector(d);
  if (kind == "combined") {
    std::vector<double> v = morphology_vector(d);
    append(v, d.d2, kD2Weight);
    return v;
  }
  if (kind == "granulometry") {
    std::vector<double> v = d.granulometry;
    v.insert(v.end(), d.anti_granulometry.begin(), d.anti_granulometry.end());
    return v;
  }
  if (kind == "pattern_spectrum") return d.pattern_spectrum;
  if (kind == "spatial") {
    std::vector<double> v = d.opening_residue;
    v.insert(v.end(), d.closing_residue.begin(), d.closing_residue.end());
    return v;
  }
  if (kind == "d2") return d.d2;
  throw InputError("", "unknown descriptor '" + kind +
                           "' (expected combined, morphology, granulometry, pattern_spectrum, "
                           "spatial or d2)");
}

Metric parse_metric(const std::string& name) {
  if (name == "l1") return Metric::L1;
  if (name == "l2") return Metric::L2;
  if (name == "chi2") return Metric::ChiSquare;
  throw InputError("", "unknown metric '" + name + "' (expected l1, l2 or chi2)");
}

const char* to_string(Metric metric) {
  switch (metric) {
    case Metric::L1:
      return "l1";
    case Metric::L2:
      return "l2";
    case Metric::ChiSquare:
      return "chi2";
  }
  return "?";
}

double distance(const std::vector<double>& a, const std::vector<double>& b, Metric metric) {
  if (a.size() != b.size())
    throw InputError("", "descriptors of different lengths: computed with other settings");
  double sum = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const double diff = a[i] - b[i];
    switch (metric) {
      case Metric::L1:
        sum += std::abs(diff);
        break;
      case Metric::L2:
        sum += diff * diff;
        break;
      case Metric::ChiSquare: {
        const double mass = std::abs(a[i]) + std::abs(b[i]);
        if (mass > 0) sum += diff * diff / mass;
        break;
      }
    }
  }
  return metric == Metric::L2 ? std::sqrt(sum) : sum;
}

double l1_distance(const std::vector<double>& a, const std::vector<double>& b) {
  return distance(a, b, Metric::L1);
}

}  // namespace morphex

// SPDX-License-Identifier: GPL-3.0-or-later
// k-nearest-neighbour search over descriptor vectors at collection scale (a million vectors and
// more): the vectors are rows of one contiguous row-major matrix of doubles, scanned in parallel
// blocks with a vectorisable kernel, and the candidates re-ranked with the reference distance
// (morphex/descriptors.h), so that the answer is exactly the one a plain loop over `distance`
// gives, ties broken by row order.
//
// Errors: a vector of another length than the matrix's throws InputError ("computed with other
// settings"), as `distance` does.
#pragma once

#include <cstddef>
#include <limits>
#include <vector>

#include "morphex/descriptors.h"

namespace morphex {

struct Match {
  std::size_t row = 0;
  double distance = 0;
};

class DescriptorMatrix {
 public:
  explicit DescriptorMatrix(std::size_t dims) : dims_(dims) {}
  std::size_t dims() const { return dims_; }
  std::size_t rows() const { return dims_ ? values_.size() / dims_ : 0; }
  void reserve(std::size_t rows) { values_.reserve(rows * dims_); }
  void add(const std::vector<double>& row);
  const double* row(std::size_t i) const { return values_.data() + i * dims_; }

  static constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();
  // The k rows nearest to `query` (all rows but `exclude`), nearest first, ties by row.
  std::vector<Match> nearest(const std::vector<double>& query, std::size_t k, Metric metric,
                             std::size_t exclude = kNone) const;

 private:
  std::size_t dims_;
  std::vector<double> values_;
};

}  // namespace morphex

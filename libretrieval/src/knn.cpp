// SPDX-License-Identifier: GPL-3.0-or-later
// k nearest rows of a descriptor matrix: a parallel scan with a vectorisable kernel keeps the
// best candidates, which are then ranked by the reference distance. The kernel adds the same
// terms as `distance` in another order (four running sums), so its sums differ from the
// reference only by rounding, which the selection bounds: a row left out is provably farther
// than the k-th candidate, or the scan is repeated with more candidates.
#include "morphex/knn.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstring>
#include <limits>
#include <utility>

#include "morphex/error.h"

namespace morphex {
namespace {

template <Metric M>
inline double term(double a, double b) {
  const double diff = a - b;
  if constexpr (M == Metric::L1) return std::abs(diff);
  if constexpr (M == Metric::L2) return diff * diff;
  // `distance` skips a zero mass; then a = b = 0 and 0 / 1 adds nothing either, without a branch
  // (which would keep the compiler from vectorising).
  const double mass = std::abs(a) + std::abs(b);
  return diff * diff / (mass > 0 ? mass : 1.0);
}

// Four lanes of doubles (GCC and Clang vector extensions): lane j sums the terms i = j mod 4, the
// same four running sums on every target.
typedef double Lanes __attribute__((vector_size(32)));
typedef long long LaneBits __attribute__((vector_size(32)));

template <Metric M>
inline Lanes lane_terms(Lanes a, Lanes b) {
  const Lanes diff = a - b;
  const LaneBits sign = {LLONG_MIN, LLONG_MIN, LLONG_MIN, LLONG_MIN};
  if constexpr (M == Metric::L1) return (Lanes)((LaneBits)diff & ~sign);
  if constexpr (M == Metric::L2) return diff * diff;
  const Lanes mass = (Lanes)(((LaneBits)a & ~sign)) + (Lanes)(((LaneBits)b & ~sign));
  const Lanes zero = {0, 0, 0, 0}, one = {1, 1, 1, 1};
  const LaneBits positive = mass > zero;  // all ones where the mass is positive
  return diff * diff / (Lanes)((positive & (LaneBits)mass) | (~positive & (LaneBits)one));
}

// The metric's sums (before L2's square root) of `count` consecutive rows. Cloned for AVX2 where
// the processor has it (chi-square's divisions make it compute bound); L1 and L2 are bound by
// memory bandwidth.
template <Metric M>
inline void block_sums(const double* query, const double* rows, std::size_t count, std::size_t dims,
                       double* out) {
  for (std::size_t r = 0; r < count; ++r) {
    const double* b = rows + r * dims;
    Lanes sums = {0, 0, 0, 0};
    std::size_t i = 0;
    for (; i + 4 <= dims; i += 4) {
      Lanes qa, rb;
      std::memcpy(&qa, query + i, sizeof qa);
      std::memcpy(&rb, b + i, sizeof rb);
      sums += lane_terms<M>(qa, rb);
    }
    double sum = (sums[0] + sums[1]) + (sums[2] + sums[3]);
    for (; i < dims; ++i) sum += term<M>(query[i], b[i]);
    out[r] = sum;
  }
}

// Not under sanitizers: an ifunc resolver runs before their runtime is set up.
#if defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(undefined_behavior_sanitizer)
#define MORPHEX_NO_CLONES
#endif
#endif
#if defined(__x86_64__) && !defined(__SANITIZE_ADDRESS__) && !defined(MORPHEX_NO_CLONES)
#define MORPHEX_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define MORPHEX_CLONES
#endif
MORPHEX_CLONES void sums_l1(const double* q, const double* rows, std::size_t count,
                            std::size_t dims, double* out) {
  block_sums<Metric::L1>(q, rows, count, dims, out);
}
MORPHEX_CLONES void sums_l2(const double* q, const double* rows, std::size_t count,
                            std::size_t dims, double* out) {
  block_sums<Metric::L2>(q, rows, count, dims, out);
}
MORPHEX_CLONES void sums_chi2(const double* q, const double* rows, std::size_t count,
                              std::size_t dims, double* out) {
  block_sums<Metric::ChiSquare>(q, rows, count, dims, out);
}

template <Metric M>
void scan_block(const double* q, const double* rows, std::size_t count, std::size_t dims,
                double* out) {
  if constexpr (M == Metric::L1) sums_l1(q, rows, count, dims, out);
  if constexpr (M == Metric::L2) sums_l2(q, rows, count, dims, out);
  if constexpr (M == Metric::ChiSquare) sums_chi2(q, rows, count, dims, out);
}

// The reference sum: `distance`'s loop, term by term in order.
template <Metric M>
double reference_sum(const double* a, const double* b, std::size_t n) {
  double sum = 0;
  for (std::size_t i = 0; i < n; ++i) sum += term<M>(a[i], b[i]);
  return sum;
}

using Candidate = std::pair<double, std::size_t>;  // (scan sum, row): a max-heap keeps the best

void keep_best(std::vector<Candidate>& heap, Candidate c, std::size_t limit) {
  if (heap.size() < limit) {
    heap.push_back(c);
    std::push_heap(heap.begin(), heap.end());
  } else if (c < heap.front()) {
    std::pop_heap(heap.begin(), heap.end());
    heap.back() = c;
    std::push_heap(heap.begin(), heap.end());
  }
}

template <Metric M>
std::vector<Candidate> scan(const DescriptorMatrix& m, const double* query, std::size_t limit,
                            std::size_t exclude) {
  const std::size_t dims = m.dims();
  return tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, m.rows(), 4096), std::vector<Candidate>(),
      [&](const tbb::blocked_range<std::size_t>& range, std::vector<Candidate> heap) {
        constexpr std::size_t kBlock = 256;
        double sums[kBlock];
        for (std::size_t first = range.begin(); first < range.end(); first += kBlock) {
          const std::size_t count = std::min(kBlock, range.end() - first);
          scan_block<M>(query, m.row(first), count, dims, sums);
          for (std::size_t i = 0; i < count; ++i)
            if (first + i != exclude) keep_best(heap, {sums[i], first + i}, limit);
        }
        return heap;
      },
      [&](std::vector<Candidate> a, const std::vector<Candidate>& b) {
        for (const Candidate& c : b) keep_best(a, c, limit);
        return a;
      });
}

template <Metric M>
std::vector<Match> nearest_by(const DescriptorMatrix& m, const std::vector<double>& query,
                              std::size_t k, std::size_t exclude) {
  const std::size_t rows = m.rows() - (exclude < m.rows() ? 1 : 0);
  k = std::min(k, rows);
  // Sums of the same n nonnegative terms in any two orders differ by a factor within
  // (1 - g) / (1 + g), g = n u / (1 - n u); the margin also covers L2's square root.
  const double u = std::numeric_limits<double>::epsilon() / 2;
  const double g = double(m.dims() + 2) * u / (1 - double(m.dims() + 2) * u);
  const double margin = (1 - g) / (1 + g) * (1 - 4 * u);
  for (std::size_t limit = k + 16;; limit *= 4) {
    const std::vector<Candidate> heap = scan<M>(m, query.data(), std::min(limit, rows), exclude);
    std::vector<std::pair<double, Match>> ranked;  // (reference sum, match)
    double worst_scan = 0;
    for (const auto& [sum, row] : heap) {
      const double exact = reference_sum<M>(query.data(), m.row(row), m.dims());
      ranked.push_back({exact, {row, M == Metric::L2 ? std::sqrt(exact) : exact}});
      worst_scan = std::max(worst_scan, sum);
    }
    std::sort(ranked.begin(), ranked.end(), [](const auto& a, const auto& b) {
      return a.second.distance != b.second.distance ? a.second.distance < b.second.distance
                                                    : a.second.row < b.second.row;
    });
    // Every row not kept has a scan sum >= worst_scan; it is farther than the k-th kept row
    // unless rounding could reorder them: then keep more candidates and scan again.
    const bool all_kept = heap.size() >= rows;
    if (all_kept || k == 0 || worst_scan * margin > ranked[k - 1].first) {
      std::vector<Match> out;
      for (std::size_t i = 0; i < k; ++i) out.push_back(ranked[i].second);
      return out;
    }
  }
}

}  // namespace

void DescriptorMatrix::add(const std::vector<double>& row) {
  if (row.size() != dims_)
    throw InputError("", "descriptors of different lengths: computed with other settings");
  values_.insert(values_.end(), row.begin(), row.end());
}

std::vector<Match> DescriptorMatrix::nearest(const std::vector<double>& query, std::size_t k,
                                             Metric metric, std::size_t exclude) const {
  if (query.size() != dims_)
    throw InputError("", "descriptors of different lengths: computed with other settings");
  if (rows() == 0) return {};
  switch (metric) {
    case Metric::L1:
      return nearest_by<Metric::L1>(*this, query, k, exclude);
    case Metric::L2:
      return nearest_by<Metric::L2>(*this, query, k, exclude);
    case Metric::ChiSquare:
      break;
  }
  return nearest_by<Metric::ChiSquare>(*this, query, k, exclude);
}

}  // namespace morphex

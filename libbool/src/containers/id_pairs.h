// SPDX-License-Identifier: GPL-3.0-or-later
// Pairs of 32-bit ids (candidate pairs, (facet, pair), (point, corner)) sorted in their usual
// order, each compared as one 64-bit number: std::pair's comparison branches on the first ids,
// whose outcome is a coin toss in a sort, and these sorts run over every candidate pair and every
// corner at a point where the surfaces meet.
// Private to libbool.
#pragma once

#include <tbb/parallel_sort.h>

#include <cstdint>
#include <utility>

namespace morphex::detail {

inline std::uint64_t packed(const std::pair<std::uint32_t, std::uint32_t>& p) {
  return (std::uint64_t(p.first) << 32) | p.second;
}

// Sorts [begin, end) of std::pair<std::uint32_t, std::uint32_t> as operator< does, in parallel.
template <class Iterator>
void sort_id_pairs(Iterator begin, Iterator end) {
  tbb::parallel_sort(
      begin, end,
      [](const std::pair<std::uint32_t, std::uint32_t>& l,
         const std::pair<std::uint32_t, std::uint32_t>& r) { return packed(l) < packed(r); });
}

}  // namespace morphex::detail

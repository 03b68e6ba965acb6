// SPDX-License-Identifier: GPL-3.0-or-later
// Parallel passes that write a variable number of outputs per input in input order: each block of
// inputs counts its outputs, the counts become offsets, and each block then writes from its own.
#pragma once

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstddef>
#include <vector>

namespace morphex::detail {

// offsets[b] for the blocks [b * block, min(n, (b + 1) * block)) of [0, n): the sum of
// count(begin, end) over the blocks before b (offsets.back() is the total). The counts run in
// parallel.
template <class Count>
std::vector<std::size_t> block_offsets(std::size_t n, std::size_t block, Count&& count) {
  const std::size_t blocks = (n + block - 1) / block;
  std::vector<std::size_t> offsets(blocks + 1, 0);
  tbb::parallel_for(std::size_t(0), blocks, [&](std::size_t b) {
    offsets[b + 1] = count(b * block, std::min(n, (b + 1) * block));
  });
  for (std::size_t b = 0; b < blocks; ++b) offsets[b + 1] += offsets[b];
  return offsets;
}

}  // namespace morphex::detail

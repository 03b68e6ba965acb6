// SPDX-License-Identifier: GPL-3.0-or-later
// Disjoint sets over 0..n-1 with path halving: components, fans around vertices. Public because
// libmorph's convolution and descriptors group pieces with it too.
#pragma once

#include <cstdint>
#include <numeric>
#include <vector>

namespace morphex {

struct UnionFind {
  std::vector<std::uint32_t> parent;
  explicit UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  std::uint32_t find(std::uint32_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  }
  void join(std::uint32_t a, std::uint32_t b) { parent[find(a)] = find(b); }
  // find without path compression: safe to call from several threads once joins are done.
  std::uint32_t root(std::uint32_t i) const {
    while (parent[i] != i) i = parent[i];
    return i;
  }
};

}  // namespace morphex

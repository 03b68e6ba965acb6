// SPDX-License-Identifier: GPL-3.0-or-later
// Disjoint sets over 0..n-1 with union by rank and path halving: components, fans around vertices.
// Public because libmorph's convolution and descriptors group pieces with it too.
#pragma once

#include <cstdint>
#include <numeric>
#include <utility>
#include <vector>

namespace morphex {

struct UnionFind {
  std::vector<std::uint32_t> parent;
  // An upper bound on the height of each root's tree (union by rank): joins in any order, such as
  // every facet of a mesh to each of its vertices, keep the trees O(log n) deep, and the finds
  // short and in cache, where linking one root under the other as given builds long chains.
  std::vector<std::uint8_t> rank;
  explicit UnionFind(std::size_t n) : parent(n), rank(n, 0) {
    std::iota(parent.begin(), parent.end(), 0);
  }
  std::uint32_t find(std::uint32_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  }
  void join(std::uint32_t a, std::uint32_t b) {
    a = find(a);
    b = find(b);
    if (a == b) return;
    if (rank[a] < rank[b]) std::swap(a, b);
    parent[b] = a;
    rank[a] += rank[a] == rank[b];
  }
  // find without path compression: safe to call from several threads once joins are done.
  std::uint32_t root(std::uint32_t i) const {
    while (parent[i] != i) i = parent[i];
    return i;
  }
};

}  // namespace morphex

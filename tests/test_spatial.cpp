// SPDX-License-Identifier: GPL-3.0-or-later
// The box tree's three traversals (a box query, the self traversal, two trees together) against
// every pair of boxes, at sizes around every power of two: the traversals descend two levels at
// once with four boxes tested together, and a level's last four may be incomplete.
#include <gtest/gtest.h>

#include <algorithm>
#include <mutex>
#include <random>
#include <utility>
#include <vector>

#include "tree/box_tree.h"

using namespace morphex;

namespace {

using Pairs = std::vector<std::pair<std::uint32_t, std::uint32_t>>;

// n boxes in the unit cube, most small (a surface's triangles), a few long (slivers).
std::vector<FloatBox> random_boxes(std::size_t n, std::mt19937& random) {
  std::uniform_real_distribution<float> at(0, 1), small(0, 0.08f), large(0, 0.6f);
  std::vector<FloatBox> boxes(n);
  for (FloatBox& b : boxes) {
    const bool sliver = at(random) < 0.05f;
    for (int k = 0; k < 3; ++k) {
      b.lo[k] = at(random);
      b.hi[k] = b.lo[k] + (sliver ? large(random) : small(random));
    }
  }
  return boxes;
}

std::vector<std::uint32_t> ids_of(std::size_t n) {
  std::vector<std::uint32_t> ids(n);
  for (std::uint32_t i = 0; i < n; ++i) ids[i] = 1000 + i;  // reported ids, not positions
  return ids;
}

}  // namespace

TEST(Spatial, TraversalsFindExactlyTheOverlappingBoxesAtEverySize) {
  std::mt19937 random(41);
  std::size_t self_pairs = 0, cross_pairs = 0, query_hits = 0;

  for (const std::size_t n : {1,  2,  3,  4,   5,   7,   8,   9,   15,  16,   17,   31,   33,
                              63, 64, 65, 127, 129, 255, 257, 511, 513, 1023, 1025, 2047, 4097}) {
    const std::vector<FloatBox> a = random_boxes(n, random), b = random_boxes(n / 3 + 1, random);
    const std::vector<std::uint32_t> ia = ids_of(a.size()), ib = ids_of(b.size());
    const TriangleTree ta(a, ia), tb(b, ib);

    for (int q = 0; q < 16; ++q) {
      FloatBox query;  // up to 0.3 wide: from a few boxes to many
      for (int k = 0; k < 3; ++k) {
        query.lo[k] = std::uniform_real_distribution<float>(0, 1)(random);
        query.hi[k] = query.lo[k] + std::uniform_real_distribution<float>(0, 0.3f)(random);
      }
      std::vector<std::uint32_t> found, expected;
      ta.for_each_overlap(query, [&](std::uint32_t t) { found.push_back(t); });
      for (std::size_t i = 0; i < a.size(); ++i)
        if (a[i].overlaps(query)) expected.push_back(ia[i]);
      // each once
      EXPECT_TRUE(std::adjacent_find(found.begin(), found.end()) == found.end());
      std::sort(found.begin(), found.end());
      ASSERT_EQ(found, expected) << n << " boxes, query " << q;
      query_hits += expected.size();
    }

    Pairs self, self_expected;
    std::mutex lock;
    ta.for_each_self_pair([&](std::size_t, std::uint32_t i, std::uint32_t j) {
      const std::lock_guard<std::mutex> guard(lock);
      self.emplace_back(std::min(i, j), std::max(i, j));
    });
    for (std::size_t i = 0; i < a.size(); ++i)
      for (std::size_t j = i + 1; j < a.size(); ++j)
        if (a[i].overlaps(a[j])) self_expected.emplace_back(ia[i], ia[j]);
    std::sort(self.begin(), self.end());
    ASSERT_EQ(self, self_expected) << n << " boxes";
    self_pairs += self_expected.size();

    for (const bool swapped : {false, true}) {
      Pairs cross = swapped ? TriangleTree::overlapping_pairs(tb, ta)
                            : TriangleTree::overlapping_pairs(ta, tb),
            cross_expected;
      for (std::size_t i = 0; i < a.size(); ++i)
        for (std::size_t j = 0; j < b.size(); ++j)
          if (a[i].overlaps(b[j]))
            cross_expected.push_back(swapped ? std::make_pair(ib[j], ia[i])
                                             : std::make_pair(ia[i], ib[j]));
      std::sort(cross.begin(), cross.end());
      std::sort(cross_expected.begin(), cross_expected.end());
      ASSERT_EQ(cross, cross_expected) << n << " boxes" << (swapped ? ", swapped" : "");
      cross_pairs += cross_expected.size();
    }
  }
  // The cases are not empty ones.
  EXPECT_GT(self_pairs, 10000u);
  EXPECT_GT(cross_pairs, 5000u);
  EXPECT_GT(query_hits, 500u);
}

// Rays (for_each_on_ray, the winding numbers' casts) report every box they certainly cross: the
// slab test on each box shrunk by a margin, against the boxes the traversal reports.
TEST(Spatial, RaysReportEveryBoxTheyCross) {
  std::mt19937 random(47);
  std::uniform_real_distribution<double> at(0, 1), turn(-1, 1);
  std::size_t crossed = 0;
  for (const std::size_t n : {1, 3, 4, 5, 9, 17, 65, 257, 1025, 4097}) {
    const std::vector<FloatBox> boxes = random_boxes(n, random);
    const TriangleTree tree(boxes, ids_of(n));
    for (int r = 0; r < 40; ++r) {
      const std::array<double, 3> o{at(random), at(random), at(random)},
          d{turn(random), turn(random), turn(random)};
      std::vector<std::uint32_t> found;
      tree.for_each_on_ray(CGAL::Bbox_3(o[0], o[1], o[2], o[0], o[1], o[2]), d,
                           [&](std::uint32_t t) { found.push_back(t); });
      std::sort(found.begin(), found.end());
      for (std::size_t i = 0; i < n; ++i) {
        double enter = 0, exit = 1e300;
        for (int k = 0; k < 3; ++k) {
          const double lo = boxes[i].lo[k] + 1e-6, hi = boxes[i].hi[k] - 1e-6;
          if (lo >= hi) enter = 1e300;  // too thin to cross certainly
          const double t0 = (lo - o[k]) / d[k], t1 = (hi - o[k]) / d[k];
          enter = std::max(enter, std::min(t0, t1));
          exit = std::min(exit, std::max(t0, t1));
        }
        if (enter >= exit) continue;
        ++crossed;
        ASSERT_TRUE(std::binary_search(found.begin(), found.end(), 1000 + std::uint32_t(i)))
            << n << " boxes, ray " << r << ", box " << i;
      }
    }
  }
  EXPECT_GT(crossed, 500u);
}

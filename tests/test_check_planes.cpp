// SPDX-License-Identifier: GPL-3.0-or-later
// The check's face planes (check_planes.h): each face's record is written on its first use, by
// whichever thread asks first, into blocks handed out as they fill (one per thread of the arena,
// one shared by threads outside it). Every side they decide, from any thread in any order, is
// the exact orientation's.
#include <gtest/gtest.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <numeric>
#include <random>
#include <thread>
#include <vector>

#include "check/check_planes.h"
#include "exact/point_table.h"
#include "morphex/shapes.h"

using namespace morphex;

namespace {

// The side of each face's plane that a vertex of another face lies on, asked of `planes` for the
// faces in `order` (2: undecided), from every thread at once.
std::vector<std::array<int, 3>> sides(const Mesh& m, const detail::FacePlanes& planes,
                                      const std::vector<std::uint32_t>& order) {
  const std::size_t nf = m.num_triangles();
  std::vector<std::array<int, 3>> out(nf);
  tbb::parallel_for(std::size_t(0), nf, [&](std::size_t i) {
    const std::uint32_t g = order[i], f = std::uint32_t((g * 7 + 1) % nf);
    for (int k = 0; k < 3; ++k) out[g][k] = planes.side(g, m.triangles[f][k]).value_or(2);
  });
  return out;
}

}  // namespace

TEST(FacePlanes, SidesDecidedFromAnyThreadInAnyOrderAreTheExactOnes) {
  // In doubles, and turned by a rational rotation (points known within an error of their
  // doubles): 2,304 faces, nine blocks of records.
  const Mesh torus = make_torus(48, 24, 2.0, 0.7);
  for (const Mesh& m : {torus, transformed(torus, quaternion_rotation(5, 1, 2, 3))}) {
    const detail::PointTable table(m, m, true);
    const std::size_t nf = m.num_triangles();
    std::vector<std::uint32_t> order(nf);
    std::iota(order.begin(), order.end(), 0u);
    std::shuffle(order.begin(), order.end(), std::mt19937(7));
    const detail::FacePlanes planes(m, table.input_near_doubles(), table.input_error());
    ASSERT_FALSE(planes.empty());
    const std::vector<std::array<int, 3>> first = sides(m, planes, order);
    std::size_t decided = 0;
    for (std::uint32_t g = 0; g < nf; ++g) {
      const std::uint32_t f = std::uint32_t((g * 7 + 1) % nf);
      const Triangle& t = m.triangles[g];
      for (int k = 0; k < 3; ++k) {
        if (first[g][k] == 2) continue;
        ++decided;
        const CGAL::Sign exact =
            table.orientation(table.vertex(0, t[0]), table.vertex(0, t[1]), table.vertex(0, t[2]),
                              table.vertex(0, m.triangles[f][k]));
        ASSERT_EQ(first[g][k], int(exact)) << "face " << g << ", corner " << k << " of " << f;
      }
    }
    EXPECT_GT(decided, 2 * nf);  // the doubles decide most sides
    // Asked again (every record read back, none written) and of fresh planes in reverse order.
    EXPECT_EQ(sides(m, planes, order), first);
    std::reverse(order.begin(), order.end());
    const detail::FacePlanes again(m, table.input_near_doubles(), table.input_error());
    EXPECT_EQ(sides(m, again, order), first);
    // From threads outside TBB's arena (they share one cursor, under a lock), two at once.
    const detail::FacePlanes outside(m, table.input_near_doubles(), table.input_error());
    std::vector<std::array<int, 3>> by_threads(nf);
    auto ask = [&](std::size_t from, std::size_t step) {
      for (std::size_t i = from; i < nf; i += step) {
        const std::uint32_t g = order[i], f = std::uint32_t((g * 7 + 1) % nf);
        for (int k = 0; k < 3; ++k)
          by_threads[g][k] = outside.side(g, m.triangles[f][k]).value_or(2);
      }
    };
    std::thread one(ask, 0, 2), two(ask, 1, 2);
    one.join();
    two.join();
    EXPECT_EQ(by_threads, first);
  }
}

// SPDX-License-Identifier: GPL-3.0-or-later
// Progress reports: nested ranges, counters from many threads, and what a Boolean and an opening
// report (monotone shares that end at 1, the phases a user would recognise).
#include <gtest/gtest.h>
#include <tbb/parallel_for.h>

#include <mutex>
#include <thread>

#include "morphex/boolean.h"
#include "morphex/check.h"
#include "morphex/morphology.h"
#include "morphex/progress.h"
#include "morphex/shapes.h"
#include "morphex/solidify.h"
#include "morphex/structuring_element.h"

using namespace morphex;

namespace {

struct Recorded {
  std::mutex mutex;
  std::vector<std::pair<double, std::string>> reports;
  ProgressSink sink() {
    return [this](double share, const std::string& phase) {
      std::lock_guard<std::mutex> lock(mutex);
      reports.emplace_back(share, phase);
    };
  }
  bool monotone() const {
    for (std::size_t i = 1; i < reports.size(); ++i)
      if (reports[i].first < reports[i - 1].first) return false;
    return true;
  }
  bool saw_phase(const std::string& text) const {
    for (const auto& r : reports)
      if (r.second.find(text) != std::string::npos) return true;
    return false;
  }
};

TEST(Progress, NothingHappensWithoutAScope) {
  ProgressPhase phase(0, 0.5, "alone");
  ProgressCounter counter(10);
  counter.add(5);  // must not crash or report anywhere
  SUCCEED();
}

TEST(Progress, NestedPhasesMapIntoTheirCallersRange) {
  Recorded r;
  {
    ProgressScope scope(r.sink());
    ProgressPhase outer(0.5, 1, "dilation");
    {
      ProgressPhase inner(0.5, 1, "uniting pieces");
      ProgressCounter counter(4);
      counter.add(2);
    }
  }
  ASSERT_FALSE(r.reports.empty());
  EXPECT_TRUE(r.monotone());
  // outer starts at 0.5; inner covers [0.75, 1]; half of it is 0.875.
  EXPECT_DOUBLE_EQ(r.reports.front().first, 0.5);
  bool half_of_inner = false;
  for (const auto& [share, phase] : r.reports)
    if (share == 0.875 && phase == "dilation: uniting pieces") half_of_inner = true;
  EXPECT_TRUE(half_of_inner);
  EXPECT_DOUBLE_EQ(r.reports.back().first, 1.0);
}

TEST(Progress, ACounterCountsFromEveryThreadAndMutesItsOwnThread) {
  Recorded r;
  {
    ProgressScope scope(r.sink());
    ProgressCounter counter(1000);
    tbb::parallel_for(0, 1000, [&](int) { counter.add(1); });
    // Work the counter counts reports nothing of its own on this thread.
    ProgressPhase muted(0, 1, "muted");
  }
  EXPECT_TRUE(r.monotone());
  ASSERT_FALSE(r.reports.empty());
  EXPECT_DOUBLE_EQ(r.reports.back().first, 1.0);
  EXPECT_FALSE(r.saw_phase("muted"));
  // Throttled: far fewer calls than units.
  EXPECT_LE(r.reports.size(), 1002u);
}

TEST(Progress, ASinkThatThrowsDoesNotFailTheOperation) {
  ProgressScope scope([](double, const std::string&) { throw std::runtime_error("display"); });
  const BooleanResult result = compute_boolean(
      check_solid(make_cube(1)), check_solid(make_cube(1, Point(1, 1, 1))), BooleanOp::Union);
}

TEST(Progress, ABooleanReportsItsStepsInOrderToTheEnd) {
  Recorded r;
  // The operands are checked where they are made (check_solid reports its own passes).
  const Solid a = check_solid(make_cube(1)),
              b = check_solid(make_cube(1, Point(FT(1) / 2, FT(1) / 3, FT(1) / 5)));
  {
    ProgressScope scope(r.sink());
    const BooleanResult result = compute_boolean(a, b, BooleanOp::Union);
  }
  EXPECT_TRUE(r.monotone());
  ASSERT_FALSE(r.reports.empty());
  EXPECT_DOUBLE_EQ(r.reports.back().first, 1.0);
  for (const char* step :
       {"pairing triangles", "intersecting", "retriangulating", "classifying", "assembling"})
    EXPECT_TRUE(r.saw_phase(step)) << step;
}

TEST(Progress, AnOpeningByAnOctahedronMovesOneBarThroughBothHalves) {
  Recorded r;
  const Solid cube = check_solid(make_cube(1));  // checked where it is made, not by the opening
  {
    ProgressScope scope(r.sink());
    const Mesh opened = opening(cube, parse_structuring_element("octahedron:r=1/4"));
    EXPECT_FALSE(opened.empty());
  }
  EXPECT_TRUE(r.monotone());
  ASSERT_FALSE(r.reports.empty());
  EXPECT_DOUBLE_EQ(r.reports.back().first, 1.0);
  EXPECT_TRUE(r.saw_phase("erosion"));
  EXPECT_TRUE(r.saw_phase("dilation"));
  // Reports while the erosion runs stay in the first half, the dilation's in the second.
  for (const auto& [share, phase] : r.reports) {
    if (phase.rfind("erosion", 0) == 0) EXPECT_LE(share, 0.5 + 1e-12) << phase;
    if (phase.rfind("dilation", 0) == 0) EXPECT_GE(share, 0.5 - 1e-12) << phase;
  }
}

TEST(Progress, SolidifyReportsTheCheckAndTheRepairsSteps) {
  // Two overlapping cubes in one mesh: a closed chain that crosses itself, which the repair
  // resolves by its winding arrangement.
  Mesh two = make_cube(1);
  const Mesh other = make_cube(1, Point(FT(1) / 2, FT(1) / 3, FT(1) / 5));
  const auto offset = VertexIndex(two.points.size());
  two.points.insert(two.points.end(), other.points.begin(), other.points.end());
  for (const Triangle& t : other.triangles)
    two.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
  Recorded r;
  {
    ProgressScope scope(r.sink());
    EXPECT_TRUE(solidify(two).report.changed);
  }
  EXPECT_TRUE(r.monotone());
  ASSERT_FALSE(r.reports.empty());
  EXPECT_DOUBLE_EQ(r.reports.back().first, 1.0);
  EXPECT_TRUE(r.saw_phase("checking"));
  EXPECT_TRUE(r.saw_phase("repairing"));
  EXPECT_TRUE(r.saw_phase("intersecting"));  // the arrangement's own steps, inside the repair's
}

TEST(Progress, TheCheckReportsItsPasses) {
  Recorded r;
  {
    ProgressScope scope(r.sink());
    EXPECT_TRUE(check_mesh(make_cube(1)).valid_solid());
  }
  EXPECT_TRUE(r.monotone());
  ASSERT_FALSE(r.reports.empty());
  EXPECT_DOUBLE_EQ(r.reports.back().first, 1.0);
  for (const char* pass : {"points and faces", "edges and vertex stars", "self-intersections"})
    EXPECT_TRUE(r.saw_phase(pass)) << pass;
}

}  // namespace

// SPDX-License-Identifier: GPL-3.0-or-later
// The curves that plots show, against curves known in closed form (an exact cube's and two boxes'
// granulometries), and the SVG chart writer: structure, ticks, escaping, errors. The Python tests
// parse the same SVG with an XML parser.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "morphex/boolean.h"
#include "morphex/descriptors.h"
#include "morphex/plot.h"
#include "morphex/retrieval.h"
#include "morphex/shapes.h"

using namespace morphex;

namespace {

std::size_t count(const std::string& text, const std::string& part) {
  std::size_t n = 0;
  for (auto at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++n;
  return n;
}

// The d attribute of every path of class `kind`, in order.
std::vector<std::string> paths(const std::string& svg, const std::string& kind) {
  std::vector<std::string> out;
  const std::string start = "class=\"" + kind + "\" d=\"";
  for (auto at = svg.find(start); at != std::string::npos; at = svg.find(start, at + 1)) {
    const auto from = at + start.size();
    out.push_back(svg.substr(from, svg.find('"', from) - from));
  }
  return out;
}

DescriptorSettings few_samples() {
  DescriptorSettings s;
  s.d2_samples = 512;
  s.d2_bins = 16;
  return s;
}

// The pattern spectrum is the granulometry's decrements, from 1 at radius 0.
void expect_spectrum_of(const Descriptors& d) {
  ASSERT_EQ(d.pattern_spectrum.size(), d.granulometry.size());
  double previous = 1;
  for (std::size_t k = 0; k < d.granulometry.size(); ++k) {
    EXPECT_NEAR(d.pattern_spectrum[k], previous - d.granulometry[k], 1e-12) << k;
    previous = d.granulometry[k];
  }
}

}  // namespace

// The unit cube A (half side h = 1/2, so L = 1 and thickness T = 3 vol / area = 1/2) opened by a
// cube of half side r: A itself while r < h (A is a union of such cubes), nothing once r > h (no
// such cube fits). Closed by any cube: A itself (A is convex).
TEST(DescriptorCurves, ExactCubeGranulometryIsOneStepAtItsHalfSide) {
  DescriptorSettings s = few_samples();
  s.scales = 6;
  s.open_from = 0.1;  // radii 0.05 to 0.8, in units of L: across h = 1/2, none on it
  s.open_to = 1.6;
  const Descriptors d = describe(check_solid(make_cube(FT(1) / 2)), s);
  EXPECT_DOUBLE_EQ(d.scale_length, 1);
  EXPECT_NEAR(d.thickness, 0.5, 1e-12);
  ASSERT_EQ(d.open_radii.size(), 6u);
  ASSERT_EQ(d.granulometry.size(), 6u);
  std::size_t below = 0;
  for (std::size_t k = 0; k < d.open_radii.size(); ++k) {
    const double r = d.open_radii[k];
    EXPECT_NEAR(r, 0.5 * 0.1 * std::pow(16.0, double(k) / 5), 1e-6) << k;  // T geometric(...)
    ASSERT_GT(std::abs(r - 0.5), 1e-3);
    EXPECT_NEAR(d.granulometry[k], r < 0.5 ? 1.0 : 0.0, 1e-12) << "r = " << r;
    below += r < 0.5;
  }
  EXPECT_EQ(below, 5u);  // both sides of the step are measured
  expect_spectrum_of(d);
  EXPECT_NEAR(d.pattern_spectrum.back(), 1, 1e-12);  // all the volume goes at once
  ASSERT_EQ(d.anti_granulometry.size(), 6u);
  for (double c : d.anti_granulometry) EXPECT_NEAR(c, 0, 1e-12);
}

// Two boxes of volume 1/2 each (so L = 1), one above the other with a gap of 1/4: a block A of
// thickness 1/2 under a plate B of thickness 1/8 whose footprint holds A's. Opening by a cube of
// half side r removes B once r > 1/16 and A once r > 1/4: a two-step granulometry 1, 1/2, 0.
// Closing by a cube of half side s bridges the gap over A's footprint (volume 1 x 1 x 1/4) once
// s > 1/8, and adds nothing before (the dilated boxes stay apart, each box is convex).
TEST(DescriptorCurves, TwoBoxesGiveATwoStepGranulometryAndAOneStepClosing) {
  const Mesh block = make_box(Point(0, 0, 0), Point(1, 1, FT(1) / 2));
  const Mesh plate = make_box(Point(0, 0, FT(3) / 4), Point(2, 2, FT(7) / 8));
  const Mesh a = compute_boolean(check_solid(block), check_solid(plate), BooleanOp::Union).solid;
  DescriptorSettings s = few_samples();
  s.normalise_pose = false;  // keep the boxes on the cube's axes
  s.facet_budget = 0;        // and exactly these boxes
  s.scales = 5;
  s.open_from = 0.1;  // T = 3 / 13: radii 0.023 to 0.46, across 1/16 and 1/4
  s.open_to = 2;
  s.close_from = 0.05;  // 0.05 to 0.4, across 1/8
  s.close_to = 0.4;
  const Descriptors d = describe(check_solid(a), s);
  EXPECT_NEAR(d.thickness, 3.0 / 13, 1e-9);
  std::set<double> levels;
  for (std::size_t k = 0; k < d.open_radii.size(); ++k) {
    const double r = d.open_radii[k];
    ASSERT_GT(std::min(std::abs(r - 1.0 / 16), std::abs(r - 0.25)), 1e-3);
    const double expected = (r < 1.0 / 16 ? 0.5 : 0) + (r < 0.25 ? 0.5 : 0);
    EXPECT_NEAR(d.granulometry[k], expected, 1e-5) << "r = " << r;
    levels.insert(expected);
  }
  EXPECT_EQ(levels.size(), 3u);  // 1, 1/2 and 0 are all measured
  expect_spectrum_of(d);
  std::set<double> filled;
  for (std::size_t k = 0; k < d.close_radii.size(); ++k) {
    const double s_k = d.close_radii[k];
    ASSERT_GT(std::abs(s_k - 0.125), 1e-3);
    const double expected = s_k > 0.125 ? 0.25 : 0;
    EXPECT_NEAR(d.anti_granulometry[k], expected, 1e-5) << "s = " << s_k;
    filled.insert(expected);
  }
  EXPECT_EQ(filled.size(), 2u);
  // The figure shows these very numbers.
  const Figure figure = descriptor_figure(d, "boxes");
  ASSERT_EQ(figure.charts.size(), 4u);
  EXPECT_EQ(figure.charts[0].series[0].y, d.granulometry);
  EXPECT_EQ(figure.charts[0].series[0].x, d.open_radii);
  EXPECT_EQ(figure.charts[1].series[0].y, d.anti_granulometry);
  const Series& bars = figure.charts[2].series[0];
  EXPECT_TRUE(bars.bars);
  EXPECT_EQ(bars.y, d.pattern_spectrum);
  ASSERT_EQ(bars.x.size(), d.open_radii.size() + 1);  // bin edges 0, r_1, ..., r_n
  EXPECT_EQ(bars.x[0], 0);
  EXPECT_EQ(bars.x[1], d.open_radii[0]);
}

TEST(DescriptorCurves, WithoutClosingsTheFigureHasNoAntiGranulometry) {
  DescriptorSettings s = few_samples();
  s.scales = 2;
  s.closings = false;
  const Figure figure = descriptor_figure(describe(check_solid(make_cube(1)), s), "cube");
  ASSERT_EQ(figure.charts.size(), 3u);
  EXPECT_EQ(figure.charts[1].title.rfind("Pattern spectrum", 0), 0u);
}

TEST(Svg, OnePathPerSeriesALegendAndNiceTicks) {
  Chart chart;
  chart.title = "Two <curves> & a histogram";
  chart.x_label = "x";
  chart.y_label = "y";
  chart.series.push_back({"rising", {0, 1, 2, 3}, {0.13, 0.4, 0.6, 0.87}, false});
  chart.series.push_back({"gap", {0, 1, 2, 3}, {0.2, NAN, 0.3, 0.25}, false});
  chart.series.push_back({"bins", {0, 1, 2}, {0.5, 0.25}, true});
  const std::string svg = to_svg(chart);
  EXPECT_EQ(svg.rfind("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg ", 0), 0u);
  EXPECT_NE(svg.find("viewBox=\"0 0 640 420\""), std::string::npos);
  EXPECT_EQ(count(svg, "<g class=\"series\">"), 3u);
  EXPECT_EQ(count(svg, "class=\"line\""), 2u);
  EXPECT_EQ(count(svg, "class=\"bars\""), 1u);
  EXPECT_EQ(count(svg, "<g class=\"legend\">"), 1u);
  for (const char* name : {">rising<", ">gap<", ">bins<"})
    EXPECT_NE(svg.find(name), std::string::npos);
  // y spans 0 (under the bars) to 0.87: ticks 0, 0.2, ..., 1 with one decimal; x 0 to 3 by 1
  for (const char* tick : {">0.0<", ">0.2<", ">0.8<", ">1.0<", ">0<", ">3<"})
    EXPECT_NE(svg.find(tick), std::string::npos) << tick;
  EXPECT_EQ(svg.find(">1.2<"), std::string::npos);
  EXPECT_EQ(svg.find(">4<"), std::string::npos);
  // the point that is not a number breaks its line: two pieces in one path
  const std::vector<std::string> lines = paths(svg, "line");
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(count(lines[0], "M"), 1u);
  EXPECT_EQ(count(lines[1], "M"), 2u);
  EXPECT_EQ(count(paths(svg, "bars")[0], "Z"), 2u);  // two bins
  EXPECT_NE(svg.find("Two &lt;curves&gt; &amp; a histogram"), std::string::npos);
  EXPECT_EQ(svg, to_svg(chart));  // the same text every time
  EXPECT_EQ(svg.find("nan"), std::string::npos);
}

TEST(Svg, TextIsEscapedAndMadeValidUtf8) {
  Chart chart;
  chart.title = "t";
  chart.series.push_back({"a<b&c>\"d'", {0, 1}, {0, 1}, false});
  chart.series.push_back({std::string("x\xFF y\x07z caf\xC3\xA9"), {0}, {1}, false});
  const std::string svg = to_svg(chart);
  EXPECT_NE(svg.find(">a&lt;b&amp;c&gt;&quot;d&apos;<"), std::string::npos);
  EXPECT_EQ(svg.find("a<b"), std::string::npos);
  // a byte that is not UTF-8 becomes U+FFFD, a control character a space
  EXPECT_NE(svg.find(">x\xEF\xBF\xBD y z caf\xC3\xA9<"), std::string::npos);
  EXPECT_EQ(svg.find('\x07'), std::string::npos);
  // a name too long for the legend is cut with an ellipsis, on a character boundary
  chart.series[1].name = std::string(60, 'x') + "\xC3\xA9";
  const std::string cut = to_svg(chart);
  EXPECT_NE(cut.find("xxxx\xE2\x80\xA6<"), std::string::npos);
}

TEST(Svg, GridOfPanelsUnderATitle) {
  Chart one;
  one.title = "one";
  one.series.push_back({"s", {0, 1}, {2, 2}, false});  // a constant: a range around it
  Figure figure{"Figure", {one, one, one}, 2};
  const std::string svg = to_svg(figure);
  EXPECT_NE(svg.find("width=\"1280\" height=\"876\" viewBox=\"0 0 1280 876\""), std::string::npos);
  EXPECT_EQ(count(svg, "<g class=\"chart\">"), 3u);
  EXPECT_EQ(count(svg, "<clipPath id=\"plot-"), 3u);  // one id per panel
  EXPECT_NE(svg.find("<clipPath id=\"plot-2\">"), std::string::npos);
  EXPECT_EQ(count(svg, "<g class=\"legend\">"), 0u);  // one series: the title names it
  EXPECT_NE(svg.find("<title>Figure</title>"), std::string::npos);
  const auto path = (std::filesystem::temp_directory_path() / "morphex-test-plot.svg").string();
  write_svg(path, figure);
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_EQ(text.str(), svg);
  std::filesystem::remove(path);
}

TEST(Svg, UnusableChartsAreRefused) {
  Chart chart;
  chart.title = "c";
  chart.series.push_back({"short", {0, 1, 2}, {0, 1}, false});
  EXPECT_THROW(to_svg(chart), InputError);
  chart.series[0] = {"bins", {0, 1}, {0, 1}, true};  // bars need one edge more
  EXPECT_THROW(to_svg(chart), InputError);
  chart.series[0] = {"ok", {0, 1}, {0, 1}, false};
  chart.x_min = 1;
  chart.x_max = 1;
  try {
    to_svg(chart);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "chart 'c' x axis: the axis range is empty");
  }
  EXPECT_THROW(to_svg(Figure{"", {chart}, 0}), InputError);
}

TEST(Svg, PrecisionRecallChartHasOneSeriesPerKind) {
  PrecisionRecall pr;
  pr.recall = recall_levels();
  pr.precision.assign(pr.recall.size(), 0.5);
  pr.queries = 4;
  const Chart chart = precision_recall_chart({{"d2", pr}, {"morphology", pr}}, "PR");
  ASSERT_EQ(chart.series.size(), 2u);
  EXPECT_EQ(chart.series[1].name, "morphology");
  EXPECT_EQ(chart.series[1].x, pr.recall);
  EXPECT_EQ(*chart.x_max, 1);
  EXPECT_EQ(*chart.y_min, 0);
  const std::string svg = to_svg(chart);
  EXPECT_EQ(count(svg, "class=\"line\""), 2u);
  EXPECT_EQ(count(svg, "class=\"markers\""), 2u);
}

// SPDX-License-Identifier: GPL-3.0-or-later
// Charts as SVG files, written by the project itself: no GUI, no plotting library, no Python.
// Line charts with markers and histograms, laid out in a grid of panels, with 1-2-5 ticks, a
// legend and the Okabe-Ito colours (told apart by colour-blind readers, and by marker shape too).
// The text is the same for the same data (no date, no random ids), so written files can be
// committed and compared.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "morphex/descriptors.h"
#include "morphex/retrieval.h"

namespace morphex {

struct Series {
  std::string name;  // the legend's text (any UTF-8; escaped when written)
  // A line through (x[i], y[i]) with a marker on each point; a point with a value that is not
  // finite leaves a gap. With `bars`, a histogram instead: bar i spans x[i] to x[i + 1] up from 0,
  // so x holds one value more than y (the bins' edges).
  std::vector<double> x, y;
  bool bars = false;
};

struct Chart {
  std::string title, x_label, y_label;
  std::vector<Series> series;
  // The axes span the data (and 0 under bars), widened to the next tick; these fix either end.
  std::optional<double> x_min, x_max, y_min, y_max;
};

// Charts in a grid `columns` wide (panels of 640 x 420 pixels), row by row, under a title.
struct Figure {
  std::string title;
  std::vector<Chart> charts;
  int columns = 2;
};

// The SVG document. Throws InputError naming the chart and series when a series' x and y do not
// fit together, or a fixed axis range is empty.
std::string to_svg(const Figure& figure);
std::string to_svg(const Chart& chart);
// to_svg written atomically to `path` (morphex/io.h).
void write_svg(const std::string& path, const Figure& figure);

// The charts of a description (morphex/descriptors.h): its granulometry, anti-granulometry (when
// closings were computed), pattern spectrum and D2 distribution, titled with `name` (a mesh).
Figure descriptor_figure(const Descriptors& d, const std::string& name);

// The averaged precision-recall curve of each descriptor kind (morphex/retrieval.h), one series
// each, on [0, 1] x [0, 1].
Chart precision_recall_chart(const std::vector<std::pair<std::string, PrecisionRecall>>& curves,
                             const std::string& title);

}  // namespace morphex

// SPDX-License-Identifier: GPL-3.0-or-later
// The charts of morphex's own data (morphex/plot.h): a description's curves and the retrieval
// evaluation's precision-recall curves. Labels say what the numbers are: descriptors.h scales the
// filtered copy to unit volume, so radii are in units of L = cbrt(volume) and volumes are shares
// of the solid's.
#include <locale>
#include <sstream>

#include "morphex/plot.h"

namespace morphex {
namespace {

std::string rounded(double v) {
  std::ostringstream out;
  out.imbue(std::locale::classic());
  out.precision(4);
  out << v;
  return out.str();
}

}  // namespace

Figure descriptor_figure(const Descriptors& d, const std::string& name) {
  Figure figure;
  figure.title = name + ": L = cbrt(volume) = " + rounded(d.scale_length) +
                 ", thickness 3 volume / area = " + rounded(d.thickness) + " L";
  Chart g;
  g.title = "Granulometry: vol(open(A, r)) / vol(A)";
  g.x_label = "opening cube half side r / L";
  g.y_label = "volume left / vol(A)";
  g.series.push_back({"granulometry", d.open_radii, d.granulometry, false});
  g.x_min = 0;
  g.y_min = 0;
  g.y_max = 1;
  figure.charts.push_back(g);
  if (!d.close_radii.empty()) {
    Chart c;
    c.title = "Anti-granulometry: vol(close(A, s) \\ A) / vol(A)";
    c.x_label = "closing cube half side s / L";
    c.y_label = "volume added / vol(A)";
    c.series.push_back({"anti-granulometry", d.close_radii, d.anti_granulometry, false});
    c.x_min = 0;
    c.y_min = 0;
    figure.charts.push_back(c);
  }
  // p_k = g_{k-1} - g_k with g_0 = 1 at r = 0: the volume removed by radii from r_{k-1} to r_k.
  Chart p;
  p.title = "Pattern spectrum: volume removed between radii";
  p.x_label = "opening cube half side r / L";
  p.y_label = "volume removed / vol(A)";
  Series bars{"pattern spectrum", {0.0}, d.pattern_spectrum, true};
  bars.x.insert(bars.x.end(), d.open_radii.begin(), d.open_radii.end());
  if (d.open_radii.size() != d.pattern_spectrum.size()) bars.x.clear(), bars.y.clear();
  p.series.push_back(bars);
  p.x_min = 0;
  p.y_min = 0;
  figure.charts.push_back(p);
  // D2 spans [0, 3) times the mean distance in d2.size() bins (descriptors.h).
  Chart h;
  h.title = "D2: distances between random surface points";
  h.x_label = "distance / mean distance";
  h.y_label = "share of point pairs";
  Series d2{"D2", {}, d.d2, true};
  for (std::size_t i = 0; i <= d.d2.size(); ++i)
    d2.x.push_back(3.0 * double(i) / double(d.d2.size()));
  if (d.d2.empty()) d2.x.clear();
  h.series.push_back(d2);
  h.x_min = 0;
  h.x_max = 3;
  h.y_min = 0;
  figure.charts.push_back(h);
  return figure;
}

Chart precision_recall_chart(const std::vector<std::pair<std::string, PrecisionRecall>>& curves,
                             const std::string& title) {
  Chart chart;
  chart.title = title;
  chart.x_label = "recall";
  chart.y_label = "mean interpolated precision";
  for (const auto& [kind, curve] : curves)
    chart.series.push_back({kind, curve.recall, curve.precision, false});
  chart.x_min = 0;
  chart.x_max = 1;
  chart.y_min = 0;
  chart.y_max = 1;
  return chart;
}

}  // namespace morphex

// SPDX-License-Identifier: GPL-3.0-or-later
// The SVG chart writer (morphex/plot.h). SVG cannot measure text, so widths are estimated from the
// number of characters (0.6 em each, generous for sans-serif faces): labels longer than their room
// are cut with an ellipsis instead of running over their neighbours.
#include "morphex/plot.h"
#include "morphex/internal/files.h"

#include <algorithm>
#include <cmath>
#include <locale>
#include <sstream>

#include "morphex/error.h"
#include "morphex/io.h"

namespace morphex {
namespace {

constexpr double kPanelWidth = 640, kPanelHeight = 420, kTitleBand = 36;
constexpr double kFont = 12, kCharWidth = 0.6 * kFont;
// Okabe and Ito's colour-blind-safe palette, strongest contrast on white first (its yellow left
// out).
const char* const kColours[] = {"#0072B2", "#D55E00", "#009E73", "#CC79A7",
                                "#E69F00", "#56B4E9", "#000000"};
constexpr std::size_t kColourCount = sizeof kColours / sizeof kColours[0];

// A coordinate with at most two decimals, in the C locale whatever the process's locale.
std::string num(double v) {
  std::ostringstream out;
  out.imbue(std::locale::classic());
  out.setf(std::ios::fixed);
  out.precision(2);
  out << (std::abs(v) < 0.005 ? 0.0 : v);
  std::string s = out.str();
  s.erase(s.find_last_not_of('0') + 1);
  if (s.back() == '.') s.pop_back();
  return s;
}

// Valid UTF-8 without the characters XML 1.0 forbids: an invalid byte becomes U+FFFD, a control
// character a space.
std::string clean_utf8(const std::string& text) {
  std::string out;
  const auto* s = reinterpret_cast<const unsigned char*>(text.data());
  const std::size_t n = text.size();
  for (std::size_t i = 0; i < n;) {
    const unsigned char c = s[i];
    if (c < 0x80) {
      out += c < 0x20 && c != '\t' ? ' ' : char(c);
      ++i;
      continue;
    }
    const int length = c >= 0xF0 ? 4 : c >= 0xE0 ? 3 : c >= 0xC2 ? 2 : 0;
    char32_t code = length == 4 ? c & 0x07 : length == 3 ? c & 0x0F : c & 0x1F;
    bool ok = length > 0 && c < 0xF5 && i + length <= n;
    for (int k = 1; ok && k < length; ++k) {
      ok = (s[i + k] & 0xC0) == 0x80;
      code = (code << 6) | (s[i + k] & 0x3F);
    }
    // Overlong forms, surrogates, beyond U+10FFFF, and the two non-characters XML excludes.
    ok = ok && !(length == 3 && code < 0x800) && !(length == 4 && code < 0x10000) &&
         !(code >= 0xD800 && code <= 0xDFFF) && code <= 0x10FFFF && code != 0xFFFE &&
         code != 0xFFFF;
    if (ok) {
      out.append(text, i, std::size_t(length));
      i += std::size_t(length);
    } else {
      out += "\xEF\xBF\xBD";
      ++i;
    }
  }
  return out;
}

std::size_t characters(const std::string& utf8) {
  return std::size_t(std::count_if(utf8.begin(), utf8.end(), [](char c) {
    return (static_cast<unsigned char>(c) & 0xC0) != 0x80;
  }));
}

// At most `limit` characters of clean UTF-8, the last one an ellipsis when it was cut.
std::string shortened(const std::string& utf8, std::size_t limit) {
  if (characters(utf8) <= limit) return utf8;
  std::size_t kept = 0, i = 0;
  for (; i < utf8.size(); ++i)
    if ((static_cast<unsigned char>(utf8[i]) & 0xC0) != 0x80 && ++kept == limit) break;
  return utf8.substr(0, i) + "\xE2\x80\xA6";
}

std::string escaped(const std::string& utf8) {
  std::string out;
  for (char c : utf8) switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      default:
        out += c;
    }
  return out;
}

// Text for an element: cleaned, cut to fit `width` pixels at `font` size, escaped.
std::string text_fitting(const std::string& text, double width, double font = kFont) {
  const auto limit = std::size_t(std::max(4.0, width / (0.6 * font)));
  return escaped(shortened(clean_utf8(text), limit));
}

// One axis: its ends and the ticks between them, 1, 2 or 5 times a power of ten apart.
struct Axis {
  double lo = 0, hi = 1, step = 0.2;

  std::vector<double> ticks() const {
    std::vector<double> out;
    const double first = std::ceil(lo / step - 1e-9);
    for (double k = first; (k - 1e-9) * step <= hi; ++k) out.push_back(k * step);
    return out;
  }
  std::string label(double v) const {
    std::ostringstream out;
    out.imbue(std::locale::classic());
    if (std::abs(v) < step * 1e-6) v = 0;  // no "-0" or "1e-17"
    const double magnitude = std::max(std::abs(lo), std::abs(hi));
    if (magnitude >= 1e6 || step < 1e-5) {
      out.precision(3);
      out << v;
    } else {
      out.setf(std::ios::fixed);
      out.precision(int(std::max(0.0, -std::floor(std::log10(step) + 1e-9))));
      out << v;
    }
    return out.str();
  }
};

double nice_step(double span, int target) {
  const double raw = span / target, power = std::pow(10.0, std::floor(std::log10(raw)));
  const double f = raw / power;
  return (f <= 1 ? 1 : f <= 2 ? 2 : f <= 5 ? 5 : 10) * power;
}

// The axis over [lo, hi] (the data's; infinite when there is none), with fixed ends kept and
// free ends moved out to the next tick.
Axis make_axis(double lo, double hi, std::optional<double> fixed_lo, std::optional<double> fixed_hi,
               const std::string& where) {
  if (!(lo <= hi)) lo = 0, hi = 1;  // no data
  if (fixed_lo) lo = *fixed_lo;
  if (fixed_hi) hi = *fixed_hi;
  if (fixed_lo && fixed_hi && !(*fixed_lo < *fixed_hi))
    throw InputError(where, "the axis range is empty");
  if (!(hi > lo)) {  // one value: a range around it
    const double span = lo != 0 ? std::abs(lo) * 0.2 : 1;
    if (!fixed_hi)
      hi = lo + span;
    else
      lo = hi - span;
  }
  Axis a;
  a.step = nice_step(hi - lo, 5);
  // Data a thousandth of a step past a tick (a radius rounded onto its grid) stays inside it: the
  // plot area's inset leaves room for it.
  a.lo = fixed_lo ? lo : std::floor(lo / a.step + 1e-3) * a.step;
  a.hi = fixed_hi ? hi : std::ceil(hi / a.step - 1e-3) * a.step;
  return a;
}

void check_series(const Chart& chart, const Series& s) {
  const std::size_t expected = s.y.size() + (s.bars ? 1 : 0);
  if (s.x.size() != expected && !(s.bars && s.y.empty() && s.x.empty()))
    throw InputError("chart '" + chart.title + "'",
                     "series '" + s.name + "': " + std::to_string(s.x.size()) + " x values for " +
                         std::to_string(s.y.size()) + " y values (" +
                         (s.bars ? "bars need one edge more" : "a line needs as many") + ")");
}

// The marker of series k at (x, y), as a closed path: circle, square, triangle, diamond, inverted
// triangle, plus, in turn.
std::string marker(std::size_t k, double x, double y) {
  const double r = 3.5;
  std::ostringstream p;
  p.imbue(std::locale::classic());
  switch (k % 6) {
    case 0:
      p << "M" << num(x - r) << " " << num(y) << "a" << r << " " << r << " 0 1 0 " << 2 * r << " 0a"
        << r << " " << r << " 0 1 0 " << -2 * r << " 0Z";
      break;
    case 1:
      p << "M" << num(x - r) << " " << num(y - r) << "h" << 2 * r << "v" << 2 * r << "h" << -2 * r
        << "Z";
      break;
    case 2:
      p << "M" << num(x) << " " << num(y - 1.2 * r) << "L" << num(x + 1.1 * r) << " "
        << num(y + 0.8 * r) << "L" << num(x - 1.1 * r) << " " << num(y + 0.8 * r) << "Z";
      break;
    case 3:
      p << "M" << num(x) << " " << num(y - 1.3 * r) << "L" << num(x + 1.3 * r) << " " << num(y)
        << "L" << num(x) << " " << num(y + 1.3 * r) << "L" << num(x - 1.3 * r) << " " << num(y)
        << "Z";
      break;
    case 4:
      p << "M" << num(x) << " " << num(y + 1.2 * r) << "L" << num(x + 1.1 * r) << " "
        << num(y - 0.8 * r) << "L" << num(x - 1.1 * r) << " " << num(y - 0.8 * r) << "Z";
      break;
    default: {
      const double a = 0.45 * r, b = 1.2 * r;
      p << "M" << num(x - a) << " " << num(y - b) << "h" << num(2 * a) << "v" << num(b - a) << "h"
        << num(b - a) << "v" << num(2 * a) << "h" << num(a - b) << "v" << num(b - a) << "h"
        << num(-2 * a) << "v" << num(a - b) << "h" << num(a - b) << "v" << num(-2 * a) << "h"
        << num(b - a) << "Z";
    }
  }
  return p.str();
}

const char* colour(std::size_t k) {
  return kColours[k % kColourCount];
}
// Beyond the palette, lines repeat its colours dashed.
std::string dash(std::size_t k) {
  return k < kColourCount ? "" : " stroke-dasharray=\"7 4\"";
}

// The plot area of a panel, and the mapping of data onto it (inset a little, so that markers on
// the ends of a fixed range are not cut by the frame).
struct Frame {
  double left, top, width, height, y_label_x;
  Axis x, y;
  static constexpr double kInset = 7;

  double px(double v) const {
    return left + kInset + (v - x.lo) / (x.hi - x.lo) * (width - 2 * kInset);
  }
  double py(double v) const {
    return top + height - kInset - (v - y.lo) / (y.hi - y.lo) * (height - 2 * kInset);
  }
};

void draw_axes(std::ostream& out, const Chart& chart, const Frame& f) {
  out << "<g class=\"grid\" stroke=\"#e3e3e3\" stroke-width=\"1\">\n";
  for (double t : f.x.ticks())
    out << "<line x1=\"" << num(f.px(t)) << "\" y1=\"" << num(f.top) << "\" x2=\"" << num(f.px(t))
        << "\" y2=\"" << num(f.top + f.height) << "\"/>\n";
  for (double t : f.y.ticks())
    out << "<line x1=\"" << num(f.left) << "\" y1=\"" << num(f.py(t)) << "\" x2=\""
        << num(f.left + f.width) << "\" y2=\"" << num(f.py(t)) << "\"/>\n";
  out << "</g>\n<rect class=\"frame\" x=\"" << num(f.left) << "\" y=\"" << num(f.top)
      << "\" width=\"" << num(f.width) << "\" height=\"" << num(f.height)
      << "\" fill=\"none\" stroke=\"#555\" stroke-width=\"1\"/>\n";
  out << "<g class=\"ticks\" fill=\"#333\">\n";
  const double bottom = f.top + f.height;
  for (double t : f.x.ticks())
    out << "<path d=\"M" << num(f.px(t)) << " " << num(bottom) << "v4\" stroke=\"#555\"/>"
        << "<text x=\"" << num(f.px(t)) << "\" y=\"" << num(bottom + 17)
        << "\" text-anchor=\"middle\">" << escaped(f.x.label(t)) << "</text>\n";
  for (double t : f.y.ticks())
    out << "<path d=\"M" << num(f.left) << " " << num(f.py(t)) << "h-4\" stroke=\"#555\"/>"
        << "<text x=\"" << num(f.left - 7) << "\" y=\"" << num(f.py(t) + 4)
        << "\" text-anchor=\"end\">" << escaped(f.y.label(t)) << "</text>\n";
  out << "</g>\n";
  out << "<text class=\"x-label\" x=\"" << num(f.left + f.width / 2) << "\" y=\""
      << num(bottom + 40) << "\" text-anchor=\"middle\" font-size=\"13\">"
      << text_fitting(chart.x_label, f.width, 13) << "</text>\n";
  const double cy = f.top + f.height / 2;
  out << "<text class=\"y-label\" transform=\"translate(" << num(f.y_label_x) << " " << num(cy)
      << ") rotate(-90)\" text-anchor=\"middle\" font-size=\"13\">"
      << text_fitting(chart.y_label, f.height, 13) << "</text>\n";
}

// Series k: one path (the line, or the bars) and, for lines, one path of markers.
void draw_series(std::ostream& out, const Series& s, std::size_t k, const Frame& f) {
  out << "<g class=\"series\">\n";
  std::ostringstream d;
  if (s.bars) {
    for (std::size_t i = 0; i < s.y.size(); ++i) {
      if (!std::isfinite(s.y[i]) || !std::isfinite(s.x[i]) || !std::isfinite(s.x[i + 1])) continue;
      const double x0 = f.px(s.x[i]), x1 = f.px(s.x[i + 1]), y0 = f.py(0), y1 = f.py(s.y[i]);
      d << "M" << num(x0) << " " << num(y0) << "H" << num(x1) << "V" << num(y1) << "H" << num(x0)
        << "Z";
    }
    out << "<path class=\"bars\" d=\"" << d.str() << "\" fill=\"" << colour(k)
        << "\" fill-opacity=\"0.55\" stroke=\"" << colour(k) << "\" stroke-width=\"1\"/>\n";
  } else {
    bool open = false;
    std::ostringstream marks;
    for (std::size_t i = 0; i < s.y.size(); ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) {
        open = false;
        continue;
      }
      const double x = f.px(s.x[i]), y = f.py(s.y[i]);
      d << (open ? "L" : "M") << num(x) << " " << num(y);
      open = true;
      marks << marker(k, x, y);
    }
    out << "<path class=\"line\" d=\"" << d.str() << "\" fill=\"none\" stroke=\"" << colour(k)
        << "\" stroke-width=\"2\" stroke-linejoin=\"round\"" << dash(k) << "/>\n";
    out << "<path class=\"markers\" d=\"" << marks.str() << "\" fill=\"" << colour(k)
        << "\" stroke=\"white\" stroke-width=\"0.8\"/>\n";
  }
  out << "</g>\n";
}

void draw_legend(std::ostream& out, const Chart& chart, double x, double y, double width) {
  out << "<g class=\"legend\">\n";
  for (std::size_t k = 0; k < chart.series.size(); ++k) {
    const Series& s = chart.series[k];
    const double cy = y + 20.0 * double(k);
    if (s.bars)
      out << "<rect x=\"" << num(x) << "\" y=\"" << num(cy - 6) << "\" width=\"22\" height=\"12\""
          << " fill=\"" << colour(k) << "\" fill-opacity=\"0.55\" stroke=\"" << colour(k) << "\"/>";
    else
      out << "<path d=\"M" << num(x) << " " << num(cy) << "h22\" stroke=\"" << colour(k)
          << "\" stroke-width=\"2\"" << dash(k) << "/><path d=\"" << marker(k, x + 11, cy)
          << "\" fill=\"" << colour(k) << "\" stroke=\"white\" stroke-width=\"0.8\"/>";
    out << "<text x=\"" << num(x + 28) << "\" y=\"" << num(cy + 4) << "\">"
        << text_fitting(s.name, width - 28) << "</text>\n";
  }
  out << "</g>\n";
}

// The data's extent along x (or y) over every series; bars stand on 0.
std::pair<double, double> extent(const Chart& chart, bool along_x) {
  double lo = INFINITY, hi = -INFINITY;
  for (const Series& s : chart.series) {
    for (double v : along_x ? s.x : s.y)
      if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
    if (s.bars && !along_x && !s.y.empty()) lo = std::min(lo, 0.0), hi = std::max(hi, 0.0);
  }
  return {lo, hi};
}

void draw_chart(std::ostream& out, const Chart& chart, double ox, double oy, std::size_t index) {
  for (const Series& s : chart.series) check_series(chart, s);
  const std::string where = "chart '" + chart.title + "'";
  const auto [x_lo, x_hi] = extent(chart, true);
  const auto [y_lo, y_hi] = extent(chart, false);
  Frame f{0,
          0,
          0,
          0,
          ox + 20,
          make_axis(x_lo, x_hi, chart.x_min, chart.x_max, where + " x axis"),
          make_axis(y_lo, y_hi, chart.y_min, chart.y_max, where + " y axis")};
  std::size_t tick_chars = 1;
  for (double t : f.y.ticks()) tick_chars = std::max(tick_chars, f.y.label(t).size());
  // A legend beside the plot when there is more than one series, as wide as its longest name.
  double legend = 0;
  if (chart.series.size() > 1) {
    std::size_t longest = 0;
    for (const Series& s : chart.series) longest = std::max(longest, characters(s.name));
    legend = std::min(210.0, 46 + kCharWidth * double(longest));
  }
  f.left = ox + 34 + kCharWidth * double(tick_chars) + 10;
  f.top = oy + 42;
  f.width = ox + kPanelWidth - 18 - legend - f.left;
  f.height = kPanelHeight - 42 - 58;
  out << "<g class=\"chart\">\n<text class=\"title\" x=\"" << num(ox + kPanelWidth / 2) << "\" y=\""
      << num(oy + 26) << "\" text-anchor=\"middle\" font-size=\"15\" "
      << "font-weight=\"bold\">" << text_fitting(chart.title, kPanelWidth - 24, 15) << "</text>\n";
  draw_axes(out, chart, f);
  out << "<clipPath id=\"plot-" << index << "\"><rect x=\"" << num(f.left) << "\" y=\""
      << num(f.top) << "\" width=\"" << num(f.width) << "\" height=\"" << num(f.height)
      << "\"/></clipPath>\n<g clip-path=\"url(#plot-" << index << ")\">\n";
  for (std::size_t k = 0; k < chart.series.size(); ++k) draw_series(out, chart.series[k], k, f);
  out << "</g>\n";
  if (chart.series.empty())
    out << "<text x=\"" << num(f.left + f.width / 2) << "\" y=\"" << num(f.top + f.height / 2)
        << "\" text-anchor=\"middle\" fill=\"#777\">no data</text>\n";
  if (legend > 0) draw_legend(out, chart, f.left + f.width + 14, f.top + 10, legend - 14);
  out << "</g>\n";
}

}  // namespace

std::string to_svg(const Figure& figure) {
  if (figure.columns < 1) throw InputError("figure", "expected at least one column");
  const std::size_t n = std::max<std::size_t>(1, figure.charts.size());
  const std::size_t columns = std::min(n, std::size_t(figure.columns));
  const std::size_t rows = (n + columns - 1) / columns;
  const double band = figure.title.empty() ? 0 : kTitleBand;
  const double width = kPanelWidth * double(columns), height = band + kPanelHeight * double(rows);
  std::ostringstream out;
  out.imbue(std::locale::classic());
  out << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      << "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"" << num(width)
      << "\" height=\"" << num(height) << "\" viewBox=\"0 0 " << num(width) << " " << num(height)
      << "\" font-family=\"DejaVu Sans, Verdana, Arial, sans-serif\" font-size=\"" << kFont
      << "\">\n";
  const std::string title = !figure.title.empty()   ? figure.title
                            : figure.charts.empty() ? ""
                                                    : figure.charts[0].title;
  out << "<title>" << escaped(clean_utf8(title)) << "</title>\n"
      << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  if (!figure.title.empty())
    out << "<text class=\"figure-title\" x=\"" << num(width / 2)
        << "\" y=\"25\" text-anchor=\"middle\" font-size=\"17\" font-weight=\"bold\">"
        << text_fitting(figure.title, width - 24, 17) << "</text>\n";
  for (std::size_t i = 0; i < figure.charts.size(); ++i)
    draw_chart(out, figure.charts[i], kPanelWidth * double(i % columns),
               band + kPanelHeight * double(i / columns), i);
  out << "</svg>\n";
  return out.str();
}

std::string to_svg(const Chart& chart) {
  return to_svg(Figure{"", {chart}, 1});
}

void write_svg(const std::string& path, const Figure& figure) {
  const std::string text = to_svg(figure);  // errors before the file is touched
  write_file_atomically(path, [&](std::ostream& out) { out << text; });
}

}  // namespace morphex

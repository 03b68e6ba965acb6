// SPDX-License-Identifier: GPL-3.0-or-later
// The data of the plots and the SVG writer (morphex/plot.h, morphex/retrieval.h):
// evaluate_retrieval on a distance matrix (scores, per class, precision-recall), the charts of a
// description and of an evaluation as dicts, and plot_svg, which writes any such chart without a
// plotting library.
#include "morphex/plot.h"
#include "common.h"
#include "morphex/internal/files.h"
#include "morphex/io.h"
#include "morphex/retrieval.h"
#include "morphex/retrieval_json.h"

namespace morphex::python {
namespace {

py::dict scores_dict(const RetrievalScores& s) {
  return from_json(s);
}

py::dict curve_dict(const PrecisionRecall& pr) {
  py::dict j;
  j["recall"] = to_numpy(pr.recall);
  j["precision"] = to_numpy(pr.precision);
  return j;
}

py::dict per_class_dict(const std::vector<ClassScores>& classes) {
  py::dict out;
  for (const ClassScores& c : classes) {
    out[c.name.c_str()] = from_json(c);
  }
  return out;
}

py::dict evaluate_matrix(const std::vector<std::string>& names,
                         const std::vector<std::string>& classes,
                         const std::vector<std::vector<double>>& distance) {
  std::vector<QueryScores> queries;
  {
    py::gil_scoped_release release;
    queries = score_queries(names, classes, distance);
  }
  return evaluation_dict(mean_scores(queries), class_scores(queries, classes),
                         precision_recall(queries));
}

std::vector<double> doubles(const py::handle& value, const char* what) {
  try {
    return value.cast<std::vector<double>>();
  } catch (const py::cast_error&) {
    throw InputError(what, "expected a sequence of numbers");
  }
}

std::optional<double> optional_number(const py::dict& d, const char* key) {
  if (!d.contains(key) || d[key].is_none()) return std::nullopt;
  return d[key].cast<double>();
}

std::string text(const py::dict& d, const char* key) {
  return d.contains(key) && !d[key].is_none() ? py::str(d[key]).cast<std::string>() : "";
}

Chart to_chart(const py::handle& value) {
  if (!py::isinstance<py::dict>(value))
    throw InputError("chart", "expected a dict with title, x_label, y_label and series");
  const py::dict d = py::reinterpret_borrow<py::dict>(value);
  Chart c;
  c.title = text(d, "title");
  c.x_label = text(d, "x_label");
  c.y_label = text(d, "y_label");
  c.x_min = optional_number(d, "x_min");
  c.x_max = optional_number(d, "x_max");
  c.y_min = optional_number(d, "y_min");
  c.y_max = optional_number(d, "y_max");
  if (d.contains("series"))
    for (const py::handle& item : d["series"]) {
      if (!py::isinstance<py::dict>(item))
        throw InputError("chart '" + c.title + "'", "expected each series as a dict");
      const py::dict s = py::reinterpret_borrow<py::dict>(item);
      Series series;
      series.name = text(s, "name");
      const std::string where = "series '" + series.name + "'";
      if (!s.contains("x") || !s.contains("y")) throw InputError(where, "expected x and y");
      series.x = doubles(s["x"], (where + " x").c_str());
      series.y = doubles(s["y"], (where + " y").c_str());
      series.bars = s.contains("bars") && py::bool_(s["bars"]);
      c.series.push_back(std::move(series));
    }
  return c;
}

py::dict from_chart(const Chart& c) {
  py::dict d;
  d["title"] = c.title;
  d["x_label"] = c.x_label;
  d["y_label"] = c.y_label;
  py::list series;
  for (const Series& s : c.series) {
    py::dict j;
    j["name"] = s.name;
    j["x"] = to_numpy(s.x);
    j["y"] = to_numpy(s.y);
    j["bars"] = s.bars;
    series.append(j);
  }
  d["series"] = series;
  const std::pair<const char*, const std::optional<double>*> ends[] = {
      {"x_min", &c.x_min}, {"x_max", &c.x_max}, {"y_min", &c.y_min}, {"y_max", &c.y_max}};
  for (const auto& [key, v] : ends) d[key] = *v ? py::cast(**v) : py::none();
  return d;
}

// A figure dict, a chart dict or a list of chart dicts.
Figure to_figure(const py::object& value, const std::optional<std::string>& title, int columns) {
  Figure f;
  f.columns = columns;
  if (py::isinstance<py::dict>(value) && value.cast<py::dict>().contains("charts")) {
    const py::dict d = value.cast<py::dict>();
    f.title = text(d, "title");
    for (const py::handle& chart : d["charts"]) f.charts.push_back(to_chart(chart));
    if (d.contains("columns") && !d["columns"].is_none()) f.columns = d["columns"].cast<int>();
  } else if (py::isinstance<py::dict>(value)) {
    f.charts.push_back(to_chart(value));
    f.columns = 1;
  } else {
    for (const py::handle& chart : value) f.charts.push_back(to_chart(chart));
  }
  if (title) f.title = *title;
  return f;
}

// The Descriptors fields the charts show, from describe()'s dict.
Descriptors descriptors_from(const py::dict& d) {
  Descriptors out;
  const auto array = [&](const char* key) {
    if (!d.contains(key)) throw InputError("descriptors", std::string("expected '") + key + "'");
    return doubles(d[key], key);
  };
  out.open_radii = array("open_radii");
  out.close_radii = array("close_radii");
  out.granulometry = array("granulometry");
  out.anti_granulometry = array("anti_granulometry");
  out.pattern_spectrum = array("pattern_spectrum");
  out.d2 = array("d2");
  out.scale_length = d.contains("scale_length") ? d["scale_length"].cast<double>() : 0;
  out.thickness = d.contains("thickness") ? d["thickness"].cast<double>() : 0;
  return out;
}

py::dict descriptor_figure_dict(const py::dict& d, const std::string& name) {
  const Figure f = descriptor_figure(descriptors_from(d), name);
  py::dict out;
  out["title"] = f.title;
  py::list charts;
  for (const Chart& c : f.charts) charts.append(from_chart(c));
  out["charts"] = charts;
  out["columns"] = f.columns;
  return out;
}

// {kind: {..., "precision_recall": {"recall", "precision"}, "queries"}}, as Index.evaluate and
// evaluate_retrieval (under a name) return it.
py::dict precision_recall_chart_dict(const py::dict& evaluation, const std::string& title) {
  std::vector<std::pair<std::string, PrecisionRecall>> curves;
  for (const auto& [kind, scores] : evaluation) {
    const std::string name = py::str(kind);
    if (!py::isinstance<py::dict>(scores) || !scores.cast<py::dict>().contains("precision_recall"))
      throw InputError(name, "expected a dict with 'precision_recall' (as Index.evaluate returns)");
    const py::dict s = scores.cast<py::dict>();
    const py::dict pr = s["precision_recall"].cast<py::dict>();
    PrecisionRecall curve;
    curve.recall = doubles(pr["recall"], "recall");
    curve.precision = doubles(pr["precision"], "precision");
    curve.queries = s.contains("queries") ? s["queries"].cast<std::size_t>() : 0;
    curves.emplace_back(name, std::move(curve));
  }
  return from_chart(precision_recall_chart(curves, title));
}

std::string plot_svg(const py::object& charts, const py::object& path,
                     const std::optional<std::string>& title, int columns) {
  const std::string svg = to_svg(to_figure(charts, title, columns));
  if (!path.is_none()) {
    const std::string file = to_path(path);
    write_file_atomically(file, [&](std::ostream& out) { out << svg; });
  }
  return svg;
}

}  // namespace

py::dict evaluation_dict(const RetrievalScores& scores, const std::vector<ClassScores>& per_class,
                         const PrecisionRecall& curve) {
  py::dict out = scores_dict(scores);
  out["per_class"] = per_class_dict(per_class);
  out["precision_recall"] = curve_dict(curve);
  return out;
}

void register_plots(py::module_& m) {
  m.def("evaluate_retrieval", &evaluate_matrix, py::arg("names"), py::arg("classes"),
        py::arg("distance"),
        R"doc(Retrieval scores of a distance matrix, as `morphex evaluate` computes them.

names, classes: one per model; distance: an n x n matrix (distance[i][j] ranks j for query i;
ties by name). Every model whose class has another member queries all the others. Returns
{'nearest_neighbor', 'first_tier', 'second_tier', 'e_measure', 'dcg', 'queries', 'per_class':
{class: {the same scores, 'models'}}, 'precision_recall': {'recall', 'precision'}}: the curve is
the mean over the queries of the interpolated precision at the recall levels 0, 0.05, ..., 1.)doc");
  m.def("descriptor_figure", &descriptor_figure_dict, py::arg("descriptors"), py::arg("name") = "",
        R"doc(The charts of a description (a dict from describe()), as `morphex describe --plot`.

Returns {'title', 'columns', 'charts': [granulometry, anti-granulometry (when closings were
computed), pattern spectrum, D2]}, each chart {'title', 'x_label', 'y_label', 'series': [{'name',
'x', 'y', 'bars'}], 'x_min', 'x_max', 'y_min', 'y_max'}; bars have one x (bin edge) more than y.
plot_svg() draws it.)doc");
  m.def("precision_recall_chart", &precision_recall_chart_dict, py::arg("evaluation"),
        py::arg("title") = "Precision-recall",
        R"doc(The precision-recall chart of an evaluation, as `morphex evaluate --plot`.

evaluation: {descriptor kind: scores} as Index.evaluate returns it (for evaluate_retrieval's
result, give {'name': result}). Returns a chart dict for plot_svg().)doc");
  m.def("plot_svg", &plot_svg, py::arg("charts"), py::arg("path") = py::none(), py::kw_only(),
        py::arg("title") = py::none(), py::arg("columns") = 2,
        R"doc(SVG text of charts, written by morphex itself (no plotting library needed).

charts: a figure dict ({'title', 'charts', 'columns'}), one chart dict or a list of them (see
descriptor_figure). path: also write it there (atomically). title, columns: the figure's title
and the number of panels per row. Raises ValueError for a series whose x and y do not fit.)doc");
}

}  // namespace morphex::python

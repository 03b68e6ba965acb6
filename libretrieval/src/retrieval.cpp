// SPDX-License-Identifier: GPL-3.0-or-later
#include "morphex/retrieval.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numeric>
#include <sstream>

#include "morphex/mesh.h"

namespace morphex {

std::map<std::string, std::string> parse_cla(const std::string& text, const std::string& name) {
  std::istringstream in(text);
  std::string line;
  int number = 0;
  auto next = [&]() {
    while (std::getline(in, line)) {
      ++number;
      if (line.find_first_not_of(" \t\r") != std::string::npos) return true;
    }
    return false;
  };
  auto fail = [&](const std::string& problem) -> void {
    throw InputError(name, "line " + std::to_string(number) + ": " + problem);
  };
  if (!next() || line.rfind("PSB", 0) != 0) fail("expected the header \"PSB 1\"");
  std::size_t classes = 0, models = 0;
  if (!next() || !(std::istringstream(line) >> classes >> models))
    fail("expected \"<number of classes> <number of models>\"");
  std::map<std::string, std::string> labels;
  for (std::size_t c = 0; c < classes; ++c) {
    std::string class_name, parent;
    std::size_t count = 0;
    if (!next() || !(std::istringstream(line) >> class_name >> parent >> count))
      fail("expected \"<class> <parent class> <number of models>\"");
    for (std::size_t m = 0; m < count; ++m) {
      std::string model;
      if (!next() || !(std::istringstream(line) >> model)) fail("expected a model name");
      if (!labels.emplace(model, class_name).second) fail("model '" + model + "' listed twice");
    }
  }
  if (labels.size() != models)
    fail("the header announces " + std::to_string(models) + " models, the classes list " +
         std::to_string(labels.size()));
  return labels;
}

std::map<std::string, std::string> read_cla(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path, "cannot open the label file");
  std::stringstream text;
  text << in.rdbuf();
  return parse_cla(text.str(), path);
}

RetrievalScores evaluate_retrieval(const std::vector<std::string>& names,
                                   const std::vector<std::string>& classes,
                                   const std::vector<std::vector<double>>& distance) {
  RetrievalScores s;
  const std::size_t n = names.size();
  for (std::size_t q = 0; q < n; ++q) {
    const auto members = std::size_t(std::count(classes.begin(), classes.end(), classes[q]));
    if (members < 2) continue;
    const std::size_t relevant = members - 1;
    std::vector<std::size_t> ranking;
    for (std::size_t j = 0; j < n; ++j)
      if (j != q) ranking.push_back(j);
    std::sort(ranking.begin(), ranking.end(), [&](std::size_t a, std::size_t b) {
      if (distance[q][a] != distance[q][b]) return distance[q][a] < distance[q][b];
      return names[a] < names[b];
    });
    auto hit = [&](std::size_t rank) { return classes[ranking[rank]] == classes[q]; };
    auto hits_within = [&](std::size_t k) {
      std::size_t h = 0;
      for (std::size_t i = 0; i < std::min(k, ranking.size()); ++i) h += hit(i);
      return h;
    };
    ++s.queries;
    s.nearest_neighbor += hit(0);
    s.first_tier += double(hits_within(relevant)) / double(relevant);
    s.second_tier += double(hits_within(2 * relevant)) / double(relevant);
    const std::size_t k32 = std::min<std::size_t>(32, ranking.size());
    const double found = double(hits_within(k32));
    const double precision = found / double(k32), recall = found / double(relevant);
    s.e_measure += found > 0 ? 2 * precision * recall / (precision + recall) : 0;
    double dcg = 0, ideal = 0;
    for (std::size_t i = 0; i < ranking.size(); ++i) {
      const double discount = i == 0 ? 1.0 : 1.0 / std::log2(double(i + 1));
      dcg += hit(i) * discount;
      if (i < relevant) ideal += discount;
    }
    s.dcg += dcg / ideal;
  }
  if (s.queries > 0) {
    const double m = double(s.queries);
    s.nearest_neighbor /= m;
    s.first_tier /= m;
    s.second_tier /= m;
    s.e_measure /= m;
    s.dcg /= m;
  }
  return s;
}

}  // namespace morphex

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

std::vector<double> recall_levels() {
  std::vector<double> levels;
  for (int l = 0; l <= 20; ++l) levels.push_back(l / 20.0);
  return levels;
}

namespace {

// The scores of query q, whose class has `relevant` other members, from its ranking.
QueryScores score_query(std::size_t q, const std::vector<std::size_t>& ranking,
                        const std::vector<std::string>& classes, std::size_t relevant) {
  auto hit = [&](std::size_t rank) { return classes[ranking[rank]] == classes[q]; };
  auto hits_within = [&](std::size_t k) {
    std::size_t h = 0;
    for (std::size_t i = 0; i < std::min(k, ranking.size()); ++i) h += hit(i);
    return h;
  };
  QueryScores s;
  s.query = q;
  s.nearest_neighbor = hit(0);
  s.first_tier = double(hits_within(relevant)) / double(relevant);
  s.second_tier = double(hits_within(2 * relevant)) / double(relevant);
  const std::size_t k32 = std::min<std::size_t>(32, ranking.size());
  const double found = double(hits_within(k32));
  const double precision = found / double(k32), recall = found / double(relevant);
  s.e_measure = found > 0 ? 2 * precision * recall / (precision + recall) : 0;
  double dcg = 0, ideal = 0;
  // at_member[k]: the precision at the rank of the k-th class member found (k = 1 .. relevant).
  std::vector<double> at_member(relevant + 1, 0.0);
  std::size_t members = 0;
  for (std::size_t i = 0; i < ranking.size(); ++i) {
    const double discount = i == 0 ? 1.0 : 1.0 / std::log2(double(i + 1));
    dcg += hit(i) * discount;
    if (i < relevant) ideal += discount;
    if (hit(i)) {
      ++members;
      at_member[members] = double(members) / double(i + 1);
    }
  }
  s.dcg = dcg / ideal;
  // Interpolated precision at recall r: the best precision at a recall of at least r. Between two
  // members the precision only falls, so the ranks of the members are the candidates.
  for (double level : recall_levels()) {
    double best = 0;
    for (std::size_t k = 1; k <= relevant; ++k)  // k / relevant >= level, rounding forgiven
      if (double(k) >= level * double(relevant) - 1e-9) best = std::max(best, at_member[k]);
    s.precision.push_back(best);
  }
  return s;
}

void accumulate(RetrievalScores& sum, const QueryScores& q) {
  ++sum.queries;
  sum.nearest_neighbor += q.nearest_neighbor;
  sum.first_tier += q.first_tier;
  sum.second_tier += q.second_tier;
  sum.e_measure += q.e_measure;
  sum.dcg += q.dcg;
}

void divide(RetrievalScores& s) {
  if (s.queries == 0) return;
  const double m = double(s.queries);
  s.nearest_neighbor /= m;
  s.first_tier /= m;
  s.second_tier /= m;
  s.e_measure /= m;
  s.dcg /= m;
}

}  // namespace

std::vector<QueryScores> score_queries(const std::vector<std::string>& names,
                                       const std::vector<std::string>& classes,
                                       const std::vector<std::vector<double>>& distance) {
  const std::size_t n = names.size();
  bool square = classes.size() == n && distance.size() == n;
  for (const auto& row : distance) square = square && row.size() == n;
  if (!square)
    throw InputError("evaluate", "expected one class per name and an n x n distance matrix");
  std::map<std::string, std::size_t> class_size;
  for (const std::string& c : classes) ++class_size[c];
  std::vector<QueryScores> out;
  for (std::size_t q = 0; q < n; ++q) {
    const std::size_t members = class_size[classes[q]];
    if (members < 2) continue;
    std::vector<std::size_t> ranking;
    for (std::size_t j = 0; j < n; ++j)
      if (j != q) ranking.push_back(j);
    std::sort(ranking.begin(), ranking.end(), [&](std::size_t a, std::size_t b) {
      if (distance[q][a] != distance[q][b]) return distance[q][a] < distance[q][b];
      return names[a] < names[b];
    });
    out.push_back(score_query(q, ranking, classes, members - 1));
  }
  return out;
}

RetrievalScores mean_scores(const std::vector<QueryScores>& queries) {
  RetrievalScores s;
  for (const QueryScores& q : queries) accumulate(s, q);
  divide(s);
  return s;
}

std::vector<ClassScores> class_scores(const std::vector<QueryScores>& queries,
                                      const std::vector<std::string>& classes) {
  std::map<std::string, ClassScores> by_name;
  for (const std::string& c : classes) {
    ClassScores& entry = by_name[c];
    entry.name = c;
    ++entry.models;
  }
  for (const QueryScores& q : queries) accumulate(by_name.at(classes.at(q.query)).scores, q);
  std::vector<ClassScores> out;
  for (auto& [name, entry] : by_name) {
    divide(entry.scores);
    out.push_back(std::move(entry));
  }
  return out;
}

PrecisionRecall precision_recall(const std::vector<QueryScores>& queries) {
  PrecisionRecall out;
  out.recall = recall_levels();
  out.precision.assign(out.recall.size(), 0.0);
  for (const QueryScores& q : queries)
    for (std::size_t l = 0; l < out.precision.size(); ++l) out.precision[l] += q.precision.at(l);
  out.queries = queries.size();
  if (out.queries > 0)
    for (double& p : out.precision) p /= double(out.queries);
  return out;
}

RetrievalScores evaluate_retrieval(const std::vector<std::string>& names,
                                   const std::vector<std::string>& classes,
                                   const std::vector<std::vector<double>>& distance) {
  return mean_scores(score_queries(names, classes, distance));
}

std::vector<ClassScores> evaluate_per_class(const std::vector<std::string>& names,
                                            const std::vector<std::string>& classes,
                                            const std::vector<std::vector<double>>& distance) {
  return class_scores(score_queries(names, classes, distance), classes);
}

PrecisionRecall precision_recall(const std::vector<std::string>& names,
                                 const std::vector<std::string>& classes,
                                 const std::vector<std::vector<double>>& distance) {
  return precision_recall(score_queries(names, classes, distance));
}

}  // namespace morphex

// SPDX-License-Identifier: GPL-3.0-or-later
// Retrieval evaluation with the Princeton Shape Benchmark's measures, and its .cla label files.
#pragma once

#include <map>
#include <string>
#include <vector>

namespace morphex {

// model name (file stem) -> class name. Throws InputError naming the file and line.
std::map<std::string, std::string> read_cla(const std::string& path);
std::map<std::string, std::string> parse_cla(const std::string& text, const std::string& name);

struct RetrievalScores {
  double nearest_neighbor = 0, first_tier = 0, second_tier = 0, e_measure = 0, dcg = 0;
  std::size_t queries = 0;  // models whose class has at least one other member
};

// The recall levels of the precision-recall curves: 0, 0.05, ..., 1 (21 levels).
std::vector<double> recall_levels();

// One query's scores. Every labelled model queries all the others, ranked by distance(i, j) (ties
// by name). For a query of class size C (itself included): NN = is the nearest a class member; FT,
// ST = the fraction of the C-1 class members within the first C-1, 2(C-1) results; E = 2PR/(P+R)
// over the first 32 results; DCG = sum of rel_i / log2(i) (rel_1 undiscounted) over the whole
// ranking, divided by its ideal value. precision[l] is the interpolated precision at
// recall_levels()[l]: the best precision k'/n over the ranks n where the recall k'/(C-1) is at
// least that level (so it never rises with recall, and is 1 at recall 0 when the nearest is a
// member).
struct QueryScores {
  std::size_t query = 0;  // index into the names
  double nearest_neighbor = 0, first_tier = 0, second_tier = 0, e_measure = 0, dcg = 0;
  std::vector<double> precision;
};

// The scores of every model whose class has another member, in the order of `names`. Throws
// InputError when the sizes disagree.
std::vector<QueryScores> score_queries(const std::vector<std::string>& names,
                                       const std::vector<std::string>& classes,
                                       const std::vector<std::vector<double>>& distance);

// The means over the queries.
RetrievalScores mean_scores(const std::vector<QueryScores>& queries);

struct ClassScores {
  std::string name;
  std::size_t models = 0;  // the class size; scores.queries is 0 for a class of one model
  RetrievalScores scores;  // the means over the class's queries
};
// One entry per class of `classes` (the labels of the scored names), in name order.
std::vector<ClassScores> class_scores(const std::vector<QueryScores>& queries,
                                      const std::vector<std::string>& classes);

// The Princeton Shape Benchmark's averaged precision-recall curve: the mean over the queries of
// their interpolated precision at each recall level.
struct PrecisionRecall {
  std::vector<double> recall, precision;  // recall_levels(), and the mean precision at each
  std::size_t queries = 0;
};
PrecisionRecall precision_recall(const std::vector<QueryScores>& queries);

// The same from the distances: the means over the queries, per class, and the curve.
RetrievalScores evaluate_retrieval(const std::vector<std::string>& names,
                                   const std::vector<std::string>& classes,
                                   const std::vector<std::vector<double>>& distance);
std::vector<ClassScores> evaluate_per_class(const std::vector<std::string>& names,
                                            const std::vector<std::string>& classes,
                                            const std::vector<std::vector<double>>& distance);
PrecisionRecall precision_recall(const std::vector<std::string>& names,
                                 const std::vector<std::string>& classes,
                                 const std::vector<std::vector<double>>& distance);

}  // namespace morphex

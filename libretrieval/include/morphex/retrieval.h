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

// Every labelled model queries all the others, ranked by distance(i, j) (ties by name).
// Per query of class size C (itself included): NN = is the nearest a class member; FT, ST = the
// fraction of the C-1 class members within the first C-1, 2(C-1) results; E = 2PR/(P+R) over the
// first 32 results; DCG = sum of rel_i / log2(i) (rel_1 undiscounted) over the whole ranking,
// divided by its ideal value. Scores are means over the queries.
RetrievalScores evaluate_retrieval(const std::vector<std::string>& names,
                                   const std::vector<std::string>& classes,
                                   const std::vector<std::vector<double>>& distance);

}  // namespace morphex

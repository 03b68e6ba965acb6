// SPDX-License-Identifier: GPL-3.0-or-later
// "Did you mean" hints: the known name nearest to a mistyped one, by edit distance.
#pragma once

#include <algorithm>
#include <string>
#include <vector>

namespace morphex {

// Levenshtein distance: insertions, deletions and substitutions, one row at a time.
inline std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j < row.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row.back();
}

// The candidate nearest to `word`, or "" when even the nearest differs in more than half of
// `word` (a hint that far off would mislead).
inline std::string nearest_name(const std::string& word,
                                const std::vector<std::string>& candidates) {
  std::string best;
  std::size_t best_distance = std::max<std::size_t>(2, (word.size() + 1) / 2) + 1;
  for (const std::string& c : candidates)
    if (const std::size_t d = edit_distance(word, c); d < best_distance) {
      best_distance = d;
      best = c;
    }
  return best;
}

}  // namespace morphex

// SPDX-License-Identifier: GPL-3.0-or-later
// k-nearest-neighbour queries at collection scale: DescriptorMatrix (morphex/knn.h) against the
// plain loop over `distance` that query_index used before (vectors of vectors, every distance,
// a full sort), on synthetic descriptors of the default kind's length, same run. Every answer of
// the scan is checked equal to the loop's. Prints one table; --json FILE writes it as JSON.
#include <sys/resource.h>
#include <tbb/global_control.h>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <optional>
#include <random>

#include "bench_harness.h"
#include "morphex/index.h"
#include "morphex/internal/huge_pages.h"
#include "morphex/internal/stopwatch.h"
#include "morphex/knn.h"

namespace {

using namespace morphex;

double peak_rss_mb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return double(usage.ru_maxrss) / 1024.0;
}

// Rows that look like descriptor blocks: nonnegative histogram-like values in [0, 1).
std::vector<double> random_row(std::mt19937_64& rng, std::size_t dims) {
  std::uniform_real_distribution<double> value(0.0, 1.0);
  std::vector<double> row(dims);
  for (double& v : row) v = value(rng);
  return row;
}

// The loop the index used before: every distance, sorted, ties by row.
std::vector<Match> plain_loop(const std::vector<std::vector<double>>& rows,
                              const std::vector<double>& query, std::size_t k, Metric metric) {
  std::vector<Match> all;
  all.reserve(rows.size());
  for (std::size_t r = 0; r < rows.size(); ++r)
    all.push_back({r, distance(query, rows[r], metric)});
  std::sort(all.begin(), all.end(), [](const Match& a, const Match& b) {
    return a.distance != b.distance ? a.distance < b.distance : a.row < b.row;
  });
  all.resize(std::min(k, all.size()));
  return all;
}

// query_index end to end on a stored index: loading one kind from SQLite, then the scan.
nlohmann::json time_index_query(std::size_t rows, std::size_t dims, std::size_t k,
                                std::mt19937_64& rng) {
  namespace fs = std::filesystem;
  const fs::path file = fs::temp_directory_path() / ("bench-knn-" + std::to_string(::getpid()));
  fs::remove(file);
  const Stopwatch write;
  {
    IndexDb db(file.string());
    IndexedMesh m;
    m.hash = m.settings = "synthetic";
    m.status = "ok";
    for (std::size_t r = 0; r < rows; ++r) {
      m.name = "m" + std::to_string(r);
      m.path = "/synthetic/" + m.name + ".off";
      m.descriptors = {{"combined", random_row(rng, dims)}, {"d2", random_row(rng, 64)}};
      db.store(m);
    }
  }
  const double write_s = write.seconds();
  IndexDb db(file.string());
  const Stopwatch load;
  const std::size_t loaded = db.load(true, {"combined"}).size();
  const double load_s = load.seconds();
  const Stopwatch query;
  const auto found = query_index(db, "m0", k, "combined", Metric::L1);
  const double query_s = query.seconds();
  std::cout << "query_index on a stored index of " << loaded << " meshes: written in "
            << std::setprecision(1) << write_s << " s; loading the kind " << std::setprecision(2)
            << load_s << " s; query by name (loading included) " << query_s << " s, "
            << found.size() << " neighbours\n";
  for (const char* suffix : {"", "-wal", "-shm"}) fs::remove(file.string() + suffix);
  return {
      {"index_rows", loaded}, {"write_s", write_s}, {"load_s", load_s}, {"query_index_s", query_s}};
}

}  // namespace

int main(int argc, char** argv) {
  morphex::use_huge_page_malloc(argv);  // first: it may restart the process
  bench::Harness harness("k-nearest-neighbour queries: DescriptorMatrix against the plain loop");
  CLI::App& app = harness.app();
  std::size_t rows = 1000000, dims = 185, k = 10;
  int queries = 10, plain_queries = 3;
  std::vector<unsigned> thread_counts = {1, 2};
  app.add_option("--rows", rows, "Indexed descriptors")->capture_default_str();
  app.add_option("--dims", dims, "Descriptor length (185: the default combined kind)")
      ->capture_default_str();
  app.add_option("-k", k, "Neighbours per query")->capture_default_str();
  app.add_option("--queries", queries, "Queries per metric and thread count")
      ->capture_default_str();
  app.add_option("--plain-queries", plain_queries, "Queries of the plain loop (slow)")
      ->capture_default_str();
  harness.add_thread_counts(thread_counts, "Thread counts to measure (comma-separated)");
  harness.add_json("Also write the table as JSON");
  std::size_t index_rows = 0;
  app.add_option("--index-rows", index_rows,
                 "Also store this many descriptors in a temporary SQLite index and time "
                 "query_index on it, loading included (0: skip)")
      ->capture_default_str();
  if (const std::optional<int> stop = harness.parse(argc, argv)) return *stop;

  std::mt19937_64 rng(20261125);
  const Stopwatch load;
  DescriptorMatrix matrix(dims);
  matrix.reserve(rows);
  std::vector<std::vector<double>> plain;
  plain.reserve(rows);
  for (std::size_t r = 0; r < rows; ++r) {
    plain.push_back(random_row(rng, dims));
    matrix.add(plain.back());
  }
  std::cout << rows << " descriptors of " << dims << " doubles (" << std::fixed
            << std::setprecision(0) << double(rows * dims * sizeof(double)) / 1048576.0
            << " MiB matrix) made in " << std::setprecision(2) << load.seconds() << " s\n";
  std::vector<std::vector<double>> probes;
  for (int q = 0; q < queries; ++q) probes.push_back(random_row(rng, dims));

  nlohmann::json table = nlohmann::json::array();
  std::cout << std::left << std::setw(7) << "metric" << std::right << std::setw(9) << "threads"
            << std::setw(14) << "scan med s" << std::setw(12) << "scan max s" << std::setw(14)
            << "plain med s" << std::setw(10) << "speed-up" << std::setw(10) << "agree" << '\n';
  for (const Metric metric : {Metric::L1, Metric::L2, Metric::ChiSquare}) {
    for (const unsigned threads : thread_counts) {
      tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
      std::vector<double> scan_s, plain_s;
      int agree = 0;
      for (int q = 0; q < queries; ++q) {
        const Stopwatch t;
        const std::vector<Match> got = matrix.nearest(probes[q], k, metric);
        scan_s.push_back(t.seconds());
        if (q >= plain_queries || threads != thread_counts.front()) continue;
        const Stopwatch p;
        const std::vector<Match> expected = plain_loop(plain, probes[q], k, metric);
        plain_s.push_back(p.seconds());
        const bool same = std::equal(got.begin(), got.end(), expected.begin(), expected.end(),
                                     [](const Match& a, const Match& b) {
                                       return a.row == b.row && a.distance == b.distance;
                                     });
        agree += same;
        if (!same) {
          std::cerr << "bench_knn: the scan disagrees with the plain loop\n";
          return 1;
        }
      }
      const double plain_median = bench::median_of(plain_s);
      table.push_back({{"metric", to_string(metric)},
                       {"threads", threads},
                       {"rows", rows},
                       {"dims", dims},
                       {"k", k},
                       {"scan_median_s", bench::median_of(scan_s)},
                       {"scan_max_s", *std::max_element(scan_s.begin(), scan_s.end())},
                       {"plain_median_s", plain_median},
                       {"agreeing_queries", agree}});
      std::cout << std::left << std::setw(7) << to_string(metric) << std::right << std::setw(9)
                << threads << std::setprecision(4) << std::setw(14) << bench::median_of(scan_s)
                << std::setw(12) << *std::max_element(scan_s.begin(), scan_s.end());
      if (plain_s.empty())
        std::cout << std::setw(14) << "-" << std::setw(10) << "-" << std::setw(10) << "-";
      else
        std::cout << std::setw(14) << plain_median << std::setprecision(1) << std::setw(9)
                  << plain_median / bench::median_of(scan_s) << "x" << std::setw(7) << agree << "/"
                  << plain_s.size();
      std::cout << '\n';
    }
  }
  std::cout << "peak memory " << std::setprecision(0) << peak_rss_mb()
            << " MiB (matrix and the plain loop's vectors)\n";
  if (index_rows > 0) table.push_back(time_index_query(index_rows, dims, k, rng));
  if (!harness.write_json(table)) return 2;
  return 0;
}

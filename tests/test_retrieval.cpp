// SPDX-License-Identifier: GPL-3.0-or-later
// Descriptors and retrieval: metrics on a hand-checked example, .cla parsing, scale invariance and
// the documented rotation behaviour of the granulometry, the procedural collection.
#include <gtest/gtest.h>

#include <sqlite3.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <random>

#include "morphex/boolean.h"
#include "morphex/check.h"
#include "morphex/collection.h"
#include "morphex/descriptors.h"
#include "morphex/index.h"
#include "morphex/index_mpi.h"  // threads_per_rank: inline, no MPI needed
#include "morphex/io.h"
#include "morphex/knn.h"
#include "morphex/retrieval.h"
#include "morphex/shapes.h"
#include "morphex/simplify.h"

using namespace morphex;

namespace {

Mesh l_shape() {
  return compute_boolean(check_solid(make_box(Point(0, 0, 0), Point(2, FT(1) / 2, FT(1) / 2))),
                         check_solid(make_box(Point(0, 0, 0), Point(FT(1) / 2, 3, FT(1) / 2))),
                         BooleanOp::Union)
      .solid;
}

DescriptorSettings quick() {
  DescriptorSettings s;
  s.scales = 2;
  s.closings = false;
  s.d2_samples = 512;
  return s;
}

}  // namespace

TEST(Retrieval, ScoresOfAHandCheckedExample) {
  // a1, a2 in class A; b1, b2 in class B. Rankings (nearest first):
  //   a1: b1 a2 b2   a2: b1 a1 b2   b1: a2 a1 b2   b2: b1 a1 a2
  const std::vector<std::string> names = {"a1", "a2", "b1", "b2"}, classes = {"A", "A", "B", "B"};
  const std::vector<std::vector<double>> d = {
      {0, 1, 0.7, 3}, {1, 0, 0.5, 4}, {0.7, 0.5, 0, 1}, {3, 4, 1, 0}};
  const RetrievalScores s = evaluate_retrieval(names, classes, d);
  EXPECT_EQ(s.queries, 4u);
  EXPECT_DOUBLE_EQ(s.nearest_neighbor, 0.25);  // only b2 finds its class first
  EXPECT_DOUBLE_EQ(s.first_tier, 0.25);
  EXPECT_DOUBLE_EQ(s.second_tier, 0.75);                  // b1's class mate is third
  EXPECT_DOUBLE_EQ(s.e_measure, 0.5);                     // 3 results, 1 relevant: P = 1/3, R = 1
  EXPECT_DOUBLE_EQ(s.dcg, (3 + 1 / std::log2(3.0)) / 4);  // ranks 2 count fully, rank 3 by 1/log2 3
}

// a1, a2, a3 in class A; b1, b2 in B; c1 alone in C, last in every ranking. Rankings:
//   a1: a2 b1 a3 b2 c1   a2: a1 a3 b1 b2 c1   a3: a2 a1 b1 b2 c1
//   b1: a1 a2 a3 b2 c1   b2: a1 a2 a3 b1 c1
TEST(Retrieval, PrecisionRecallAndClassScoresOfAHandCheckedExample) {
  const std::vector<std::string> names = {"a1", "a2", "a3", "b1", "b2", "c1"};
  const std::vector<std::string> classes = {"A", "A", "A", "B", "B", "C"};
  const std::vector<std::vector<double>> d = {
      {0, 1, 4, 2, 5, 100},  {1, 0, 3, 6, 7, 100},  {4, 3, 0, 8, 9, 100},
      {2, 6, 8, 0, 10, 100}, {5, 7, 9, 10, 0, 100}, {100, 100, 100, 100, 100, 0},
  };
  const std::vector<QueryScores> queries = score_queries(names, classes, d);
  ASSERT_EQ(queries.size(), 5u);  // c1 has no class mate to find
  // a1 finds its mates at ranks 1 and 3: precision 1 up to recall 1/2, then 2/3. a2 and a3 find
  // theirs first (precision 1 throughout); b1 and b2 find their one mate 4th (1/4 throughout).
  const PrecisionRecall pr = precision_recall(queries);
  ASSERT_EQ(pr.recall.size(), 21u);
  ASSERT_EQ(pr.precision.size(), 21u);
  EXPECT_EQ(pr.queries, 5u);
  for (std::size_t l = 0; l < 21; ++l) {
    EXPECT_DOUBLE_EQ(pr.recall[l], double(l) / 20);
    EXPECT_NEAR(pr.precision[l], l <= 10 ? (3 + 0.5) / 5 : (2 + 2.0 / 3 + 0.5) / 5, 1e-12) << l;
  }
  EXPECT_EQ(queries[0].precision[10], 1.0);  // recall 1/2 is reached at rank 1
  EXPECT_NEAR(queries[0].precision[11], 2.0 / 3, 1e-15);
  // Per class: 6 results per query, so E is over 5 results (P = found / 5, R = 1).
  const std::vector<ClassScores> per_class = class_scores(queries, classes);
  ASSERT_EQ(per_class.size(), 3u);
  const ClassScores &a = per_class[0], &b = per_class[1], &c = per_class[2];
  EXPECT_EQ(a.name, "A");
  EXPECT_EQ(a.models, 3u);
  EXPECT_EQ(a.scores.queries, 3u);
  EXPECT_DOUBLE_EQ(a.scores.nearest_neighbor, 1);
  EXPECT_DOUBLE_EQ(a.scores.first_tier, (0.5 + 1 + 1) / 3);  // a1 has b1 among its first two
  EXPECT_DOUBLE_EQ(a.scores.second_tier, 1);
  EXPECT_DOUBLE_EQ(a.scores.e_measure, 4.0 / 7);  // P = 2/5, R = 1
  EXPECT_DOUBLE_EQ(a.scores.dcg, ((1 + 1 / std::log2(3.0)) / 2 + 2) / 3);
  EXPECT_EQ(b.name, "B");
  EXPECT_EQ(b.models, 2u);
  EXPECT_EQ(b.scores.queries, 2u);
  EXPECT_DOUBLE_EQ(b.scores.nearest_neighbor, 0);
  EXPECT_DOUBLE_EQ(b.scores.second_tier, 0);
  EXPECT_DOUBLE_EQ(b.scores.e_measure, 1.0 / 3);  // P = 1/5, R = 1
  EXPECT_DOUBLE_EQ(b.scores.dcg, 0.5);            // 1 / log2(4)
  EXPECT_EQ(c.name, "C");
  EXPECT_EQ(c.models, 1u);
  EXPECT_EQ(c.scores.queries, 0u);
  // The means over all queries are the means of the classes' sums, as evaluate_retrieval has them.
  const RetrievalScores all = evaluate_retrieval(names, classes, d);
  EXPECT_EQ(all.queries, 5u);
  EXPECT_DOUBLE_EQ(all.nearest_neighbor, 3.0 / 5);
  EXPECT_NEAR(all.dcg, (3 * a.scores.dcg + 2 * b.scores.dcg) / 5, 1e-15);
  EXPECT_NEAR(all.e_measure, (3 * a.scores.e_measure + 2 * b.scores.e_measure) / 5, 1e-15);
  EXPECT_EQ(evaluate_per_class(names, classes, d).size(), 3u);
  EXPECT_EQ(precision_recall(names, classes, d).precision, pr.precision);
  EXPECT_THROW(score_queries(names, {"A"}, d), InputError);
}

TEST(Retrieval, ClaFilesAreParsedAndCheckedWithLineNumbers) {
  const auto labels = parse_cla("PSB 1\n2 3\n\nA 0 2\nx\ny\n\nB 0 1\nz\n", "l.cla");
  EXPECT_EQ(labels.size(), 3u);
  EXPECT_EQ(labels.at("y"), "A");
  EXPECT_EQ(labels.at("z"), "B");
  try {
    parse_cla("PSB 1\n1 3\nA 0 2\nx\ny\n", "l.cla");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "l.cla: line 5: the header announces 3 models, the classes list 2");
  }
  EXPECT_THROW(parse_cla("OFF\n", "l.cla"), InputError);
}

// Every component of every descriptor kind agrees within `tolerance`.
void expect_same_descriptors(const Descriptors& a, const Descriptors& b, double tolerance) {
  for (const std::string& kind : descriptor_kinds()) {
    const auto u = descriptor_vector(a, kind), v = descriptor_vector(b, kind);
    ASSERT_EQ(u.size(), v.size()) << kind;
    for (std::size_t i = 0; i < u.size(); ++i)
      EXPECT_NEAR(u[i], v[i], tolerance) << kind << "[" << i << "]";
  }
}

TEST(Descriptors, ScaledCopyHasTheSameGranulometry) {
  const Mesh a = l_shape();
  const Mesh b = transformed(a, Transformation(CGAL::SCALING, FT(5) / 2));
  const Descriptors da = describe(check_solid(a), quick()), db = describe(check_solid(b), quick());
  ASSERT_EQ(da.granulometry.size(), 2u);
  EXPECT_NEAR(db.scale_length / da.scale_length, 2.5, 1e-12);
  for (std::size_t i = 0; i < 2; ++i) EXPECT_NEAR(da.granulometry[i], db.granulometry[i], 1e-9);
  EXPECT_LT(da.granulometry[1], da.granulometry[0]);  // growing cubes remove more
  EXPECT_LT(da.granulometry[1], 0.9);
  EXPECT_LT(l1_distance(da.d2, db.d2), 1e-9);  // same samples, distances divided by their mean
}

// An asymmetric solid (three distinct principal moments, non-zero skew on the first two axes)
// under an exact similarity: scale 5/2, a rational rotation, a rational shift.
TEST(Descriptors, InvariantUnderExactScaleRotationAndTranslation) {
  const Mesh a = compute_boolean(check_solid(l_shape()),
                                 check_solid(make_box(Point(FT(3) / 2, 0, 0), Point(2, 1, 1))),
                                 BooleanOp::Union)
                     .solid;
  const Transformation similarity = Transformation(CGAL::TRANSLATION, Vector(FT(7) / 3, -1, 2)) *
                                    Transformation(CGAL::SCALING, FT(5) / 2) *
                                    quaternion_rotation(3, 1, -2, 5);
  Mesh b = transformed(a, similarity);
  make_exact(b);
  DescriptorSettings s;
  s.scales = 3;
  s.d2_samples = 2000;
  const Descriptors da = describe(check_solid(a), s), db = describe(check_solid(b), s);
  EXPECT_NEAR(db.scale_length / da.scale_length, 2.5, 1e-12);
  ASSERT_EQ(da.granulometry.size(), 3u);
  ASSERT_EQ(da.anti_granulometry.size(), 3u);
  ASSERT_EQ(da.opening_residue.size(), 18u);
  // The rotated copy is turned back to the principal axes in double precision, so its cubes meet
  // the surface within rounding of the original's: the same descriptor up to rounding.
  expect_same_descriptors(da, db, 1e-6);
  // ... and not a trivial one: the scales were chosen so that the openings see the arms.
  EXPECT_GT(da.granulometry.front(), 0.5);
  EXPECT_LT(da.granulometry.back(), da.granulometry.front());
  EXPECT_GT(da.anti_granulometry.back(), 0.0);
}

TEST(Descriptors, PoseNormalisationMakesRotatedCopiesAgree) {
  const Mesh a = l_shape();
  const Mesh turned = transformed(a, quaternion_rotation(3, 1, -2, 5));
  const Descriptors da = describe(check_solid(a), quick()),
                    dt = describe(check_solid(turned), quick());
  for (std::size_t i = 0; i < 2; ++i) EXPECT_NEAR(da.granulometry[i], dt.granulometry[i], 1e-3);
  // Documented: without pose normalisation the cube SE sees the rotation.
  DescriptorSettings raw = quick();
  raw.normalise_pose = false;
  const Descriptors ra = describe(check_solid(a), raw), rt = describe(check_solid(turned), raw);
  EXPECT_GT(l1_distance(ra.granulometry, rt.granulometry), 1e-3);
}

TEST(Descriptors, ScalesFollowTheThicknessSoFewAreEmptyOrFull) {
  // A ball and a flat ellipsoid (a fifth as thick): the same default scales, relative to each
  // one's thickness, leave both with informative openings (neither all full nor all empty).
  const Mesh ball = make_icosphere(2, 1);
  Mesh flat = transformed(ball, Transformation(2, 0, 0, 0, FT(3) / 2, 0, 0, 0, FT(1) / 5));
  make_exact(flat);
  for (const Mesh& m : {ball, flat}) {
    DescriptorSettings s;
    s.closings = false;
    s.d2_samples = 64;
    const Descriptors d = describe(check_solid(m), s);
    ASSERT_EQ(d.granulometry.size(), std::size_t(s.scales));
    const auto full = std::count_if(d.granulometry.begin(), d.granulometry.end(),
                                    [](double g) { return g > 0.999; });
    const auto empty = std::count_if(d.granulometry.begin(), d.granulometry.end(),
                                     [](double g) { return g < 0.001; });
    EXPECT_LE(full + empty, 3) << "thickness " << d.thickness;
    EXPECT_GT(d.granulometry.front(), 0.8);
  }
}

TEST(Descriptors, MetricsOnAHandCheckedPair) {
  const std::vector<double> a = {1, 0, 2}, b = {0, 0, 4};
  EXPECT_DOUBLE_EQ(distance(a, b, Metric::L1), 3);
  EXPECT_DOUBLE_EQ(distance(a, b, Metric::L2), std::sqrt(5.0));
  EXPECT_DOUBLE_EQ(distance(a, b, Metric::ChiSquare), 1.0 / 1 + 4.0 / 6);  // the 0/0 term omitted
  EXPECT_EQ(parse_metric("chi2"), Metric::ChiSquare);
  EXPECT_THROW(parse_metric("cosine"), InputError);
  EXPECT_THROW(distance(a, {1, 2}, Metric::L1), InputError);
}

TEST(Simplify, CopyIsAValidSolidWithinTheBudgetAndCloseInVolume) {
  const Mesh sphere = make_icosphere(4, 1);  // 5,120 facets
  SimplifyReport report;
  const Mesh copy = simplified_solid(to_double(sphere), 500, &report);
  EXPECT_TRUE(report.simplified);
  EXPECT_EQ(report.input_facets, 5120u);
  EXPECT_LE(copy.triangles.size(), 510u);
  EXPECT_EQ(report.output_facets, copy.triangles.size());
  EXPECT_TRUE(check_mesh(copy).valid_solid());
  const double v = CGAL::to_double(signed_volume(copy)),
               v0 = CGAL::to_double(signed_volume(sphere));
  EXPECT_NEAR(v / v0, 1.0, 0.02);
  // Small enough already: the input comes back unchanged.
  const Mesh same = simplified_solid(to_double(sphere), 10000, &report);
  EXPECT_FALSE(report.simplified);
  EXPECT_EQ(same.triangles.size(), 5120u);
}

TEST(Descriptors, InvalidInputIsRefused) {
  Mesh open = make_cube(FT(1));
  open.triangles.pop_back();
  EXPECT_THROW(describe(check_solid(open)), InvalidSolid);
}

TEST(Collection, EveryShapeIsAValidSolidWithItsLabel) {
  const auto meshes = make_collection(2, 7);
  ASSERT_EQ(meshes.size(), 2 * collection_families().size());
  for (const LabelledMesh& m : meshes) {
    const MeshReport r = check_mesh(m.mesh);
    EXPECT_TRUE(r.valid_solid()) << m.name << ": " << describe_problems(r);
    EXPECT_EQ(m.name.rfind(m.label + "-", 0), 0u);
    EXPECT_EQ(r.genus, m.label == "frame" ? 1 : 0) << m.name;
  }
  EXPECT_EQ(to_cla(meshes).rfind("PSB 1\n6 12\n", 0), 0u);
  // deterministic for a seed
  EXPECT_EQ(signed_volume(make_collection(1, 7)[0].mesh), signed_volume(meshes[0].mesh));
}

// The index library end to end: a small labelled collection indexed through a quick descriptor
// pipeline, resumed, queried by name and by file, evaluated against its labels.
TEST(Index, IndexResumeQueryAndEvaluate) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("morphex-index-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const auto meshes = make_collection(2, 5);
  std::map<std::string, std::string> labels;
  std::vector<IndexItem> items;
  WriteOptions exact;
  exact.exact = true;
  for (const LabelledMesh& m : meshes) {
    const std::string path = (dir / (m.name + ".off")).string();
    write_mesh(m.mesh, path, exact);
    items.push_back(index_item(path));
    labels[m.name] = m.label;
  }
  items.push_back(index_item((dir / "missing.off").string()));
  const nlohmann::json quick = nlohmann::json::parse(
      R"({"pipeline": [{"type": "read", "path": "${input}"},
          {"type": "describe", "scales": 2, "closings": false, "d2_samples": 256}]})");
  const IndexPipeline pipeline = make_index_pipeline(&quick, "quick", {}, true);
  IndexDb db((dir / "index.sqlite").string());
  std::size_t calls = 0;
  const IndexSummary first =
      index_meshes(db, pipeline, items,
                   [&](const IndexItem&, const std::string&, const IndexProgress&) { ++calls; });
  EXPECT_EQ(first.indexed, meshes.size());
  ASSERT_EQ(first.errors.size(), 1u);
  EXPECT_EQ(first.errors[0].first, items.back().path);
  EXPECT_TRUE(std::filesystem::path(first.errors[0].first).is_absolute());
  EXPECT_EQ(calls, meshes.size() + 1);
  // a re-run skips what is up to date; another pipeline re-describes
  EXPECT_EQ(index_meshes(db, pipeline, items).skipped, meshes.size());

  const std::string& probe = meshes[0].name;
  const auto by_name = query_index(db, probe, 3, "d2", Metric::L1);
  ASSERT_EQ(by_name.size(), 3u);
  EXPECT_TRUE(std::none_of(by_name.begin(), by_name.end(),
                           [&](const Neighbour& n) { return n.name == probe; }));
  EXPECT_LE(by_name[0].distance, by_name[1].distance);
  // by its path, an indexed mesh is the same query as by its name (issue 44: they disagreed)
  const auto by_path = query_index(db, items[0].file, 3, "d2", Metric::L1);
  ASSERT_EQ(by_path.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(by_path[i].name, by_name[i].name);
    EXPECT_EQ(by_path[i].distance, by_name[i].distance);
  }
  // the same mesh as a file, not looked up in the index, is described again: itself at 0
  const auto by_file = query_index(db, items[0].file, 1, "d2", Metric::L1, false);
  ASSERT_EQ(by_file.size(), 1u);
  EXPECT_EQ(by_file[0].name, probe);
  EXPECT_EQ(by_file[0].distance, 0.0);
  EXPECT_THROW(query_index(db, (dir / "nosuch.off").string(), 1, "d2", Metric::L1), InputError);

  labels.erase(meshes[1].name);
  const IndexEvaluation e = evaluate_index(db, labels, Metric::L1);
  EXPECT_EQ(e.models, meshes.size() - 1);
  EXPECT_EQ(e.unlabelled, 1u);
  ASSERT_FALSE(e.scores.empty());
  for (const auto& [kind, s] : e.scores) {
    EXPECT_EQ(s.queries, meshes.size() - 2) << kind;  // the unlabelled one's partner is alone
    EXPECT_GE(s.nearest_neighbor, 0.0);
    EXPECT_LE(s.nearest_neighbor, 1.0);
  }
  // a pipeline without a describe stage is refused before any work
  const nlohmann::json no_describe =
      nlohmann::json::parse(R"({"pipeline": [{"type": "read", "path": "${input}"}]})");
  EXPECT_THROW(make_index_pipeline(&no_describe, "bad", {}, false), pipeline::PipelineError);
  fs::remove_all(dir);
}

// The matrix scan gives exactly the plain loop's answer (distances bit for bit, ties by row) on
// every metric, with repeated rows (ties the rounding of reordered sums could swap), an excluded
// row, zero entries (chi-square's empty bins) and k beyond the number of rows.
TEST(DescriptorMatrix, NearestEqualsThePlainLoop) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> value(0.0, 1.0);
  const std::size_t dims = 37, rows = 3000;
  DescriptorMatrix matrix(dims);
  std::vector<std::vector<double>> plain;
  for (std::size_t r = 0; r < rows; ++r) {
    std::vector<double> row(dims);
    for (double& v : row) v = value(rng) < 0.2 ? 0.0 : value(rng);
    if (r % 100 == 7) row = plain[r - 7];  // exact duplicates
    plain.push_back(row);
    matrix.add(row);
  }
  EXPECT_THROW(matrix.add(std::vector<double>(dims + 1)), InputError);
  for (const Metric metric : {Metric::L1, Metric::L2, Metric::ChiSquare}) {
    for (const std::size_t query_row : {std::size_t(0), std::size_t(107), std::size_t(2999)}) {
      const std::vector<double>& query = plain[query_row];
      for (const std::size_t exclude : {DescriptorMatrix::kNone, query_row}) {
        for (const std::size_t k : {std::size_t(1), std::size_t(25), rows + 5}) {
          std::vector<Match> expected;
          for (std::size_t r = 0; r < rows; ++r)
            if (r != exclude) expected.push_back({r, distance(query, plain[r], metric)});
          std::sort(expected.begin(), expected.end(), [](const Match& a, const Match& b) {
            return a.distance != b.distance ? a.distance < b.distance : a.row < b.row;
          });
          expected.resize(std::min(k, expected.size()));
          const std::vector<Match> got = matrix.nearest(query, k, metric, exclude);
          ASSERT_EQ(got.size(), expected.size());
          for (std::size_t i = 0; i < got.size(); ++i) {
            EXPECT_EQ(got[i].row, expected[i].row) << to_string(metric) << " rank " << i;
            EXPECT_EQ(got[i].distance, expected[i].distance) << to_string(metric) << " rank " << i;
          }
        }
      }
    }
  }
}

// Descriptors are stored as binary doubles and read back bit for bit, only the kinds asked for;
// an index written by earlier versions (JSON text vectors) still reads.
TEST(IndexDb, DescriptorsRoundTripAndOldJsonVectors) {
  namespace fs = std::filesystem;
  const fs::path file = fs::temp_directory_path() / ("morphex-db-" + std::to_string(::getpid()));
  fs::remove(file);
  const std::vector<double> a = {0.1, 1.0 / 3.0, -2.5e-300, 6.02e23}, b = {1, 2};
  {
    IndexDb db(file.string());
    IndexedMesh m;
    m.name = "m";
    m.path = "/x/m.off";
    m.hash = "h";
    m.settings = "s";
    m.status = "ok";
    m.descriptors = {{"a", a}, {"b", b}};
    db.store(m);
    const auto only_a = db.load(true, {"a"});
    ASSERT_EQ(only_a.size(), 1u);
    EXPECT_EQ(only_a[0].descriptors.size(), 1u);
    EXPECT_EQ(only_a[0].descriptors.at("a"), a);
    EXPECT_TRUE(db.load(true, {})[0].descriptors.empty());
    EXPECT_EQ(db.load()[0].descriptors.at("b"), b);
    EXPECT_EQ(db.status("/x/m.off", "h", "s"), "ok");
    EXPECT_EQ(db.status("/x/m.off", "other", "s"), "");
  }
  sqlite3* raw = nullptr;
  ASSERT_EQ(sqlite3_open(file.string().c_str(), &raw), SQLITE_OK);
  const std::string old = "UPDATE descriptors SET vector = '" + nlohmann::json(a).dump() + "'";
  ASSERT_EQ(sqlite3_exec(raw, old.c_str(), nullptr, nullptr, nullptr), SQLITE_OK);
  sqlite3_close(raw);
  IndexDb db(file.string());
  EXPECT_EQ(db.load()[0].descriptors.at("b"), a);
  EXPECT_TRUE(db.remove("/x/m.off"));
  EXPECT_FALSE(db.remove("/x/m.off"));
  EXPECT_TRUE(db.load(false).empty());
  fs::remove(file);
}

// How MPI ranks share a node's threads (decided by libretrieval, the command line passes only the
// user's --threads): the user's number wins; otherwise the cores are shared, at least one each.
TEST(Retrieval, RanksShareTheirNodesCoresUnlessThreadsAreGiven) {
  EXPECT_EQ(threads_per_rank(0, 4, 16), 4u);
  EXPECT_EQ(threads_per_rank(0, 3, 8), 2u);
  EXPECT_EQ(threads_per_rank(0, 8, 2), 1u);  // more ranks than cores: one thread each
  EXPECT_EQ(threads_per_rank(0, 1, 8), 8u);
  EXPECT_EQ(threads_per_rank(0, 0, 8), 8u);   // an unknown count of ranks: this one alone
  EXPECT_EQ(threads_per_rank(6, 4, 16), 6u);  // --threads 6
}

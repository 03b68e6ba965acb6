// SPDX-License-Identifier: GPL-3.0-or-later
// The libraries' result structs as JSON (morphex/json.h, morph_json.h, retrieval_json.h): the keys
// and values on hand-checked cases, as the command line and Python print them.
#include <gtest/gtest.h>

#include "morphex/check.h"
#include "morphex/descriptor_settings.h"
#include "morphex/json.h"
#include "morphex/morph_json.h"
#include "morphex/retrieval_json.h"
#include "morphex/shapes.h"

namespace morphex {
namespace {

using nlohmann::json;

TEST(Json, UnitCubeCheckReport) {
  const json j = check_mesh(make_cube(FT(1) / 2));
  EXPECT_EQ(j["valid"], true);
  EXPECT_EQ(j["closed"], true);
  EXPECT_EQ(j["faces"], 12);
  EXPECT_EQ(j["vertices"], 8);
  EXPECT_EQ(j["components"], 1);
  EXPECT_EQ(j["genus"], 0);
  EXPECT_EQ(j["volume_exact"], "1");
  EXPECT_EQ(j["volume"], 1.0);
  EXPECT_EQ(j["volume_approx"], 1.0);
  EXPECT_EQ(j["self_intersecting"], false);
  EXPECT_EQ(j["self_intersections"], 0);
  EXPECT_FALSE(j.contains("first_self_intersection"));
  EXPECT_EQ(j["bbox"], json::parse(R"({"min": [-0.5, -0.5, -0.5], "max": [0.5, 0.5, 0.5]})"));
  for (const char* key :
       {"border_edges", "non_manifold_edges", "non_manifold_vertices", "degenerate_faces"})
    EXPECT_EQ(j[key], 0) << key;
  EXPECT_EQ(j["consistently_oriented"], true);
  EXPECT_EQ(j["outward"], true);
  EXPECT_EQ(j.size(), 18u);
}

TEST(Json, OpenSurfaceHasNoVolumeOrGenus) {
  Mesh open = make_cube(FT(1));
  open.triangles.pop_back();
  const json j = check_mesh(open);
  EXPECT_EQ(j["closed"], false);
  EXPECT_EQ(j["valid"], false);
  EXPECT_EQ(j["border_edges"], 3);
  EXPECT_TRUE(j["genus"].is_null());
  EXPECT_TRUE(j["volume"].is_null());
  EXPECT_TRUE(j["volume_exact"].is_null());
}

TEST(Json, BooleanAndUnionStats) {
  BooleanStats s;
  s.candidate_pairs = 10;
  s.cut_facets_a = 3;
  s.cut_facets_b = 4;
  s.segments = 5;
  s.seconds.classify = 0.25;
  const json j = s;
  EXPECT_EQ(j["candidate_pairs"], 10);
  EXPECT_EQ(j["intersected_facets"], 7);
  EXPECT_EQ(j["segments"], 5);
  EXPECT_EQ(j["phases"]["classify"], 0.25);
  EXPECT_EQ(j["phases"].size(), 5u);  // steps 2-7; the input check is the Solids'
  UnionStats u;
  u.binary_unions = 2;
  u.disjoint_merges = 1;
  EXPECT_EQ(json(u), json::parse(R"({"binary_unions": 2, "disjoint_merges": 1})"));
}

TEST(Json, RepairSolidifyAndRounding) {
  RepairReport r;
  r.changed = true;
  r.intersecting_pairs = 2;
  const json rj = r;
  EXPECT_EQ(rj["changed"], true);
  EXPECT_EQ(rj["intersecting_pairs"], 2);
  EXPECT_EQ(rj.size(), 9u);

  SolidifyReport s;
  s.method = "soup";
  s.changed = true;
  s.filled_holes = 1;
  const json sj = s;
  EXPECT_EQ(sj["method"], "soup");
  EXPECT_EQ(sj["filled_holes"], 1);
  EXPECT_EQ(sj["summary"], describe(s));
  EXPECT_EQ(sj["summary"], "soup: filled holes 1");

  RoundingReport g;
  g.broken_pairs = 3;
  g.seconds_check = 0.5;
  json gj = g;
  EXPECT_EQ(gj["resolved_pairs"], 3);
  EXPECT_EQ(gj["phases"]["check"], 0.5);
  EXPECT_FALSE(gj.contains("volume_change"));  // not measured
  g.volume_measured = true;
  g.volume_change = -0.125;
  gj = g;
  EXPECT_EQ(gj["volume_change"], -0.125);
  EXPECT_EQ(gj["relative_volume_change"], 0.0);
}

TEST(Json, MorphologyStatsAndDescriptors) {
  MorphologyStats m;
  m.pieces = 6;
  m.binary_unions = 5;
  EXPECT_EQ(json(m)["pieces"], 6);
  EXPECT_EQ(json(m)["binary_unions"], 5);
  MinkowskiStats k;
  k.seconds_union = 2;
  EXPECT_EQ(json(k)["phases"]["union"], 2.0);

  Descriptors d;
  d.scale_length = 2;
  d.thickness = 0.5;
  d.facets = 12;
  d.open_radii = {0.1, 0.2};
  d.granulometry = {1, 0.5};
  d.pattern_spectrum = {0, 0.5};
  d.components = {1, 1};
  d.opening_residue.assign(12, 0);
  d.d2 = {0.25, 0.75};
  const json j = d;
  EXPECT_EQ(j["scale_length"], 2.0);
  EXPECT_EQ(j["filtered_facets"], 12);
  EXPECT_EQ(j["simplified"], false);
  EXPECT_EQ(j["granulometry"], json::parse("[1.0, 0.5]"));
  EXPECT_EQ(j["d2"], json::parse("[0.25, 0.75]"));
  for (const std::string& kind : descriptor_kinds())
    EXPECT_EQ(j["vectors"][kind], json(descriptor_vector(d, kind))) << kind;
  EXPECT_EQ(j["vectors"]["d2"], j["d2"]);
  // read back (as `morphex describe` reads the describe stage's report)
  EXPECT_EQ(json(j.get<Descriptors>()), j);
  EXPECT_THROW(json({{"granulometry", "high"}}).get<Descriptors>(), InputError);
}

TEST(Json, RetrievalResults) {
  RetrievalScores s;
  s.nearest_neighbor = 1;
  s.first_tier = 0.5;
  s.queries = 4;
  const json sj = s;
  EXPECT_EQ(sj, json::parse(R"({"nearest_neighbor": 1.0, "first_tier": 0.5, "second_tier": 0.0,
                                "e_measure": 0.0, "dcg": 0.0, "queries": 4})"));
  ClassScores c{"chairs", 5, s};
  json cj = c;
  EXPECT_EQ(cj["models"], 5);
  cj.erase("models");
  EXPECT_EQ(cj, sj);
  PrecisionRecall pr{{0, 1}, {1, 0.5}, 3};
  EXPECT_EQ(json(pr), json::parse(R"({"recall": [0.0, 1.0], "precision": [1.0, 0.5]})"));
  Neighbour n{"cube", "/data/cube.off", 0.25, 7};
  EXPECT_EQ(json(n), json::parse(R"({"name": "cube", "path": "/data/cube.off",
                                     "distance": 0.25, "id": 7})"));
}

TEST(Json, IndexSummaryAndEntry) {
  IndexSummary s;
  s.indexed = 3;
  s.skipped = 1;
  s.errors = {{"/a.off", "not closed"}};
  s.seconds = 30;
  s.processes = 2;
  const json j = s;
  EXPECT_EQ(j["indexed"], 3);
  EXPECT_EQ(j["failed"], 1);
  EXPECT_EQ(j["meshes_per_minute"], 8.0);  // (3 + 1) meshes in half a minute
  EXPECT_EQ(j["errors"], json::parse(R"([{"path": "/a.off", "error": "not closed"}])"));
  EXPECT_EQ(j["processes"], 2);
  EXPECT_EQ(json(IndexSummary{})["meshes_per_minute"], 0.0);

  IndexedMesh m;
  m.name = "cube";
  m.status = "ok";
  m.settings = "s";
  m.repair = R"({"changed": true})";
  m.descriptors = {{"d2", {0.5}}};
  json e = m;
  EXPECT_EQ(e["settings_id"], text_hash("s").substr(0, 8));
  EXPECT_EQ(e["repair"]["changed"], true);
  EXPECT_EQ(e["descriptors"]["d2"], json::parse("[0.5]"));
  EXPECT_FALSE(e.contains("error"));
  m.repair.clear();
  m.error = "failed";
  e = m;
  EXPECT_TRUE(e["repair"].is_null());
  EXPECT_EQ(e["error"], "failed");
}

// The table of descriptor settings: names, defaults and the library's checks.
TEST(DescriptorSettings, TableNamesEverySettingWithItsDefault) {
  const json j = DescriptorSettings{};
  EXPECT_EQ(j, json::parse(R"({"scales": 8, "open_from": 0.05, "open_to": 0.6,
      "close_from": 0.02, "close_to": 0.35, "closings": true, "pose": true, "facet_budget": 300,
      "d2_samples": 200000, "d2_bins": 64, "seed": 1})"));
  EXPECT_EQ(descriptor_settings_table().size(), j.size());
  DescriptorSettings s;
  s.scales = 3;
  s.normalise_pose = false;
  s.seed = 7;
  const DescriptorSettings back = json(s).get<DescriptorSettings>();
  EXPECT_EQ(back.to_string(), s.to_string());
}

// Every setting refused out of its range, with its name as where() and in the message.
TEST(DescriptorSettings, BadValueOfEachSettingIsRefusedByName) {
  const std::pair<const char*, json> bad[] = {
      {"scales", 0},        {"scales", 65},        {"open_from", 0},  {"open_to", -1},
      {"close_from", 0.0},  {"close_to", -0.5},    {"closings", 1},   {"pose", "yes"},
      {"facet_budget", -1}, {"d2_samples", 15},    {"d2_bins", 4097}, {"seed", -1},
      {"scales", 2.5},      {"d2_samples", "many"}};
  for (const auto& [name, value] : bad) {
    try {
      json{{name, value}}.get<DescriptorSettings>();
      ADD_FAILURE() << name << " = " << value.dump() << " was accepted";
    } catch (const InputError& e) {
      EXPECT_EQ(e.where(), name);
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
    }
  }
  const json unknown = {{"scale", 2}};  // not a setting
  EXPECT_THROW(unknown.get<DescriptorSettings>(), InputError);
}

TEST(DescriptorSettings, RadiiMustGrowAndDescribeChecksThemToo) {
  DescriptorSettings s;
  s.open_from = 0.7;
  try {
    check_descriptor_settings(s);
    ADD_FAILURE() << "open_from > open_to was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "open_from");
    EXPECT_NE(std::string(e.what()).find("must not exceed"), std::string::npos);
  }
  s = {};
  s.close_to = 0.01;
  EXPECT_THROW(check_descriptor_settings(s), InputError);
  s = {};
  s.d2_bins = 1;
  try {
    describe(check_solid(make_cube(FT(1))), s);
    ADD_FAILURE() << "describe took d2_bins = 1";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "d2_bins");
  }
  EXPECT_NO_THROW(check_descriptor_settings(DescriptorSettings{}));
}

}  // namespace
}  // namespace morphex

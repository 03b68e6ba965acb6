// SPDX-License-Identifier: GPL-3.0-or-later
// Pipelines: golden runs with exact volumes, a table of invalid pipelines with their exact error
// text, variable substitution, and a multi-input run with one bad mesh among good ones.
#include <gtest/gtest.h>

#include <filesystem>

#include "morphex/descriptor_settings.h"
#include "morphex/descriptors.h"
#include "morphex/io.h"
#include "morphex/minkowski.h"
#include "morphex/pipeline.h"
#include "morphex/shapes.h"
#include "morphex/structuring_element.h"

using namespace morphex;
namespace mp = morphex::pipeline;
namespace fs = std::filesystem;

namespace {

const std::string kData = MORPHEX_TEST_DATA_DIR;

std::string fresh_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("morphex-pipeline-" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir.string();
}

mp::RunReport run_text(const std::string& text, const mp::RunOptions& options = {}) {
  return mp::run(mp::parse_document(text, "p.json"), "p.json", options);
}

// The problems of an invalid pipeline, one text per line.
std::vector<std::string> problems_of(const std::string& text, const mp::Variables& variables = {}) {
  try {
    mp::validate(mp::parse_document(text, "p.json"), "p.json", variables);
  } catch (const mp::PipelineError& e) {
    std::vector<std::string> out;
    for (const auto& p : e.problems()) out.push_back(p.text());
    return out;
  }
  return {};
}

const mp::StageReport& stage(const mp::InputReport& input, const std::string& tag) {
  for (const auto& s : input.stages)
    if (s.tag == tag) return s;
  throw std::runtime_error("no stage tagged " + tag);
}

}  // namespace

TEST(Pipeline, ChainedMorphologyAndBooleansGiveExactVolumes) {
  const std::string out = fresh_dir("golden");
  const mp::RunReport report = run_text(R"({"pipeline": [
      {"type": "read", "path": ")" + kData +
                                        R"(/unit_cube.off", "tag": "in"},
      {"type": "dilate", "se": {"shape": "cube", "r": "1/4"}, "tag": "grown"},
      {"type": "erode", "se": "cube:r=1/4", "tag": "back"},
      {"type": "translate", "inputs": ["in"], "offset": ["1/2", 0, 0], "tag": "moved"},
      {"type": "union", "inputs": ["in", "moved"], "tag": "both"},
      {"type": "difference", "inputs": ["grown", "in"], "tag": "shell"},
      {"type": "scale", "inputs": ["in"], "factor": 2, "tag": "big"},
      {"type": "rotate", "inputs": ["moved"], "axis": "z", "degrees": 90, "tag": "turned"},
      {"type": "write", "inputs": ["shell"], "path": ")" +
                                        out + R"(/shell.off", "exact": true}]})");
  const mp::InputReport& r = report.inputs[0];
  EXPECT_EQ(stage(r, "in").volume, "1");
  EXPECT_EQ(stage(r, "grown").volume, "27/8");
  EXPECT_EQ(stage(r, "back").volume, "1");  // a cube is open and closed for a smaller cube
  EXPECT_EQ(stage(r, "both").volume, "3/2");
  EXPECT_EQ(stage(r, "shell").volume, "19/8");
  EXPECT_EQ(stage(r, "big").volume, "8");
  EXPECT_EQ(stage(r, "turned").volume, "1");
  EXPECT_EQ(stage(r, "turned").faces, 12u);
  // the exact file holds exactly the shell
  EXPECT_EQ(to_rational_string(signed_volume(read_mesh(out + "/shell.off"))), "19/8");
}

TEST(Pipeline, SimplifyStageGivesAValidCoarserSolid) {
  const std::string dir = fresh_dir("simplify");
  write_mesh(make_icosphere(3, 1), dir + "/sphere.off");  // 1,280 facets
  const mp::RunReport report = run_text(R"({"pipeline": [
      {"type": "read", "path": ")" + dir +
                                        R"(/sphere.off"},
      {"type": "simplify", "facets": 200, "tag": "coarse"},
      {"type": "check", "tag": "checked"}]})");
  const mp::StageReport& coarse = stage(report.inputs[0], "coarse");
  EXPECT_LE(coarse.faces, 200u);
  EXPECT_GE(coarse.faces, 150u);
  EXPECT_TRUE(coarse.extra["simplified"].get<bool>());
  EXPECT_TRUE(stage(report.inputs[0], "checked").extra["valid"].get<bool>());
  EXPECT_FALSE(problems_of(R"({"pipeline": [{"type": "read", "path": "x.off"},
      {"type": "simplify", "facets": 2}]})")
                   .empty());
}

TEST(Pipeline, VariablesComeFromSetThenFromTheDocument) {
  const std::string out = fresh_dir("variables");
  const std::string text = R"({"variables": {"r": "1/4", "out_dir": "/nowhere"},
    "pipeline": [{"type": "read", "path": "${input}"},
                 {"type": "dilate", "se": {"shape": "cube", "r": "${r}"}},
                 {"type": "write", "path": "${out_dir}/${stem}-grown.off"}]})";
  mp::RunOptions options;
  options.inputs = {kData + "/unit_cube.off"};
  options.variables = {{"out_dir", out}};
  const mp::RunReport report = run_text(text, options);
  EXPECT_EQ(report.inputs[0].stages.back().volume, "27/8");
  EXPECT_TRUE(fs::exists(out + "/unit_cube-grown.off"));
  options.variables["r"] = "1/2";
  EXPECT_EQ(run_text(text, options).inputs[0].stages.back().volume, "8");
}

// The describe stage's options are the table of descriptor settings: its defaults, ranges and
// names, and the library's check of the radii together (at run time, naming the setting).
TEST(Pipeline, DescribeStageTakesTheDescriptorSettingsTable) {
  const mp::StageInfo* describe = mp::StageRegistry::builtin().find("describe");
  ASSERT_TRUE(describe);
  ASSERT_EQ(describe->options.size(), descriptor_settings_table().size());
  for (std::size_t i = 0; i < describe->options.size(); ++i) {
    const DescriptorSettingInfo& setting = descriptor_settings_table()[i];
    EXPECT_EQ(describe->options[i].name, setting.name);
    EXPECT_EQ(*describe->options[i].default_value, setting.value(DescriptorSettings{}));
  }
  const auto problems =
      problems_of(R"([{"type": "read", "path": "a.off"}, {"type": "describe", "d2_bins": 2}])");
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_NE(problems[0].find("pipeline[1].d2_bins"), std::string::npos) << problems[0];
  mp::RunOptions options;
  options.inputs = {kData + "/unit_cube.off"};
  options.variables = {{"from", "0.7"}};
  const mp::RunReport report = run_text(
      R"([{"type": "read", "path": "${input}"},
          {"type": "describe", "scales": 2, "d2_samples": 256, "open_from": "${from}"}])",
      options);
  ASSERT_FALSE(report.ok());
  EXPECT_NE(report.inputs[0].error.find("open_from: open_from/close_from must not exceed"),
            std::string::npos)
      << report.inputs[0].error;
  options.variables = {{"from", "0.1"}};  // a number option's value from a variable
  EXPECT_TRUE(run_text(R"([{"type": "read", "path": "${input}"},
          {"type": "describe", "scales": 2, "d2_samples": 256, "open_from": "${from}"}])",
                       options)
                  .ok());
}

TEST(Pipeline, OneBadMeshAmongGoodOnesFailsAloneAndKeepsTheOthers) {
  const std::string out = fresh_dir("multi");
  mp::RunOptions options;
  options.inputs = {kData + "/unit_cube.off", kData + "/open_cube.off",
                    kData + "/third_cube_exact.off", kData + "/missing.off"};
  const mp::RunReport report = run_text(R"({"pipeline": [
      {"type": "read", "path": "${input}"},
      {"type": "dilate", "se": "octahedron:r=1/8"},
      {"type": "write", "path": ")" + out + R"(/${stem}.off"}]})",
                                        options);
  ASSERT_EQ(report.inputs.size(), 4u);
  EXPECT_FALSE(report.ok());
  EXPECT_TRUE(report.inputs[0].ok);
  EXPECT_TRUE(report.inputs[2].ok);
  EXPECT_FALSE(report.inputs[1].ok);
  EXPECT_EQ(
      report.inputs[1].error.rfind(
          "pipeline[0] (read): " + kData + "/open_cube.off: mesh is not closed: 4 border edges", 0),
      0u)
      << report.inputs[1].error;
  EXPECT_NE(report.inputs[3].error.find("missing.off"), std::string::npos);
  EXPECT_TRUE(fs::exists(out + "/unit_cube.off"));
  EXPECT_TRUE(fs::exists(out + "/third_cube_exact.off"));
  EXPECT_FALSE(fs::exists(out + "/open_cube.off"));
  const nlohmann::json j = report.to_json();
  EXPECT_EQ(j["inputs"][1]["name"], "open_cube");
  EXPECT_EQ(j["inputs"][0]["stages"][1]["type"], "dilate");
}

TEST(Pipeline, RepairStageTakesWhatReadWouldRefuse) {
  mp::RunOptions options;
  options.inputs = {kData + "/crossing_cubes.off"};
  const mp::RunReport repaired = run_text(R"({"pipeline": [{"type": "read", "path": "${input}"},
                                                           {"type": "repair"},
                                                           {"type": "check"}]})",
                                          options);
  EXPECT_EQ(repaired.inputs[0].stages[1].volume, "15/8");
  EXPECT_EQ(repaired.inputs[0].stages[1].extra["repair"]["intersecting_pairs"], 18);
  // Without the repair stage the read refuses the mesh and says what would take it.
  const mp::RunReport refused = run_text(R"({"pipeline": [{"type": "read", "path": "${input}"},
                                                          {"type": "check"}]})",
                                         options);
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.inputs[0].error.find("self-intersects"), std::string::npos);
  EXPECT_NE(refused.inputs[0].error.find("a repair stage after the read repairs it"),
            std::string::npos);
}

TEST(Pipeline, SeveralInputsWritingOneFileAreRefused) {
  mp::RunOptions options;
  options.inputs = {kData + "/unit_cube.off", kData + "/third_cube_exact.off"};
  try {
    run_text(R"({"pipeline": [{"type": "read", "path": "${input}"},
                              {"type": "write", "path": "/tmp/same.off"}]})",
             options);
    FAIL() << "expected a PipelineError";
  } catch (const mp::PipelineError& e) {
    EXPECT_EQ(e.problems().at(0).text(),
              "pipeline[1].path: every input would write the same file /tmp/same.off (put "
              "${stem} in the path)");
  }
}

struct InvalidCase {
  const char* name;
  std::string json;
  std::vector<std::string> expected;
};

class InvalidPipelines : public ::testing::TestWithParam<InvalidCase> {};

TEST_P(InvalidPipelines, ReportEveryProblemWithItsLocation) {
  EXPECT_EQ(problems_of(GetParam().json), GetParam().expected);
}

const std::string kRead = R"({"type": "read", "path": "a.off", "tag": "in"})";

INSTANTIATE_TEST_SUITE_P(
    Table, InvalidPipelines,
    ::testing::Values(
        InvalidCase{
            "empty", R"({"pipeline": []})", {"pipeline: expected a non-empty array of stages"}},
        InvalidCase{"unknown_type",
                    "[" + kRead + R"(, {"type": "dilation", "se": "cube:r=1"}])",
                    {"pipeline[1].type: unknown stage 'dilation' (did you mean 'dilate'?)"}},
        InvalidCase{"negative_radius",
                    "[" + kRead + R"(, {"type": "open", "se": {"shape": "ball", "r": -1}}])",
                    {"pipeline[1].se.r: expected a positive number, got -1"}},
        InvalidCase{"unknown_and_missing_option",
                    "[" + kRead + R"(, {"type": "dilate", "radius": 2}])",
                    {"pipeline[1].radius: unknown option for 'dilate' (known: se)",
                     "pipeline[1].se: missing (required by 'dilate')"}},
        InvalidCase{"wrong_types",
                    "[" + kRead +
                        R"(, {"type": "write", "path": "b.off", "exact": "yes"},
                             {"type": "translate", "inputs": "in", "offset": [1, "x", 3]},
                             {"type": "rotate", "inputs": "in", "axis": "w", "degrees": 5}])",
                    {"pipeline[1].exact: expected true or false, got \"yes\"",
                     "pipeline[2].offset[1]: expected a number, got \"x\"",
                     "pipeline[3].axis: expected one of x, y, z, got \"w\""}},
        InvalidCase{
            "bad_shape",
            "[" + kRead + R"(, {"type": "dilate", "se": {"shape": "sphere"}}])",
            {"pipeline[1].se.shape: unknown structuring element shape 'sphere' (did you "
             "mean 'ball'? expected cube, box, octahedron, ball, zonoball, cylinder or mesh)"}},
        InvalidCase{"tags",
                    "[" + kRead + R"(, {"type": "read", "path": "b.off", "tag": "in"},
                             {"type": "union", "inputs": ["in", "nope"]},
                             {"type": "difference", "inputs": ["in"]}])",
                    {"pipeline[1].tag: duplicate tag 'in' (first used by pipeline[0])",
                     "pipeline[2].inputs[1]: unknown tag 'nope'",
                     "pipeline[3].inputs: 'difference' takes 2 inputs, got 1"}},
        InvalidCase{"first_needs_input",
                    R"([{"type": "dilate", "se": "cube:r=1"}])",
                    {"pipeline[0].inputs: 'dilate' needs an input: it cannot come first"}},
        InvalidCase{"cycle",
                    "[" + kRead + R"(, {"type": "union", "inputs": ["in", "b"], "tag": "a"},
                             {"type": "dilate", "inputs": ["a"], "se": "cube:r=1", "tag": "b"}])",
                    {"pipeline[1].inputs: cycle: a -> b -> a"}},
        InvalidCase{"overwrite_input",
                    "[" + kRead + R"(, {"type": "write", "path": "a.off"}])",
                    {"pipeline[1].path: would overwrite the input read by pipeline[0] (a.off)"}},
        InvalidCase{"unknown_variable",
                    R"([{"type": "read", "path": "${mesh}"}])",
                    {"pipeline[0].path: unknown variable ${mesh} (set it with --set mesh=VALUE)"}},
        InvalidCase{"top_level",
                    R"({"pipline": [], "pipeline": [{"type": "read", "path": "a"}]})",
                    {"pipline: unknown top-level key (expected \"pipeline\", and optionally "
                     "\"description\" and \"variables\")"}}),
    [](const auto& info) { return std::string(info.param.name); });

TEST(Pipeline, MalformedJsonNamesLineAndColumn) {
  try {
    mp::parse_document("{\"pipeline\": [\n  {\"type\": \"read\",, }\n]}", "p.json");
    FAIL() << "expected a PipelineError";
  } catch (const mp::PipelineError& e) {
    EXPECT_EQ(e.problems().at(0).location, "p.json:2:19");  // the second comma
    EXPECT_EQ(e.problems().at(0).message.rfind("malformed JSON: ", 0), 0u);
  }
}

TEST(Pipeline, NumberTooLargeForADoubleIsMalformedJsonWithItsPosition) {
  // Found by fuzzing: nlohmann reports it as out_of_range, without a position.
  try {
    mp::parse_document("{\"pipeline\": [\n  {\"type\": \"scale\", \"factor\": 1e999}]}", "p.json");
    FAIL() << "expected a PipelineError";
  } catch (const mp::PipelineError& e) {
    EXPECT_EQ(e.problems().at(0).location, "p.json:2:31");  // the 1 of 1e999
    EXPECT_EQ(e.problems().at(0).message, "malformed JSON: number overflow parsing '1e999'");
  }
}

TEST(Pipeline, RegistryDocumentsEveryStage) {
  const auto& registry = mp::StageRegistry::builtin();
  for (const char* type :
       {"read", "write", "dilate", "erode", "open", "close", "union", "intersection", "difference",
        "minkowski", "translate", "scale", "rotate", "check", "repair", "simplify", "describe"}) {
    const mp::StageInfo* s = registry.find(type);
    ASSERT_NE(s, nullptr) << type;
    EXPECT_FALSE(s->description.empty()) << type;
    for (const auto& o : s->options) EXPECT_FALSE(o.description.empty()) << type << "." << o.name;
  }
  EXPECT_EQ(registry.closest("erosion"), "erode");
}

TEST(Pipeline, ExamplesAreValid) {
  for (const auto& entry : fs::directory_iterator(MORPHEX_SOURCE_DIR "/pipelines/examples")) {
    if (entry.path().extension() != ".json") continue;
    EXPECT_NO_THROW(mp::validate(mp::load_document(entry.path().string()), entry.path().string(),
                                 {}, {"input", "stem"}))
        << entry.path();
  }
}

// One error model for every library (morphex/error.h): each bad input is a morphex::Error whose
// what() is "<where>: <problem>", and its kind tells an invalid solid from other bad input.
TEST(ErrorModel, EveryLibraryThrowsAMorphexErrorWithWhereAndProblem) {
  try {  // libbool: a file that cannot be read
    read_mesh("/nonexistent/dir/mesh.off");
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "/nonexistent/dir/mesh.off");
    EXPECT_EQ(std::string(e.what()), e.where() + ": " + e.problem());
  }
  Mesh open = make_cube(FT(1));
  open.triangles.pop_back();
  try {  // libbool: a mesh that is not a valid solid where one is needed (the operations take
         // Solids)
    check_solid(open, "first operand");
    ADD_FAILURE() << "no error";
  } catch (const InvalidSolid& e) {
    EXPECT_EQ(e.where(), "first operand");
    EXPECT_EQ(std::string(e.what()), "first operand: " + e.problem());
    EXPECT_NE(e.problem().find("mesh is not closed"), std::string::npos);
    const Error& base = e;  // and an InputError, an Error, a std::runtime_error
    EXPECT_EQ(std::string(base.what()), e.what());
  }
  try {  // libmorph: a bad structuring element, with the parameter at fault
    parse_structuring_element("ball:r=-1");
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.where(), "ball: r");
    EXPECT_NE(e.problem().find("positive"), std::string::npos);
  }
  try {  // pipelines: every problem, the first one's location as where()
    mp::validate(nlohmann::json::parse(R"({"pipeline": [{"type": "nosuch"}]})"), "p.json", {});
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.where(), "pipeline[0].type");
    EXPECT_FALSE(e.problem().empty());
  }
  EXPECT_THROW(parse_metric("cosine"), InputError);
}

// Typed options: validation builds a stage's structuring element once and the stage uses it.
TEST(Validate, StructuringElementsAreBuiltOnceByValidation) {
  const mp::Pipeline p =
      mp::validate(nlohmann::json::parse(R"({"pipeline": [{"type": "read", "path": "a.off"},
                                {"type": "dilate", "se": {"shape": "cube", "r": "1/4"}}]})"),
                   "p.json", {});
  ASSERT_EQ(p.stages.size(), 2u);
  EXPECT_TRUE(p.stages[0].elements.empty());
  ASSERT_EQ(p.stages[1].elements.count("se"), 1u);
  const StructuringElement& se = *p.stages[1].elements.at("se");
  EXPECT_EQ(se.shape, "cube");
  EXPECT_EQ(signed_volume(se.mesh), FT(1) / 8);  // a cube of half side 1/4
}

// Progress moves inside a long stage: describe reports each filter, so the run's count of
// finished stages takes values between 1 (read done) and 2 (describe done), never goes back, and
// ends at the number of stages.
TEST(Pipeline, ProgressMovesInsideTheDescribeStage) {
  mp::RunOptions options;
  options.inputs = {kData + "/unit_cube.off"};
  std::vector<double> seen;
  options.on_progress = [&](double done, std::size_t total, const std::string&,
                            const std::string&) {
    EXPECT_EQ(total, 2u);
    seen.push_back(done);
  };
  const mp::RunReport report = run_text(R"({"pipeline": [
      {"type": "read", "path": "${input}"},
      {"type": "describe", "scales": 3, "d2_samples": 256}]})",
                                        options);
  ASSERT_FALSE(seen.empty());
  EXPECT_TRUE(std::is_sorted(seen.begin(), seen.end()));
  EXPECT_EQ(seen.back(), 2.0);
  // 3 openings and 3 closings reported inside describe (D2's share comes with the stage's end)
  EXPECT_EQ(std::count_if(seen.begin(), seen.end(), [](double d) { return d > 1 && d < 2; }), 6);
}

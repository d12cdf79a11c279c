// Evaluation files: the YAML tree, versions, unknown keys with "did you mean", file:line and
// key path in every message.
#include <gtest/gtest.h>

#include <fstream>

#include "core/errors.hpp"
#include "evaluation/evaluation_file.hpp"
#include "evaluation/yaml_tree.hpp"
#include "unit/synthetic_roads.hpp"

namespace orch {
namespace {

class EvaluationFileTest : public ::testing::Test {
 protected:
  EvaluationFileTest() : dir_("evalfile") {
    std::ofstream(dir_.path() / "scenario.json") << "{}";
  }
  LoadedEvaluation load(const std::string& text) {
    const auto path = dir_.path() / "eval.yaml";
    std::ofstream(path) << text;
    return load_evaluation(path.string());
  }
  std::string errors(const std::string& text) { return load(text).diagnostics.format(); }

  test::TempDir dir_;
};

const char* kValid = R"(ScenarioFormatVersion: 2.0.0
ScenarioName: cut-in
ScenarioDescription: "a test"
VehicleModel: car.sedan
LocalMapPath: ${ORCH_TEST_EVAL_HOME}/maps
Evaluation:
  UseCaseName: scenario_executor
  UseCaseFormatVersion: 0.1.0
  Conditions:
    Scenario: scenario.json
    Seed: 7
    Step: 0.1
    MaxTime: 60
    Traffic: light
    Backend: traci
    Criteria:
      - Name: ttc
        Metric: ttc
        Min: 2
      - Name: rate
        Metric: thw
        Min: 1.0
        PassRate: 90
      - Name: nc
        Type: no_collision
        With: [1, bg.4]
      - Name: lane
        Type: keep_lane
        Duration: 0.5
        FromScene: 1
        ToScene: 3
)";

TEST_F(EvaluationFileTest, ReadsEveryKey) {
  ::setenv("ORCH_TEST_EVAL_HOME", "/home/tester", 1);
  const LoadedEvaluation e = load(kValid);
  ASSERT_TRUE(e.file) << e.diagnostics.format();
  const EvaluationFile& f = *e.file;
  EXPECT_EQ(f.name, "cut-in");
  EXPECT_EQ(f.vehicle_model, "car.sedan");
  EXPECT_EQ(f.local_map_path, "/home/tester/maps");
  EXPECT_EQ(f.scenario_file, (dir_.path() / "scenario.json").string());
  EXPECT_EQ(*f.seed, 7);
  EXPECT_DOUBLE_EQ(*f.step, 0.1);
  EXPECT_DOUBLE_EQ(*f.max_time, 60);
  EXPECT_EQ(*f.traffic, "light");
  EXPECT_EQ(*f.backend, "traci");
  ASSERT_EQ(f.criteria.size(), 4u);
  EXPECT_EQ(f.criteria[0].metric, "ttc");
  EXPECT_EQ(f.criteria[0].mode, criteria::Mode::AllOf);
  EXPECT_EQ(f.criteria[1].mode, criteria::Mode::PassRate);
  EXPECT_DOUBLE_EQ(f.criteria[1].pass_rate, 90);
  EXPECT_EQ(f.criteria[2].with, (std::vector<std::string>{"1", "bg.4"}));
  EXPECT_EQ(f.criteria[3].mode, criteria::Mode::Duration);
  EXPECT_DOUBLE_EQ(*f.criteria[3].max, 0);
  EXPECT_EQ(*f.criteria[3].from_scene, 1);
  EXPECT_EQ(f.conditions["Seed"], 7);
}

TEST_F(EvaluationFileTest, UnknownKeysWithDidYouMeanFileLineAndPath) {
  std::string text = kValid;
  text.replace(text.find("        Min: 2"), 14, "        Minn: 2");
  const std::string e = errors(text);
  EXPECT_NE(e.find("eval.yaml:19: error: /Evaluation/Conditions/Criteria/0/Minn: "), std::string::npos) << e;
  EXPECT_NE(e.find("did you mean \"Min\""), std::string::npos) << e;
}

TEST_F(EvaluationFileTest, UnknownMetricAndTypeWithDidYouMean) {
  std::string text = kValid;
  text.replace(text.find("Metric: ttc"), 11, "Metric: tcc");
  text.replace(text.find("Type: no_collision"), 18, "Type: no_colision");
  const std::string e = errors(text);
  EXPECT_NE(e.find("eval.yaml:18: error: /Evaluation/Conditions/Criteria/0/Metric: "), std::string::npos) << e;
  EXPECT_NE(e.find("did you mean \"ttc\""), std::string::npos) << e;
  EXPECT_NE(e.find("eval.yaml:25: error: /Evaluation/Conditions/Criteria/2/Type: "), std::string::npos) << e;
  EXPECT_NE(e.find("did you mean \"no_collision\""), std::string::npos) << e;
  EXPECT_EQ(load(text).diagnostics.error_count(), 2) << e;  // a wrong type is one error, not a cascade
}

TEST_F(EvaluationFileTest, VersionsThisBuildDoesNotKnow) {
  std::string text = kValid;
  text.replace(text.find("2.0.0"), 5, "3.0.0");
  text.replace(text.find("0.1.0"), 5, "0.2.0");
  const std::string e = errors(text);
  EXPECT_NE(e.find("eval.yaml:1: error: /ScenarioFormatVersion: format version 3.0.0 is not known"), std::string::npos)
      << e;
  EXPECT_NE(e.find("eval.yaml:8: error: /Evaluation/UseCaseFormatVersion: use case format version 0.2.0"),
            std::string::npos)
      << e;
}

TEST_F(EvaluationFileTest, MissingRequiredKeysAndBounds) {
  const std::string e = errors(R"(ScenarioFormatVersion: 2.1.0
Evaluation:
  UseCaseName: scenario_exec
  UseCaseFormatVersion: 0.1.0
  Conditions:
    Scenario: nowhere.json
    Criteria:
      - Name: a
        Metric: gap
      - Name: a
        Type: max_speed
        Max: 30
)");
  EXPECT_NE(e.find("ScenarioName"), std::string::npos) << e;
  EXPECT_NE(e.find("did you mean \"scenario_executor\""), std::string::npos) << e;
  EXPECT_NE(e.find("no scenario file"), std::string::npos) << e;
  EXPECT_NE(e.find("a metric criterion needs \"Min\" or \"Max\""), std::string::npos) << e;
  EXPECT_NE(e.find(":10: error: /Evaluation/Conditions/Criteria/1/Name: criterion name \"a\" is used twice"),
            std::string::npos)
      << e;
}

TEST_F(EvaluationFileTest, InvalidYamlAndRepeatedKeysNameTheLine) {
  EXPECT_NE(errors("ScenarioName: [a\nb: c\n").find("eval.yaml:"), std::string::npos);
  const std::string e = errors("ScenarioName: a\nScenarioName: b\n");
  EXPECT_NE(e.find("eval.yaml:2: error: /ScenarioName: duplicate key"), std::string::npos) << e;
}

// The soak's find (seed 2679876088): bytes that are not UTF-8 in a YAML string reached the
// outputs and ended the run as an internal error. Now the reader names the line.
TEST_F(EvaluationFileTest, BytesThatAreNotUtf8NameTheirLine) {
  const std::string e = errors("ScenarioName: a\nScenarioDescription: b\xff\xfe c\n");
  EXPECT_NE(e.find("eval.yaml:2: error: /: invalid UTF-8: a YAML file is UTF-8 text"), std::string::npos) << e;
}

TEST(YamlTree, ScalarsTypedQuotedStayStrings) {
  const JsonDocument d = parse_yaml_document("a: 1\nb: 1.5\nc: true\nd: ~\ne: \"2\"\nf: 2.0.0\ng: [x, 3]\n", "t.yaml");
  EXPECT_EQ(d.root()["a"], 1);
  EXPECT_EQ(d.root()["b"], 1.5);
  EXPECT_EQ(d.root()["c"], true);
  EXPECT_TRUE(d.root()["d"].is_null());
  EXPECT_EQ(d.root()["e"], "2");
  EXPECT_EQ(d.root()["f"], "2.0.0");
  EXPECT_EQ(d.root()["g"][1], 3);
  EXPECT_EQ(d.line_of("/g/1"), 7);
  EXPECT_EQ(d.line_of("/c"), 3);
}

TEST(ExpandVariables, DollarNameAndBraces) {
  ::setenv("ORCH_TEST_VAR", "/x", 1);
  ::unsetenv("ORCH_TEST_UNSET");
  EXPECT_EQ(expand_variables("$ORCH_TEST_VAR/a/${ORCH_TEST_VAR}b"), "/x/a//xb");
  EXPECT_EQ(expand_variables("a$ORCH_TEST_UNSET/b"), "a/b");
}

}  // namespace
}  // namespace orch

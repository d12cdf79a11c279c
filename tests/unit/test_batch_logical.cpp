// Logical scenario files: the seed's parameter_space read into plain values, and every
// mistake reported like the scenario loader does (file:line: error: /pointer: message).
#include <gtest/gtest.h>

#include "batch/logical_scenario.hpp"
#include "core/errors.hpp"
#include "json/json_document.hpp"

using namespace orch;
using namespace orch::batch;

namespace {

const std::string kDir = std::string(ORCH_SOURCE_DIR) + "/scenarios/nightly/";

LogicalScenario parse(const std::string& text) {
  return read_logical_scenario(JsonDocument::parse(text, kDir + "logical_test.json"));
}

// The messages of a logical file that must not load.
std::string errors_of(const std::string& text) {
  try {
    parse(text);
  } catch (const ScenarioError& e) {
    return e.what();
  }
  return "(loaded without errors)";
}

std::string with_space(const std::string& space) {
  return R"({"uuid": "L1", "template": "cut_in.template.json", "parameter_space": )" + space + "}";
}

}  // namespace

TEST(BatchLogical, ShippedNightlyCutInReadsWithItsDistributions) {
  const auto l = load_logical_scenario(kDir + "logical_344b1b1a-8831-46a0-a4e1-e7104d3ce4b5.json");
  EXPECT_EQ(l.uuid, "344b1b1a-8831-46a0-a4e1-e7104d3ce4b5");
  EXPECT_EQ(l.parent_abstract_uuid, "48f5362a-58a0-4eec-8e08-5cb3e05ad57b");
  EXPECT_EQ(l.template_file.filename(), "cut_in.template.json");
  EXPECT_EQ(l.parameter_file().filename(), "logical_344b1b1a-8831-46a0-a4e1-e7104d3ce4b5_parameters.json");
  ASSERT_NE(l.find("cut_in.gap"), nullptr);
  EXPECT_EQ(l.find("cut_in.gap")->unit, "m");
  EXPECT_TRUE(std::holds_alternative<Uniform>(l.find("cut_in.gap")->distribution));
  const auto& n = std::get<Normal>(l.find("cut_in.final_speed")->distribution);
  EXPECT_EQ(n.mean, 60.0);
  EXPECT_EQ(n.min, 30.0);
  EXPECT_TRUE(std::holds_alternative<Choice>(l.find("cut_in.decel")->distribution));
  EXPECT_EQ(l.sumo_config.max_time, 90.0);
  // Ordered by key, whatever the order in the file: sampling depends on names, not layout.
  for (std::size_t i = 1; i < l.parameters.size(); ++i) EXPECT_LT(l.parameters[i - 1].key(), l.parameters[i].key());
}

TEST(BatchLogical, TypesAreInferredWhenNotDeclared) {
  const auto l = parse(with_space(R"({"g": {
      "a": {"distribution": "constant", "value": 3},
      "b": {"distribution": "constant", "value": "x"},
      "c": {"distribution": "choice", "choices": [1, 2.5]},
      "d": {"distribution": "choice", "choices": [true, false]},
      "e": {"distribution": "uniform", "min": 0, "max": 1}}})"));
  EXPECT_EQ(l.find("g.a")->type, ValueType::Int);
  EXPECT_EQ(l.find("g.b")->type, ValueType::String);
  EXPECT_EQ(l.find("g.c")->type, ValueType::Float);
  EXPECT_EQ(l.find("g.d")->type, ValueType::Bool);
  EXPECT_EQ(l.find("g.e")->type, ValueType::Float);
}

TEST(BatchLogical, MisspeltDistributionGetsDidYouMeanWithLineAndPointer) {
  const std::string e = errors_of(R"({"uuid": "L1", "template": "cut_in.template.json",
    "parameter_space": {"ego": {
      "speed": {"distribution": "unifrom", "min": 1, "max": 2}}}})");
  EXPECT_NE(e.find("logical_test.json:3: error: /parameter_space/ego/speed/distribution"), std::string::npos) << e;
  EXPECT_NE(e.find("did you mean \"uniform\""), std::string::npos) << e;
}

TEST(BatchLogical, EachDistributionNeedsItsOwnFields) {
  EXPECT_NE(errors_of(with_space(R"({"g": {"p": {"distribution": "normal", "mean": 1}}})")).find("needs \"std\""),
            std::string::npos);
  EXPECT_NE(errors_of(with_space(R"({"g": {"p": {"distribution": "constant"}}})")).find("needs \"value\""),
            std::string::npos);
  EXPECT_NE(errors_of(with_space(R"({"g": {"p": {"distribution": "choice", "choices": []}}})")).find("at least one"),
            std::string::npos);
  const std::string extra = errors_of(with_space(R"({"g": {"p": {"distribution": "uniform", "min": 1, "maxx": 2}}})"));
  EXPECT_NE(extra.find("unknown key \"maxx\""), std::string::npos) << extra;
  EXPECT_NE(extra.find("did you mean \"max\""), std::string::npos) << extra;
}

TEST(BatchLogical, InconsistentValuesAreErrors) {
  EXPECT_NE(errors_of(with_space(R"({"g": {"p": {"distribution": "uniform", "min": 5, "max": 2}}})")).find("below \"min\""),
            std::string::npos);
  EXPECT_NE(errors_of(with_space(R"({"g": {"p": {"distribution": "normal", "mean": 0, "std": -1}}})")).find("negative"),
            std::string::npos);
  EXPECT_NE(errors_of(with_space(R"({"g": {"p": {"type": "int", "distribution": "uniform", "min": 0.5, "max": 2}}})"))
                .find("whole-number"),
            std::string::npos);
  EXPECT_NE(errors_of(with_space(R"({"g": {"p": {"type": "string", "distribution": "uniform", "min": 0, "max": 2}}})"))
                .find("\"float\" or \"int\""),
            std::string::npos);
  EXPECT_NE(errors_of(with_space(R"({"g": {"p": {"type": "float", "distribution": "choice", "choices": [1, "x"]}}})"))
                .find("choice \"x\" is not of type \"float\""),
            std::string::npos);
}

TEST(BatchLogical, NamesMustMakeUnambiguousPlaceholders) {
  EXPECT_NE(errors_of(with_space(R"({"a.b": {"p": {"distribution": "constant", "value": 1}}})")).find("no dots"),
            std::string::npos);
  EXPECT_NE(errors_of(with_space(R"({"g": {"p.q": {"distribution": "constant", "value": 1}}})")).find("no dots"),
            std::string::npos);
  EXPECT_NE(errors_of(with_space("{}")).find("defines no parameter"), std::string::npos);
}

TEST(BatchLogical, TemplateMustExistAndUuidMustNameFiles) {
  const std::string missing = errors_of(R"({"uuid": "L1", "template": "nope.json", "parameter_space":
    {"g": {"p": {"distribution": "constant", "value": 1}}}})");
  EXPECT_NE(missing.find("/template: template scenario"), std::string::npos) << missing;
  EXPECT_NE(missing.find("does not exist"), std::string::npos) << missing;
  const std::string bad_uuid = errors_of(R"({"uuid": "../x", "template": "cut_in.template.json", "parameter_space":
    {"g": {"p": {"distribution": "constant", "value": 1}}}})");
  EXPECT_NE(bad_uuid.find("cannot name files"), std::string::npos) << bad_uuid;
}

TEST(BatchLogical, UnknownTopLevelKeyIsReported) {
  const std::string e = errors_of(R"({"uuid": "L1", "template": "cut_in.template.json", "parameter_spaces": {},
    "parameter_space": {"g": {"p": {"distribution": "constant", "value": 1}}}})");
  EXPECT_NE(e.find("unknown key \"parameter_spaces\""), std::string::npos) << e;
}

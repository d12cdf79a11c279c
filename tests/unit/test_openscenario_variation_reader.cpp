// OpenSCENARIO parameter variation files: the shipped ones read into the model, then one
// broken variant per kind of error, each naming the file, the line and the element path.
#include <gtest/gtest.h>

#include <filesystem>

#include "core/errors.hpp"
#include "openscenario/variation.hpp"
#include "support/cli_runner.hpp"
#include "support/xosc_variation.hpp"

namespace orch::openscenario {
namespace {

using orch::test::TempDir;

const std::string kNightly = std::string(ORCH_SOURCE_DIR) + "/scenarios/openscenario/nightly/";

// A deterministic variation over the shipped lead_brake.xosc with `body` inside Deterministic.
std::string deterministic(const std::string& body, const std::string& scenario = kNightly + "lead_brake.xosc") {
  return orch::test::deterministic_variation(body, scenario);
}

std::string stochastic(const std::string& body, const std::string& attributes = R"(numberOfTestRuns="10" randomSeed="7")") {
  return R"(<?xml version="1.0"?>
<OpenSCENARIO>
  <FileHeader revMajor="1" revMinor="2" date="2026-01-01T00:00:00" author="t" description="v"/>
  <ParameterValueDistribution>
    <ScenarioFile filepath=")" + kNightly + R"(lead_brake.xosc"/>
    <Stochastic )" + attributes + R"(>
)" + body + R"(
    </Stochastic>
  </ParameterValueDistribution>
</OpenSCENARIO>
)";
}

// The error of loading `text` as a variation file, as "file:line: error: path: message".
std::string error_of(const std::string& text) {
  TempDir dir;
  const auto file = dir.write("x_variation.xosc", text);
  try {
    load_variation(file.string());
  } catch (const ScenarioError& e) {
    std::string message = e.diagnostics().format();
    const auto at = message.find(file.string());
    if (at != std::string::npos) message.replace(at, file.string().size(), "FILE");
    return message;
  }
  return "no error";
}

TEST(OpenScenarioVariation, ReadsTheShippedGridIntoFactorsInFileOrder) {
  const Variation v = load_variation(kNightly + "lead_brake_grid_variation.xosc");
  EXPECT_FALSE(v.stochastic);
  EXPECT_EQ(v.scenario_file, std::filesystem::path(kNightly + "lead_brake.xosc").lexically_normal().string());
  ASSERT_EQ(v.factors.size(), 3u);
  EXPECT_EQ(v.factors[0].parameters, std::vector<std::string>{"Decel_mps2"});
  std::vector<std::string> decels;
  for (const auto& o : v.factors[0].options) decels.push_back(o.at(0));
  EXPECT_EQ(decels, (std::vector<std::string>{"4", "6", "8", "10"}));  // DistributionRange 4..10 step 2
  EXPECT_EQ(v.factors[1].options, (std::vector<std::vector<std::string>>{{"60"}, {"80"}}));
  EXPECT_EQ(v.factors[2].parameters, (std::vector<std::string>{"Gap_m", "BrakeTime_s"}));
  EXPECT_EQ(v.factors[2].options, (std::vector<std::vector<std::string>>{{"25", "4"}, {"8", "6"}}));
  EXPECT_EQ(v.parameter_names(), (std::vector<std::string>{"Decel_mps2", "LeadSpeed_kph", "Gap_m", "BrakeTime_s"}));
  ASSERT_NE(v.declaration("Gap_m"), nullptr);
  EXPECT_EQ(v.declaration("Gap_m")->type, "double");
}

TEST(OpenScenarioVariation, ReadsTheShippedStochasticFile) {
  const Variation v = load_variation(kNightly + "lead_brake_variation.xosc");
  EXPECT_TRUE(v.stochastic);
  EXPECT_EQ(v.number_of_test_runs, 50);
  EXPECT_EQ(v.random_seed, 1.0);
  ASSERT_EQ(v.distributions.size(), 4u);
  const auto& normal = std::get<NormalDistribution>(v.distributions[1].distribution);
  EXPECT_EQ(normal.expected_value, 8.0);
  EXPECT_EQ(normal.variance, 6.25);
  ASSERT_TRUE(normal.range.has_value());
  EXPECT_EQ(normal.range->lower, 4.0);
  EXPECT_EQ(std::get<ProbabilityDistributionSet>(v.distributions[2].distribution).elements.size(), 3u);
  EXPECT_EQ(std::get<HistogramDistribution>(v.distributions[3].distribution).bins.size(), 2u);
}

TEST(OpenScenarioVariation, RangeStepsStopAtTheUpperLimitWithoutRoundingOff) {
  TempDir dir;
  const auto file = dir.write("r_variation.xosc", deterministic(R"(
      <DeterministicSingleParameterDistribution parameterName="Gap_m">
        <DistributionRange stepWidth="0.3"><Range lowerLimit="10" upperLimit="10.9"/></DistributionRange>
      </DeterministicSingleParameterDistribution>)"));
  const Variation v = load_variation(file.string());
  std::vector<std::string> values;
  for (const auto& o : v.factors.at(0).options) values.push_back(o.at(0));
  // 10.9 is reached within rounding (10 + 3 * 0.3 = 10.899999999999999).
  ASSERT_EQ(values.size(), 4u);
  EXPECT_EQ(values[0], "10");
  EXPECT_EQ(values[1], "10.3");
}

TEST(OpenScenarioVariation, MisspeltElementGetsDidYouMean) {
  const std::string e = error_of(deterministic(R"(
      <DeterministicSingleParameterDistribution parameterName="Gap_m">
        <DistributionRage stepWidth="1"><Range lowerLimit="1" upperLimit="3"/></DistributionRage>
      </DeterministicSingleParameterDistribution>)"));
  EXPECT_NE(e.find("FILE:9: error: /OpenSCENARIO/ParameterValueDistribution/Deterministic/"
                   "DeterministicSingleParameterDistribution/DistributionRage"), std::string::npos) << e;
  EXPECT_NE(e.find("did you mean \"DistributionRange\""), std::string::npos) << e;
}

TEST(OpenScenarioVariation, MisspeltAttributeGetsDidYouMean) {
  const std::string e = error_of(stochastic(R"(
      <StochasticDistribution parameterName="Gap_m">
        <NormalDistribution expectedValue="20" varianse="4"/>
      </StochasticDistribution>)"));
  EXPECT_NE(e.find("FILE:9: error:"), std::string::npos) << e;
  EXPECT_NE(e.find("NormalDistribution/@varianse"), std::string::npos) << e;
  EXPECT_NE(e.find("did you mean \"variance\""), std::string::npos) << e;
}

TEST(OpenScenarioVariation, UnknownParameterNamesTheScenarioAndSuggests) {
  const std::string e = error_of(deterministic(R"(
      <DeterministicSingleParameterDistribution parameterName="Gap_n">
        <DistributionSet><Element value="3"/></DistributionSet>
      </DeterministicSingleParameterDistribution>)"));
  EXPECT_NE(e.find("FILE:8: error:"), std::string::npos) << e;
  EXPECT_NE(e.find("declares no parameter \"Gap_n\""), std::string::npos) << e;
  EXPECT_NE(e.find("did you mean \"Gap_m\""), std::string::npos) << e;
}

TEST(OpenScenarioVariation, ValueOfTheWrongTypeIsAnError) {
  const std::string e = error_of(deterministic(R"(
      <DeterministicSingleParameterDistribution parameterName="Gap_m">
        <DistributionSet><Element value="3"/><Element value="far"/></DistributionSet>
      </DeterministicSingleParameterDistribution>)"));
  EXPECT_NE(e.find("value of parameter \"Gap_m\" (double): \"far\" is not a number"), std::string::npos) << e;
}

TEST(OpenScenarioVariation, MissingScenarioFileIsNamed) {
  const std::string e = error_of(deterministic(R"(
      <DeterministicSingleParameterDistribution parameterName="Gap_m">
        <DistributionSet><Element value="3"/></DistributionSet>
      </DeterministicSingleParameterDistribution>)", "/nonexistent/lead.xosc"));
  EXPECT_NE(e.find("FILE:5: error: /OpenSCENARIO/ParameterValueDistribution/ScenarioFile/@filepath: no scenario file "
                   "/nonexistent/lead.xosc"), std::string::npos) << e;
}

TEST(OpenScenarioVariation, ParameterVariedTwiceIsAnError) {
  const std::string e = error_of(deterministic(R"(
      <DeterministicSingleParameterDistribution parameterName="Gap_m">
        <DistributionSet><Element value="3"/></DistributionSet>
      </DeterministicSingleParameterDistribution>
      <DeterministicMultiParameterDistribution><ValueSetDistribution><ParameterValueSet>
        <ParameterAssignment parameterRef="Gap_m" value="4"/>
      </ParameterValueSet></ValueSetDistribution></DeterministicMultiParameterDistribution>)"));
  EXPECT_NE(e.find("parameter \"Gap_m\" is varied twice"), std::string::npos) << e;
}

// A set may leave out parameters another set assigns (esmini's cut-in_parameter_set.xosc):
// that run keeps the scenario's declared default.
TEST(OpenScenarioVariation, ValueSetLeavingOutAParameterRunsItAtTheScenarioDefault) {
  TempDir dir;
  const auto file = dir.write("x_variation.xosc", deterministic(R"(
      <DeterministicMultiParameterDistribution><ValueSetDistribution>
        <ParameterValueSet><ParameterAssignment parameterRef="Gap_m" value="4"/>
                           <ParameterAssignment parameterRef="Decel_mps2" value="7"/></ParameterValueSet>
        <ParameterValueSet><ParameterAssignment parameterRef="Decel_mps2" value="9"/></ParameterValueSet>
        <ParameterValueSet><ParameterAssignment parameterRef="BrakeTime_s" value="3"/></ParameterValueSet>
      </ValueSetDistribution></DeterministicMultiParameterDistribution>)"));
  const Variation v = load_variation(file.string());
  ASSERT_EQ(v.factors.size(), 1u);
  EXPECT_EQ(v.factors[0].parameters, (std::vector<std::string>{"Gap_m", "Decel_mps2", "BrakeTime_s"}));
  const std::string gap = v.declaration("Gap_m")->value, decel = v.declaration("Decel_mps2")->value,
                    brake = v.declaration("BrakeTime_s")->value;
  EXPECT_EQ(v.factors[0].options,
            (std::vector<std::vector<std::string>>{{"4", "7", brake}, {gap, "9", brake}, {gap, decel, "3"}}));
}

TEST(OpenScenarioVariation, ParameterAssignedTwiceInOneSetIsAnError) {
  const std::string e = error_of(deterministic(R"(
      <DeterministicMultiParameterDistribution><ValueSetDistribution>
        <ParameterValueSet><ParameterAssignment parameterRef="Gap_m" value="4"/>
                           <ParameterAssignment parameterRef="Gap_m" value="5"/></ParameterValueSet>
      </ValueSetDistribution></DeterministicMultiParameterDistribution>)"));
  EXPECT_NE(e.find("FILE:10: error:"), std::string::npos) << e;
  EXPECT_NE(e.find("parameter \"Gap_m\" is assigned twice in this ParameterValueSet"), std::string::npos) << e;
}

// The standard leaves a UserDefinedDistribution's content to the tool defining its type: the
// error names the type and the standard distributions to write instead (stochastic or not).
TEST(OpenScenarioVariation, UserDefinedDistributionNamesItsTypeAndWhatToUseInstead) {
  const std::string e = error_of(stochastic(R"(
      <StochasticDistribution parameterName="Gap_m">
        <UserDefinedDistribution type="mine">x</UserDefinedDistribution>
      </StochasticDistribution>)"));
  EXPECT_NE(e.find("UserDefinedDistribution (type \"mine\") cannot be sampled"), std::string::npos) << e;
  EXPECT_NE(e.find("ProbabilityDistributionSet"), std::string::npos) << e;
  EXPECT_NE(e.find("FILE:"), std::string::npos) << e;
  const std::string d = error_of(deterministic(R"(
      <DeterministicSingleParameterDistribution parameterName="Gap_m">
        <UserDefinedDistribution type="sweep">1 2 3</UserDefinedDistribution>
      </DeterministicSingleParameterDistribution>)"));
  EXPECT_NE(d.find("UserDefinedDistribution (type \"sweep\")"), std::string::npos) << d;
  EXPECT_NE(d.find("DistributionSet"), std::string::npos) << d;
}

TEST(OpenScenarioVariation, BadNumbersAreErrors) {
  EXPECT_NE(error_of(stochastic(R"(<StochasticDistribution parameterName="Gap_m"><UniformDistribution><Range lowerLimit="1" upperLimit="2"/></UniformDistribution></StochasticDistribution>)",
                                R"(numberOfTestRuns="0")")).find("numberOfTestRuns: must be >= 1"), std::string::npos);
  EXPECT_NE(error_of(stochastic(R"(<StochasticDistribution parameterName="Gap_m"><UniformDistribution><Range lowerLimit="5" upperLimit="2"/></UniformDistribution></StochasticDistribution>)"))
                .find("upperLimit 2 is below lowerLimit 5"), std::string::npos);
  EXPECT_NE(error_of(stochastic(R"(<StochasticDistribution parameterName="Gap_m"><NormalDistribution expectedValue="5" variance="-1"/></StochasticDistribution>)"))
                .find("variance: must be >= 0"), std::string::npos);
  EXPECT_NE(error_of(stochastic(R"(<StochasticDistribution parameterName="Gap_m"><Histogram><Bin weight="0"><Range lowerLimit="1" upperLimit="2"/></Bin></Histogram></StochasticDistribution>)"))
                .find("a weight must be > 0"), std::string::npos);
  EXPECT_NE(error_of(deterministic(R"(<DeterministicSingleParameterDistribution parameterName="Gap_m"><DistributionRange stepWidth="0"><Range lowerLimit="1" upperLimit="2"/></DistributionRange></DeterministicSingleParameterDistribution>)"))
                .find("stepWidth must be > 0"), std::string::npos);
}

TEST(OpenScenarioVariation, AnotherMajorRevisionIsAnError) {
  std::string text = deterministic(R"(<DeterministicSingleParameterDistribution parameterName="Gap_m"><DistributionSet><Element value="3"/></DistributionSet></DeterministicSingleParameterDistribution>)");
  text.replace(text.find("revMajor=\"1\""), 12, "revMajor=\"2\"");
  EXPECT_NE(error_of(text).find("OpenSCENARIO 2.2 is not supported"), std::string::npos);
}

// The scenario reader reads 1.0 to 1.3, and so does the variation reader: a 1.3 variation of
// the shipped 1.3 sample hill_variables.xosc reads; 1.4 is named as the revision not read.
TEST(OpenScenarioVariation, ReadsRevision13LikeTheScenarioReader) {
  std::string text = deterministic(R"(<DeterministicSingleParameterDistribution parameterName="VanSpeed"><DistributionSet><Element value="12"/><Element value="18"/></DistributionSet></DeterministicSingleParameterDistribution>)",
                                   std::string(ORCH_SOURCE_DIR) + "/scenarios/openscenario/hill_variables.xosc");
  text.replace(text.find("revMinor=\"2\""), 12, "revMinor=\"3\"");
  TempDir dir;
  const Variation v = load_variation(dir.write("hill_variation.xosc", text).string());
  EXPECT_EQ(v.rev_minor, 3);
  ASSERT_EQ(v.factors.size(), 1u);
  EXPECT_EQ(v.factors[0].options, (std::vector<std::vector<std::string>>{{"12"}, {"18"}}));
  text.replace(text.find("revMinor=\"3\""), 12, "revMinor=\"4\"");
  const std::string error = error_of(text);
  EXPECT_NE(error.find("@revMinor: OpenSCENARIO 1.4 is not supported: this reads 1.0 to 1.3"), std::string::npos) << error;
}

TEST(OpenScenarioVariation, RecognisedByContent) {
  EXPECT_TRUE(is_variation_file(kNightly + "lead_brake_variation.xosc"));
  EXPECT_FALSE(is_variation_file(kNightly + "lead_brake.xosc"));
}

}  // namespace
}  // namespace orch::openscenario

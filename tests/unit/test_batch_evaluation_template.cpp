// A logical scenario whose template is an evaluation YAML naming a scenario that is a
// template too: placeholders of both files count, both are bound with the same values, and
// the bound evaluation file names the bound scenario beside it (template_file.hpp). And
// `batch --ssm` reaches every run's command line.
#include <gtest/gtest.h>

#include <algorithm>

#include "batch/batch_runner.hpp"
#include "batch/logical_scenario.hpp"
#include "batch/sampling.hpp"
#include "batch/template_file.hpp"
#include "support/cli_runner.hpp"

using namespace orch;
using namespace orch::batch;
using orch::test::TempDir;

namespace {

const char* kEvaluation = R"(ScenarioFormatVersion: 2.0.0
ScenarioName: t
Evaluation:
  UseCaseName: scenario_executor
  UseCaseFormatVersion: 0.1.0
  Conditions:
    Scenario: SCENARIO
    Criteria:
      - {Name: min_ttc, Metric: ttc, Min: "${criteria.min_ttc}"}
)";

struct Files {
  TempDir dir;
  LogicalScenario logical;
  JsonDocument tmpl;

  Files(const std::string& scenario_text, const std::string& parameters, const std::string& scenario_name = "s.json")
      : logical(write(scenario_text, parameters, scenario_name)),
        tmpl(load_template(logical.template_file)) {}

  LogicalScenario write(const std::string& scenario_text, const std::string& parameters, const std::string& name) {
    std::string eval = kEvaluation;
    eval.replace(eval.find("SCENARIO"), 8, name);
    dir.write("eval.template.yaml", eval);
    dir.write(name, scenario_text);
    return read_logical_scenario(JsonDocument::parse(
        R"({"uuid": "L1", "template": "eval.template.yaml", "parameter_space": )" + parameters + "}",
        (dir / "logical_L1.json").string()));
  }

  [[nodiscard]] ParameterSet set(const nlohmann::json& values) const {
    ParameterSet s;
    s.uuid = "P1";
    s.sampled_values = values;
    return s;
  }
};

const std::string kBoth = R"({
  "criteria": {"min_ttc": {"type": "float", "distribution": "constant", "value": 2.5}},
  "lead": {"decel": {"type": "float", "distribution": "constant", "value": 4}}})";

const std::string kScenarioTemplate = R"({"title": "t",
  "scenario": {"scenes": [{"actions": [{"speed": {"accel": {"type": "specify", "value": "${lead.decel}"}}}]}]}})";

}  // namespace

TEST(EvaluationTemplate, APlaceholderInTheNamedScenarioCountsAndBindsIntoScenarioJson) {
  const Files f(kScenarioTemplate, kBoth);
  ASSERT_EQ(scenario_template_of(f.tmpl), (f.dir / "s.json").lexically_normal());
  const Diagnostics d = check_templates(f.logical, f.tmpl);
  EXPECT_FALSE(d.has_errors()) << d.format();

  const auto files = bound_run_files(f.logical, f.tmpl, f.set({{"criteria", {{"min_ttc", 2.5}}}, {"lead", {{"decel", 4.5}}}}));
  ASSERT_EQ(files.size(), 2u);
  EXPECT_EQ(files[0].name, "evaluation.yaml");
  const auto evaluation = nlohmann::json::parse(files[0].text);
  EXPECT_EQ(evaluation["Evaluation"]["Conditions"]["Scenario"], "scenario.json");  // beside it in the run folder
  EXPECT_EQ(evaluation["Evaluation"]["Conditions"]["Criteria"][0]["Min"], 2.5);
  EXPECT_EQ(files[1].name, "scenario.json");
  const auto scenario = nlohmann::json::parse(files[1].text);
  EXPECT_EQ(scenario["scenario"]["scenes"][0]["actions"][0]["speed"]["accel"]["value"], 4.5);
}

TEST(EvaluationTemplate, ProblemsInTheNamedScenarioAreReportedInItsFile) {
  // A placeholder naming no parameter, at its own file and line; a parameter neither file
  // uses, naming both files.
  const Files f(R"({"title": "t",
  "value": "${lead.decl}"})",
                R"({"criteria": {"min_ttc": {"type": "float", "distribution": "constant", "value": 2.5}},
                    "lead": {"decel": {"type": "float", "distribution": "constant", "value": 4}}})");
  const std::string text = check_templates(f.logical, f.tmpl).format();
  EXPECT_NE(text.find("s.json:2: error: /value: placeholder ${lead.decl} names no parameter"), std::string::npos)
      << text;
  EXPECT_NE(text.find("did you mean \"lead.decel\""), std::string::npos) << text;
  EXPECT_NE(text.find("parameter \"lead.decel\" is used nowhere in the template"), std::string::npos) << text;
  EXPECT_NE(text.find("eval.template.yaml and "), std::string::npos) << text;
}

TEST(EvaluationTemplate, APlainNamedScenarioStaysWhereItIsByAbsolutePath) {
  const Files f(R"({"title": "no placeholders"})",
                R"({"criteria": {"min_ttc": {"type": "float", "distribution": "constant", "value": 2.5}}})");
  EXPECT_FALSE(scenario_template_of(f.tmpl));
  const auto files = bound_run_files(f.logical, f.tmpl, f.set({{"criteria", {{"min_ttc", 2.0}}}}));
  ASSERT_EQ(files.size(), 1u);
  const auto evaluation = nlohmann::json::parse(files[0].text);
  EXPECT_EQ(evaluation["Evaluation"]["Conditions"]["Scenario"], (f.dir / "s.json").lexically_normal().string());
  // A parameter used only in a file that is not a template is used nowhere.
  const Files unused(R"({"title": "no placeholders"})", kBoth);
  EXPECT_TRUE(check_templates(unused.logical, unused.tmpl).has_errors());
}

TEST(BatchCommandLine, SsmIsPassedToEveryRun) {
  orch::batch::BatchOptions o;
  o.orchestrator = "/bin/orchestrator";
  orch::batch::PlannedRun run;
  run.set.seed = 3;
  const auto without = orch::batch::run_command_line(o, run, "/out/runs/r1", "/out/runs/r1/evaluation.yaml");
  EXPECT_EQ(std::count(without.begin(), without.end(), "--ssm"), 0);
  EXPECT_EQ(without.at(2), "/out/runs/r1/evaluation.yaml");
  o.ssm = true;
  const auto with = orch::batch::run_command_line(o, run, "/out/runs/r1", "/out/runs/r1/evaluation.yaml");
  EXPECT_EQ(std::count(with.begin(), with.end(), "--ssm"), 1);
}

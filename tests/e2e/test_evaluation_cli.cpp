// `orchestrator run EVAL.yaml` and `validate EVAL.yaml` on real files: criteria in the
// verdict, result.json's criteria list, result.jsonl read as an evaluator reads it (the last
// line), ScenarioFormatError for an invalid file.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <sstream>

#include "support/cli_runner.hpp"

using namespace orch::test;

namespace {

std::string shipped() { return source_path("scenarios/evaluation/highway_cut_in.yaml"); }

std::vector<nlohmann::json> jsonl(const std::filesystem::path& p) {
  std::vector<nlohmann::json> lines;
  std::ifstream in(p);
  for (std::string line; std::getline(in, line);) lines.push_back(nlohmann::json::parse(line));
  return lines;
}

// The shipped file with one text replaced, written beside nothing: the scenario by absolute path.
std::filesystem::path variant(const TempDir& dir, const std::string& from, const std::string& to) {
  std::string text = slurp(shipped());
  text.replace(text.find("../highway_cut_in.json"), 22, source_path("scenarios/highway_cut_in.json"));
  if (!from.empty()) text.replace(text.find(from), from.size(), to);
  const auto path = dir / "eval.yaml";
  std::ofstream(path) << text;
  return path;
}

}  // namespace

TEST(EvaluationCli, ShippedCutInPassesEveryCriterionAndTheLastLineSaysSo) {
  TempDir out;
  const auto r = run_scenario(shipped(), out, {"--jsonl-every", "10"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto result = read_json(out / "result.json");
  EXPECT_EQ(result["verdict"], "success");
  ASSERT_EQ(result["criteria"].size(), 7u);
  for (const auto& c : result["criteria"]) {
    EXPECT_TRUE(c["success"].get<bool>()) << c.dump();
    for (const char* key : {"name", "actor", "metric", "expected", "actual", "at_time", "success"})
      EXPECT_TRUE(c.contains(key)) << key;
  }
  EXPECT_EQ(result["criteria"][2]["metric"], "ttc");
  EXPECT_EQ(result["metrics"]["0"]["min_ttc"]["partner"], 1);
  EXPECT_EQ(result["inputs"]["evaluation"]["path"], shipped());

  const auto lines = jsonl(out / "result.jsonl");
  ASSERT_GE(lines.size(), 3u);
  EXPECT_EQ(lines.front()["Condition"]["Scenario"], "../highway_cut_in.json");
  const long long steps = result["steps"];
  EXPECT_EQ(static_cast<long long>(lines.size()), 2 + (steps + 9) / 10);  // every 10th step
  const auto& frame = lines[lines.size() - 2];
  EXPECT_EQ(frame["Frame"]["no_collision"]["Result"]["Total"], "Success");
  EXPECT_TRUE(frame["Stamp"].contains("System"));
  const auto& last = lines.back();
  EXPECT_TRUE(last["Result"]["Success"].get<bool>());
  EXPECT_EQ(last["Result"]["Summary"].get<std::string>().rfind("Passed: ", 0), 0u);
  EXPECT_DOUBLE_EQ(last["Stamp"]["Simulation"].get<double>(), result["sim_time"].get<double>());
  EXPECT_TRUE(last["Frame"].empty());
  EXPECT_EQ(slurp(out / "metrics.csv").substr(0, 20), "time,actor_id,leader");
}

TEST(EvaluationCli, AFailingCriterionFailsTheRunNamingExpectedAndActual) {
  TempDir dir, out;
  const auto eval = variant(dir, "Min: 4.0", "Min: 20.0");
  const auto r = run_scenario(eval.string(), out);
  ASSERT_EQ(r.exit_code, 1) << r.output;
  const auto result = read_json(out / "result.json");
  EXPECT_EQ(result["verdict"], "failure");
  const std::string reason = result["reason"];
  EXPECT_NE(reason.find("criteria failed: min_ttc: expected ttc >= 20 at every step, actual "), std::string::npos)
      << reason;
  EXPECT_EQ(result["criteria"][2]["success"], false);
  EXPECT_LT(result["criteria"][2]["actual"].get<double>(), 20.0);
  const auto last = jsonl(out / "result.jsonl").back();
  EXPECT_FALSE(last["Result"]["Success"].get<bool>());
  EXPECT_EQ(last["Result"]["Summary"].get<std::string>().rfind("Failed: criteria failed: min_ttc", 0), 0u);
}

TEST(EvaluationCli, AnInvalidFileEndsWithScenarioFormatError) {
  TempDir dir, out;
  const auto eval = variant(dir, "Metric: ttc", "Metrc: ttc");
  const auto r = run_scenario(eval.string(), out);
  ASSERT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("eval.yaml:20: error: /Evaluation/Conditions/Criteria/2/Metrc: unknown key"),
            std::string::npos)
      << r.output;
  EXPECT_EQ(read_json(out / "result.json")["verdict"], "error");
  const auto last = jsonl(out / "result.jsonl").back();
  EXPECT_FALSE(last["Result"]["Success"].get<bool>());
  const std::string summary = last["Result"]["Summary"];
  EXPECT_EQ(summary.rfind("ScenarioFormatError: ", 0), 0u) << summary;
  EXPECT_NE(summary.find("eval.yaml:"), std::string::npos) << summary;
}

TEST(EvaluationCli, ACriterionNamingAnUnknownActorIsAnErrorBeforeSumoStarts) {
  TempDir dir, out;
  const auto eval = variant(dir, "Metric: ttc", "Actor: 9\n        Metric: ttc");
  const auto r = run_scenario(eval.string(), out);
  ASSERT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(read_json(out / "result.json")["reason"].get<std::string>().find("names actor 9"), std::string::npos);
  EXPECT_EQ(jsonl(out / "result.jsonl").back()["Result"]["Summary"].get<std::string>().rfind("ScenarioFormatError", 0),
            0u);
}

TEST(EvaluationCli, ValidateChecksEvaluationFilesAndTheirScenario) {
  const auto ok = run_cli({"validate", shipped()});
  EXPECT_EQ(ok.exit_code, 0) << ok.output;
  TempDir dir;
  const auto bad = run_cli({"validate", variant(dir, "2.0.0", "4.0.0").string()});
  EXPECT_EQ(bad.exit_code, 1) << bad.output;
  EXPECT_NE(bad.output.find("eval.yaml:3: error: /ScenarioFormatVersion: format version 4.0.0 is not known"),
            std::string::npos)
      << bad.output;
}

// The values of one column of a CSV text, by header name.
std::vector<std::string> csv_column(const std::string& csv, const std::string& name) {
  std::istringstream lines(csv);
  std::string line;
  std::getline(lines, line);
  const auto split = [](const std::string& row) {
    std::vector<std::string> cells;
    std::istringstream in(row);
    for (std::string cell; std::getline(in, cell, ',');) cells.push_back(cell);
    return cells;
  };
  const auto header = split(line);
  const auto at = std::find(header.begin(), header.end(), name);
  std::vector<std::string> values;
  if (at == header.end()) return values;
  while (std::getline(lines, line)) values.push_back(split(line).at(static_cast<std::size_t>(at - header.begin())));
  return values;
}

TEST(EvaluationCli, NightlyBatchWithAnEvaluationTemplateTabulatesCriteriaAndMetrics) {
  TempDir out;
  const auto logical = source_path("scenarios/evaluation/nightly/logical_5d3c2a4e-6f1b-4c8e-9a7d-2b1e0f9c8d71.json");
  const auto r = run_cli({"batch", logical, "--out", out.path().string(), "--jobs", "2"});
  ASSERT_EQ(r.exit_code, 1) << r.output;  // some runs fail their criteria, none errs
  const auto summary = read_json(out / "summary.json");
  ASSERT_EQ(summary["runs"].size(), 8u);
  int success = 0, failure = 0;
  for (const auto& run : summary["runs"]) {
    ASSERT_EQ(run["criteria"].size(), 4u) << run.dump();
    ASSERT_TRUE(run["metrics"].contains("0"));
    // The bound threshold is the one judged: min_ttc fails exactly when the required TTC
    // exceeds the run's minimum TTC.
    const double required = run["sampled_values"]["criteria"]["min_ttc"];
    const double measured = run["metrics"]["0"]["min_ttc"]["value"];
    EXPECT_EQ(run["criteria"][1]["success"].get<bool>(), measured >= required) << run.dump();
    EXPECT_DOUBLE_EQ(run["criteria"][1]["actual"].get<double>(), measured);
    // The scenario the evaluation template names is a template too: the run drove the lead's
    // sampled deceleration (scenario.json beside evaluation.yaml in the run folder).
    const std::filesystem::path dir = out / run["run_dir"].get<std::string>();
    const double decel = run["sampled_values"]["lead"]["decel"];
    EXPECT_NE(slurp(dir / "run.log").find(fmt::format("speed: actor 1 to 0.0 km/h at {:g} m/s^2", decel)),
              std::string::npos)
        << decel << "\n" << slurp(dir / "run.log");
    EXPECT_NE(slurp(dir / "evaluation.yaml").find("\"Scenario\": \"scenario.json\""), std::string::npos);
    (run["verdict"] == "success" ? success : failure)++;
  }
  EXPECT_GT(success, 0);
  EXPECT_GT(failure, 0);
  // One row per run, the parameters, each criterion's actual value and each metric summary.
  const std::string csv = slurp(out / "metrics.csv");
  std::istringstream lines(csv);
  std::string header;
  std::getline(lines, header);
  for (const char* column : {"run_id,logical_uuid,parameter_uuid,seed,verdict", "criteria.min_ttc", "lead.decel",
                             "criterion.min_ttc.actual", "criterion.min_ttc.success", "metrics.0.min_ttc"})
    EXPECT_NE(header.find(column), std::string::npos) << column;
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 9);
  // The parameter range gives passing and failing criteria: the TTC requirement (a threshold
  // parameter) and the deceleration bound (met or not depending on how hard the lead brakes).
  for (const char* criterion : {"criterion.min_ttc.success", "criterion.deceleration.success"}) {
    const auto column = csv_column(csv, criterion);
    EXPECT_GT(std::count(column.begin(), column.end(), "true"), 0) << criterion << "\n" << csv;
    EXPECT_GT(std::count(column.begin(), column.end(), "false"), 0) << criterion << "\n" << csv;
  }
  // JUnit: a failing run's message names its failing criteria with expected and actual values.
  const std::string junit = slurp(out / "junit.xml");
  EXPECT_NE(junit.find("message=\"criteria failed: min_ttc: expected ttc >= "), std::string::npos);
}

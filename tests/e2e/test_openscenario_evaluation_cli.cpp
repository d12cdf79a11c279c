// OpenSCENARIO runs judged and shown like ScenarioExecutor runs, through the real CLI on
// SUMO: metrics.csv of the entities (by name), criteria from an evaluation file whose
// scenario is a .xosc (a passing and a failing one decide the verdict), the storyboard's
// transitions as result.json events, and the ego chosen by the documented rule.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

#include "support/cli_runner.hpp"

using namespace orch::test;

namespace {

const std::string kCutIn = source_path("scenarios/openscenario/cut_in_traffic.xosc");
const std::string kEvaluation = source_path("scenarios/evaluation/openscenario_cut_in.yaml");

std::vector<std::vector<std::string>> csv_rows(const std::filesystem::path& p) {
  std::vector<std::vector<std::string>> rows;
  std::ifstream in(p);
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> cells;
    std::stringstream s(line);
    for (std::string cell; std::getline(s, cell, ',');) cells.push_back(cell);
    if (!line.empty() && line.back() == ',') cells.emplace_back();
    rows.push_back(std::move(cells));
  }
  return rows;
}

nlohmann::json last_jsonl_line(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::string line, last;
  while (std::getline(in, line)) last = line;
  return nlohmann::json::parse(last);
}

// The shipped evaluation file with one text replaced, its scenario by absolute path.
std::filesystem::path variant(const TempDir& dir, const std::string& from, const std::string& to) {
  std::string text = slurp(kEvaluation);
  const std::string scenario = "../openscenario/cut_in_traffic.xosc";
  text.replace(text.find(scenario), scenario.size(), kCutIn);
  if (!from.empty()) {
    const auto at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    text.replace(at, from.size(), to);
  }
  const auto path = dir / "eval.yaml";
  std::ofstream(path) << text;
  return path;
}

}  // namespace

TEST(OpenScenarioEvaluationCli, CutInMeasuresItsEntitiesByNameLikeTheEgosExposure) {
  TempDir out;
  const auto r = run_scenario(kCutIn, out);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto result = read_json(out / "result.json");
  const auto rows = csv_rows(out / "metrics.csv");
  ASSERT_GT(rows.size(), 100u);
  // The columns metrics.csv has always had come first; a metric added later appends its own.
  ASSERT_GE(rows[0].size(), 14u);
  EXPECT_EQ(std::vector<std::string>(rows[0].begin(), rows[0].begin() + 14),
            (std::vector<std::string>{"time", "actor_id", "leader", "gap", "rel_speed", "ttc", "thw", "drac", "accel",
                                      "jerk", "lat_accel", "lane_departure", "min_dist", "min_dist_to"}));
  // The ego's smallest TTC in metrics.csv is result.json's, and the one its exposure watch saw.
  double min_ttc = std::numeric_limits<double>::infinity();
  std::size_t ego_rows = 0, led_by_cut_in = 0;
  for (std::size_t i = 1; i < rows.size(); ++i) {
    ASSERT_EQ(rows[i].size(), rows[0].size()) << i;
    if (rows[i][1] != "Ego") continue;
    ++ego_rows;
    led_by_cut_in += rows[i][2] == "CutIn";
    if (!rows[i][5].empty()) min_ttc = std::min(min_ttc, std::stod(rows[i][5]));
  }
  EXPECT_EQ(static_cast<long long>(ego_rows), result["steps"].get<long long>());
  EXPECT_GT(led_by_cut_in, 100u) << "the car cut in ahead of the ego and stayed its leader";
  ASSERT_TRUE(std::isfinite(min_ttc));
  const auto& ego = result["metrics"]["Ego"];
  EXPECT_NEAR(ego["min_ttc"]["value"].get<double>(), min_ttc, 1e-3);
  EXPECT_EQ(ego["min_ttc"]["partner"], "CutIn");
  EXPECT_NEAR(ego["min_ttc"]["value"].get<double>(), result["ego_exposure"]["min_ttc"].get<double>(), 0.05);
  EXPECT_NEAR(ego["min_gap"]["value"].get<double>(), result["ego_exposure"]["min_gap"].get<double>(), 0.05);
  EXPECT_TRUE(result["metrics"].contains("CutIn"));
}

TEST(OpenScenarioEvaluationCli, StoryboardTransitionsAreEventsInTimeOrderAsRunLogHasThem) {
  TempDir out;
  const auto r = run_scenario(kCutIn, out);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto result = read_json(out / "result.json");
  const auto& events = result["events"];
  ASSERT_GT(events.size(), 10u);
  const std::string log = slurp(out / "run.log");
  double last = 0;
  std::map<std::string, double> started;
  for (const auto& e : events) {
    const double t = e["time"];
    EXPECT_GE(t, last) << e.dump();
    last = t;
    const std::string text = e["text"];
    EXPECT_EQ(e["kind"], text.rfind("action ", 0) == 0 ? "action" : "storyboard") << text;
    EXPECT_NE(log.find(text + "\n"), std::string::npos) << "run.log has the same line: " << text;
    if (text.ends_with(" startTransition")) started.emplace(text, t);
  }
  ASSERT_TRUE(started.count("act CutInAct startTransition"));
  EXPECT_DOUBLE_EQ(started["act CutInAct startTransition"], 0.0);
  ASSERT_TRUE(started.count("event CutInEvent startTransition"));
  EXPECT_GT(started["event CutInEvent startTransition"], 1.0) << "the cut-in waits for its trigger";
  EXPECT_EQ(events.back()["text"], "storyboard  stopTransition");
  EXPECT_DOUBLE_EQ(events.back()["time"].get<double>(), result["sim_time"].get<double>());
}

TEST(OpenScenarioEvaluationCli, ShippedEvaluationOfTheXoscPassesEveryCriterion) {
  TempDir out;
  const auto r = run_scenario(kEvaluation, out, {"--jsonl-every", "20"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto result = read_json(out / "result.json");
  EXPECT_EQ(result["verdict"], "success") << result["reason"];
  ASSERT_EQ(result["criteria"].size(), 7u);
  for (const auto& c : result["criteria"]) EXPECT_TRUE(c["success"].get<bool>()) << c.dump();
  EXPECT_EQ(result["criteria"][2]["name"], "min_ttc");
  EXPECT_NEAR(result["criteria"][2]["actual"].get<double>(), result["metrics"]["Ego"]["min_ttc"]["value"].get<double>(),
              1e-6);
  EXPECT_EQ(result["criteria"][6]["actor"], 1) << "Actor 1: the second entity, CutIn";
  EXPECT_EQ(result["inputs"]["evaluation"]["path"], kEvaluation);
  EXPECT_EQ(last_jsonl_line(out / "result.jsonl")["Result"]["Success"], true);
}

TEST(OpenScenarioEvaluationCli, AFailingCriterionFailsTheRunThatReachedItsStopTrigger) {
  TempDir dir, out;
  const auto r = run_scenario(variant(dir, "Min: 4.0", "Min: 40.0").string(), out);
  EXPECT_EQ(r.exit_code, 1) << r.output;
  const auto result = read_json(out / "result.json");
  EXPECT_EQ(result["verdict"], "failure");
  const std::string reason = result["reason"];
  EXPECT_EQ(reason.rfind("criteria failed: min_ttc: expected ttc >= 40 at every step, actual ", 0), 0u) << reason;
  EXPECT_NE(reason.find("(the Storyboard's StopTrigger fired"), std::string::npos) << reason;
  const auto last = last_jsonl_line(out / "result.jsonl");
  EXPECT_EQ(last["Result"]["Success"], false);
  EXPECT_EQ(last["Result"]["Summary"].get<std::string>().rfind("Failed: criteria failed: min_ttc", 0), 0u);
}

TEST(OpenScenarioEvaluationCli, CriteriaNamingWhatAnOpenScenarioRunLacksAreErrors) {
  TempDir dir, out;
  auto r = run_scenario(variant(dir, "Actor: 1", "Actor: 5").string(), out);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  std::string reason = read_json(out / "result.json")["reason"];
  EXPECT_NE(reason.find("eval.yaml"), std::string::npos) << reason;
  EXPECT_NE(reason.find("criterion \"cut_in_car_braking\" names actor 5; the OpenSCENARIO file has 2 entities"),
            std::string::npos)
      << reason;
  EXPECT_EQ(last_jsonl_line(out / "result.jsonl")["Result"]["Summary"].get<std::string>().rfind("ScenarioFormatError", 0),
            0u);
  TempDir dir2, out2;
  r = run_scenario(variant(dir2, "FromTime: 10", "FromScene: 2").string(), out2);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  reason = read_json(out2 / "result.json")["reason"];
  EXPECT_NE(reason.find("an OpenSCENARIO run has none"), std::string::npos) << reason;
}

TEST(OpenScenarioEvaluationCli, TheSeedsOvertakingEgoIsChosenByItsSystemUnderTestController) {
  TempDir out;
  const auto r = run_scenario(source_path("scenarios/openscenario/overtaking.xosc"), out);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto result = read_json(out / "result.json");
  bool ego_marked = false;
  for (const auto& a : result["actors"]) ego_marked |= a["sumo_id"] == "Ego" && a["ego"] == true;
  EXPECT_TRUE(ego_marked) << result["actors"].dump();
  EXPECT_NE(slurp(out / "run.log").find("Ego: driven by SUMO (controller SystemUnderTest is a system under test); the "
                                        "ego of metrics and the report because its controller is named SystemUnderTest"),
            std::string::npos);
}

// A logical scenario whose template is an evaluation YAML naming the .xosc: the required
// minimum TTC is the parameter; each run passes exactly when the ego's TTC keeps it.
TEST(OpenScenarioEvaluationCli, BatchOfAnEvaluationTemplateJudgesEachRunByItsBoundThreshold) {
  TempDir dir;
  std::string yaml = slurp(kEvaluation);
  const std::string scenario = "../openscenario/cut_in_traffic.xosc";
  yaml.replace(yaml.find(scenario), scenario.size(), kCutIn);
  yaml.replace(yaml.find("Min: 4.0"), 8, "Min: \"${criteria.min_ttc}\"");
  std::ofstream(dir / "cut_in.template.yaml") << yaml;
  const std::string uuid = "7e1f0c2a-osc-eval";
  std::ofstream(dir / ("logical_" + uuid + ".json")) << R"({"uuid": ")" << uuid << R"(", "name": "OSC cut-in TTC",
    "template": "cut_in.template.yaml", "sumo_config": {"step": 0.05, "max_time": 60},
    "parameter_space": {"criteria": {"min_ttc": {"type": "float", "unit": "s", "distribution": "uniform", "min": 20.0, "max": 45.0}}}})";
  const std::string logical = (dir / ("logical_" + uuid + ".json")).string();
  ASSERT_EQ(run_cli({"sample", logical, "--count", "4", "--seed", "3"}).exit_code, 0);
  const auto r = run_cli({"batch", logical, "--out", (dir / "out").string(), "--jobs", "2"});
  ASSERT_LE(r.exit_code, 1) << r.output;
  const auto summary = read_json(dir / "out" / "summary.json");
  ASSERT_EQ(summary["runs"].size(), 4u) << summary.dump();
  int successes = 0, failures = 0;
  for (const auto& run : summary["runs"]) {
    const double required = run["sampled_values"]["criteria"]["min_ttc"];
    double achieved = -1;
    for (const auto& c : run["criteria"])
      if (c["name"] == "min_ttc") achieved = c["actual"];
    EXPECT_GT(achieved, 20.0) << run.dump();
    EXPECT_EQ(run["verdict"], achieved >= required ? "success" : "failure") << run.dump();
    (achieved >= required ? successes : failures)++;
  }
  EXPECT_GE(successes, 1);
  EXPECT_GE(failures, 1);
  // The batch's metrics.csv has the ego's summary under its entity name.
  EXPECT_NE(slurp(dir / "out" / "metrics.csv").find(",metrics.Ego.min_ttc,"), std::string::npos);
}

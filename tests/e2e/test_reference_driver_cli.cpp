// The R157 reference driver through the CLI: the same bytes on both backends, the
// evaluation file's EgoModel (bad parameters are errors with "did you mean"), the reference
// run and its criterion, and the nightly example's batch with the `preventable` column.
#include <gtest/gtest.h>

#include <filesystem>
#include <set>

#include "support/cli_runner.hpp"
#include "support/ego_plugin_run.hpp"
#include "support/trace_csv.hpp"

using namespace orch::test;
namespace fs = std::filesystem;

namespace {

std::string sample(const std::string& name) { return source_path("scenarios/" + name); }

// The ego's speeds in trace.csv, one per row of the ego (actor 0).
std::vector<double> ego_speeds(const fs::path& trace) {
  const Trace t(trace);
  std::vector<double> out;
  for (const auto& row : t.actor(0)) out.push_back(row.num("speed"));
  return out;
}

std::string evaluation_yaml(const std::string& scenario, const std::string& extra, const std::string& criteria) {
  return "ScenarioFormatVersion: 2.0.0\nScenarioName: r157\n" + extra +
         "Evaluation:\n  UseCaseName: scenario_executor\n  UseCaseFormatVersion: 0.1.0\n  Conditions:\n"
         "    Scenario: " + scenario + "\n    Criteria:\n" + criteria;
}

}  // namespace

TEST(ReferenceDriverCli, LibsumoAndTraciGiveByteIdenticalTracesWithTheR157Ego) {
  TempDir a, b;
  auto run = [&](const TempDir& out, const char* backend) {
    return run_cli({"run", sample("highway_cut_in.json"), "--out", out.path().string(), "-q", "--no-report",
                    "--ego-model", "r157", "--traffic", "dense", "--seed", "3", "--max-time", "20", "--backend",
                    backend});
  };
  const auto ra = run(a, "libsumo");
  const auto rb = run(b, "traci");
  EXPECT_EQ(ra.exit_code, rb.exit_code) << ra.output << rb.output;
  EXPECT_EQ(read_json(a / "result.json")["ego_model"], "r157");
  for (const char* file : {"trace.csv", "metrics.csv"}) {
    SCOPED_TRACE(file);
    const std::string bytes = slurp(a / file);
    EXPECT_GT(bytes.size(), 1000u);
    EXPECT_TRUE(bytes == slurp(b / file));
  }
}

// The lead vehicle brakes at 5 m/s^2 to a stop: the reference driver keeps its following
// distance, stops behind it without touching it, and drives otherwise than SUMO's model.
TEST(ReferenceDriverCli, R157EgoStopsBehindTheBrakingLead) {
  TempDir sumo, r157;
  ASSERT_EQ(run_cli({"run", sample("alks_lead_brake.json"), "--out", sumo.path().string(), "-q", "--no-report"})
                .exit_code,
            0);
  const auto r = run_cli({"run", sample("alks_lead_brake.json"), "--out", r157.path().string(), "-q", "--no-report",
                          "--ego-model", "r157"});
  const auto result = read_json(r157 / "result.json");
  EXPECT_EQ(result["verdict"], "success") << result["reason"];
  EXPECT_TRUE(result["collision"].is_null());
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(ego_speeds(sumo / "trace.csv"), ego_speeds(r157 / "trace.csv"));
  EXPECT_NE(slurp(r157 / "run.log").find("UN R157 reference driver"), std::string::npos);
  // The trace says who drove the ego: the model, not SUMO's driver.
  const Trace by_model(r157 / "trace.csv"), by_sumo(sumo / "trace.csv");
  for (const auto& row : by_model.actor(0)) ASSERT_EQ(row.str("driver"), "r157");
  for (const auto& row : by_sumo.actor(0)) ASSERT_EQ(row.str("driver"), "sumo");
}

TEST(ReferenceDriverCli, UnknownEgoModelParameterIsAnErrorWithDidYouMean) {
  TempDir dir;
  const auto file = dir.write("bad.yaml", evaluation_yaml(sample("alks_lead_brake.json"),
                                                          "EgoModel:\n  Name: r157\n  Parameters: {brake_reaction_tme: 1.0}\n",
                                                          "      - {Name: no_collision, Type: no_collision}\n"));
  const auto v = run_cli({"validate", file.string()});
  EXPECT_NE(v.exit_code, 0);
  EXPECT_NE(v.output.find("brake_reaction_tme"), std::string::npos) << v.output;
  EXPECT_NE(v.output.find("did you mean \"brake_reaction_time\""), std::string::npos) << v.output;
  EXPECT_NE(v.output.find("/EgoModel/Parameters"), std::string::npos) << v.output;
  const auto bad_name = dir.write("bad_name.yaml", evaluation_yaml(sample("alks_lead_brake.json"), "EgoModel: r175\n",
                                                                   "      - {Name: no_collision, Type: no_collision}\n"));
  const auto n = run_cli({"validate", bad_name.string()});
  EXPECT_NE(n.output.find("did you mean \"r157\""), std::string::npos) << n.output;
}

// A scripted car runs into the ego from behind: no driver ahead could avoid that, so the
// reference driver is hit too. With no_preventable_collision the collision is unavoidable
// and does not fail the run; the evaluation file's EgoModel and parameters are used.
TEST(ReferenceDriverCli, NoPreventableCollisionPassesAnUnavoidableCollision) {
  TempDir dir;
  const auto file = dir.write(
      "rear.yaml", evaluation_yaml(sample("ego_rear_ended.json"),
                                   "EgoModel: {Name: sumo}\n",
                                   "      - {Name: not_preventable, Type: no_preventable_collision}\n"));
  const auto r = run_cli({"run", file.string(), "--out", (dir / "out").string(), "-q", "--no-report"});
  const auto result = read_json(dir / "out" / "result.json");
  ASSERT_FALSE(result["collision"].is_null()) << result["reason"];
  EXPECT_EQ(result["preventable"], "unavoidable");
  EXPECT_TRUE(fs::exists(dir / "out" / "reference" / "trace.csv"));
  bool found = false;
  for (const auto& c : result["criteria"])
    if (c["name"] == "not_preventable") {
      found = true;
      EXPECT_TRUE(c["success"].get<bool>());
    }
  EXPECT_TRUE(found);
  EXPECT_EQ(result["verdict"], "success") << result["reason"];
  EXPECT_NE(result["reason"].get<std::string>().find("unavoidable"), std::string::npos);
  EXPECT_EQ(r.exit_code, 0) << r.output;
}

// The nightly example with --reference-run: every run's row in the batch's metrics.csv and
// the batch report carry `preventable`.
TEST(ReferenceDriverCli, NightlyBatchWithReferenceRunHasThePreventableColumn) {
  TempDir dir;
  for (const auto& e : fs::directory_iterator(source_path("scenarios/nightly")))
    if (e.path().filename().string().find("_parameters.json") == std::string::npos)
      fs::copy_file(e.path(), dir / e.path().filename().string());
  std::vector<std::string> args{"batch"};
  for (const char* uuid : {"344b1b1a-8831-46a0-a4e1-e7104d3ce4b5", "9202dd94-2666-4583-a45c-f8396b848ae9"}) {
    const auto logical = (dir / (std::string("logical_") + uuid + ".json")).string();
    ASSERT_EQ(run_cli({"sample", logical, "--count", "2", "--seed", "1"}).exit_code, 0);
    args.push_back(logical);
  }
  args.insert(args.end(), {"--out", (dir / "out").string(), "--jobs", "2", "--reference-run"});
  const auto r = run_cli(args);
  ASSERT_NE(r.exit_code, 2) << r.output;
  const std::string csv = slurp(dir / "out" / "metrics.csv");
  const std::string header = csv.substr(0, csv.find('\n'));
  ASSERT_NE(header.find(",preventable"), std::string::npos) << header;
  // Every run has a value: count the rows that name one.
  int rows = 0, with_value = 0;
  std::size_t at = csv.find('\n') + 1;
  while (at < csv.size()) {
    const std::size_t end = csv.find('\n', at);
    const std::string row = csv.substr(at, end - at);
    ++rows;
    if (row.find(",no_collision") != std::string::npos || row.find(",preventable") != std::string::npos ||
        row.find(",unavoidable") != std::string::npos)
      ++with_value;
    at = end + 1;
  }
  EXPECT_EQ(rows, 4);
  EXPECT_EQ(with_value, rows);
  const std::string report = slurp(dir / "out" / "report.html");
  EXPECT_NE(report.find("\"preventable\":\""), std::string::npos);
}

// `preventable` end to end (issue 26): a plug-in ego that takes over at 0.5 s and never brakes
// (drive.py handover: the set speed, SUMO's checks off) runs into the lead car braking at
// 6 m/s^2 from 65 km/h 30 m ahead; the reference run's R157 driver perceives the decelerating
// lead vehicle and stops behind it. With Gap_m=3, Decel_mps2=10 and BrakeTime_s=1 neither
// stops in time: the same conflict (the lead car, within a second) in both runs, unavoidable.
TEST(ReferenceDriverCli, APluginEgoThatDoesNotBrakeCollidesPreventably) {
  const std::string scenario = sample("openscenario/lead_brake_hand_over.xosc");
  for (const bool close : {false, true}) {
    TempDir out;
    std::vector<std::string> extra{"--reference-run", "--no-report"};
    if (close)
      extra.insert(extra.end(), {"--param", "Gap_m=3", "--param", "Decel_mps2=10", "--param", "BrakeTime_s=1"});
    const auto r = run_with_plugin(scenario, out,
                                   python_client("drive.py", {"--port", "{port}", "--mode", "handover", "--speed",
                                                              std::to_string(65 / 3.6)}),
                                   extra, 120);
    ASSERT_FALSE(r.result.is_null()) << r.orchestrator_output << r.plugin_output;
    ASSERT_TRUE(r.result["collision"].is_object()) << r.result.dump(1);
    EXPECT_EQ(r.result["collision"]["with"], "LeadVehicle");
    if (close) {
      ASSERT_TRUE(r.result["reference_collision"].is_object()) << r.result.dump(1);
      EXPECT_EQ(r.result["reference_collision"]["with"], "LeadVehicle");
      EXPECT_EQ(r.result["preventable"], "unavoidable");
    } else {
      EXPECT_TRUE(r.result["reference_collision"].is_null()) << r.result["reference_collision"].dump();
      EXPECT_EQ(r.result["preventable"], "preventable");
      EXPECT_EQ(r.result["verdict"], "failure");
      // The careful driver's answer is in the reference run's log.
      const std::string log = slurp(out / "reference" / "run.log");
      EXPECT_NE(log.find("r157: decelerating lead vehicle (LeadVehicle"), std::string::npos) << log;
    }
  }
}


// The ScenarioExecutor twin of ego_does_not_brake_outcomes.xosc (issue 26): three parameter sets
// of scenarios/nightly/logical_4aae47a9-..., run with the cruise ego (its route's speed, no
// braking) and a reference run: a car drives away (no_collision), a car brakes to a stop 40 m
// ahead (the cruise ego hits it, the R157 driver stops: preventable), a car runs into the ego
// from behind (both are hit: unavoidable).
TEST(ReferenceDriverCli, TheCruiseEgoBatchGivesAllThreeVerdicts) {
  TempDir dir;
  for (const char* f : {"ego_does_not_brake.template.json", "logical_4aae47a9-c775-4dd8-9373-02c03b91dd6b.json",
                        "logical_4aae47a9-c775-4dd8-9373-02c03b91dd6b_parameters.json"})
    fs::copy_file(source_path(std::string("scenarios/nightly/") + f), dir / f);
  const auto r = run_cli({"batch", (dir / "logical_4aae47a9-c775-4dd8-9373-02c03b91dd6b_parameters.json").string(),
                          "--ego-model", "cruise", "--reference-run", "--jobs", "2", "--out", (dir / "out").string()});
  ASSERT_NE(r.exit_code, 2) << r.output;
  std::multiset<std::string> outcomes;
  for (const auto& run : fs::directory_iterator(dir / "out" / "runs")) {
    const auto result = read_json(run.path() / "result.json");
    outcomes.insert(result["preventable"].get<std::string>());
    EXPECT_EQ(result["ego_model"], "cruise") << run.path();
    const Trace trace(run.path() / "trace.csv");
    for (const auto& row : trace.actor(0)) ASSERT_EQ(row.str("driver"), "cruise") << run.path();
    EXPECT_NE(slurp(run.path() / "run.log").find("ego driven by the cruise model"), std::string::npos);
    if (result["preventable"] == "no_collision") continue;
    EXPECT_EQ(result["collision"]["with"], "actor 1") << result.dump(1);
    // The cruise ego never brakes: its speed never falls while it drives (it starts standing).
    const auto speeds = ego_speeds(run.path() / "trace.csv");
    for (std::size_t i = 1; i < speeds.size(); ++i) ASSERT_GE(speeds[i], speeds[i - 1] - 1e-3) << run.path() << " row " << i;
    if (result["preventable"] == "unavoidable")
      EXPECT_EQ(result["reference_collision"]["with"], "actor 1") << result.dump(1);
    else
      EXPECT_TRUE(result["reference_collision"].is_null()) << result.dump(1);
  }
  EXPECT_EQ(outcomes, (std::multiset<std::string>{"no_collision", "preventable", "unavoidable"}));
  const std::string csv = slurp(dir / "out" / "metrics.csv");
  for (const char* outcome : {",no_collision", ",preventable", ",unavoidable"})
    EXPECT_NE(csv.find(outcome), std::string::npos) << outcome << "\n" << csv;
}

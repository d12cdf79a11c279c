// The eight OSC-ALKS files run on SUMO with the real CLI: to the Storyboard's StopTrigger
// with no error, byte-identical traces on libsumo and traci, and the entities SUMO placed
// within 0.10 m of the positions another player (esmini) computes.
#include <gtest/gtest.h>

#include <cmath>
#include <fmt/format.h>

#include "shared_data/alks_references.hpp"
#include "support/cli_runner.hpp"
#include "support/trace_csv.hpp"

using namespace orch::test;

namespace {

const char* const kAlksFiles[] = {
    "alks_scenario_4_1_1_free_driving_template",
    "alks_scenario_4_1_2_swerving_lead_vehicle_template",
    "alks_scenario_4_2_1_fully_blocking_target_template",
    "alks_scenario_4_2_4_multiple_blocking_targets_template",
    "alks_scenario_4_3_1_follow_lead_vehicle_comfortable_template",
    "alks_scenario_4_4_1_cut_in_no_collision_template",
    "alks_scenario_4_5_1_cut_out_fully_blocking_template",
    "alks_scenario_4_6_1_forward_detection_range_template",
};

class AlksOnSumo : public ::testing::TestWithParam<const char*> {};

TEST_P(AlksOnSumo, RunsToTheStopTriggerOnBothBackendsWithTheReferencePositions) {
  const std::string name = GetParam();
  const std::string file = std::string(ORCH_SHARED_DATA_DIR) + "/openscenario/" + name + ".xosc";
  TempDir out;
  for (const char* backend : {"libsumo", "traci"}) {
    const auto r = run_cli({"run", file, "--backend", backend, "--out", (out / backend).string(), "-q"});
    const auto result = read_json(out / backend / "result.json");
    EXPECT_EQ(result["verdict"], "success") << backend << ": " << result["reason"] << "\n" << r.output;
    EXPECT_NE(result["reason"].get<std::string>().find("StopTrigger"), std::string::npos) << result["reason"];
    EXPECT_EQ(r.exit_code, 0) << r.output;
  }
  const std::string traced = slurp(out / "libsumo" / "trace.csv");
  EXPECT_EQ(traced, slurp(out / "traci" / "trace.csv")) << "the backends' traces differ";

  const Trace trace(out / "libsumo" / "trace.csv");
  int checked = 0;
  for (const Reference& ref : kAlksReferences) {
    if (name != ref.file) continue;
    const std::string time = fmt::format("{:.3f}", ref.time);
    const Trace::Row* row = nullptr;
    for (const auto& candidate : trace.rows())
      if (candidate.str("time") == time && candidate.str("actor_id") == ref.entity) row = &candidate;
    ASSERT_NE(row, nullptr) << ref.entity << " has no row at t=" << time;
    EXPECT_NEAR(row->num("x"), ref.x, 0.10) << ref.entity << " @" << time;
    EXPECT_NEAR(row->num("y"), ref.y, 0.10) << ref.entity << " @" << time;
    EXPECT_NEAR(std::remainder(row->num("heading") - ref.heading, 2 * M_PI), 0.0, 0.01) << ref.entity << " @" << time;
    EXPECT_NEAR(row->num("speed"), ref.speed, 0.01) << ref.entity << " @" << time;
    ++checked;
  }
  // Every scenario's entities are on SUMO lanes the whole run (the lane hints hold).
  for (const auto& row : trace.rows()) ASSERT_FALSE(row.str("edge").empty()) << row.str("actor_id") << " @" << row.str("time");
  RecordProperty("reference_positions", checked);
}

INSTANTIATE_TEST_SUITE_P(OscAlks, AlksOnSumo, ::testing::ValuesIn(kAlksFiles));

}  // namespace

// --traffic on the converted net: background cars on the driving lanes only (the hard
// shoulders are closed to them), around a cut-in that still runs to its StopTrigger.
TEST(AlksOnSumoWithTraffic, DenseBackgroundTrafficKeepsOffTheShoulders) {
  const std::string file =
      std::string(ORCH_SHARED_DATA_DIR) + "/openscenario/alks_scenario_4_4_1_cut_in_no_collision_template.xosc";
  TempDir out;
  const auto r = run_cli({"run", file, "--traffic", "dense", "--out", out.path().string(), "-q"});
  const auto result = read_json(out / "result.json");
  EXPECT_NE(result["verdict"], "error") << result["reason"] << "\n" << r.output;
  EXPECT_NE(result["reason"].get<std::string>().find("StopTrigger"), std::string::npos) << result["reason"];
  EXPECT_EQ(result["traffic"], "dense");
  const std::string routes = slurp(out / "traffic.rou.xml");
  EXPECT_NE(routes.find("departLane=\"1\""), std::string::npos);
  EXPECT_EQ(routes.find("departLane=\"0\""), std::string::npos) << "a flow on the hard shoulder (SUMO lane 0)";
  const auto log = slurp(out / "run.log");
  EXPECT_NE(log.find("background traffic dense"), std::string::npos) << log;
  const auto at_end = log.find(" background vehicles in SUMO at the end");
  ASSERT_NE(at_end, std::string::npos) << log;
  const auto line_start = log.rfind('\n', at_end) + 1;
  EXPECT_GT(std::stoi(log.substr(line_start, at_end - line_start)), 50) << log;
}

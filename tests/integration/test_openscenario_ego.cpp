// The ego of OpenSCENARIO runs on real SUMO: driven by SUMO's car-following model, moved
// laterally by the storyboard's LaneChangeAction, and handed to an external ego on SUMO's
// own Python TraCI client by an ActivateControllerAction (--ego-port), in lockstep.
#include <gtest/gtest.h>

#include "support/ego_plugin_run.hpp"
#include "support/trace_csv.hpp"

using namespace orch::test;

namespace {

const std::string kScenario = source_path("scenarios/openscenario/ego_hand_over.xosc");

struct EgoRow {
  double t, y, speed;
  int lane;
  std::string driver;
};

std::vector<EgoRow> ego_rows(const std::filesystem::path& trace_file) {
  Trace trace(trace_file);
  std::vector<EgoRow> out;
  for (const auto& r : trace.rows())
    if (r.str("actor_id") == "Ego")
      out.push_back({r.num("time"), r.num("y"), r.num("speed"), r.integer("lane"), r.str("driver")});
  return out;
}

const EgoRow& at(const std::vector<EgoRow>& rows, double t) {
  for (const auto& r : rows)
    if (r.t >= t - 1e-6) return r;
  return rows.back();
}

}  // namespace

TEST(OpenScenarioEgo, SumoDrivesTheEgoAndTheStoryboardChangesItsLane) {
  TempDir out;
  const auto r = run_scenario(kScenario, out);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto rows = ego_rows(out / "trace.csv");
  ASSERT_GT(rows.size(), 290u);
  const EgoRow& start = at(rows, 1.0);
  EXPECT_EQ(start.driver, "sumo");
  EXPECT_NEAR(start.speed, 20.0, 0.01);  // its Init SpeedAction is SUMO's desired speed
  EXPECT_EQ(at(rows, 3.5).driver, "script");  // the storyboard moves it during the lane change
  const EgoRow& after = at(rows, 6.0);
  EXPECT_EQ(after.driver, "sumo");
  EXPECT_EQ(after.lane, start.lane + 1);
  EXPECT_NEAR(after.y - start.y, 3.75, 0.05);  // one lane (3.75 m wide) to the left on the straight road
  // SUMO's car-following model, not the storyboard, keeps it behind the slower car (14 m/s)
  // in its new lane: the storyboard's speed is still 20 m/s.
  EXPECT_LT(rows.back().speed, 15.0);
  const auto result = read_json(out / "result.json");
  EXPECT_EQ(result["verdict"], "success");
}

TEST(OpenScenarioEgo, ActivateControllerActionHandsTheEgoToAnExternalEgo) {
  TempDir out;
  const auto r = run_with_plugin(kScenario, out,
                                 python_client("drive.py", {"--port", "{port}", "--mode", "handover", "--speed", "12",
                                                            "--summary", (out / "summary.json").string()}));
  ASSERT_EQ(r.orchestrator_exit, 0) << r.orchestrator_output << r.plugin_output;
  EXPECT_EQ(r.plugin_exit, 0) << r.plugin_output;
  EXPECT_EQ(r.result["verdict"], "success");
  const auto summary = read_json(out / "summary.json");
  // The hand-over came with the ActivateControllerAction at 8 s, and only then.
  ASSERT_EQ(summary["hand_over"].size(), 1u) << summary.dump();
  EXPECT_NEAR(summary["hand_over"][0][0].get<double>(), 8.05, 0.06);
  EXPECT_EQ(summary["hand_over"][0][1], "1");
  EXPECT_EQ(summary["vehicles"], nlohmann::json::array({"SlowCar", "ego"}));
  const auto rows = ego_rows(out / "trace.csv");
  for (const auto& row : rows) {
    if (row.t < 1.95) {
      EXPECT_EQ(row.driver, "sumo") << row.t;
    }
    if (row.t > 8.2) {
      EXPECT_EQ(row.driver, "plugin") << row.t;
      EXPECT_NEAR(row.speed, 12.0, 1e-3) << row.t;  // exactly what the external ego commands
    }
  }
  EXPECT_EQ(at(rows, 6.0).lane, at(rows, 1.0).lane + 1);  // the storyboard's lane change before
  // Every step the external ego asked for is one the world took.
  EXPECT_EQ(r.result["ego_plugin"]["steps_driven"].get<long long>(), summary["steps"].get<long long>());
  EXPECT_EQ(r.result["ego_plugin"]["client"], "integration test client (Python traci)");
}

TEST(OpenScenarioEgo, ExternalEgoNeedsAnEgo) {
  TempDir out;
  // every_condition.xosc has no ego by any rule (docs/openscenario.md "The ego"): with
  // --ego-port it must be named.
  const auto r = run_scenario(source_path("scenarios/openscenario/every_condition.xosc"), out,
                              {"--ego-port", "0", "--ego-wait", "1"});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(read_json(out / "result.json")["reason"].get<std::string>().find("name it with --ego NAME"),
            std::string::npos);
}

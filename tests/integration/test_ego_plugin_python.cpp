// An external ego plug-in on SUMO's own Python TraCI client (Debian's sumo-tools) drives the
// ego of shipped scenarios in lockstep; the assertions are on the orchestrator's trace and
// result, as a user would check a system under test.
#include <gtest/gtest.h>

#include "support/ego_plugin_run.hpp"
#include "support/trace_csv.hpp"

using namespace orch::test;

namespace {

constexpr double kEgoLength = 4.51;   // vehicle.toyota.prius
constexpr double kSignLength = 0.8;   // static.prop.warningconstruction

std::vector<std::string> drive(std::vector<std::string> args, const TempDir& out) {
  args.insert(args.begin(), {"--port", "{port}", "--summary", (out / "summary.json").string()});
  return python_client("drive.py", args);
}

}  // namespace

// The ego alone on the ALKS road (Waypoint02 is lane 1 of 0..2); it ends after 700 m.
const char* kFreeRoad = R"({
  "map_id": "ALKS_Road",
  "actors": {"ego": {"actor_id": 0, "model_id": "vehicle.toyota.prius"}, "others": []},
  "scenario": {
    "opening_scene": {
      "ego": {"start_position": {"wp_id": "Waypoint02", "wp_idx": 5}, "end_position": {"wp_id": "Waypoint02", "wp_idx": 2000}},
      "others": [], "next_scenes": [1]},
    "scenes": [],
    "ending_scenes": [{"scene_id": 1, "conditions": {"and": [
      {"position": {"actor_id": 0, "type": "reach", "wp_id": "Waypoint02", "wp_idx": 705, "tolerance": 2}}]}}]
  },
  "stop_conditions": {"or": [{"simulation_time": {"comparison": ">=", "value": 120}}]}
})";

TEST(EgoPluginPython, HoldsTheCommandedSpeedChangesLanesAndSignalsInLockstep) {
  TempDir out;
  const auto r = run_with_plugin(out.write("free_road.json", kFreeRoad).string(), out,
                                 drive({"--mode", "hold", "--speed", "15", "--lane-change", "5:2", "--lane-change",
                                        "15:1", "--signals-at", "3"},
                                       out));
  ASSERT_EQ(r.orchestrator_exit, 0) << r.orchestrator_output << r.plugin_output;
  EXPECT_EQ(r.plugin_exit, 0) << r.plugin_output;
  EXPECT_EQ(r.result["verdict"], "success");

  Trace trace(out / "trace.csv");
  const auto ego = trace.actor(0);
  ASSERT_GT(ego.size(), 500u);
  bool in_left_lane = false;
  for (const auto& row : ego) {
    const double t = row.num("time");
    if (t > 0.051) {
      EXPECT_EQ(row.str("driver"), "plugin") << "t=" << t;
    }
    if (t >= 10) {
      EXPECT_NEAR(row.num("speed"), 15.0, 1e-3) << "t=" << t;  // exactly what it commanded
    }
    if (t > 3.05) {
      EXPECT_TRUE(row.integer("signals") & 2) << "t=" << t;  // the left blinker it set
    }
    if (t > 9 && t < 15) in_left_lane = in_left_lane || row.integer("lane") == 2;
  }
  EXPECT_TRUE(in_left_lane);                   // changeLane(2) at t=5
  EXPECT_EQ(ego.back().integer("lane"), 1);    // and back at t=15
  EXPECT_EQ(trace.actor(0).front().str("driver"), "sumo");  // inserted before the plug-in came

  const auto summary = read_json(out / "summary.json");
  EXPECT_EQ(summary["version"][0], 20);
  EXPECT_DOUBLE_EQ(summary["delta_t"].get<double>(), 0.05);
  EXPECT_NE(summary["refused"].get<std::string>().find("only the vehicle 'ego'"), std::string::npos);
  EXPECT_NE(summary["not_implemented"].get<std::string>().find("not implemented"), std::string::npos);
  EXPECT_EQ(summary["vehicles"], nlohmann::json::array({"ego"}));
  EXPECT_NE(summary["refused"].get<std::string>().find("'actor1'"), std::string::npos);
  // Every step the plug-in asked for is one the world took, and the run ended it cleanly.
  const auto& plugin = r.result["ego_plugin"];
  EXPECT_EQ(plugin["client"], "integration test client (Python traci)");
  EXPECT_EQ(plugin["order"], 1);
  EXPECT_EQ(plugin["steps_driven"].get<long long>(), summary["steps"].get<long long>());
  EXPECT_GT(r.result["timing"]["plugin_s"].get<double>(), 0.0);  // the lockstep waits are its own part
  // One setSpeed per step, and the refused one for actor1.
  EXPECT_EQ(plugin["commands"]["vehicle.setSpeed"].get<long long>(), summary["steps"].get<long long>() + 1);
  EXPECT_EQ(plugin["commands"]["vehicle.changeLane"], 2);
  EXPECT_EQ(plugin["peer"].get<std::string>().rfind("127.0.0.1:", 0), 0u);
  EXPECT_EQ(plugin["end"], "closed by the plug-in at the end of the run");
  EXPECT_EQ(r.result["steps"].get<long long>(), summary["steps"].get<long long>() + 1);
}

TEST(EgoPluginPython, StopsBeforeAnObstacleItPerceivedThroughItsContextSubscription) {
  TempDir out;
  const auto r = run_with_plugin(source_path("scenarios/alks_obstacle_stop.json"), out,
                                 drive({"--mode", "perceive", "--speed", "20", "--range", "80"}, out));
  ASSERT_EQ(r.orchestrator_exit, 0) << r.orchestrator_output << r.plugin_output;
  EXPECT_EQ(r.result["verdict"], "success") << r.result["reason"];
  const auto summary = read_json(out / "summary.json");
  ASSERT_FALSE(summary["perceived"].is_null());
  EXPECT_EQ(summary["perceived"]["id"], "actor1");  // the sign, by its documented SUMO id
  EXPECT_LE(summary["perceived"]["gap"].get<double>(), 80.0);

  Trace trace(out / "trace.csv");
  const auto ego = trace.actor(0);
  const auto sign = trace.actor(1);
  const double ego_front = ego.back().num("x") + kEgoLength / 2;
  const double sign_rear = sign.back().num("x") - kSignLength / 2;
  EXPECT_LT(ego_front, sign_rear);
  EXPECT_GT(ego_front, sign_rear - 6.0);
  EXPECT_NEAR(ego.back().num("speed"), 0.0, 0.1);
  // With SUMO's checks off, nothing but the plug-in slowed the ego: before it perceived the
  // sign it held its 20 m/s.
  for (const auto& row : ego) {
    if (row.num("time") > 12 && row.num("time") < summary["perceived"]["time"].get<double>()) {
      EXPECT_NEAR(row.num("speed"), 20.0, 1e-3);
    }
  }
}

// A plug-in's context subscription is answered from SUMO's own, which it shares with the
// orchestrator's 75 m one around the ego: smaller and larger ranges both give exactly the
// vehicles a brute-force census finds, and neither changes what the orchestrator sees.
TEST(EgoPluginPython, ContextSubscriptionsMatchABruteForceCensusAndLeaveTheRunAsItIs) {
  std::vector<std::unique_ptr<TempDir>> outs;
  for (const char* range : {"30", "150"}) {
    outs.push_back(std::make_unique<TempDir>());
    const TempDir& out = *outs.back();
    const auto r = run_with_plugin(source_path("scenarios/alks_lead_brake.json"), out,
                                   drive({"--mode", "census", "--speed", "20", "--range", range}, out),
                                   {"--traffic", "dense", "--trace-background", "--max-time", "15"});
    ASSERT_EQ(r.plugin_exit, 0) << r.plugin_output;
    const auto census = read_json(out / "summary.json")["census"];
    EXPECT_GT(census["checks"].get<int>(), 25) << range;
    EXPECT_EQ(census["mismatches"], nlohmann::json::array()) << range;
    EXPECT_GT(census["most"].get<int>(), std::string(range) == "30" ? 2 : 12) << range;  // dense traffic around
  }
  for (const char* file : {"trace.csv", "counts.csv", "background.csv"})
    EXPECT_EQ(slurp(outs[0]->path() / file), slurp(outs[1]->path() / file)) << file;
}

// The ego drives off the end of its 300 m route and SUMO removes it, and its widened context
// subscription with it: the run goes on to its stop condition exactly as with a narrow one.
TEST(EgoPluginPython, AnEgoThatLeavesWithAWideContextSubscriptionLeavesTheRunAsWithANarrowOne) {
  std::string text = kFreeRoad;
  const std::string end = R"("end_position": {"wp_id": "Waypoint02", "wp_idx": 2000})";
  ASSERT_NE(text.find(end), std::string::npos);
  text.replace(text.find(end), end.size(), R"("end_position": {"wp_id": "Waypoint02", "wp_idx": 300})");
  const std::string stop = R"("value": 120)";
  ASSERT_NE(text.find(stop), std::string::npos);
  text.replace(text.find(stop), stop.size(), R"("value": 30)");
  std::vector<std::unique_ptr<TempDir>> outs;
  for (const char* range : {"30", "150"}) {
    outs.push_back(std::make_unique<TempDir>());
    const TempDir& out = *outs.back();
    const auto r = run_with_plugin(out.write("leave.json", text).string(), out,
                                   drive({"--mode", "census", "--speed", "25", "--range", range}, out),
                                   {"--traffic", "light"});
    ASSERT_EQ(r.plugin_exit, 0) << r.plugin_output;
    EXPECT_EQ(r.result["verdict"], "failure") << range << ": " << r.result["reason"];
    EXPECT_NE(r.result["reason"].get<std::string>().find("stop condition met"), std::string::npos) << range;
    const auto census = read_json(out / "summary.json")["census"];
    EXPECT_GT(census["ego_left"].get<double>(), 5.0) << range;  // it did leave, before the end (30 s)
    EXPECT_LT(census["ego_left"].get<double>(), 29.0) << range;
    EXPECT_EQ(census["mismatches"], nlohmann::json::array()) << range;
  }
  EXPECT_EQ(slurp(outs[0]->path() / "trace.csv"), slurp(outs[1]->path() / "trace.csv"));
}

TEST(EgoPluginPython, WithoutPerceptionTheSameDriverHitsTheObstacleAndTheRunFails) {
  TempDir out;
  const auto r = run_with_plugin(source_path("scenarios/alks_obstacle_stop.json"), out,
                                 drive({"--mode", "blind", "--speed", "20"}, out));
  EXPECT_EQ(r.orchestrator_exit, 1) << r.orchestrator_output;
  EXPECT_EQ(r.result["verdict"], "failure") << r.result["reason"];
}

TEST(EgoPluginPython, HandOverReachesThePluginAsAVehicleParameterInTheSameStep) {
  TempDir out;
  std::string text = slurp(source_path("scenarios/alks_lead_brake.json"));
  const std::string brake = "\"actions\": [{\"speed\": {\"actor_id\": 1, \"type\": \"absolute\", \"value\": 0,";
  ASSERT_NE(text.find(brake), std::string::npos);
  text.replace(text.find(brake), brake.size(),
               "\"actions\": [{\"hand_over\": {\"actor_id\": 0, \"hand_over\": true, \"brake\": 0.5}}, "
               "{\"speed\": {\"actor_id\": 1, \"type\": \"absolute\", \"value\": 0,");
  const auto file = out.write("hand_over.json", text);
  const auto r = run_with_plugin(file.string(), out, drive({"--mode", "hold", "--speed", "17.5"}, out));
  ASSERT_EQ(r.orchestrator_exit, 0) << r.orchestrator_output << r.plugin_output;
  const double brakes_at = r.result["scenes"][2]["enter_time"];
  const auto summary = read_json(out / "summary.json");
  ASSERT_EQ(summary["hand_over"].size(), 1u) << summary.dump();
  EXPECT_EQ(summary["hand_over"][0][1], "1");
  EXPECT_NEAR(summary["hand_over"][0][0].get<double>(), brakes_at, 1e-9);
  ASSERT_EQ(r.result["hand_overs"].size(), 1u);
  EXPECT_EQ(r.result["hand_overs"][0]["hand_over"], true);
  EXPECT_DOUBLE_EQ(r.result["hand_overs"][0]["brake"].get<double>(), 0.5);
}

// `orchestrator run` end to end: the binary, real SUMO (libsumo), the shipped maps and
// sample scenarios, checked through the files it writes.
#include <gtest/gtest.h>

#include <cmath>

#include "support/cli_runner.hpp"
#include "support/trace_csv.hpp"

using namespace orch::test;

namespace {

std::vector<int> scene_ids(const nlohmann::json& result) {
  std::vector<int> ids;
  for (const auto& s : result["scenes"]) ids.push_back(s["scene_id"].get<int>());
  return ids;
}

}  // namespace

TEST(RunCli, SampleCutInSucceedsWithTheDocumentedOutputs) {
  TempDir out;
  const auto r = run_scenario(source_path("scenarios/highway_cut_in.json"), out);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto result = read_json(out / "result.json");
  EXPECT_EQ(result["verdict"], "success");
  EXPECT_EQ(result["ending_scene"], 5);
  EXPECT_EQ(scene_ids(result), (std::vector<int>{0, 1, 2, 3, 4, 5}));
  EXPECT_EQ(result["backend"], "libsumo");
  EXPECT_EQ(result["seed"], 42);
  EXPECT_DOUBLE_EQ(result["step"].get<double>(), 0.05);
  EXPECT_NE(result["sumo_version"].get<std::string>().find("1.15"), std::string::npos);
  EXPECT_EQ(result["inputs"]["scenario"]["sha256"].get<std::string>().size(), 64u);
  EXPECT_EQ(result["inputs"]["net"]["sha256"].get<std::string>().size(), 64u);
  // Scene entry times rise, and the run ended when the ending scene was entered.
  double last = -1;
  for (const auto& s : result["scenes"]) {
    EXPECT_GE(s["enter_time"].get<double>(), last);
    last = s["enter_time"].get<double>();
  }
  EXPECT_DOUBLE_EQ(last, result["sim_time"].get<double>());

  Trace trace(out / "trace.csv");
  EXPECT_EQ(trace.header().rfind("time,scene_id,actor_id,x,y,heading,speed,accel,edge,lane,lane_pos,lat_offset", 0), 0u);
  EXPECT_EQ(static_cast<long long>(trace.rows().size()), result["trace_rows"].get<long long>());
  // The run log tells the story, one line per transition and action, with times.
  const std::string log = slurp(out / "run.log");
  EXPECT_NE(log.find("scene 2 -> 3"), std::string::npos);
  EXPECT_NE(log.find("lane_change: actor 1 to the lane of Waypoint02 over 3 s"), std::string::npos);

  // Where the wall time went: the parts add up to it, and SUMO's steps take most of it.
  const auto& timing = result["timing"];
  double sum = 0;
  for (const char* part : {"start_s", "sumo_step_s", "orchestrator_s", "plugin_s", "finish_s"}) {
    ASSERT_TRUE(timing[part].is_number()) << part;
    EXPECT_GE(timing[part].get<double>(), 0.0) << part;
    sum += timing[part].get<double>();
  }
  EXPECT_NEAR(sum, result["wall_time_s"].get<double>(), 1e-6);
  EXPECT_EQ(timing["plugin_s"].get<double>(), 0.0);  // no plug-in
  EXPECT_GT(timing["start_s"].get<double>(), 0.0);
  EXPECT_GT(timing["orchestrator_s"].get<double>(), 0.0);
  EXPECT_GT(timing["sumo_step_s"].get<double>(), 0.0);
  // The observers' shares (trace, metrics, ...) are parts of the orchestrator's own time.
  // (With two cars on the road SUMO's step is as short as the orchestrator's: no ordering
  // between them is asserted; scripts/bench/ measures the shares in dense traffic.)
  double observers = 0;
  for (const char* name : {"trace", "traffic_trace", "metrics"}) {
    ASSERT_TRUE(timing["observers_s"][name].is_number()) << name;
    EXPECT_GT(timing["observers_s"][name].get<double>(), 0.0) << name;
    observers += timing["observers_s"][name].get<double>();
  }
  EXPECT_LE(observers, timing["orchestrator_s"].get<double>());
}

TEST(RunCli, SameInputsAndSeedGiveAByteIdenticalTrace) {
  TempDir a, b;
  ASSERT_EQ(run_scenario(source_path("scenarios/highway_cut_in.json"), a, {"--seed", "7"}).exit_code, 0);
  ASSERT_EQ(run_scenario(source_path("scenarios/highway_cut_in.json"), b, {"--seed", "7"}).exit_code, 0);
  const std::string ta = slurp(a / "trace.csv");
  EXPECT_GT(ta.size(), 10000u);
  EXPECT_EQ(ta, slurp(b / "trace.csv"));
  EXPECT_EQ(read_json(a / "result.json")["seed"], 7);
}

TEST(RunCli, StepLengthIsHonoured) {
  TempDir out;
  ASSERT_EQ(run_scenario(source_path("scenarios/highway_cut_in.json"), out, {"--step", "0.1"}).exit_code, 0);
  Trace trace(out / "trace.csv");
  const auto ego = trace.actor(0);
  ASSERT_GT(ego.size(), 10u);
  EXPECT_NEAR(ego[1].num("time") - ego[0].num("time"), 0.1, 1e-9);
}

TEST(RunCli, ScriptedCarCutsInWithItsBlinkerOn) {
  TempDir out;
  ASSERT_EQ(run_scenario(source_path("scenarios/highway_cut_in.json"), out).exit_code, 0);
  const auto result = read_json(out / "result.json");
  const double blinker_on = result["scenes"][2]["enter_time"];  // scene 2: blinker
  const double change = result["scenes"][3]["enter_time"];      // scene 3: lane change, 3 s
  const double blinker_off = result["scenes"][4]["enter_time"];
  Trace trace(out / "trace.csv");
  for (const auto& row : trace.actor(1)) {
    const double t = row.num("time");
    const int lane = row.integer("lane");
    const bool left_blinker = (row.integer("signals") & 2) != 0;
    if (t < change) {
      EXPECT_EQ(lane, 0) << "t=" << t;  // Waypoint03, the right lane
    }
    if (t >= change + 3.0 - 1e-9) {
      EXPECT_EQ(lane, 1) << "t=" << t;
    }
    if (t > blinker_on + 1e-9 && t <= blinker_off + 1e-9) {
      EXPECT_TRUE(left_blinker) << "t=" << t;
    }
    if (t > blinker_off + 0.05 + 1e-9 || t <= blinker_on) {
      EXPECT_FALSE(left_blinker) << "t=" << t;
    }
  }
}

TEST(RunCli, EgoStopsBeforeAStationaryObstacle) {
  TempDir out;
  const auto r = run_scenario(source_path("scenarios/alks_obstacle_stop.json"), out);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  Trace trace(out / "trace.csv");
  const auto ego = trace.actor(0);
  const auto sign = trace.actor(1);
  ASSERT_FALSE(ego.empty());
  ASSERT_FALSE(sign.empty());
  const double ego_front = ego.back().num("x") + 4.51 / 2;
  const double sign_rear = sign.back().num("x") - 0.8 / 2;
  EXPECT_LT(ego_front, sign_rear);             // stopped short of it...
  EXPECT_GT(ego_front, sign_rear - 6.0);        // ...close behind it, as a driver would
  EXPECT_NEAR(ego.back().num("speed"), 0.0, 0.1);
}

TEST(RunCli, EgoStopsBehindALeadVehicleThatBrakesHard) {
  TempDir out;
  ASSERT_EQ(run_scenario(source_path("scenarios/alks_lead_brake.json"), out).exit_code, 0);
  Trace trace(out / "trace.csv");
  const auto lead = trace.actor(1);
  // The lead's deceleration is the scenario's: 5 m/s^2 once it brakes.
  double hardest = 0;
  for (const auto& row : lead) hardest = std::min(hardest, row.num("accel"));
  EXPECT_NEAR(hardest, -5.0, 1e-6);
  const auto ego = trace.actor(0);
  EXPECT_LT(ego.back().num("x") + 4.51 / 2, lead.back().num("x") - 4.61 / 2);
}

TEST(RunCli, PedestrianBesideTheRoadDoesNotStopTheEgo) {
  TempDir out;
  ASSERT_EQ(run_scenario(source_path("scenarios/pedestrian_roadside.json"), out).exit_code, 0);
  Trace trace(out / "trace.csv");
  double slowest_after_start = 1e9;
  for (const auto& row : trace.actor(0))
    if (row.num("time") > 15) slowest_after_start = std::min(slowest_after_start, row.num("speed"));
  EXPECT_GT(slowest_after_start, 20.0);  // 80 km/h road; no braking for the pedestrian
  const auto ped = trace.actor(1);
  ASSERT_FALSE(ped.empty());
  EXPECT_NEAR(ped.front().num("y"), -11.5 - 2.6, 0.05);  // right of Waypoint03, off the lane centre
}

TEST(RunCli, MaxTimeEndsTheRunAsAFailure) {
  TempDir out;
  const auto r = run_scenario(source_path("scenarios/highway_cut_in.json"), out, {"--max-time", "5"});
  EXPECT_EQ(r.exit_code, 1) << r.output;
  const auto result = read_json(out / "result.json");
  EXPECT_EQ(result["verdict"], "failure");
  EXPECT_NE(result["reason"].get<std::string>().find("--max-time 5"), std::string::npos);
  EXPECT_NEAR(result["sim_time"].get<double>(), 5.0, 1e-9);
}

TEST(RunCli, StopConditionEndsTheRunAsAFailure) {
  TempDir out;
  // The lead brakes; with the stop condition moved before the ending can be reached.
  std::string text = slurp(source_path("scenarios/alks_lead_brake.json"));
  const std::string from = "\"comparison\": \">=\", \"value\": 120";
  text.replace(text.find(from), from.size(), "\"comparison\": \">=\", \"value\": 12");
  const auto file = out.write("early_stop.json", text);
  const auto r = run_scenario(file.string(), out);
  EXPECT_EQ(r.exit_code, 1) << r.output;
  const auto result = read_json(out / "result.json");
  EXPECT_EQ(result["verdict"], "failure");
  EXPECT_NE(result["reason"].get<std::string>().find("stop condition"), std::string::npos);
  EXPECT_TRUE(result["ending_scene"].is_null());
}

TEST(RunCli, InvalidScenarioIsAnErrorWithTheFileLineAndPointer) {
  TempDir out;
  std::string text = slurp(source_path("scenarios/alks_lead_brake.json"));
  const std::string key = "\"description\": \"Both at 60 km/h\"";
  text.replace(text.find(key), key.size(), "\"descripton\": \"Both at 60 km/h\"");
  const auto file = out.write("typo.json", text);
  const auto r = run_scenario(file.string(), out);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  const auto result = read_json(out / "result.json");
  EXPECT_EQ(result["verdict"], "error");
  const std::string reason = result["reason"];
  EXPECT_NE(reason.find("typo.json:"), std::string::npos) << reason;
  EXPECT_NE(reason.find("/scenario/scenes/0"), std::string::npos) << reason;
  EXPECT_NE(reason.find("did you mean \"description\""), std::string::npos) << reason;
  // It never got to a step: all of its time was the start and the finish.
  EXPECT_EQ(result["timing"]["sumo_step_s"].get<double>(), 0.0);
  EXPECT_EQ(result["timing"]["orchestrator_s"].get<double>(), 0.0);
}

// An actor placed by a distance behind its target that would stand before its route begins:
// an error naming the place (libsumo 1.15 crashed reading such a vehicle).
TEST(RunCli, AStartBeforeTheRouteBeginsIsAnError) {
  TempDir out;
  std::string text = slurp(source_path("scenarios/collision_stop_in_front.json"));
  const std::string key = "\"distance\": 11,";
  ASSERT_NE(text.find(key), std::string::npos);
  text.replace(text.find(key), key.size(), "\"distance\": -400,");
  const auto file = out.write("behind.json", text);
  const auto r = run_scenario(file.string(), out);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  const std::string reason = read_json(out / "result.json")["reason"];
  EXPECT_NE(reason.find("behind.json:"), std::string::npos) << reason;
  EXPECT_NE(reason.find("/scenario/opening_scene/others/1/start_position"), std::string::npos) << reason;
  EXPECT_NE(reason.find("before the start of its route Waypoint03"), std::string::npos) << reason;
}

TEST(RunCli, UnknownMapIsAnError) {
  TempDir out;
  std::string text = slurp(source_path("scenarios/alks_lead_brake.json"));
  text.replace(text.find("\"ALKS_Road\""), 11, "\"ALKS_Rode\"");
  const auto r = run_scenario(out.write("badmap.json", text).string(), out);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  const auto result = read_json(out / "result.json");
  EXPECT_EQ(result["verdict"], "error");
  EXPECT_NE(result["reason"].get<std::string>().find("ALKS_Rode"), std::string::npos);
}

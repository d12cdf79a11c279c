// The real ScenarioExecutor files users wrote (../shared/data/roadeditor) run on SUMO.
#include <gtest/gtest.h>

#include <cmath>

#include "support/cli_runner.hpp"
#include "support/trace_csv.hpp"

using namespace orch::test;

namespace {

std::string shared_scenario(const std::string& name) {
  return std::string(ORCH_SHARED_DATA_DIR) + "/roadeditor/scenarios/" + name + ".json";
}

struct Expected {
  const char* file;
  std::vector<int> scenes;  // scene ids visited, opening (0) first
  const char* verdict = "success";
};
void PrintTo(const Expected& e, std::ostream* os) { *os << e.file; }

class SharedScenario : public ::testing::TestWithParam<Expected> {};

}  // namespace

TEST_P(SharedScenario, RunsToItsEndingScene) {
  const Expected& e = GetParam();
  TempDir out;
  const auto r = run_cli({"run", shared_scenario(e.file), "--out", out.path().string(), "-q"});
  const auto result = read_json(out / "result.json");
  EXPECT_EQ(result["verdict"], e.verdict) << result["reason"];
  EXPECT_EQ(r.exit_code, std::string(e.verdict) == "success" ? 0 : 1) << r.output;
  std::vector<int> visited;
  for (const auto& s : result["scenes"]) visited.push_back(s["scene_id"]);
  EXPECT_EQ(visited, e.scenes);
  EXPECT_EQ(result["ending_scene"].get<int>(), e.scenes.back());
  if (std::string(e.verdict) == "failure") {
    EXPECT_NE(result["reason"].get<std::string>().find("the ego collided"), std::string::npos) << result["reason"];
  }
}

INSTANTIATE_TEST_SUITE_P(
    RealFiles, SharedScenario,
    ::testing::Values(Expected{"highway_cutin", {0, 1, 2, 3, 4, 5, 6}},
                      Expected{"ALKS_Scenario_4.1_1_FreeDriving_TEMPLATE", {0, 1, 2}},
                      Expected{"ALKS_Scenario_4.2_1_FullyBlockingTarget_TEMPLATE", {0, 1, 2}},
                      Expected{"ALKS_Scenario_4.2_2_PartiallyBlockingTarget_TEMPLATE", {0, 1, 2}},
                      Expected{"ALKS_Scenario_4.2_4_MultipleBlockingTargets_TEMPLATE", {0, 1, 2}},
                      Expected{"ALKS_Scenario_4.3_1_FollowLeadVehicleComfortable_TEMPLATE", {0, 1, 2, 3, 4}},
                      Expected{"ALKS_Scenario_4.3_2_FollowLeadVehicleEmergencyBrake_TEMPLATE", {0, 1, 2, 3}},
                      Expected{"ALKS_Scenario_4.6_1_ForwardDetectionRange_TEMPLATE", {0, 1}},
                      Expected{"ALKS_Scenario_4.1_2_SwervingLeadVehicle_TEMPLATE", {0, 1, 2, 3, 4}},
                      Expected{"ALKS_Scenario_4.1_3_SwervingSideVehicle_TEMPLATE", {0, 1, 2, 3, 4}},
                      Expected{"ALKS_Scenario_4.4_1_CutInNoCollision_TEMPLATE", {0, 1, 2, 3}},
                      // The cut-in the template calls unavoidable: the ego hits it, so the run
                      // reaches its ending scene and still fails.
                      Expected{"ALKS_Scenario_4.4_2_CutInUnavoidableCollision_TEMPLATE", {0, 1, 2, 3}, "failure"},
                      Expected{"ALKS_Scenario_4.5_1_CutOutFullyBlocking_TEMPLATE", {0, 1, 2, 3}}),
    [](const auto& param_info) {
      std::string name = param_info.param.file;
      for (char& c : name)
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
      return name;
    });

// highway_cutin: actor 1 stays on Waypoint01's lane until scene 4, is on Waypoint02's lane
// at most 3 s (the action's time) later with a smooth lateral profile, and its right
// blinker is on from scene 3 until scene 5.
TEST(HighwayCutin, LaneChangeAndBlinkerFollowTheScenes) {
  TempDir out;
  ASSERT_EQ(run_cli({"run", shared_scenario("highway_cutin"), "--out", out.path().string(), "-q"}).exit_code, 0);
  const auto result = read_json(out / "result.json");
  auto enter = [&](int id) {
    for (const auto& s : result["scenes"])
      if (s["scene_id"] == id) return s["enter_time"].get<double>();
    ADD_FAILURE() << "scene " << id << " not visited";
    return 0.0;
  };
  const double scene3 = enter(3), scene4 = enter(4), scene5 = enter(5);
  EXPECT_NEAR(scene4 - scene3, 3.0, 0.051);  // scene 3 holds for its duration

  Trace trace(out / "trace.csv");
  const auto car = trace.actor(1);
  ASSERT_GT(car.size(), 100u);
  // On this curved highway, SUMO lane 2 = Waypoint01 (left), 1 = Waypoint02, 4 m apart.
  double previous_offset = NAN;
  for (const auto& row : car) {
    const double t = row.num("time");
    const int lane = row.integer("lane");
    const double from_target = row.num("lat_offset") + (lane == 2 ? 4.0 : lane == 1 ? 0.0 : -4.0);
    if (t <= scene4 + 1e-9) {
      EXPECT_EQ(lane, 2) << "t=" << t;
    }
    if (t >= scene4 + 3.0 - 1e-9) {
      EXPECT_EQ(lane, 1) << "t=" << t;
      EXPECT_NEAR(from_target, 0.0, 0.05) << "t=" << t;
    }
    if (t > scene4 && t < scene4 + 3.0 + 1e-9) {
      // Smooth: monotone towards the new lane, no step larger than the profile's peak rate
      // (15/8 * 4 m / 3 s) allows in 0.05 s.
      // (SUMO's lane centre lies within 2 cm of the waypoints: that much wobble is the map.)
      EXPECT_LE(from_target, previous_offset + 0.02) << "t=" << t;
      EXPECT_LE(previous_offset - from_target, 1.875 * 4.0 / 3.0 * 0.05 + 0.02) << "t=" << t;
    }
    previous_offset = from_target;
    const bool right_blinker = (row.integer("signals") & 1) != 0;
    if (t > scene3 + 1e-9 && t <= scene5 + 1e-9) {
      EXPECT_TRUE(right_blinker) << "t=" << t;
    }
    if (t <= scene3 + 1e-9 || t > scene5 + 0.05 + 1e-9) {
      EXPECT_FALSE(right_blinker) << "t=" << t;
    }
  }
}

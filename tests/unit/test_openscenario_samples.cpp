// The OpenSCENARIO samples in scenarios/openscenario/ load and play as they describe
// (storyboard runtime, no simulator).
#include <gtest/gtest.h>

#include "opendrive/xodr_reader.hpp"
#include "openscenario/storyboard_runtime.hpp"
#include "openscenario/xosc_reader.hpp"

namespace orch::openscenario {
namespace {

double start_of(const StoryboardRuntime& runtime, const std::string& action) {
  for (const TransitionLog& l : runtime.log())
    if (l.name == action && l.transition == "startTransition") return l.time;
  return -1;
}

TEST(OpenScenarioSamples, OvertakingChangesLeftAt30mAndBack5mAhead) {
  const Scenario scenario = load_scenario(std::string(ORCH_SOURCE_DIR) + "/scenarios/openscenario/overtaking.xosc");
  const auto roads = opendrive::read_xodr_file(scenario.road_file);
  StoryboardRuntime runtime(scenario, roads);
  const auto& ego = runtime.entities().at("Ego");
  const auto& car = runtime.entities().at("Overtaker");
  EXPECT_NEAR(car.pose.x, 100.0 - 79.0, 1e-9);
  EXPECT_NEAR(car.pose.y, ego.pose.y, 1e-9);
  double back_start_gap = -1;
  while (!runtime.finished() && runtime.time() < 60) {
    runtime.step(0.05);
    if (back_start_gap < 0 && start_of(runtime, "ChangeBack") >= 0)
      back_start_gap = (car.pose.x + 1.4 - 2.25) - (ego.pose.x + 1.4 + 2.25);  // rear of car - front of ego
  }
  ASSERT_TRUE(runtime.finished());
  // Gap between the boxes: 79 - 4.5 = 74.5 m closing at 20 km/h: below 30 m after 8.01 s.
  EXPECT_NEAR(start_of(runtime, "ChangeLeft"), 8.05, 1e-9);
  EXPECT_GT(back_start_gap, 5.0);
  EXPECT_LT(back_start_gap, 5.0 + (150 - 130) / 3.6 * 0.05 + 1e-6);  // within one step of 5 m
  EXPECT_EQ(car.lane, -3);  // back on the rightmost lane
  EXPECT_NEAR(car.pose.y, ego.pose.y, 1e-9);
  EXPECT_GT(car.pose.x, ego.pose.x);
  // The run ends 2 s after the return finished.
  const double back_end = start_of(runtime, "ChangeBack") + 3.0;
  EXPECT_NEAR(runtime.time(), back_end + 2.0, 0.05 + 1e-9);
}

// Without SUMO every event of every_condition.xosc starts too, at the times its story gives.
TEST(OpenScenarioSamples, EveryConditionStartsItsEvent) {
  const Scenario scenario = load_scenario(std::string(ORCH_SOURCE_DIR) + "/scenarios/openscenario/every_condition.xosc");
  const auto roads = opendrive::read_xodr_file(scenario.road_file);
  StoryboardRuntime runtime(scenario, roads);
  while (!runtime.finished() && runtime.time() < 60) runtime.step(0.05);
  ASSERT_TRUE(runtime.finished());
  for (const char* event : {"AddObstacle", "LeadSpeedsUp", "MarkAccelerating", "FollowerChases", "CountFaster",
                            "FollowerChangesLane", "DoubleAfterLaneChange", "WalkerStepsAside", "WalkerStops",
                            "MarkOffRoad", "FollowerStops", "ClearObstacle", "MarkStopped", "LeadToTheEnd",
                            "EndReached"})
    EXPECT_GE(start_of(runtime, event), 0.0) << event;
  EXPECT_NEAR(start_of(runtime, "AddObstacle"), 1.0, 1e-9);
  EXPECT_NEAR(start_of(runtime, "LeadSpeedsUp"), 2.0, 1e-9);     // 30 m at 15 m/s
  EXPECT_NEAR(start_of(runtime, "MarkAccelerating"), 2.05, 1e-9);  // the first step of the ramp
  EXPECT_EQ(runtime.parameters().at("Phase").value, "100");
  // Phase: 1, + 1 (faster), * 2 (beside the lead), then 10 (stopped), 11 (walker off road), 100 (end).
  EXPECT_FALSE(runtime.entities().at("Obstacle").placed);
  EXPECT_LT(runtime.entities().at("Walker").pose.y, -10.0);  // beyond the shoulder
  EXPECT_DOUBLE_EQ(runtime.entities().at("Follower").speed, 0.0);
  EXPECT_GE(runtime.entities().at("Lead").s, 600.0);
  // AcquirePositionAction replaced the assigned route by one to s = 590, which it passed.
  ASSERT_EQ(runtime.entities().at("Lead").route.size(), 1u);
  EXPECT_NEAR(runtime.entities().at("Lead").route[0].s, 590.0, 1e-9);
  EXPECT_EQ(runtime.entities().at("Lead").route_passed, 1u);
}

}  // namespace
}  // namespace orch::openscenario

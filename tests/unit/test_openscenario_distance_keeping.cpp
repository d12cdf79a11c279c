// LongitudinalDistanceAction with DynamicConstraints (distance_keeping.cpp) in the storyboard
// runtime, on a straight two-lane road (no simulator): it acts from the step after its
// start, as every other action started then, and its jerk limits (maxAccelerationRate,
// maxDecelerationRate) bound how fast its acceleration changes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include "core/errors.hpp"
#include "opendrive/xodr_reader.hpp"
#include "openscenario/storyboard_runtime.hpp"
#include "openscenario/xosc_reader.hpp"
#include "support/cli_runner.hpp"
#include "unit/openscenario_snippets.hpp"

namespace orch::openscenario {
namespace {

constexpr double kStep = 0.05;

std::string at_time(double at) {
  return R"(<Condition name="c" delay="0" conditionEdge="none"><ByValueCondition><SimulationTimeCondition value=")" +
         std::to_string(at) + R"(" rule="greaterOrEqual"/></ByValueCondition></Condition>)";
}

// A keeps `distance` m behind B within `constraints` (attributes of DynamicConstraints), from `start` s.
std::string keep_distance(double distance, const std::string& constraints, double start = 1) {
  return R"(<Event name="Keep" priority="parallel"><Action name="KeepAction"><PrivateAction><LongitudinalAction>
<LongitudinalDistanceAction entityRef="B" distance=")" +
         std::to_string(distance) + R"(" freespace="false" continuous="true"><DynamicConstraints )" + constraints +
         R"(/></LongitudinalDistanceAction></LongitudinalAction></PrivateAction></Action><StartTrigger><ConditionGroup>)" +
         at_time(start) + "</ConditionGroup></StartTrigger></Event>";
}

class DistanceKeeping : public ::testing::Test {
 protected:
  // A at s = 10, B at s = `b_at`, both at 10 m/s in lane -1; A's maneuver holds `events`.
  void load(double b_at, const std::string& events) {
    const std::string text = R"(<?xml version="1.0"?><OpenSCENARIO>
<FileHeader revMajor="1" revMinor="2" date="2024-01-01T00:00:00" author="t" description="distance keeping"/>
<RoadNetwork><LogicFile filepath="road.xodr"/></RoadNetwork>
<Entities>)" + test::vehicle("A") + test::vehicle("B") +
                             R"(</Entities>
<Storyboard><Init><Actions>)" + test::place("A", 10, -1, 10) +
                             test::place("B", b_at, -1, 10) + R"(</Actions></Init>
<Story name="S"><Act name="Act"><ManeuverGroup name="G" maximumExecutionCount="1">
<Actors selectTriggeringEntities="false"><EntityRef entityRef="A"/></Actors><Maneuver name="M">)" +
                             events + R"(</Maneuver></ManeuverGroup><StartTrigger><ConditionGroup>)" + at_time(0) +
                             R"(</ConditionGroup></StartTrigger></Act></Story>
<StopTrigger><ConditionGroup>)" + at_time(100) + R"(</ConditionGroup></StopTrigger></Storyboard></OpenSCENARIO>)";
    dir_.write("road.xodr", test::kStraightTwoLaneRoad);
    scenario_ = load_scenario(dir_.write("s.xosc", text).string());
    roads_ = opendrive::read_xodr_file((dir_ / "road.xodr").string());
    runtime_ = std::make_unique<StoryboardRuntime>(scenario_, roads_);
  }
  [[nodiscard]] const EntityState& entity(const std::string& name) const { return runtime_->entities().at(name); }
  // Steps until the action has started (its start transition logged).
  void run_to_start() {
    while (test::transition_times(*runtime_, "KeepAction", "startTransition").empty()) runtime_->step(kStep);
  }

  orch::test::TempDir dir_;
  Scenario scenario_;
  opendrive::RoadNetwork roads_;
  std::unique_ptr<StoryboardRuntime> runtime_;
};

// B is 100 m ahead, the distance to keep 30 m: A speeds up at once. In the step after the
// action started, A already moves at its new speed (10 + 2 * 0.05 m/s): 0.505 m, not 0.5 m.
TEST_F(DistanceKeeping, ItActsFromTheStepAfterItsStart) {
  load(110, keep_distance(30, R"(maxAcceleration="2" maxDeceleration="3" maxSpeed="20")"));
  run_to_start();
  const double s = entity("A").s;
  runtime_->step(kStep);
  EXPECT_NEAR(entity("A").s - s, (10 + 2 * kStep) * kStep, 1e-9);
}

// The same with jerk limits of 1 m/s^3: the acceleration grows by at most 0.05 m/s^2 a
// step and falls by at most that, within [-3, 2] m/s^2, and A still settles 30 m behind B.
TEST_F(DistanceKeeping, TheJerkLimitsBoundTheChangeOfTheAcceleration) {
  load(110, keep_distance(30, R"(maxAcceleration="2" maxDeceleration="3" maxSpeed="20" maxAccelerationRate="1" maxDecelerationRate="1")"));
  run_to_start();
  // The speed for the step after the start is set at the start (from 10 m/s).
  double speed = entity("A").speed, acceleration = (speed - 10) / kStep, top = 0, lowest = 0;
  ASSERT_NEAR(acceleration, 1.0 * kStep, 1e-9);
  while (runtime_->time() < 60 - 1e-9) {
    runtime_->step(kStep);
    const double a = (entity("A").speed - speed) / kStep;
    speed = entity("A").speed;
    ASSERT_LE(a - acceleration, 1.0 * kStep + 1e-9) << "at t=" << runtime_->time();
    ASSERT_GE(a - acceleration, -1.0 * kStep - 1e-9) << "at t=" << runtime_->time();
    ASSERT_LE(a, 2.0 + 1e-9);
    ASSERT_GE(a, -3.0 - 1e-9);
    top = std::max(top, a);
    lowest = std::min(lowest, a);
    acceleration = a;
  }
  EXPECT_NEAR(top, 2.0, 1e-9);  // the limits are reached on the way
  EXPECT_LT(lowest, -1.0);
  EXPECT_NEAR(entity("B").s - entity("A").s, 30.0, 0.1);
  EXPECT_NEAR(entity("A").speed, 10.0, 0.1);
}

// Without jerk limits the acceleration jumps to its limit in the first step.
TEST_F(DistanceKeeping, WithoutJerkLimitsTheAccelerationJumps) {
  load(110, keep_distance(30, R"(maxAcceleration="2" maxDeceleration="3" maxSpeed="20")"));
  run_to_start();
  const double speed = entity("A").speed;
  runtime_->step(kStep);
  EXPECT_NEAR((entity("A").speed - speed) / kStep, 2.0, 1e-9);
}

// Started before the first step (at 0 s: no step size yet), the speed stays as it is until
// the first step's end, and then changes within the limits (no jump to the braking law's
// speed, 10 + sqrt(2 * 3 * 70) m/s).
TEST_F(DistanceKeeping, StartedBeforeTheFirstStepTheSpeedDoesNotJump) {
  load(110, keep_distance(30, R"(maxAcceleration="2" maxDeceleration="3" maxSpeed="40")", 0));
  ASSERT_FALSE(test::transition_times(*runtime_, "KeepAction", "startTransition").empty());
  EXPECT_DOUBLE_EQ(entity("A").speed, 10.0);
  runtime_->step(kStep);
  EXPECT_NEAR(entity("A").speed, 10 + 2 * kStep, 1e-9);
}

TEST_F(DistanceKeeping, ARateThatIsNotPositiveIsAnError) {
  try {
    load(110, keep_distance(30, R"(maxAcceleration="2" maxAccelerationRate="0")"));
    FAIL() << "expected an error";
  } catch (const ScenarioError& e) {
    EXPECT_NE(std::string(e.what()).find("maxAccelerationRate"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("must be positive"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace orch::openscenario

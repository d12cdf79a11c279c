// LongitudinalDistanceAction with DynamicConstraints (distance_keeping.cpp) in the storyboard
// runtime, on a straight two-lane road (no simulator): it acts from the step after its
// start, as every other action started then, its law is esmini's damped spring, and its jerk
// limits (maxAccelerationRate, maxDecelerationRate) bound how fast its acceleration builds up.
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
#include "unit/xodr_network_snippets.hpp"

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
  // `two_roads`: on road 1 of two in a row along +x (xodr_two_in_a_row), B at `b_at` on road 2.
  void load(double b_at, const std::string& events, bool two_roads = false, double a_at = 10) {
    std::string a = test::place("A", a_at, -1, 10), b = test::place("B", b_at, -1, 10);
    if (two_roads) {
      a.replace(a.find("roadId=\"0\""), 10, "roadId=\"1\"");
      b.replace(b.find("roadId=\"0\""), 10, "roadId=\"2\"");
    }
    const std::string text = R"(<?xml version="1.0"?><OpenSCENARIO>
<FileHeader revMajor="1" revMinor="2" date="2024-01-01T00:00:00" author="t" description="distance keeping"/>
<RoadNetwork><LogicFile filepath="road.xodr"/></RoadNetwork>
<Entities>)" + test::vehicle("A") + test::vehicle("B") +
                             R"(</Entities>
<Storyboard><Init><Actions>)" + a + b + R"(</Actions></Init>
<Story name="S"><Act name="Act"><ManeuverGroup name="G" maximumExecutionCount="1">
<Actors selectTriggeringEntities="false"><EntityRef entityRef="A"/></Actors><Maneuver name="M">)" +
                             events + R"(</Maneuver></ManeuverGroup><StartTrigger><ConditionGroup>)" + at_time(0) +
                             R"(</ConditionGroup></StartTrigger></Act></Story>
<StopTrigger><ConditionGroup>)" + at_time(100) + R"(</ConditionGroup></StopTrigger></Storyboard></OpenSCENARIO>)";
    dir_.write("road.xodr", two_roads ? test::xodr_two_in_a_row() : std::string(test::kStraightTwoLaneRoad));
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

// Started at 0 s (no step size before the first step): the speed stays as it is until the
// first step, which sets it within the limits (no jump to the spring's pull of 0.4 * 2 * 70
// m/s^2) and moves A with it, as one started later moves in the step after its start
// (esmini's distance_test.xosc: 0.126 m behind at 0.5 s when it waited a step).
TEST_F(DistanceKeeping, StartedAtZeroItActsFromTheFirstStep) {
  load(110, keep_distance(30, R"(maxAcceleration="2" maxDeceleration="3" maxSpeed="20")", 0));
  ASSERT_FALSE(test::transition_times(*runtime_, "KeepAction", "startTransition").empty());
  EXPECT_DOUBLE_EQ(entity("A").speed, 10.0);
  const double s = entity("A").s;
  runtime_->step(kStep);
  EXPECT_NEAR(entity("A").s - s, (10 + 2 * kStep) * kStep, 1e-9);
  runtime_->step(kStep);
  EXPECT_NEAR(entity("A").s - s, (10 + 2 * kStep) * kStep + (10 + 4 * kStep) * kStep, 1e-9);
}

// The same with jerk limits of 1 m/s^3, read as esmini reads them: while the law asks for an
// acceleration, it rises by at most 0.05 m/s^2 a step; while it asks for a deceleration, it
// falls by at most that; easing off is not bounded (the law's 2 m/s^2 drops by more than
// 0.05 m/s^2 in a step as A nears its place). Within [-3, 2] m/s^2, and A settles 30 m behind B.
TEST_F(DistanceKeeping, TheJerkLimitsBoundOnlyTheBuildUpOfTheAcceleration) {
  load(110, keep_distance(30, R"(maxAcceleration="2" maxDeceleration="3" maxSpeed="20" maxAccelerationRate="1" maxDecelerationRate="1")"));
  run_to_start();
  // The speed for the step after the start is set at the start (from 10 m/s).
  double speed = entity("A").speed, acceleration = (speed - 10) / kStep, top = 0, lowest = 0, eased = 0;
  ASSERT_NEAR(acceleration, 1.0 * kStep, 1e-9);
  while (runtime_->time() < 60 - 1e-9) {
    runtime_->step(kStep);
    const double a = (entity("A").speed - speed) / kStep;
    speed = entity("A").speed;
    if (a >= 0) {
      ASSERT_LE(a - acceleration, 1.0 * kStep + 1e-9) << "at t=" << runtime_->time();
      eased = std::max(eased, acceleration - a);
    } else {
      ASSERT_GE(a - acceleration, -1.0 * kStep - 1e-9) << "at t=" << runtime_->time();
    }
    ASSERT_LE(a, 2.0 + 1e-9);
    ASSERT_GE(a, -3.0 - 1e-9);
    top = std::max(top, a);
    lowest = std::min(lowest, a);
    acceleration = a;
  }
  EXPECT_NEAR(top, 2.0, 1e-9);  // the limits are reached on the way
  EXPECT_LT(lowest, -1.0);
  EXPECT_GT(eased, 1.0 * kStep + 1e-6);
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

// Without jerk limits the law is esmini's damped spring, a = k e - 2 sqrt(k) (v - v_ref), the
// stiffness k 0.4 1/m times maxDeceleration while short of the target and times
// maxAcceleration while too close. 1 m short, at B's speed: 1.2 m/s^2 (the braking-distance
// law would ask for sqrt(2 * 3 * 1) m/s more at once, its limit of 2 m/s^2).
TEST_F(DistanceKeeping, WithoutJerkLimitsTheAccelerationIsADampedSpringsShortOfTheTarget) {
  load(41, keep_distance(30, R"(maxAcceleration="2" maxDeceleration="3" maxSpeed="20")"));
  run_to_start();  // the speed for the step after the start is set at the start
  EXPECT_NEAR(entity("A").speed, 10 + 0.4 * 3 * 1.0 * kStep, 1e-9);
}

// 1 m too close: k = 0.4 * maxAcceleration, -0.8 m/s^2.
TEST_F(DistanceKeeping, WithoutJerkLimitsTheAccelerationIsADampedSpringsTooClose) {
  load(39, keep_distance(30, R"(maxAcceleration="2" maxDeceleration="3" maxSpeed="20")"));
  run_to_start();
  EXPECT_NEAR(entity("A").speed, 10 - 0.4 * 2 * 1.0 * kStep, 1e-9);
}

// B on the next road (past road 1's end), 41 m ahead along A's heading, the distance to keep
// 40 m: measured across the road boundary, A is 1 m short: 1.2 m/s^2, as on one road (it
// was measured as 0 m, and A braked to B's speed).
TEST_F(DistanceKeeping, TheDistanceIsMeasuredAcrossARoadsEnd) {
  load(1, keep_distance(40, R"(maxAcceleration="2" maxDeceleration="3" maxSpeed="20")"), true, 60);
  run_to_start();
  ASSERT_EQ(entity("A").road_id, "1");
  ASSERT_EQ(entity("B").road_id, "2");
  EXPECT_NEAR(entity("A").speed, 10 + 0.4 * 3 * 1.0 * kStep, 1e-9);
}

// The vehicle's Performance (maxAcceleration 10 m/s^2 here) caps DynamicConstraints that
// allow more (15 m/s^2), as it caps a SpeedAction's transition.
TEST_F(DistanceKeeping, TheVehiclesPerformanceCapsTheConstraints) {
  load(110, keep_distance(30, R"(maxAcceleration="15" maxDeceleration="15" maxSpeed="100")"));
  run_to_start();
  EXPECT_NEAR(entity("A").speed, 10 + 10 * kStep, 1e-9);
}

// The spring's damping: from 100 m short it speeds up at its limit, then eases into B's speed
// 30 m behind B without passing the target by more than 0.5 m (critically damped).
TEST_F(DistanceKeeping, TheSpringSettlesAtTheDistanceWithoutSwinging) {
  load(110, keep_distance(30, R"(maxAcceleration="2" maxDeceleration="3" maxSpeed="20")"));
  run_to_start();
  double closest = 1e9;
  while (runtime_->time() < 40 - 1e-9) {
    runtime_->step(kStep);
    closest = std::min(closest, entity("B").s - entity("A").s);
  }
  EXPECT_GT(closest, 30.0 - 0.5);
  EXPECT_NEAR(entity("B").s - entity("A").s, 30.0, 0.1);
  EXPECT_NEAR(entity("A").speed, 10.0, 0.1);
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

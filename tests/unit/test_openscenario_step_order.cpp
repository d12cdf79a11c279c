// The order of the running actions within one step of the storyboard runtime (no simulator):
// a LaneChangeAction that comes before the entity's SpeedAction in the file moves the entity
// with the speed from before the step's speed update, as esmini steps them
// (EntityState::lane_change_before_speed, docs/openscenario.md "The storyboard runtime").
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "opendrive/xodr_reader.hpp"
#include "openscenario/storyboard_runtime.hpp"
#include "openscenario/xosc_reader.hpp"
#include "support/cli_runner.hpp"
#include "unit/openscenario_snippets.hpp"

namespace orch::openscenario {
namespace {

using test::kStraightTwoLaneRoad;
using test::place;
using test::vehicle;

std::string at_one_second(const std::string& name) {
  return R"(<StartTrigger><ConditionGroup><Condition name=")" + name +
         R"(" delay="0" conditionEdge="none"><ByValueCondition><SimulationTimeCondition value="1" rule="greaterOrEqual"/></ByValueCondition></Condition></ConditionGroup></StartTrigger>)";
}

// Into lane -2 in 2 s (sinusoidal).
const std::string kLaneChange = R"(<Event name="Change" priority="parallel"><Action name="ChangeAction"><PrivateAction><LateralAction>
  <LaneChangeAction><LaneChangeActionDynamics dynamicsShape="sinusoidal" value="2" dynamicsDimension="time"/>
  <LaneChangeTarget><AbsoluteTargetLane value="-2"/></LaneChangeTarget></LaneChangeAction></LateralAction></PrivateAction></Action>)" +
                                at_one_second("ChangeStart") + "</Event>";

// From 20 to 10 m/s at 5 m/s^2: over the same 2 s.
const std::string kBrake = R"(<Event name="Brake" priority="parallel"><Action name="BrakeAction"><PrivateAction><LongitudinalAction>
  <SpeedAction><SpeedActionDynamics dynamicsShape="linear" value="5" dynamicsDimension="rate"/>
  <SpeedActionTarget><AbsoluteTargetSpeed value="10"/></SpeedActionTarget></SpeedAction></LongitudinalAction></PrivateAction></Action>)" +
                           at_one_second("BrakeStart") + "</Event>";

// A on lane -1 at s 10, 20 m/s; its maneuver holds `events` (in this order).
class StepOrder : public ::testing::Test {
 protected:
  // A's s at `until`.
  double s_at(const std::string& events, double until) {
    const std::string text = R"(<?xml version="1.0"?><OpenSCENARIO>
<FileHeader revMajor="1" revMinor="2" date="2024-01-01T00:00:00" author="t" description="step order"/>
<RoadNetwork><LogicFile filepath="road.xodr"/></RoadNetwork>
<Entities>)" + vehicle("A") + R"(</Entities>
<Storyboard><Init><Actions>)" + place("A", 10, -1, 20) + R"(</Actions></Init>
<Story name="S"><Act name="Act"><ManeuverGroup name="G" maximumExecutionCount="1">
<Actors selectTriggeringEntities="false"><EntityRef entityRef="A"/></Actors><Maneuver name="M">)" +
                             events + R"(</Maneuver></ManeuverGroup><StartTrigger/></Act></Story>
<StopTrigger/></Storyboard></OpenSCENARIO>)";
    dir_.write("road.xodr", kStraightTwoLaneRoad);
    scenario_ = load_scenario(dir_.write("s.xosc", text).string());
    roads_ = opendrive::read_xodr_file((dir_ / "road.xodr").string());
    StoryboardRuntime runtime(scenario_, roads_);
    test::run_until(runtime, until);
    EXPECT_EQ(runtime.entities().at("A").lane, -2);
    return runtime.entities().at("A").s;
  }

  orch::test::TempDir dir_;
  Scenario scenario_;
  opendrive::RoadNetwork roads_;
};

// Braking during the lane change: with the lane change first in the file, each of its 40
// steps moves with the speed of the step before, 0.25 m/s more: 0.0125 m a step, 0.5 m in all
// (a little more along the road: the lateral motion takes its share of a smaller speed).
TEST_F(StepOrder, LaneChangeBeforeTheSpeedActionMovesWithTheSpeedBeforeTheStep) {
  const double lane_change_first = s_at(kLaneChange + kBrake, 4.0);
  const double speed_first = s_at(kBrake + kLaneChange, 4.0);
  EXPECT_NEAR(lane_change_first - speed_first, 0.5, 0.01);
  // After the lane change both move alike: the gap stays.
  EXPECT_NEAR(s_at(kLaneChange + kBrake, 5.0) - s_at(kBrake + kLaneChange, 5.0), lane_change_first - speed_first, 1e-9);
}

// With the speed action first the lane change moves with the step's own speed: as far as
// with no lane change at all, less only the lateral motion's share (about 0.25 m: the mean
// v_lat^2 / 2v over the 2 s, v_lat up to 2.75 m/s).
TEST_F(StepOrder, SpeedActionBeforeTheLaneChangeMovesWithTheStepsSpeed) {
  const double speed_first = s_at(kBrake + kLaneChange, 3.0);
  // 1 s at 20 m/s, then 2 s of braking to 10 m/s, each step at its end speed.
  double straight = 10 + 20;  // the first second at 20 m/s
  for (int k = 0; k < 40; ++k) straight += 0.05 * (20 - 0.25 * (k + 1));
  EXPECT_LT(speed_first, straight);
  EXPECT_GT(speed_first, straight - 0.4);
}

}  // namespace
}  // namespace orch::openscenario

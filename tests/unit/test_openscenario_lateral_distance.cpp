// LateralDistanceAction in the storyboard's motion model: the lateral speed a step allows
// within the DynamicConstraints, and through the reader and runtime: put at the distance at
// once, driven there within maxSpeed, and kept while the other entity changes lanes.
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "opendrive/xodr_reader.hpp"
#include "openscenario/lateral_distance.hpp"
#include "openscenario/storyboard_runtime.hpp"
#include "openscenario/xosc_reader.hpp"
#include "support/cli_runner.hpp"
#include "unit/openscenario_snippets.hpp"

namespace orch::openscenario {
namespace {

using test::place;
using test::run_until;
using test::transition_times;
using test::vehicle;

TEST(LateralSpeedStep, WithoutMaxAccelerationLimitsTheSpeedAndBrakesToStopOnTheTarget) {
  EXPECT_DOUBLE_EQ(lateral_speed_step(1.0, 0, 0.05, std::nullopt, std::nullopt, std::nullopt), 20.0);  // at once
  EXPECT_DOUBLE_EQ(lateral_speed_step(1.0, 0, 0.05, 2.0, std::nullopt, std::nullopt), 2.0);
  EXPECT_DOUBLE_EQ(lateral_speed_step(-1.0, 0, 0.05, 2.0, std::nullopt, std::nullopt), -2.0);
  // 0.02 m left at 1 m/s: braking at 4 m/s^2 stops within sqrt(2 * 4 * 0.02) = 0.4 m/s; one step brakes by 0.2.
  EXPECT_NEAR(lateral_speed_step(0.02, 1.0, 0.05, 2.0, std::nullopt, 4.0), 0.8, 1e-12);
  // Moving away from the target: braking (the deceleration limit) before turning back.
  EXPECT_NEAR(lateral_speed_step(1.0, -1.0, 0.05, 2.0, std::nullopt, 4.0), -0.8, 1e-12);
}

TEST(LateralSpeedStep, WithMaxAccelerationIsADampedSpringWithinTheLimits) {
  // k = 0.4 x 5 = 2 1/s^2: 4 m away asks for 8 m/s^2, limited to 5.
  EXPECT_NEAR(lateral_speed_step(4.0, 0, 0.05, 3.0, 5.0, std::nullopt), 0.25, 1e-12);
  EXPECT_NEAR(lateral_speed_step(10.0, 2.9, 0.05, 3.0, 5.0, std::nullopt), 3.0, 1e-12);  // maxSpeed
  // 1 m away at 1 m/s: 2 x 1 - 2 sqrt(2) x 1 = -0.828 m/s^2, it eases in before the target.
  EXPECT_NEAR(lateral_speed_step(1.0, 1.0, 0.05, std::nullopt, 5.0, std::nullopt), 1 - 0.05 * (2 * std::sqrt(2.0) - 2),
              1e-12);
  // Slowing down stays within maxDeceleration (esmini ignores it): -7.66 -> -5 -> -1 m/s^2.
  EXPECT_NEAR(lateral_speed_step(-1.0, 2.0, 0.05, 3.0, 5.0, 1.0), 1.95, 1e-12);
}

TEST(LateralSpeedStep, FollowsEsminisLateralPositions) {
  // esmini 3.6 (--fixed_timestep 0.05), straight_500m.xodr: the entity at t = 1.535 keeps
  // 4 m to the right of one at t = -1.535 (target -5.535), maxSpeed 3, maxAcceleration 5,
  // from 1.10 s; esmini's t (its CSV, to the mm) at 2.5, 3.0 and 4.0 s.
  double t = 1.535, speed = 0;
  std::map<int, double> at_step;
  for (int step = 1; step <= 58; ++step) {
    speed = lateral_speed_step(-5.535 - t, speed, 0.05, 3.0, 5.0, std::nullopt);
    t += speed * 0.05;
    at_step[step] = t;
  }
  EXPECT_NEAR(at_step[28], -1.834, 0.0015);
  EXPECT_NEAR(at_step[38], -3.130, 0.0015);
  EXPECT_NEAR(at_step[58], -4.643, 0.0015);
}

// Road 0 along +x, three lanes to the right: centres at t = -1.75, -5.25, -8.75.
constexpr const char* kThreeLanes = R"(<OpenDRIVE><header revMajor="1" revMinor="6"/>
<road id="0" length="2000" junction="-1"><planView><geometry s="0" x="0" y="0" hdg="0" length="2000"><line/></geometry></planView>
<lanes><laneSection s="0"><right>
 <lane id="-1" type="driving"><width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane>
 <lane id="-2" type="driving"><width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane>
 <lane id="-3" type="driving"><width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane>
</right></laneSection></lanes></road></OpenDRIVE>)";

class LateralDistance : public ::testing::Test {
 protected:
  void load(const std::string& action, const std::string& more_events = "") {
    const std::string text = R"(<?xml version="1.0"?><OpenSCENARIO>
<FileHeader revMajor="1" revMinor="1" date="2024-01-01T00:00:00" author="t" description="lateral"/>
<RoadNetwork><LogicFile filepath="road.xodr"/></RoadNetwork>
<Entities>)" + vehicle("A") + vehicle("B") + R"(</Entities>
<Storyboard><Init><Actions>)" + place("A", 50, -3, 10) + place("B", 50, -1, 10) + R"(</Actions></Init>
<Story name="S"><Act name="Act"><ManeuverGroup name="G" maximumExecutionCount="1">
<Actors selectTriggeringEntities="false"><EntityRef entityRef="A"/></Actors><Maneuver name="M">
<Event name="Keep" priority="parallel"><Action name="KeepAction"><PrivateAction><LateralAction>)" + action +
                             R"(</LateralAction></PrivateAction></Action><StartTrigger><ConditionGroup><Condition name="T1" delay="0" conditionEdge="none">
<ByValueCondition><SimulationTimeCondition value="1" rule="greaterOrEqual"/></ByValueCondition></Condition></ConditionGroup></StartTrigger></Event>
</Maneuver></ManeuverGroup>)" + more_events + R"(<StartTrigger><ConditionGroup><Condition name="Go" delay="0" conditionEdge="none">
<ByValueCondition><SimulationTimeCondition value="0" rule="greaterOrEqual"/></ByValueCondition></Condition></ConditionGroup></StartTrigger></Act></Story>
<StopTrigger/></Storyboard></OpenSCENARIO>)";
    dir_.write("road.xodr", kThreeLanes);
    scenario_ = load_scenario(dir_.write("s.xosc", text).string());
    roads_ = opendrive::read_xodr_file((dir_ / "road.xodr").string());
    runtime_ = std::make_unique<StoryboardRuntime>(scenario_, roads_);
  }
  [[nodiscard]] double t_of(const std::string& name) const { return runtime_->entities().at(name).t; }
  test::TempDir dir_;
  Scenario scenario_;
  opendrive::RoadNetwork roads_;
  std::unique_ptr<StoryboardRuntime> runtime_;
};

TEST_F(LateralDistance, WithoutConstraintsTheEntityIsPutThereAtOnceAndTheActionEnds) {
  load(R"(<LateralDistanceAction entityRef="B" distance="1" freespace="true" continuous="false" coordinateSystem="road"
          displacement="rightToReferencedEntity"/>)");
  run_until(*runtime_, 1);
  EXPECT_NEAR(t_of("A"), -1.75 - 1 - 2, 1e-9);  // 1 m between the 2 m wide boxes, to B's right
  EXPECT_EQ(runtime_->entities().at("A").lane, -2);  // now in the middle lane
  const auto ended = transition_times(*runtime_, "KeepAction", "endTransition");
  ASSERT_EQ(ended.size(), 1u);
  EXPECT_NEAR(ended[0], 1.0, 1e-9);
}

TEST_F(LateralDistance, WithMaxSpeedTheEntityMovesThereNoFasterAndTheActionEndsThere) {
  load(R"(<LateralDistanceAction entityRef="B" distance="3" freespace="false" continuous="false" coordinateSystem="road">
          <DynamicConstraints maxSpeed="1.0"/></LateralDistanceAction>)");
  run_until(*runtime_, 1.05);
  // Starts measuring at t = 1 and moves from the second step after it, as esmini.
  EXPECT_NEAR(t_of("A"), -8.75, 1e-9);
  run_until(*runtime_, 2);
  EXPECT_NEAR(t_of("A"), -8.75 + 0.95, 1e-9);  // "any": stays to B's right, 1 m/s towards it
  EXPECT_TRUE(transition_times(*runtime_, "KeepAction", "endTransition").empty());
  run_until(*runtime_, 6);
  EXPECT_NEAR(t_of("A"), -1.75 - 3, 1e-9);
  const auto ended = transition_times(*runtime_, "KeepAction", "endTransition");
  ASSERT_EQ(ended.size(), 1u);
  EXPECT_NEAR(ended[0], 1.05 + 4.0, 0.051);  // 4 m at 1 m/s
}

TEST_F(LateralDistance, TheLateralSpeedBuildsUpStepByStepWithinMaxAcceleration) {
  load(R"(<LateralDistanceAction entityRef="B" distance="3" freespace="false" continuous="false" coordinateSystem="road">
          <DynamicConstraints maxSpeed="3.0" maxAcceleration="2.0" maxDeceleration="2.0"/></LateralDistanceAction>)");
  run_until(*runtime_, 1.05);
  const double before = t_of("A");
  // Moving from 1.10 s, 4 m from the target: the spring (k = 0.8) asks for more than 2 m/s^2
  // for the first 5 steps, each 0.1 m/s faster: 0.005 (1 + 2 + 3 + 4 + 5) = 0.075 m; a speed
  // lost between the steps would give 5 x 0.005 m.
  run_until(*runtime_, 1.30);
  EXPECT_NEAR(t_of("A") - before, 0.075, 1e-9);
}

TEST_F(LateralDistance, MovingSidewaysTakesItsShareOfTheSpeedAlongTheLane) {
  load(R"(<LateralDistanceAction entityRef="B" distance="3" freespace="false" continuous="false" coordinateSystem="road">
          <DynamicConstraints maxSpeed="6.0"/></LateralDistanceAction>)");
  run_until(*runtime_, 1.0);  // it starts
  const double s_before = runtime_->entities().at("A").s;
  run_until(*runtime_, 1.05);  // its first step still along the lane only
  EXPECT_NEAR(runtime_->entities().at("A").s - s_before, 10 * 0.05, 1e-9);
  run_until(*runtime_, 1.10);  // 6 m/s sideways of its 10: 8 m/s along the lane
  EXPECT_NEAR(runtime_->entities().at("A").s - s_before, 10 * 0.05 + 8 * 0.05, 1e-9);
}

TEST_F(LateralDistance, AContinuousOneKeepsTheDistanceWhileTheOtherMoves) {
  const std::string b_moves = R"(<ManeuverGroup name="GB" maximumExecutionCount="1"><Actors selectTriggeringEntities="false">
<EntityRef entityRef="B"/></Actors><Maneuver name="MB"><Event name="Shift" priority="parallel"><Action name="ShiftB"><PrivateAction><LateralAction>
<LaneOffsetAction continuous="false"><LaneOffsetActionDynamics dynamicsShape="step"/><LaneOffsetTarget><AbsoluteTargetLaneOffset value="-1.5"/></LaneOffsetTarget></LaneOffsetAction>
</LateralAction></PrivateAction></Action><StartTrigger><ConditionGroup><Condition name="T3" delay="0" conditionEdge="none">
<ByValueCondition><SimulationTimeCondition value="3" rule="greaterOrEqual"/></ByValueCondition></Condition></ConditionGroup></StartTrigger></Event></Maneuver></ManeuverGroup>)";
  // No distance: the one at the start (7 m between the centres) is kept.
  load(R"(<LateralDistanceAction entityRef="B" freespace="false" continuous="true" coordinateSystem="road"/>)", b_moves);
  run_until(*runtime_, 2);
  EXPECT_NEAR(t_of("A"), -8.75, 1e-9);
  run_until(*runtime_, 3.5);
  EXPECT_NEAR(t_of("B"), -3.25, 1e-9);
  EXPECT_NEAR(t_of("A"), -3.25 - 7, 1e-9);  // followed B sideways
  EXPECT_TRUE(transition_times(*runtime_, "KeepAction", "endTransition").empty());  // continuous: runs on
}

}  // namespace
}  // namespace orch::openscenario

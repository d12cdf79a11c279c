// AngleCondition and RelativeAngleCondition (OpenSCENARIO 1.3): an entity's heading, pitch
// or roll in the world, road or lane frame, or relative to another entity's, within a
// tolerance of an angle; and the reader's refusals.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/errors.hpp"
#include "opendrive/xodr_reader.hpp"
#include "openscenario/angle_measures.hpp"
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

constexpr double kCurvature = 0.01;  // the arc below: heading = kCurvature * s
// A car in lane -1 (centre 1.75 m outside the reference line) driving at v covers
// v * kAlongS metres of s a second.
constexpr double kAlongS = 1 / (1 + kCurvature * 1.75);

// When a car starting at s = 10 in lane -1 at 20 m/s reaches the heading `h`.
double time_to_heading(double h) { return (h / kCurvature - 10) / (20 * kAlongS); }
const std::string kArcRoad = R"(<OpenDRIVE><header revMajor="1" revMinor="6"/>
<road id="0" length="300" junction="-1"><planView><geometry s="0" x="0" y="0" hdg="0" length="300"><arc curvature="0.01"/></geometry></planView>
<lanes><laneSection s="0"><right>
 <lane id="-1" type="driving"><width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane>
 <lane id="-2" type="driving"><width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane>
</right></laneSection></lanes></road></OpenDRIVE>)";

std::string angle_event(const std::string& event, const std::string& condition) {
  return R"(<Event name=")" + event + R"(" priority="parallel"><Action name=")" + event + R"(Action">
<PrivateAction><LongitudinalAction><SpeedAction><SpeedActionDynamics dynamicsShape="step" dynamicsDimension="time" value="0"/>
<SpeedActionTarget><AbsoluteTargetSpeed value="10"/></SpeedActionTarget></SpeedAction></LongitudinalAction></PrivateAction></Action>
<StartTrigger><ConditionGroup><Condition name=")" + event + R"(Condition" delay="0" conditionEdge="none"><ByEntityCondition>
<TriggeringEntities triggeringEntitiesRule="any"><EntityRef entityRef="A"/></TriggeringEntities>
<EntityCondition>)" + condition + R"(</EntityCondition></ByEntityCondition></Condition></ConditionGroup></StartTrigger></Event>)";
}

class AngleConditions : public ::testing::Test {
 protected:
  void load(const std::string& init, const std::string& events, const std::string& road = kArcRoad) {
    const std::string text = R"(<?xml version="1.0"?><OpenSCENARIO>
<FileHeader revMajor="1" revMinor="3" date="2024-01-01T00:00:00" author="t" description="angles"/>
<RoadNetwork><LogicFile filepath="road.xodr"/></RoadNetwork>
<Entities>)" + vehicle("A") + vehicle("B") + R"(</Entities>
<Storyboard><Init><Actions>)" + init + R"(</Actions></Init>
<Story name="S"><Act name="Act"><ManeuverGroup name="G" maximumExecutionCount="1">
<Actors selectTriggeringEntities="false"><EntityRef entityRef="A"/></Actors><Maneuver name="M">)" + events +
                             R"(</Maneuver></ManeuverGroup><StartTrigger><ConditionGroup><Condition name="Go" delay="0" conditionEdge="none">
<ByValueCondition><SimulationTimeCondition value="0" rule="greaterOrEqual"/></ByValueCondition></Condition></ConditionGroup></StartTrigger>
</Act></Story><StopTrigger/></Storyboard></OpenSCENARIO>)";
    dir_.write("road.xodr", road);
    scenario_ = load_scenario(dir_.write("s.xosc", text).string());
    roads_ = opendrive::read_xodr_file((dir_ / "road.xodr").string());
    runtime_ = std::make_unique<StoryboardRuntime>(scenario_, roads_);
  }
  std::string load_error(const std::string& condition) {
    try {
      load(place("A", 10, -1, 20) + place("B", 0, -1, 0), angle_event("E", condition));
    } catch (const ScenarioError& e) {
      return e.what();
    }
    return "";
  }
  test::TempDir dir_;
  Scenario scenario_;
  opendrive::RoadNetwork roads_;
  std::unique_ptr<StoryboardRuntime> runtime_;
};

// The time the event started, or -1.
double started(const StoryboardRuntime& runtime, const std::string& event) {
  const auto times = transition_times(runtime, event, "startTransition");
  return times.empty() ? -1 : times.front();
}

TEST_F(AngleConditions, WorldHeadingTriggersWhereTheArcTurnsTheEntityThatFar) {
  // A drives at 20 m/s from s = 10 on the arc: its heading is kCurvature * s, so 0.6 rad
  // (within 0.01) first holds at s = 59, in the first step after the car gets there.
  load(place("A", 10, -1, 20) + place("B", 0, -1, 0),
       angle_event("Turned", R"(<AngleCondition angleType="heading" angle="0.6" angleTolerance="0.01" coordinateSystem="world"/>)"));
  run_until(*runtime_, 5);
  const double reached = time_to_heading(0.6 - 0.01);
  EXPECT_GE(started(*runtime_, "Turned"), reached - 1e-9);
  EXPECT_LT(started(*runtime_, "Turned"), reached + 0.05);
}

TEST_F(AngleConditions, WorldIsTheDefaultAndAnglesCompareOnTheCircle) {
  // 2 pi + 0.6 is the same direction as 0.6; no coordinateSystem: world.
  load(place("A", 10, -1, 20) + place("B", 0, -1, 0),
       angle_event("Turned", R"(<AngleCondition angleType="heading" angle=")" + std::to_string(2 * std::numbers::pi + 0.6) +
                                 R"(" angleTolerance="0.01"/>)"));
  run_until(*runtime_, 5);
  EXPECT_GE(started(*runtime_, "Turned"), time_to_heading(0.6 - 0.01) - 1e-9);
  EXPECT_LT(started(*runtime_, "Turned"), time_to_heading(0.6 - 0.01) + 0.05);
}

TEST_F(AngleConditions, RoadHeadingIsZeroWhileFollowingTheLaneAndTurnsDuringALaneChange) {
  // Following its lane on the arc, A's heading relative to the road stays 0 (the event with
  // a tolerance around 0 fires at once, the one at 0.03 not until the lane change at 1 s).
  const std::string lane_change = R"(<Event name="Change" priority="parallel"><Action name="ChangeAction"><PrivateAction><LateralAction>
<LaneChangeAction><LaneChangeActionDynamics dynamicsShape="sinusoidal" dynamicsDimension="time" value="3"/>
<LaneChangeTarget><AbsoluteTargetLane value="-2"/></LaneChangeTarget></LaneChangeAction></LateralAction></PrivateAction></Action>
<StartTrigger><ConditionGroup><Condition name="AtOne" delay="0" conditionEdge="none"><ByValueCondition>
<SimulationTimeCondition value="1" rule="greaterOrEqual"/></ByValueCondition></Condition></ConditionGroup></StartTrigger></Event>)";
  load(place("A", 10, -1, 20) + place("B", 0, -1, 0),
       angle_event("Along", R"(<AngleCondition angleType="heading" angle="0" angleTolerance="0.001" coordinateSystem="road"/>)") +
           angle_event("Turning", R"(<AngleCondition angleType="heading" angle="-0.03" angleTolerance="0.005" coordinateSystem="lane"/>)") +
           lane_change);
  run_until(*runtime_, 4);
  EXPECT_GE(started(*runtime_, "Along"), 0.0);  // in the first steps, before the lane change
  EXPECT_LT(started(*runtime_, "Along"), 0.1);
  const double turning = started(*runtime_, "Turning");
  EXPECT_GT(turning, 1.0);  // towards lane -2 (to the right): a negative heading relative to the road
  EXPECT_LT(turning, 4.0);
}

TEST_F(AngleConditions, RelativeHeadingGrowsAsTheEntityDrivesAwayAlongTheArc) {
  // B stands at s = 0 (heading 0); A drives from s = 10 at 20 m/s: A's heading minus B's is
  // kCurvature * s_A, 1.0 rad (within 0.01) first at s = 99.
  load(place("A", 10, -1, 20) + place("B", 0, -1, 0),
       angle_event("Apart", R"(<RelativeAngleCondition entityRef="B" angleType="heading" angle="1.0" angleTolerance="0.01"/>)"));
  run_until(*runtime_, 8);
  EXPECT_GE(started(*runtime_, "Apart"), time_to_heading(1.0 - 0.01) - 1e-9);
  EXPECT_LT(started(*runtime_, "Apart"), time_to_heading(1.0 - 0.01) + 0.05);
}

TEST_F(AngleConditions, RelativeAngleInRoadFrameComparesTheRoadRelativeAngles) {
  // Both follow their lanes: relative to the road both headings are 0, so their difference
  // is 0 wherever they are on the arc (the world difference is not).
  load(place("A", 10, -1, 20) + place("B", 0, -1, 0),
       angle_event("Same", R"(<RelativeAngleCondition entityRef="B" angleType="heading" angle="0" angleTolerance="0.001" coordinateSystem="road"/>)") +
           angle_event("WorldSame", R"(<RelativeAngleCondition entityRef="B" angleType="heading" angle="0" angleTolerance="0.001" coordinateSystem="world"/>)"));
  run_until(*runtime_, 2);
  EXPECT_GE(started(*runtime_, "Same"), 0.0);
  EXPECT_LT(started(*runtime_, "Same"), 0.1);
  EXPECT_EQ(started(*runtime_, "WorldSame"), -1.0);
}

TEST(AngleMeasures, PitchAndRollAreTheRoadSurfaceUnderTheEntity) {
  // A road climbing 5 % along s and banked by 0.04 rad: facing along s the entity's pitch
  // is -atan(0.05) (nose up), its roll the bank; facing against s both change sign.
  test::TempDir dir;
  const std::string road = R"(<OpenDRIVE><header revMajor="1" revMinor="6"/>
<road id="0" length="200" junction="-1"><planView><geometry s="0" x="0" y="0" hdg="0" length="200"><line/></geometry></planView>
<elevationProfile><elevation s="0" a="0" b="0.05" c="0" d="0"/></elevationProfile>
<lateralProfile><superelevation s="0" a="0.04" b="0" c="0" d="0"/></lateralProfile>
<lanes><laneSection s="0"><right><lane id="-1" type="driving"><width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane></right></laneSection></lanes></road></OpenDRIVE>)";
  const opendrive::RoadNetwork roads = opendrive::read_xodr_file(dir.write("r.xodr", road).string());
  EntityState e;
  e.placed = true;
  e.road_id = "0";
  e.s = 50;
  e.lane = -1;
  e.t = -1.75;
  e.pose = roads.road("0").world(50, -1.75);
  EXPECT_NEAR(*entity_angle(e, "pitch", "world", roads), -std::atan(0.05), 1e-9);
  EXPECT_NEAR(*entity_angle(e, "roll", "world", roads), std::atan(std::tan(0.04)), 1e-9);
  EXPECT_NEAR(*entity_angle(e, "pitch", "road", roads), 0.0, 1e-12);  // level with the surface it stands on
  e.pose.heading += std::numbers::pi;
  EXPECT_NEAR(*entity_angle(e, "pitch", "world", roads), std::atan(0.05), 1e-9);
  EXPECT_NEAR(*entity_angle(e, "roll", "world", roads), -0.04, 1e-9);
  EXPECT_NEAR(std::abs(*entity_angle(e, "heading", "road", roads)), std::numbers::pi, 1e-9);
  e.road_id = "";
  EXPECT_FALSE(entity_angle(e, "heading", "road", roads).has_value());  // on no road: no road frame
}

TEST(AngleMeasures, DifferencesAreOnTheCircle) {
  EXPECT_NEAR(angle_difference(0.1, 2 * std::numbers::pi - 0.1), 0.2, 1e-12);
  EXPECT_NEAR(angle_difference(-3.1, 3.1), 2 * std::numbers::pi - 6.2, 1e-12);
  EXPECT_NEAR(angle_difference(std::numbers::pi, -std::numbers::pi), 0.0, 1e-12);
}

TEST_F(AngleConditions, ReaderRefusesWhatTheConditionCannotMean) {
  EXPECT_NE(load_error(R"(<AngleCondition angleType="heading" angle="0" angleTolerance="0.1" coordinateSystem="entity"/>)")
                .find("cannot use entity"),
            std::string::npos);
  EXPECT_NE(load_error(R"(<AngleCondition angleType="heading" angle="0" angleTolerance="-0.1"/>)").find("angleTolerance"),
            std::string::npos);
  EXPECT_NE(load_error(R"(<AngleCondition angleType="yaw" angle="0" angleTolerance="0.1"/>)").find("angleType"),
            std::string::npos);
  EXPECT_NE(load_error(R"(<RelativeAngleCondition entityRef="Nobody" angleType="roll" angle="0" angleTolerance="0.1"/>)")
                .find("Nobody"),
            std::string::npos);
  EXPECT_NE(load_error(R"(<AngleCondition angleType="pitch" angle="0" angleTolerance="0.1" coordinateSystem="trajectory"/>)")
                .find("trajectory is not supported"),
            std::string::npos);
}

}  // namespace
}  // namespace orch::openscenario

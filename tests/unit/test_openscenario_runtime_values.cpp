// The storyboard runtime's variables (1.2) and trailers (1.3): VariableActions change a
// variable, a VariableCondition starts an event on it; a connected trailer follows its
// tractor, a disconnected one stays behind at rest. And the way an entity drives: it faces
// its lane's driving direction when placed without an Orientation, and keeps its direction
// when it changes into the oncoming lane.
#include <gtest/gtest.h>

#include <cmath>

#include "opendrive/xodr_reader.hpp"
#include "openscenario/storyboard_runtime.hpp"
#include "openscenario/xosc_reader.hpp"
#include "support/cli_runner.hpp"
#include "unit/openscenario_snippets.hpp"

namespace orch::openscenario {
namespace {

using test::kStraightTwoLaneRoad;
using test::place;
using test::run_until;
using test::transition_times;
using test::vehicle;

std::string at_time(const std::string& name, double at) {
  return R"(<StartTrigger><ConditionGroup><Condition name=")" + name +
         R"(" delay="0" conditionEdge="none"><ByValueCondition><SimulationTimeCondition value=")" +
         std::to_string(at) + R"(" rule="greaterOrEqual"/></ByValueCondition></Condition></ConditionGroup></StartTrigger>)";
}

// A straight two-way road: lane 1 (driven against s, right-hand traffic) and lane -1.
constexpr const char* kTwoWayRoad = R"(<OpenDRIVE><header revMajor="1" revMinor="6"/>
<road id="0" length="2000" junction="-1"><planView><geometry s="0" x="0" y="0" hdg="0" length="2000"><line/></geometry></planView>
<lanes><laneSection s="0"><left><lane id="1" type="driving"><width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane></left>
<right><lane id="-1" type="driving"><width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane></right></laneSection></lanes></road></OpenDRIVE>)";

class RuntimeValues : public ::testing::Test {
 protected:
  void load(const std::string& entities, const std::string& init, const std::string& events,
            const std::string& declarations = "", const char* road = kStraightTwoLaneRoad) {
    const std::string text = R"(<?xml version="1.0"?><OpenSCENARIO>
<FileHeader revMajor="1" revMinor="3" date="2024-01-01T00:00:00" author="t" description="values"/>)" + declarations +
                             R"(<RoadNetwork><LogicFile filepath="road.xodr"/></RoadNetwork>
<Entities>)" + entities + R"(</Entities>
<Storyboard><Init><Actions>)" + init + R"(</Actions></Init>
<Story name="S"><Act name="Act"><ManeuverGroup name="G" maximumExecutionCount="1">
<Actors selectTriggeringEntities="false"><EntityRef entityRef="A"/></Actors><Maneuver name="M">)" + events +
                             R"(</Maneuver></ManeuverGroup>)" + at_time("ActStart", 0) + R"(</Act></Story>
<StopTrigger/></Storyboard></OpenSCENARIO>)";
    dir_.write("road.xodr", road);
    scenario_ = load_scenario(dir_.write("s.xosc", text).string());
    roads_ = opendrive::read_xodr_file((dir_ / "road.xodr").string());
    runtime_ = std::make_unique<StoryboardRuntime>(scenario_, roads_);
  }
  test::TempDir dir_;
  Scenario scenario_;
  opendrive::RoadNetwork roads_;
  std::unique_ptr<StoryboardRuntime> runtime_;
};

TEST_F(RuntimeValues, VariableActionsChangeTheValueAVariableConditionReads) {
  const std::string declarations = R"(<VariableDeclarations>
    <VariableDeclaration name="Laps" variableType="integer" value="1"/>
    <VariableDeclaration name="Phase" variableType="string" value="start"/></VariableDeclarations>)";
  const std::string events = R"(<Event name="Count" priority="parallel" maximumExecutionCount="3">
      <Action name="Add"><GlobalAction><VariableAction variableRef="Laps"><ModifyAction><Rule><MultiplyByValue value="2"/></Rule></ModifyAction></VariableAction></GlobalAction></Action>
      <StartTrigger><ConditionGroup><Condition name="Tick" delay="0" conditionEdge="rising"><ByValueCondition>
        <SimulationTimeCondition value="1" rule="greaterOrEqual"/></ByValueCondition></Condition></ConditionGroup></StartTrigger></Event>
    <Event name="Name" priority="parallel">
      <Action name="Rename"><GlobalAction><VariableAction variableRef="Phase"><SetAction value="end"/></VariableAction></GlobalAction></Action>)" +
                             at_time("NameStart", 2) + R"(</Event>
    <Event name="Stop" priority="parallel"><Action name="Brake"><PrivateAction><LongitudinalAction><SpeedAction>
      <SpeedActionDynamics dynamicsShape="step" dynamicsDimension="time" value="0"/>
      <SpeedActionTarget><AbsoluteTargetSpeed value="0"/></SpeedActionTarget></SpeedAction></LongitudinalAction></PrivateAction></Action>
      <StartTrigger><ConditionGroup>
        <Condition name="Doubled" delay="0" conditionEdge="none"><ByValueCondition><VariableCondition variableRef="Laps" rule="equalTo" value="2"/></ByValueCondition></Condition>
        <Condition name="Ended" delay="0" conditionEdge="none"><ByValueCondition><VariableCondition variableRef="Phase" rule="equalTo" value="end"/></ByValueCondition></Condition>
      </ConditionGroup></StartTrigger></Event>)";
  load(vehicle("A"), place("A", 10, -1, 10), events, declarations);
  EXPECT_EQ(runtime_->variables().at("Laps").value, "1");
  run_until(*runtime_, 1.5);
  EXPECT_EQ(runtime_->variables().at("Laps").value, "2");  // once: the rising edge of t >= 1
  EXPECT_EQ(runtime_->variables().at("Phase").value, "start");
  EXPECT_TRUE(transition_times(*runtime_, "Brake", "startTransition").empty());  // Phase is not "end" yet
  run_until(*runtime_, 3);
  EXPECT_EQ(runtime_->variables().at("Phase").value, "end");
  const auto braked = transition_times(*runtime_, "Brake", "startTransition");
  ASSERT_EQ(braked.size(), 1u);
  EXPECT_NEAR(braked[0], 2.0, 1e-9);  // both conditions of the group hold from t = 2
  EXPECT_DOUBLE_EQ(runtime_->entities().at("A").speed, 0.0);
  EXPECT_TRUE(runtime_->parameters().empty());  // variables are no parameters
}

// A tractor A with a hitch 1 m behind its reference point; a trailer T whose coupler is 7 m
// ahead of its reference point.
std::string tractor_and_trailer(const std::string& trailer_element) {
  std::string a = vehicle("A");
  a.replace(a.find("</Vehicle>"), 0, "<TrailerHitch dx=\"-1.0\"/>" + trailer_element);
  std::string t = vehicle("T");
  t.replace(t.find("</Vehicle>"), 0, "<TrailerCoupler dx=\"7.0\"/>");
  return t + a;
}

TEST_F(RuntimeValues, AConnectedTrailerFollowsItsTractorAndStaysWhenDisconnected) {
  const std::string events = R"(<Event name="Off" priority="parallel"><Action name="Disconnect"><PrivateAction><TrailerAction><DisconnectTrailerAction/></TrailerAction></PrivateAction></Action>)" +
                             at_time("OffStart", 3) + "</Event>";
  // T is not placed by Init: it is towed from the start, so placed behind A.
  load(tractor_and_trailer("<Trailer><TrailerRef entityRef=\"T\"/></Trailer>"), place("A", 100, -1, 10), events);
  ASSERT_EQ(runtime_->trailers().at("A"), "T");
  const auto coupling_gap = [&] {
    const EntityState& a = runtime_->entities().at("A");
    const EntityState& t = runtime_->entities().at("T");
    const double hx = a.pose.x - 1.0 * std::cos(a.pose.heading), hy = a.pose.y - 1.0 * std::sin(a.pose.heading);
    const double cx = t.pose.x + 7.0 * std::cos(t.pose.heading), cy = t.pose.y + 7.0 * std::sin(t.pose.heading);
    return std::hypot(hx - cx, hy - cy);
  };
  const EntityState& t0 = runtime_->entities().at("T");
  ASSERT_TRUE(t0.placed);
  EXPECT_NEAR(t0.pose.x, runtime_->entities().at("A").pose.x - 8.0, 1e-9);  // straight behind: 1 m + 7 m
  EXPECT_NEAR(coupling_gap(), 0.0, 1e-9);
  run_until(*runtime_, 2.0);
  EXPECT_NEAR(coupling_gap(), 0.0, 1e-9);
  EXPECT_NEAR(runtime_->entities().at("T").speed, 10.0, 1e-9);
  EXPECT_NEAR(runtime_->entities().at("A").pose.x - runtime_->entities().at("T").pose.x, 8.0, 1e-6);
  run_until(*runtime_, 5.0);
  EXPECT_TRUE(runtime_->trailers().empty());
  const double left_at = runtime_->entities().at("T").pose.x;
  EXPECT_NEAR(left_at, runtime_->entities().at("A").pose.x - 8.0 - 2 * 10.0, 0.51);  // stopped at t = 3
  EXPECT_DOUBLE_EQ(runtime_->entities().at("T").speed, 0.0);
}

TEST_F(RuntimeValues, AConnectTrailerActionCouplesAnEntityPlacedApart) {
  const std::string events = R"(<Event name="On" priority="parallel"><Action name="Connect"><PrivateAction><TrailerAction><ConnectTrailerAction trailerRef="T"/></TrailerAction></PrivateAction></Action>)" +
                             at_time("OnStart", 1) + "</Event>";
  load(tractor_and_trailer(""), place("A", 100, -1, 10) + place("T", 50, -1, 0), events);
  EXPECT_TRUE(runtime_->trailers().empty());
  run_until(*runtime_, 0.5);
  EXPECT_NEAR(runtime_->entities().at("T").pose.x, 50.0, 1e-9);  // not towed yet: stands
  run_until(*runtime_, 1.5);
  ASSERT_EQ(runtime_->trailers().at("A"), "T");
  const EntityState& a = runtime_->entities().at("A");
  const EntityState& t = runtime_->entities().at("T");
  // Coupled: the coupler is on the hitch, the trailer in line behind on the straight road.
  EXPECT_NEAR(a.pose.x - t.pose.x, 8.0, 1e-6);
  EXPECT_NEAR(a.pose.y, t.pose.y, 1e-6);
}

// esmini's trailers.xosc: a tractor on a left lane (its LanePosition without Orientation) tows
// a chain of two trailers that Init teleported onto the tractor's own place and ahead of it.
// The tractor faces its lane's driving direction from the start, and the chain is lined up
// straight behind it (before, the trailers stood in front of it, on the side Init put them).
TEST_F(RuntimeValues, TrailersConnectedFromTheStartLineUpBehindTheirTractorInItsDrivingDirection) {
  std::string t = vehicle("T");
  t.replace(t.find("</Vehicle>"), 0, R"(<TrailerCoupler dx="7.0"/><TrailerHitch dx="-2.0"/><Trailer><TrailerRef entityRef="U"/></Trailer>)");
  std::string u = vehicle("U");
  u.replace(u.find("</Vehicle>"), 0, R"(<TrailerCoupler dx="4.0"/>)");
  std::string a = vehicle("A");
  a.replace(a.find("</Vehicle>"), 0, R"(<TrailerHitch dx="-1.0"/><Trailer><TrailerRef entityRef="T"/></Trailer>)");
  const std::string keep = R"(<Event name="Keep" priority="parallel"><Action name="Speed"><PrivateAction><LongitudinalAction><SpeedAction>
    <SpeedActionDynamics dynamicsShape="step" dynamicsDimension="time" value="0"/><SpeedActionTarget><AbsoluteTargetSpeed value="10"/></SpeedActionTarget>
    </SpeedAction></LongitudinalAction></PrivateAction></Action>)" + at_time("KeepStart", 50) + "</Event>";
  load(u + t + a, place("U", 150, 1, 0) + place("T", 100, 1, 0) + place("A", 100, 1, 10), keep, "", kTwoWayRoad);
  const EntityState& a0 = runtime_->entities().at("A");
  EXPECT_NEAR(std::cos(a0.pose.heading), -1.0, 1e-9);  // facing against s, the way it drives
  EXPECT_NEAR(runtime_->entities().at("T").pose.x, 100.0 + 8.0, 1e-9);         // 1 m + 7 m behind
  EXPECT_NEAR(runtime_->entities().at("U").pose.x, 100.0 + 8.0 + 6.0, 1e-9);   // 2 m + 4 m behind T
  EXPECT_NEAR(runtime_->entities().at("U").pose.y, a0.pose.y, 1e-9);
  run_until(*runtime_, 1.0);
  EXPECT_NEAR(runtime_->entities().at("A").pose.x, 90.0, 1e-6);
  EXPECT_NEAR(runtime_->entities().at("U").pose.x, 90.0 + 14.0, 1e-6);
}

// esmini's acc-test.xosc: the target changes one lane to the left, into the oncoming lane of a
// two-way road, and changes back. It drives on the way it drove (before, it turned round: the
// runtime moved every entity in its lane's driving direction).
TEST_F(RuntimeValues, AnEntityChangingIntoTheOncomingLaneKeepsItsDirection) {
  const std::string events = R"(<Event name="Over" priority="parallel"><Action name="Change"><PrivateAction><LateralAction><LaneChangeAction>
    <LaneChangeActionDynamics dynamicsShape="sinusoidal" value="1" dynamicsDimension="time"/>
    <LaneChangeTarget><RelativeTargetLane entityRef="A" value="1"/></LaneChangeTarget></LaneChangeAction></LateralAction></PrivateAction></Action>)" +
                             at_time("OverStart", 1) + "</Event>";
  load(vehicle("A"), place("A", 100, -1, 10), events, "", kTwoWayRoad);
  run_until(*runtime_, 3.0);
  const EntityState& a = runtime_->entities().at("A");
  EXPECT_EQ(a.lane, 1);
  EXPECT_NEAR(a.pose.y, 1.75, 1e-6);
  EXPECT_NEAR(a.pose.x, 100.0 + 30.0, 1.0);  // on along s at 10 m/s, less the lateral part during the change (0.8 m)
  EXPECT_NEAR(std::cos(a.pose.heading), 1.0, 1e-9);
}

// esmini's acc-test.xosc: a SpeedAction at a rate the vehicle's Performance does not allow
// (20 m/s^2 for a car of maxAcceleration 10) runs at the vehicle's limit.
TEST_F(RuntimeValues, ASpeedRateIsCappedByTheVehiclesPerformance) {
  const std::string events = R"(<Event name="Go" priority="parallel"><Action name="Faster"><PrivateAction><LongitudinalAction><SpeedAction>
    <SpeedActionDynamics dynamicsShape="linear" dynamicsDimension="rate" value="20"/><SpeedActionTarget><AbsoluteTargetSpeed value="30"/></SpeedActionTarget>
    </SpeedAction></LongitudinalAction></PrivateAction></Action>)" + at_time("GoStart", 1) + "</Event>";
  load(vehicle("A"), place("A", 100, -1, 10), events);
  run_until(*runtime_, 2.0);
  EXPECT_NEAR(runtime_->entities().at("A").speed, 20.0, 1e-6);  // 1 s at 10 m/s^2 (not 30 m/s after 1 s)
  run_until(*runtime_, 3.5);
  EXPECT_NEAR(runtime_->entities().at("A").speed, 30.0, 1e-6);
}

// esmini's lane_change_simple.xosc: a SpeedAction in a time whose shape is steeper than the
// vehicle can accelerate (0 to 25 m/s cubic in 4 s for a car of 5 m/s^2) keeps its shape and
// takes as long as the Performance needs; a time of 0 is still a jump.
TEST_F(RuntimeValues, ASpeedChangeInATimeTakesAsLongAsThePerformanceNeeds) {
  const std::string events = R"(<Event name="Go" priority="parallel"><Action name="Faster"><PrivateAction><LongitudinalAction><SpeedAction>
    <SpeedActionDynamics dynamicsShape="cubic" dynamicsDimension="time" value="1"/><SpeedActionTarget><AbsoluteTargetSpeed value="30"/></SpeedActionTarget>
    </SpeedAction></LongitudinalAction></PrivateAction></Action>)" + at_time("GoStart", 1) + "</Event>";
  load(vehicle("A"), place("A", 100, -1, 10), events);
  EXPECT_NEAR(runtime_->entities().at("A").speed, 10.0, 1e-9);  // the Init step of 0 s: at once
  run_until(*runtime_, 2.5);
  // 20 m/s cubic peaks at 1.5 * 20 / T m/s^2: T = 3 s for 10 m/s^2, so half way after 1.5 s.
  EXPECT_NEAR(runtime_->entities().at("A").speed, 20.0, 0.05);
  run_until(*runtime_, 3.0);
  EXPECT_LT(runtime_->entities().at("A").speed, 29.0);  // not there after the 1 s asked for
  run_until(*runtime_, 4.1);
  EXPECT_NEAR(runtime_->entities().at("A").speed, 30.0, 1e-9);
}

// esmini's lane_change_simple.xosc: at a road's dead end the entity stands, and two events on
// the same EndOfRoadCondition both start, although the first one teleports it away.
TEST_F(RuntimeValues, AtADeadEndTheEntityStandsAndEveryEventOnTheEndStarts) {
  const auto end_of_road = [](const std::string& name) {
    return R"(<StartTrigger><ConditionGroup><Condition name=")" + name +
           R"(" delay="0" conditionEdge="rising"><ByEntityCondition><TriggeringEntities triggeringEntitiesRule="any">
           <EntityRef entityRef="A"/></TriggeringEntities><EntityCondition><EndOfRoadCondition duration="0.5"/></EntityCondition>
           </ByEntityCondition></Condition></ConditionGroup></StartTrigger>)";
  };
  const std::string events =
      R"(<Event name="Back" priority="parallel"><Action name="Teleport"><PrivateAction><TeleportAction><Position>
      <LanePosition roadId="0" laneId="-1" s="100" offset="0"/></Position></TeleportAction></PrivateAction></Action>)" +
      end_of_road("BackAtEnd") + R"(</Event><Event name="Again" priority="parallel"><Action name="Restart"><PrivateAction>
      <LongitudinalAction><SpeedAction><SpeedActionDynamics dynamicsShape="step" dynamicsDimension="time" value="0"/>
      <SpeedActionTarget><AbsoluteTargetSpeed value="10"/></SpeedActionTarget></SpeedAction></LongitudinalAction></PrivateAction></Action>)" +
      end_of_road("AgainAtEnd") + "</Event>";
  load(vehicle("A"), place("A", 1990, -1, 10), events);
  run_until(*runtime_, 1.2);  // at the end after 1 s; the condition holds from 1.5 s
  EXPECT_NEAR(runtime_->entities().at("A").s, 2000.0, 1e-9);
  EXPECT_EQ(runtime_->entities().at("A").speed, 0.0);  // stuck at the end: standing
  run_until(*runtime_, 3.0);
  const auto back = transition_times(*runtime_, "Back", "startTransition");
  const auto again = transition_times(*runtime_, "Again", "startTransition");
  ASSERT_EQ(back.size(), 1u);
  EXPECT_EQ(again, back);
  EXPECT_NEAR(runtime_->entities().at("A").speed, 10.0, 1e-9);
  EXPECT_GT(runtime_->entities().at("A").s, 100.0);
  EXPECT_LT(runtime_->entities().at("A").s, 120.0);
}

// esmini's light_state.xosc: a negative target speed drives the car backwards, facing the
// way it faced (before, the sign was lost and it drove forwards at 3 m/s).
TEST_F(RuntimeValues, ANegativeSpeedDrivesBackwards) {
  const std::string events = R"(<Event name="Back" priority="parallel"><Action name="Reverse"><PrivateAction><LongitudinalAction><SpeedAction>
    <SpeedActionDynamics dynamicsShape="step" dynamicsDimension="time" value="0"/><SpeedActionTarget><AbsoluteTargetSpeed value="-3"/></SpeedActionTarget>
    </SpeedAction></LongitudinalAction></PrivateAction></Action>)" + at_time("BackStart", 1) + "</Event>";
  load(vehicle("A"), place("A", 100, -1, 0), events);
  run_until(*runtime_, 3.0);
  const EntityState& a = runtime_->entities().at("A");
  EXPECT_NEAR(a.s, 100.0 - 6.0, 1e-6);
  EXPECT_NEAR(std::cos(a.pose.heading), 1.0, 1e-9);  // still facing along s
  EXPECT_NEAR(a.odometer, 6.0, 1e-6);
}

// esmini's drop-bike.xosc: a bike placed 0.2 m above a car by a RelativeObjectPosition's dz
// ("relative position in the z axis") rides at that height; a teleport 0.1 m below it is
// 0.1 m above the road (before, dz was ignored: every entity was on the road).
TEST_F(RuntimeValues, ARelativePositionsDzIsTheEntitysHeightAboveTheRoad) {
  const std::string down = R"(<Event name="Drop" priority="parallel"><Action name="Down"><PrivateAction><TeleportAction><Position>
    <RelativeObjectPosition entityRef="B" dx="20" dy="0" dz="-0.1"/></Position></TeleportAction></PrivateAction></Action>)" +
                           at_time("DropStart", 1) + "</Event>";
  const std::string on_a = R"(<Private entityRef="B"><PrivateAction><TeleportAction><Position>
    <RelativeObjectPosition entityRef="A" dx="0" dy="-0.6" dz="0.2"/></Position></TeleportAction></PrivateAction></Private>)";
  load(vehicle("A") + vehicle("B"), place("A", 100, -1, 10) + on_a, down);
  EXPECT_NEAR(runtime_->entities().at("B").height, 0.2, 1e-12);
  EXPECT_NEAR(runtime_->entities().at("A").height, 0.0, 1e-12);
  run_until(*runtime_, 2.0);
  EXPECT_NEAR(runtime_->entities().at("A").height, 0.1, 1e-12);  // 0.1 m below B
}

// A WorldPosition's z is the point's height in the world frame ("The z coordinate value"):
// on a road 2 m up, z = 5 is 3 m above the lane's surface, and the entity keeps that height
// as it drives; beside the road (no lane) z = 10 is 10 m up (esmini's parking_demo.xosc
// Camera); without z the point is on the road. Before, z was ignored: every entity was on the
// road.
TEST_F(RuntimeValues, AWorldPositionsZIsTheEntitysHeightInTheWorld) {
  const std::string raised_road = R"(<OpenDRIVE><header revMajor="1" revMinor="6"/>
<road id="0" length="2000" junction="-1"><planView><geometry s="0" x="0" y="0" hdg="0" length="2000"><line/></geometry></planView>
<elevationProfile><elevation s="0" a="2" b="0" c="0" d="0"/></elevationProfile>
<lanes><laneSection s="0"><right><lane id="-1" type="driving"><width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane></right></laneSection></lanes></road></OpenDRIVE>)";
  const auto world = [](const std::string& name, const std::string& attributes) {
    return R"(<Private entityRef=")" + name + R"("><PrivateAction><TeleportAction><Position><WorldPosition )" + attributes +
           R"(/></Position></TeleportAction></PrivateAction>
  <PrivateAction><LongitudinalAction><SpeedAction><SpeedActionDynamics dynamicsShape="step" dynamicsDimension="time" value="0"/>
  <SpeedActionTarget><AbsoluteTargetSpeed value="10"/></SpeedActionTarget></SpeedAction></LongitudinalAction></PrivateAction></Private>)";
  };
  load(vehicle("A") + vehicle("B") + vehicle("C"),
       world("A", R"(x="100" y="-1.75" z="5" h="0")") + world("B", R"(x="100" y="50" z="10" h="0")") +
           world("C", R"(x="200" y="-1.75" h="0")"),
       R"(<Event name="Later" priority="parallel"><Action name="Same"><PrivateAction><LongitudinalAction><SpeedAction>
    <SpeedActionDynamics dynamicsShape="step" dynamicsDimension="time" value="0"/><SpeedActionTarget><AbsoluteTargetSpeed value="10"/></SpeedActionTarget>
    </SpeedAction></LongitudinalAction></PrivateAction></Action>)" + at_time("LaterStart", 50) + "</Event>",
       "", raised_road.c_str());
  EXPECT_NEAR(runtime_->entities().at("A").height, 3.0, 1e-9);
  EXPECT_NEAR(runtime_->entities().at("B").height, 10.0, 1e-9);
  EXPECT_NEAR(runtime_->entities().at("C").height, 0.0, 1e-12);
  run_until(*runtime_, 1.0);
  EXPECT_NEAR(runtime_->entities().at("A").s, 110.0, 1e-6);
  EXPECT_NEAR(runtime_->entities().at("A").height, 3.0, 1e-9);
}

// A trajectory through WorldPositions with z carries the entity at the heights between them
// (position mode, 10 m/s: halfway along 5 m -> 15 m up it is 10 m up); one vertex without z
// leaves the path on the road.
TEST_F(RuntimeValues, ATrajectoryThroughWorldHeightsCarriesTheEntityThere) {
  const auto flight = [](const std::string& first_z) {
    return R"(<Event name="Fly" priority="parallel"><Action name="Up"><PrivateAction><RoutingAction><FollowTrajectoryAction>
    <Trajectory name="T" closed="false"><Shape><Polyline>
      <Vertex><Position><WorldPosition x="100" y="-1.75" )" + first_z + R"( h="0"/></Position></Vertex>
      <Vertex><Position><WorldPosition x="200" y="-1.75" z="15" h="0"/></Position></Vertex></Polyline></Shape></Trajectory>
    <TimeReference><None/></TimeReference><TrajectoryFollowingMode followingMode="position"/>
    </FollowTrajectoryAction></RoutingAction></PrivateAction></Action>)" + at_time("FlyStart", 0) + "</Event>";
  };
  load(vehicle("A"), place("A", 100, -1, 10), flight(R"(z="5")"));
  run_until(*runtime_, 0.1);  // the action has started
  for (int i = 0; i < 98; ++i) {
    runtime_->step(0.05);
    const EntityState& a = runtime_->entities().at("A");
    EXPECT_NEAR(a.height, 5.0 + 0.1 * (a.pose.x - 100.0), 1e-6) << runtime_->time();
  }
  EXPECT_GT(runtime_->entities().at("A").pose.x, 149.0);
  load(vehicle("A"), place("A", 100, -1, 10), flight(""));
  run_until(*runtime_, 5.0);
  EXPECT_NEAR(runtime_->entities().at("A").height, 0.0, 1e-12);
}

// esmini's cut-in_cr.xosc: a towed trailer has no motion of its own. Each step its reference
// point moves straight towards the tractor's new hitch point (a bar), whatever speed it was
// given; before, it was first advanced along its lane at its speed and then pulled, so in a
// turn it swung in behind its tractor far faster than a trailer does.
TEST_F(RuntimeValues, ATowedTrailerMovesOnlyAlongItsBarTowardsTheHitch) {
  const std::string change = R"(<Event name="Change" priority="parallel"><Action name="Left"><PrivateAction><LateralAction><LaneChangeAction>
    <LaneChangeActionDynamics dynamicsShape="sinusoidal" dynamicsDimension="time" value="3"/><LaneChangeTarget><AbsoluteTargetLane value="-1"/></LaneChangeTarget>
    </LaneChangeAction></LateralAction></PrivateAction></Action>)" + at_time("ChangeStart", 1) + "</Event>";
  load(tractor_and_trailer("<Trailer><TrailerRef entityRef=\"T\"/></Trailer>"), place("A", 100, -2, 20), change);
  run_until(*runtime_, 1.5);  // A turns to the left
  for (int i = 0; i < 20; ++i) {
    const EntityState before = runtime_->entities().at("T");
    runtime_->step(0.05);
    const EntityState& a = runtime_->entities().at("A");
    const EntityState& t = runtime_->entities().at("T");
    const double hx = a.pose.x - 1.0 * std::cos(a.pose.heading), hy = a.pose.y - 1.0 * std::sin(a.pose.heading);
    EXPECT_NEAR(t.pose.heading, std::atan2(hy - before.pose.y, hx - before.pose.x), 1e-9) << runtime_->time();
    EXPECT_NEAR(std::hypot(hx - t.pose.x, hy - t.pose.y), 7.0, 1e-9);
  }
  const double lag = runtime_->entities().at("A").pose.heading - runtime_->entities().at("T").pose.heading;
  EXPECT_GT(lag, 0.01);  // mid-change the trailer still points more to the right than its tractor
}

// esmini's lane-change_clothoid_based_trajectory.xosc and follow_trajectory_by_front_axle.xosc:
// an untimed trajectory that ends within a step. The entity keeps its speed for the whole step
// (on along the last segment past the end), and the step ends facing the path's end, so a
// trajectory started then relative to the entity goes on in that direction.
TEST_F(RuntimeValues, AnUntimedTrajectoryEndingWithinAStepKeepsTheStepsTravelAndHeading) {
  // From (100, -5.25) 10.3 m at 10 m/s, 45 degrees to the left: it ends 0.03 s into the step at 1.05 s.
  const std::string first = R"(<Event name="First" priority="parallel"><Action name="Diagonal"><PrivateAction><RoutingAction><FollowTrajectoryAction>
    <Trajectory name="D" closed="false"><Shape><Polyline>
    <Vertex><Position><WorldPosition x="100" y="-5.25"/></Position></Vertex>
    <Vertex><Position><WorldPosition x="107.2832" y="2.0332"/></Position></Vertex></Polyline></Shape></Trajectory>
    <TimeReference><None/></TimeReference><TrajectoryFollowingMode followingMode="position"/></FollowTrajectoryAction></RoutingAction></PrivateAction></Action>)" +
                            at_time("FirstStart", 0) + "</Event>";
  const std::string second = R"(<Event name="Second" priority="parallel"><Action name="Straight"><PrivateAction><RoutingAction><FollowTrajectoryAction>
    <Trajectory name="S" closed="false"><Shape><Clothoid curvature="0" curvaturePrime="0" length="5"><Position>
    <RelativeObjectPosition entityRef="A" dx="0" dy="0"><Orientation type="relative" h="0"/></RelativeObjectPosition></Position></Clothoid></Shape></Trajectory>
    <TimeReference><None/></TimeReference><TrajectoryFollowingMode followingMode="position"/></FollowTrajectoryAction></RoutingAction></PrivateAction></Action>
    <StartTrigger><ConditionGroup><Condition name="AfterFirst" delay="0" conditionEdge="none"><ByValueCondition>
    <StoryboardElementStateCondition storyboardElementType="event" storyboardElementRef="First" state="completeState"/>
    </ByValueCondition></Condition></ConditionGroup></StartTrigger></Event>)";
  load(vehicle("A"), place("A", 100, -2, 10), first + second);
  run_until(*runtime_, 1.1);
  ASSERT_EQ(transition_times(*runtime_, "Diagonal", "endTransition").size(), 1U);
  const EntityState& a = runtime_->entities().at("A");
  // 10.5 m travelled by 1.05 s: 0.2 m past the end along 45 degrees, then the straight goes on at 45 degrees.
  const double along = 10.0 * (runtime_->time() - transition_times(*runtime_, "Diagonal", "startTransition").front());
  EXPECT_NEAR(a.odometer, along, 1e-6);
  EXPECT_NEAR(a.pose.x - 100.0, a.pose.y + 5.25, 1e-6);
  EXPECT_NEAR(std::hypot(a.pose.x - 100.0, a.pose.y + 5.25), along, 1e-6);
}

}  // namespace
}  // namespace orch::openscenario

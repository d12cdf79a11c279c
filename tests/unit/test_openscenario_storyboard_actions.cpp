// The storyboard runtime's trajectories, routes, controllers, visibility, global actions
// (entities, parameters) and the TimeToCollision and Collision conditions, on a straight
// two-lane road (no simulator).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/errors.hpp"
#include "opendrive/xodr_reader.hpp"
#include "openscenario/storyboard_runtime.hpp"
#include "openscenario/xosc_reader.hpp"
#include "support/cli_runner.hpp"
#include "unit/openscenario_snippets.hpp"

namespace orch::openscenario {
namespace {

using test::kStraightTwoLaneRoad;
using test::place;

// A vehicle (test::vehicle) or, with kind "Pedestrian", a pedestrian of the same box.
std::string object(const std::string& name, const std::string& kind = "Vehicle") {
  if (kind != "Pedestrian") return test::vehicle(name);
  return R"(<ScenarioObject name=")" + name + R"("><Pedestrian name="p" model="m" mass="80" pedestrianCategory="pedestrian">
  <BoundingBox><Center x="1.5" y="0" z="0.9"/><Dimensions width="2" length="5" height="1.8"/></BoundingBox></Pedestrian></ScenarioObject>)";
}

std::string lane_position(double s, int lane) {
  return R"(<Position><LanePosition roadId="0" laneId=")" + std::to_string(lane) + R"(" s=")" + std::to_string(s) +
         R"(" offset="0"/></Position>)";
}

std::string at_time(double at) {
  return R"(<Condition name="c" delay="0" conditionEdge="none"><ByValueCondition><SimulationTimeCondition value=")" +
         std::to_string(at) + R"(" rule="greaterOrEqual"/></ByValueCondition></Condition>)";
}

std::string by_entity(const std::string& entity, const std::string& condition) {
  return R"(<Condition name="c" delay="0" conditionEdge="none"><ByEntityCondition><TriggeringEntities triggeringEntitiesRule="any">
<EntityRef entityRef=")" + entity + R"("/></TriggeringEntities><EntityCondition>)" + condition +
         "</EntityCondition></ByEntityCondition></Condition>";
}

std::string event(const std::string& name, const std::string& action_body, const std::string& condition,
                  const std::string& kind = "PrivateAction") {
  return R"(<Event name=")" + name + R"(" priority="parallel"><Action name=")" + name + R"(Action"><)" + kind + ">" +
         action_body + "</" + kind + "></Action><StartTrigger><ConditionGroup>" + condition +
         "</ConditionGroup></StartTrigger></Event>";
}

class StoryboardActions : public ::testing::Test {
 protected:
  // `entities` and `init` are XML; A's maneuver holds `events`; `stop` is the Storyboard's
  // StopTrigger condition ("": at t = 100 s).
  void load(const std::string& entities, const std::string& init, const std::string& events,
            const std::string& parameters = "", const std::string& stop = "") {
    const std::string text = R"(<?xml version="1.0"?><OpenSCENARIO>
<FileHeader revMajor="1" revMinor="2" date="2024-01-01T00:00:00" author="t" description="actions"/>
<ParameterDeclarations>)" + parameters + R"(</ParameterDeclarations>
<RoadNetwork><LogicFile filepath="road.xodr"/></RoadNetwork>
<Entities>)" + entities + R"(</Entities>
<Storyboard><Init><Actions>)" + init + R"(</Actions></Init>
<Story name="S"><Act name="Act"><ManeuverGroup name="G" maximumExecutionCount="1">
<Actors selectTriggeringEntities="false"><EntityRef entityRef="A"/></Actors><Maneuver name="M">)" + events +
                             R"(</Maneuver></ManeuverGroup><StartTrigger><ConditionGroup>)" + at_time(0) +
                             R"(</ConditionGroup></StartTrigger></Act></Story>
<StopTrigger><ConditionGroup>)" + (stop.empty() ? at_time(100) : stop) + R"(</ConditionGroup></StopTrigger></Storyboard></OpenSCENARIO>)";
    dir_.write("road.xodr", kStraightTwoLaneRoad);
    scenario_ = load_scenario(dir_.write("s.xosc", text).string());
    roads_ = opendrive::read_xodr_file((dir_ / "road.xodr").string());
    runtime_ = std::make_unique<StoryboardRuntime>(scenario_, roads_);
  }
  // A (10 m/s) closing from 100 m to 30 m behind B (10 m/s): a non-continuous
  // LongitudinalDistanceAction from 1 s with these limits (maxSpeed 20 m/s).
  void load_closing_in(int max_acceleration, int max_deceleration) {
    load(object("A") + object("B"), place("A", 10, -1, 10) + place("B", 110, -1, 10),
         event("Close",
               R"(<LongitudinalAction><LongitudinalDistanceAction entityRef="B" distance="30" freespace="false" continuous="false">
<DynamicConstraints maxAcceleration=")" + std::to_string(max_acceleration) + R"(" maxDeceleration=")" +
                   std::to_string(max_deceleration) +
                   R"(" maxSpeed="20"/></LongitudinalDistanceAction></LongitudinalAction>)",
               at_time(1)));
  }
  // The load error's text for a scenario with `events`.
  std::string load_error(const std::string& events, const std::string& parameters = "") {
    try {
      load(object("A"), place("A", 10, -1, 10), events, parameters);
    } catch (const ScenarioError& e) {
      return e.what();
    }
    return "";
  }
  void run_until(double t) { test::run_until(*runtime_, t); }
  [[nodiscard]] std::vector<double> times(const std::string& name, const std::string& transition) const {
    return test::transition_times(*runtime_, name, transition);
  }
  [[nodiscard]] double first(const std::string& name, const std::string& transition = "startTransition") const {
    const auto t = times(name, transition);
    return t.empty() ? -1.0 : t.front();
  }
  [[nodiscard]] const EntityState& entity(const std::string& name) const { return runtime_->entities().at(name); }

  orch::test::TempDir dir_;
  Scenario scenario_;
  opendrive::RoadNetwork roads_;
  std::unique_ptr<StoryboardRuntime> runtime_;
};

std::string polyline_trajectory(const std::string& vertices, const std::string& timing,
                                const std::string& mode = "position") {
  return R"(<RoutingAction><FollowTrajectoryAction><TrajectoryRef><Trajectory name="T" closed="false"><Shape><Polyline>)" +
         vertices + R"(</Polyline></Shape></Trajectory></TrajectoryRef><TimeReference>)" + timing +
         R"(</TimeReference><TrajectoryFollowingMode followingMode=")" + mode +
         R"("/></FollowTrajectoryAction></RoutingAction>)";
}

std::string vertex(double x, double y, const std::string& time = "") {
  return "<Vertex" + (time.empty() ? std::string() : " time=\"" + time + "\"") +
         R"(><Position><WorldPosition x=")" + std::to_string(x) + R"(" y=")" + std::to_string(y) +
         R"("/></Position></Vertex>)";
}

TEST_F(StoryboardActions, TimedPolylineAbsoluteWithScaleAndOffset) {
  // Vertex times 0 and 10, scale 0.5, offset 2: due at t = 2 and t = 7 (100 m in 5 s).
  load(object("A"), place("A", 10, -1, 10),
       event("Follow",
             polyline_trajectory(vertex(20, -1.75, "0") + vertex(120, -1.75, "10"),
                                 R"(<Timing domainAbsoluteRelative="absolute" scale="0.5" offset="2"/>)"),
             at_time(1)));
  run_until(1.5);
  EXPECT_NEAR(entity("A").pose.x, 20.0, 1e-9);  // at the first vertex until it is due
  run_until(4.5);
  EXPECT_NEAR(entity("A").pose.x, 70.0, 1e-9);
  EXPECT_NEAR(entity("A").pose.y, -1.75, 1e-9);
  EXPECT_NEAR(entity("A").speed, 20.0, 1e-6);
  EXPECT_EQ(entity("A").lane, -1);
  EXPECT_NEAR(entity("A").s, 70.0, 1e-6);
  run_until(8);
  EXPECT_NEAR(first("FollowAction", "endTransition"), 7.0, 1e-9);
  EXPECT_NEAR(entity("A").pose.x, 120.0 + 20.0, 1e-6);  // then on along its lane at 20 m/s
}

TEST_F(StoryboardActions, TimedPolylineRelativeStartsWithTheAction) {
  load(object("A"), place("A", 10, -1, 10),
       event("Follow",
             polyline_trajectory(vertex(20, -1.75, "0") + vertex(60, -5.25, "4"),
                                 R"(<Timing domainAbsoluteRelative="relative" scale="1" offset="0"/>)"),
             at_time(1)));
  run_until(3);  // half way: t = 1 + 2
  EXPECT_NEAR(entity("A").pose.x, 40.0, 1e-9);
  EXPECT_NEAR(entity("A").pose.y, -3.5, 1e-9);
  EXPECT_NEAR(entity("A").pose.heading, std::atan2(-3.5, 40.0), 1e-9);
  run_until(6);
  EXPECT_NEAR(first("FollowAction", "endTransition"), 5.0, 1e-9);
  EXPECT_EQ(entity("A").lane, -2);  // continues in the lane the trajectory ended in
  EXPECT_NEAR(entity("A").pose.y, -5.25, 1e-9);
}

TEST_F(StoryboardActions, FollowModeTracksThePathUnderTheEntitysLimits) {
  // The lane change of the test above, followingMode "follow": the car stays where it is at
  // the start and steers (pure pursuit, trajectory_follow.hpp), so it is not on the
  // straight line between the vertices half way, and arrives in the lane later.
  load(object("A"), place("A", 10, -1, 10),
       event("Follow",
             polyline_trajectory(vertex(20, -1.75, "0") + vertex(60, -5.25, "4"),
                                 R"(<Timing domainAbsoluteRelative="relative" scale="1" offset="0"/>)", "follow"),
             at_time(1)));
  EXPECT_TRUE(std::get<FollowTrajectoryAction>(scenario_.storyboard.stories[0].acts[0].groups[0].maneuvers[0].events[0]
                                                   .actions[0].action)
                  .follow_mode);
  run_until(3);
  const double on_line = -1.75 - 3.5 * (entity("A").pose.x - 20.0) / 40.0;
  EXPECT_GT(std::abs(entity("A").pose.y - on_line), 0.01);  // the path is tracked, not imposed
  EXPECT_LT(std::abs(entity("A").pose.y - on_line), 0.5);
  EXPECT_GT(entity("A").pose.y, on_line);  // its heading lags the path's
  run_until(8);
  const double end = first("FollowAction", "endTransition");
  EXPECT_GE(end, 5.0 - 1e-9);
  EXPECT_LT(end, 6.0);
  EXPECT_EQ(entity("A").lane, -2);
}

TEST_F(StoryboardActions, UntimedPolylineAtTheEntitysOwnSpeed) {
  load(object("A"), place("A", 10, -1, 10),
       event("Follow", polyline_trajectory(vertex(20, -1.75) + vertex(60, -1.75) + vertex(90, -5.25), "<None/>"),
             at_time(1)));
  run_until(3);  // 2 s at 10 m/s from the first vertex
  EXPECT_NEAR(entity("A").pose.x, 40.0, 1e-9);
  const double length = 40.0 + std::hypot(30.0, 3.5);
  run_until(10);
  EXPECT_NEAR(first("FollowAction", "endTransition"), 1.0 + std::ceil(length / 10.0 / 0.05 - 1e-9) * 0.05, 1e-9);
  // 10 m to the first vertex, then 10 m/s for 9 s: the step the path ends in keeps its whole
  // travel (on past the end), so nothing is lost at the end.
  EXPECT_NEAR(entity("A").odometer, 10.0 + (10.0 - 1.0) * 10.0, 1e-6);
}

TEST_F(StoryboardActions, ClothoidEndsWhereTheReferenceDoes) {
  const double k_prime = -0.0002;
  load(object("A"), place("A", 10, -1, 10),
       event("Curve",
             R"(<RoutingAction><FollowTrajectoryAction><Trajectory name="C" closed="false"><Shape>
<Clothoid curvature="0" curvaturePrime="-0.0002" length="50" startTime="0" stopTime="5">
<Position><WorldPosition x="20" y="-1.75" h="0"/></Position></Clothoid></Shape></Trajectory>
<TimeReference><Timing domainAbsoluteRelative="relative" scale="1" offset="0"/></TimeReference>
<TrajectoryFollowingMode followingMode="position"/></FollowTrajectoryAction></RoutingAction>)",
             at_time(1)));
  // Reference: x' = cos(k' s^2 / 2), y' = sin(k' s^2 / 2), by the midpoint rule in 1 mm steps.
  double x = 20, y = -1.75;
  const int n = 50000;
  for (int i = 0; i < n; ++i) {
    const double s = (i + 0.5) * 50.0 / n;
    x += std::cos(k_prime * s * s / 2) * 50.0 / n;
    y += std::sin(k_prime * s * s / 2) * 50.0 / n;
  }
  run_until(5.95);  // one step before the end: 0.5 m short of it, on the curve
  const opendrive::Pose2 before = entity("A").pose;
  EXPECT_NEAR(std::hypot(x - before.x, y - before.y), 0.5, 0.01);
  EXPECT_NEAR(before.heading, k_prime * 49.5 * 49.5 / 2, 0.005);
  run_until(6.0);
  EXPECT_NEAR(first("CurveAction", "endTransition"), 6.0, 1e-9);
  EXPECT_EQ(entity("A").lane, -2);  // 4.2 m to the right of where it began
  // Where the path ended: the lane keeps the position (now on the lane's heading).
  EXPECT_NEAR(entity("A").pose.x, x, 1e-3);
  EXPECT_NEAR(entity("A").pose.y, y, 1e-3);
}

TEST_F(StoryboardActions, AcquirePositionEndsWhenReachedAssignRouteMapsWaypoints) {
  load(object("A"), place("A", 10, -1, 10),
       event("Acquire", "<RoutingAction><AcquirePositionAction>" + lane_position(200, -1) +
                            "</AcquirePositionAction></RoutingAction>",
             at_time(1)) +
           event("Route",
                 R"(<RoutingAction><AssignRouteAction><Route name="R" closed="false"><Waypoint routeStrategy="shortest">)" +
                     lane_position(100, -1) + R"(</Waypoint><Waypoint routeStrategy="fastest">)" + lane_position(400, -2) +
                     "</Waypoint></Route></AssignRouteAction></RoutingAction>",
                 at_time(25)));
  run_until(30);
  EXPECT_NEAR(first("AcquireAction", "endTransition"), 19.0, 1e-9);  // s = 10 + 10 t reaches 200
  EXPECT_NEAR(first("RouteAction", "endTransition"), 25.0, 1e-9);     // assigning is instantaneous
  ASSERT_EQ(entity("A").route.size(), 2u);
  EXPECT_EQ(entity("A").route[1].lane, -2);
  EXPECT_NEAR(entity("A").route[1].s, 400.0, 1e-9);
  EXPECT_EQ(entity("A").route_passed, 1u);  // s = 310: past the first waypoint only
  run_until(40);
  EXPECT_EQ(entity("A").route_passed, 2u);
}

TEST_F(StoryboardActions, AWaypointOffTheRoadIsAnErrorNamingIt) {
  load(object("A"), place("A", 10, -1, 10),
       event("Route",
             R"(<RoutingAction><AssignRouteAction><Route name="R" closed="false"><Waypoint routeStrategy="shortest">)" +
                 lane_position(100, -1) +
                 R"(</Waypoint><Waypoint routeStrategy="shortest"><Position><WorldPosition x="50" y="40"/></Position></Waypoint></Route></AssignRouteAction></RoutingAction>)",
             at_time(1)));
  try {
    run_until(2);
    FAIL() << "expected an error";
  } catch (const MapError& e) {
    EXPECT_NE(std::string(e.what()).find("waypoint 2 of route \"R\" of \"A\""), std::string::npos) << e.what();
  }
}

TEST_F(StoryboardActions, ControllersAndVisibility) {
  load(object("A"), place("A", 10, -1, 10),
       event("Assign",
             R"(<ControllerAction><AssignControllerAction><Controller name="Driver"><Properties/></Controller></AssignControllerAction></ControllerAction>)",
             at_time(1)) +
           event("Activate", R"(<ControllerAction><ActivateControllerAction longitudinal="true" lateral="true"/></ControllerAction>)",
                 at_time(2)) +
           event("Hide", R"(<VisibilityAction graphics="true" traffic="false" sensors="false"/>)", at_time(3)));
  run_until(1.5);
  EXPECT_EQ(entity("A").controller, "Driver");
  EXPECT_FALSE(entity("A").controller_active);
  run_until(2.5);
  EXPECT_TRUE(entity("A").controller_active);
  EXPECT_TRUE(entity("A").visibility.traffic);
  run_until(3.5);
  EXPECT_FALSE(entity("A").visibility.traffic);
  EXPECT_FALSE(entity("A").visibility.sensors);
  EXPECT_TRUE(entity("A").visibility.graphics);
}

TEST_F(StoryboardActions, AddAndDeleteEntities) {
  load(object("A") + object("B"), place("A", 10, -1, 10),
       event("Add", R"(<EntityAction entityRef="B"><AddEntityAction>)" + lane_position(300, -2) +
                        "</AddEntityAction></EntityAction>",
             at_time(1), "GlobalAction") +
           event("Delete", R"(<EntityAction entityRef="B"><DeleteEntityAction/></EntityAction>)", at_time(2),
                 "GlobalAction"));
  EXPECT_FALSE(entity("B").placed);
  run_until(1.5);
  ASSERT_TRUE(entity("B").placed);
  EXPECT_NEAR(entity("B").pose.x, 300.0, 1e-9);
  EXPECT_NEAR(entity("B").pose.y, -5.25, 1e-9);
  EXPECT_EQ(entity("B").speed, 0.0);
  run_until(2.5);
  EXPECT_FALSE(entity("B").placed);
  EXPECT_NEAR(first("DeleteAction", "endTransition"), 2.0, 1e-9);
}

TEST_F(StoryboardActions, ParameterActionsAndTheConditionsThatReact) {
  const std::string set = R"(<ParameterAction parameterRef="Phase"><SetAction value="2"/></ParameterAction>)";
  const std::string add =
      R"(<ParameterAction parameterRef="Phase"><ModifyAction><Rule><AddValue value="5"/></Rule></ModifyAction></ParameterAction>)";
  const std::string multiply =
      R"(<ParameterAction parameterRef="Gain"><ModifyAction><Rule><MultiplyByValue value="1.5"/></Rule></ModifyAction></ParameterAction>)";
  const auto parameter_is = [](const std::string& name, const std::string& value) {
    return R"(<Condition name="c" delay="0" conditionEdge="none"><ByValueCondition><ParameterCondition parameterRef=")" +
           name + R"(" value=")" + value + R"(" rule="equalTo"/></ByValueCondition></Condition>)";
  };
  load(object("A"), place("A", 10, -1, 10),
       event("Set", set, at_time(1), "GlobalAction") + event("Add", add, parameter_is("Phase", "2"), "GlobalAction") +
           event("Multiply", multiply, parameter_is("Phase", "7"), "GlobalAction") +
           event("Go",
                 R"(<LongitudinalAction><SpeedAction><SpeedActionDynamics dynamicsShape="step" dynamicsDimension="time" value="0"/>
<SpeedActionTarget><AbsoluteTargetSpeed value="20"/></SpeedActionTarget></SpeedAction></LongitudinalAction>)",
                 parameter_is("Gain", "3")),
       R"(<ParameterDeclaration name="Phase" parameterType="integer" value="0"/><ParameterDeclaration name="Gain" parameterType="double" value="2"/>)");
  run_until(0.5);
  EXPECT_EQ(runtime_->parameters().at("Phase").value, "0");
  run_until(1.2);
  EXPECT_NEAR(first("Set"), 1.0, 1e-9);
  EXPECT_EQ(runtime_->parameters().at("Phase").value, "7");  // set to 2, then + 5 in the same step
  EXPECT_EQ(runtime_->parameters().at("Gain").value, "3");
  EXPECT_NEAR(first("Multiply"), 1.0, 1e-9);
  EXPECT_GE(first("Go"), 1.0);
  EXPECT_DOUBLE_EQ(entity("A").speed, 20.0);
  EXPECT_EQ(scenario_.parameters[0].value, "0");  // the loaded scenario is unchanged
}

TEST_F(StoryboardActions, ParameterActionErrorsNameTheProblem) {
  EXPECT_NE(load_error(event("Set", R"(<ParameterAction parameterRef="Phase"><SetAction value="two"/></ParameterAction>)",
                             at_time(1), "GlobalAction"),
                       R"(<ParameterDeclaration name="Phase" parameterType="integer" value="0"/>)")
                .find("SetAction/@value"),
            std::string::npos);
  EXPECT_NE(load_error(event("Set", R"(<ParameterAction parameterRef="Phsae"><SetAction value="2"/></ParameterAction>)",
                             at_time(1), "GlobalAction"),
                       R"(<ParameterDeclaration name="Phase" parameterType="integer" value="0"/>)")
                .find("no parameter \"Phsae\" is declared"),
            std::string::npos);
  EXPECT_NE(load_error(event("Mod",
                             R"(<ParameterAction parameterRef="Name"><ModifyAction><Rule><AddValue value="1"/></Rule></ModifyAction></ParameterAction>)",
                             at_time(1), "GlobalAction"),
                       R"(<ParameterDeclaration name="Name" parameterType="string" value="x"/>)")
                .find("needs a numeric parameter"),
            std::string::npos);
}

std::string ttc(const std::string& target, bool freespace, const std::string& system, double value) {
  return R"(<TimeToCollisionCondition freespace=")" + std::string(freespace ? "true" : "false") +
         R"(" coordinateSystem=")" + system + R"(" relativeDistanceType="longitudinal" rule="lessThan" value=")" +
         std::to_string(value) + R"("><TimeToCollisionConditionTarget>)" + target +
         "</TimeToCollisionConditionTarget></TimeToCollisionCondition>";
}

const char* kSlow = R"(<LongitudinalAction><SpeedAction><SpeedActionDynamics dynamicsShape="step" dynamicsDimension="time" value="0"/>
<SpeedActionTarget><AbsoluteTargetSpeed value="10"/></SpeedActionTarget></SpeedAction></LongitudinalAction>)";

TEST_F(StoryboardActions, TimeToCollisionWithEntitiesAndPositions) {
  // A (10 m/s) 100 m behind B (5 m/s) in the same lane: TTC 20 s between reference points,
  // 19 s between the boxes (5 m long); a position 290 m ahead of A at rest: 29 s.
  load(object("A") + object("B"), place("A", 10, -1, 10) + place("B", 110, -1, 5),
       event("Entity", kSlow, by_entity("A", ttc(R"(<EntityRef entityRef="B"/>)", false, "entity", 10.01))) +
           event("Free", kSlow, by_entity("A", ttc(R"(<EntityRef entityRef="B"/>)", true, "road", 10.01))) +
           event("Lane", kSlow, by_entity("A", ttc(R"(<EntityRef entityRef="B"/>)", true, "lane", 10.01))) +
           event("Point", kSlow, by_entity("A", ttc(lane_position(300, -1), false, "entity", 20.01))) +
           event("Away", kSlow, by_entity("A", ttc(lane_position(5, -1), false, "entity", 1000))));
  run_until(30);
  EXPECT_NEAR(first("Entity"), 10.0, 1e-9);  // TTC (100 - 5 t) / 5 < 10.01 from t = 10
  EXPECT_NEAR(first("Free"), 9.0, 1e-9);     // (95 - 5 t) / 5
  EXPECT_NEAR(first("Lane"), 9.0, 1e-9);
  EXPECT_NEAR(first("Point"), 9.0, 1e-9);    // (290 - 10 t) / 10
  EXPECT_EQ(first("Away"), -1.0);            // a point behind A: the distance grows, infinite
}

TEST_F(StoryboardActions, CollisionByEntityAndByType) {
  // A at 10 m/s runs into B standing 50 m ahead: boxes (5 m) touch when A has covered 45 m.
  const auto collision = [](const std::string& target) {
    return "<CollisionCondition>" + target + "</CollisionCondition>";
  };
  load(object("A") + object("B") + object("P", "Pedestrian"),
       place("A", 10, -1, 10) + place("B", 60, -1, 0) + place("P", 500, -2, 0),
       event("HitB", kSlow, by_entity("A", collision(R"(<EntityRef entityRef="B"/>)"))) +
           event("HitVehicle", kSlow, by_entity("A", collision(R"(<ByType type="vehicle"/>)"))) +
           event("HitPedestrian", kSlow, by_entity("A", collision(R"(<ByType type="pedestrian"/>)"))));
  run_until(10);
  EXPECT_GE(first("HitB"), 4.5 - 1e-9);
  EXPECT_LE(first("HitB"), 4.55 + 1e-9);
  EXPECT_DOUBLE_EQ(first("HitVehicle"), first("HitB"));
  EXPECT_EQ(first("HitPedestrian"), -1.0);
}

// LongitudinalDistanceAction with DynamicConstraints: A (10 m/s) closes from 100 m to 30 m
// behind B (10 m/s) within its limits and ends there.
TEST_F(StoryboardActions, LongitudinalDistanceWithinItsLimits) {
  load_closing_in(2, 3);
  double previous = entity("A").speed, top = 0;
  while (runtime_->time() < 40 - 1e-9 && first("CloseAction", "endTransition") < 0) {
    runtime_->step(0.05);
    const double a = (entity("A").speed - previous) / 0.05;
    previous = entity("A").speed;
    top = std::max(top, entity("A").speed);
    ASSERT_LE(a, 2.0 + 1e-9) << "at t=" << runtime_->time();
    ASSERT_GE(a, -3.0 - 1e-9) << "at t=" << runtime_->time();
  }
  EXPECT_NEAR(top, 20.0, 1e-9);  // the speed limit is reached on the way
  const double end = first("CloseAction", "endTransition");
  ASSERT_GT(end, 5.0);  // not a jump: 70 m at a 10 m/s surplus at most
  EXPECT_LT(end, 40.0);
  EXPECT_NEAR(entity("B").s - entity("A").s, 30.0, 0.1);  // where it ended
  // Its speed there is not B's yet (0.67 m/s more: the deceleration limit of 3 m/s^2 caps
  // the spring's braking): the action ends at the distance (the next test).
  EXPECT_LT(entity("A").speed, 11.0);
}

// A non-continuous one ends when the distance is reached (within 0.1 m), whatever the
// speed: with a stiff spring (maxDeceleration 10) A arrives still 0.2 m/s faster than B (as
// esmini ends it; distance_test.xosc).
TEST_F(StoryboardActions, LongitudinalDistanceEndsWhenTheDistanceIsReached) {
  load_closing_in(10, 10);
  while (runtime_->time() < 40 - 1e-9 && first("CloseAction", "endTransition") < 0) runtime_->step(0.05);
  ASSERT_GT(first("CloseAction", "endTransition"), 0);
  EXPECT_NEAR(entity("B").s - entity("A").s, 30.0, 0.1);
  EXPECT_GT(entity("A").speed - entity("B").speed, 0.1);
}

// A speed change over a distance is no steeper than the vehicle's Performance allows, as one
// in a time: 15 to 35 m/s "cubic over 40 m" is 1.6 s at the mean speed, peaking at
// 18.75 m/s^2; the car of 10 m/s^2 takes 3 s (as esmini stretches it).
TEST_F(StoryboardActions, ASpeedChangeOverADistanceKeepsWithinThePerformance) {
  load(object("A"), place("A", 10, -1, 15),
       event("Faster", R"(<LongitudinalAction><SpeedAction><SpeedActionDynamics dynamicsShape="cubic" dynamicsDimension="distance" value="40"/>
<SpeedActionTarget><AbsoluteTargetSpeed value="35"/></SpeedActionTarget></SpeedAction></LongitudinalAction>)",
             at_time(1)));
  test::run_until(*runtime_, 6);
  EXPECT_NEAR(first("FasterAction", "endTransition"), 1 + 3.0, 0.051);
  EXPECT_NEAR(entity("A").speed, 35, 1e-9);
}

TEST_F(StoryboardActions, ElementsNotRunAreErrorsNamingThem) {
  EXPECT_NE(load_error(event("Profile", R"(<LongitudinalAction><SpeedProfileAction followingMode="position"/></LongitudinalAction>)", at_time(1)))
                .find("a SpeedProfileAction needs at least one SpeedProfileEntry"),  // read and run (1.2)
            std::string::npos);
  EXPECT_NE(load_error(event("Clothoids", R"(<RoutingAction><FollowTrajectoryAction><Trajectory name="T" closed="false"><Shape><ClothoidSpline/></Shape></Trajectory>
<TimeReference><None/></TimeReference><TrajectoryFollowingMode followingMode="position"/></FollowTrajectoryAction></RoutingAction>)",
                             at_time(1)))
                .find("a ClothoidSpline needs at least one ClothoidSplineSegment"),  // read and run (1.3)
            std::string::npos);
  EXPECT_EQ(load_error(event("Clear", kSlow,  // read and run (1.2)
                             by_entity("A", R"(<RelativeClearanceCondition oppositeLanes="false" distanceForward="5" distanceBackward="5" freeSpace="true"/>)"))),
            "");
  // TrafficAction is read and run (test_openscenario_traffic_actions.cpp): an empty one misses its action.
  EXPECT_NE(load_error(event("Traffic", R"(<TrafficAction/>)", at_time(1), "GlobalAction")).find("TrafficSwarmAction"),
            std::string::npos);
  // InfrastructureAction is read and run: an empty one misses its TrafficSignalAction.
  EXPECT_NE(load_error(event("Signals", R"(<InfrastructureAction/>)", at_time(1), "GlobalAction"))
                .find("TrafficSignalAction"),
            std::string::npos);
  // EnvironmentAction is read (and runs with no effect): an empty one misses its Environment.
  EXPECT_NE(load_error(event("Env", R"(<EnvironmentAction/>)", at_time(1), "GlobalAction"))
                .find("expected one of the elements"),
            std::string::npos);
  // A misspelt action: "did you mean".
  EXPECT_NE(load_error(event("Typo", R"(<RoutingAction><AcquirePositonAction/></RoutingAction>)", at_time(1)))
                .find("did you mean \"AcquirePositionAction\""),
            std::string::npos);
}

}  // namespace
}  // namespace orch::openscenario

namespace orch::openscenario {
namespace {

TEST_F(StoryboardActions, StopTriggerSeesTheEndOfAnInstantActionInTheNextStep) {
  // The teleport starts and ends at t = 1 after the stop trigger was evaluated in that step:
  // the stop trigger sees the endTransition in the following evaluation, once.
  const std::string ended = R"(<Condition name="ended" delay="0" conditionEdge="none"><ByValueCondition>
<StoryboardElementStateCondition storyboardElementType="action" storyboardElementRef="JumpAction" state="endTransition"/>
</ByValueCondition></Condition>)";
  load(object("A"), place("A", 10, -1, 10),
       event("Jump", "<TeleportAction>" + lane_position(50, -1) + "</TeleportAction>", at_time(1)), "", ended);
  run_until(0.95);
  EXPECT_FALSE(runtime_->finished());
  run_until(2);
  EXPECT_EQ(times("JumpAction", "endTransition"), std::vector<double>{1.0});
  ASSERT_TRUE(runtime_->finished());
  EXPECT_NEAR(runtime_->time(), 1.05, 1e-9);
  EXPECT_EQ(runtime_->log().back().type, "storyboard");
  EXPECT_EQ(runtime_->log().back().transition, "stopTransition");
}

}  // namespace
}  // namespace orch::openscenario

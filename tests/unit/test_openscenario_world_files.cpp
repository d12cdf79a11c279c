// OpenSCENARIO as esmini's world examples write it (issue 24): several ObjectControllers per
// entity chosen by ActivateControllerAction's objectControllerRef (1.3), a declaration whose
// value its type cannot hold (a clear error), and a scenario without a road (no LogicFile):
// entities placed and moved by world positions.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "core/errors.hpp"
#include "opendrive/road_network.hpp"
#include "opendrive/xodr_reader.hpp"
#include "openscenario/storyboard_runtime.hpp"
#include "openscenario/xosc_reader.hpp"
#include "support/cli_runner.hpp"
#include "unit/openscenario_snippets.hpp"

namespace orch::openscenario {
namespace {

using orch::test::TempDir;

std::string controller(const std::string& name, const std::string& controller_name) {
  return R"(<ObjectController)" + (name.empty() ? std::string() : R"( name=")" + name + R"(")") +
         R"(><Controller name=")" + controller_name + R"("><Properties/></Controller></ObjectController>)";
}

std::string world_teleport(double x, double y, double h) {
  return R"(<PrivateAction><TeleportAction><Position><WorldPosition x=")" + std::to_string(x) + R"(" y=")" +
         std::to_string(y) + R"(" z="0" h=")" + std::to_string(h) + R"("/></Position></TeleportAction></PrivateAction>)";
}

std::string speed(double v) {
  return R"(<PrivateAction><LongitudinalAction><SpeedAction><SpeedActionDynamics dynamicsShape="step" dynamicsDimension="time" value="0"/>
  <SpeedActionTarget><AbsoluteTargetSpeed value=")" + std::to_string(v) + R"("/></SpeedActionTarget></SpeedAction></LongitudinalAction></PrivateAction>)";
}

std::string activate(const std::string& ref) {
  return R"(<PrivateAction><ActivateControllerAction longitudinal="true" lateral="true")" +
         (ref.empty() ? std::string() : R"( objectControllerRef=")" + ref + R"(")") + "/></PrivateAction>";
}

// A 1.3 scenario with entity A (its `controllers` after the vehicle) and `init` for A; the
// road `logic` ("" : a RoadNetwork without LogicFile).
std::string scenario(const std::string& controllers, const std::string& init, const std::string& logic = "",
                     const std::string& story = "") {
  std::string vehicle = orch::test::vehicle("A");
  vehicle.insert(vehicle.rfind("</ScenarioObject>"), controllers);
  return R"(<?xml version="1.0"?><OpenSCENARIO>
<FileHeader revMajor="1" revMinor="3" date="2024-01-01T00:00:00" author="t" description="world"/>
<RoadNetwork>)" + logic + R"(</RoadNetwork>
<Entities>)" + vehicle + R"(</Entities>
<Storyboard><Init><Actions><Private entityRef="A">)" + init + R"(</Private></Actions></Init>)" + story + R"(
<StopTrigger/></Storyboard></OpenSCENARIO>)";
}

TEST(OpenScenarioObjectControllers, EveryNamedControllerIsReadAndTheFirstIsTheDefault) {
  TempDir dir;
  const Scenario s = load_scenario(
      dir.write("s.xosc", scenario(controller("Relaxed", "follow") + controller("Stiff", "followHard"),
                                   world_teleport(0, 0, 0)))
          .string());
  const Entity* a = s.entity("A");
  ASSERT_EQ(a->object_controllers.size(), 2u);
  EXPECT_EQ(a->object_controllers[1].first, "Stiff");
  EXPECT_EQ(a->object_controllers[1].second.name, "followHard");
  ASSERT_TRUE(a->controller.has_value());
  EXPECT_EQ(a->controller->name, "follow");
}

TEST(OpenScenarioObjectControllers, ActivateControllerActionActivatesTheReferencedOne) {
  TempDir dir;
  const std::string story = R"(<Story name="S"><Act name="Act"><ManeuverGroup name="G" maximumExecutionCount="1">
<Actors selectTriggeringEntities="false"><EntityRef entityRef="A"/></Actors><Maneuver name="M">
<Event name="E" priority="override"><Action name="Switch">)" + activate("Relaxed") + R"(</Action>
<StartTrigger><ConditionGroup><Condition name="C" delay="0" conditionEdge="none"><ByValueCondition>
<SimulationTimeCondition value="1" rule="greaterOrEqual"/></ByValueCondition></Condition></ConditionGroup></StartTrigger></Event>
</Maneuver></ManeuverGroup></Act></Story>)";
  const Scenario s = load_scenario(
      dir.write("s.xosc", scenario(controller("Relaxed", "follow") + controller("Stiff", "followHard"),
                                   world_teleport(0, 0, 0) + activate("Stiff"), "", story))
          .string());
  const opendrive::RoadNetwork no_roads;
  StoryboardRuntime runtime(s, no_roads);
  runtime.step(0.05);
  EXPECT_EQ(runtime.entities().at("A").controller, "followHard");
  EXPECT_TRUE(runtime.entities().at("A").controller_active);
  orch::test::run_until(runtime, 1.5);
  EXPECT_EQ(runtime.entities().at("A").controller, "follow");
}

TEST(OpenScenarioObjectControllers, AReferenceToNoControllerOfTheEntityIsAnErrorWithASuggestion) {
  TempDir dir;
  const auto path = dir.write("s.xosc", scenario(controller("Relaxed", "follow") + controller("Stiff", "followHard"),
                                                 world_teleport(0, 0, 0) + activate("Stif")));
  try {
    (void)load_scenario(path.string());
    FAIL() << "expected an error";
  } catch (const ScenarioError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("objectControllerRef \"Stif\""), std::string::npos) << what;
    EXPECT_NE(what.find("Stiff"), std::string::npos) << what;
    EXPECT_NE(what.find("/OpenSCENARIO/Storyboard/Init"), std::string::npos) << what;  // where the action is
  }
}

TEST(OpenScenarioObjectControllers, SeveralControllersMustEachHaveAName) {
  TempDir dir;
  const auto path =
      dir.write("s.xosc", scenario(controller("Relaxed", "follow") + controller("", "other"), world_teleport(0, 0, 0)));
  EXPECT_THROW((void)load_scenario(path.string()), ScenarioError);
}

TEST(OpenScenarioParameterTypes, ADeclaredValueItsTypeCannotHoldNamesTheParameterAndTheType) {
  TempDir dir;
  std::string text = scenario("", world_teleport(0, 0, 0));
  text.insert(text.find("<RoadNetwork>"),
              R"(<ParameterDeclarations><ParameterDeclaration name="FollowMode" parameterType="double" value="time"/></ParameterDeclarations>)");
  try {
    (void)load_scenario(dir.write("s.xosc", text).string());
    FAIL() << "expected an error";
  } catch (const ScenarioError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("parameter \"FollowMode\" is declared double"), std::string::npos) << what;
    EXPECT_NE(what.find("\"time\" is not a number"), std::string::npos) << what;
  }
}

// No LogicFile: the storyboard places A by its world position and a SpeedAction moves it
// straight on along its heading (there is no road to follow).
TEST(OpenScenarioWithoutRoad, AnEntityPlacedByAWorldPositionMovesAlongItsHeading) {
  TempDir dir;
  const Scenario s = load_scenario(dir.write("s.xosc", scenario("", world_teleport(1.8, -358, M_PI / 2) + speed(4))).string());
  EXPECT_TRUE(s.road_file.empty());
  const opendrive::RoadNetwork no_roads;
  StoryboardRuntime runtime(s, no_roads);
  orch::test::run_until(runtime, 2.0);
  const EntityState& a = runtime.entities().at("A");
  EXPECT_TRUE(a.placed);
  EXPECT_TRUE(a.road_id.empty());
  EXPECT_NEAR(a.pose.x, 1.8, 1e-4);  // h is written with 6 decimals
  EXPECT_NEAR(a.pose.y, -358 + 4 * runtime.time(), 1e-6);
  EXPECT_NEAR(a.pose.heading, M_PI / 2, 1e-5);
}

// Backing along a trajectory (esmini's trailer_connect.xosc): a negative speed moves the entity
// from the path's start to its end facing the other way; on no road it stops at the end.
TEST(OpenScenarioWithoutRoad, ANegativeSpeedBacksAlongATrajectoryAndTheEntityStopsAtItsEnd) {
  TempDir dir;
  const std::string trajectory = R"(<PrivateAction><RoutingAction><FollowTrajectoryAction>
<Trajectory name="Back" closed="false"><Shape><Polyline>
<Vertex><Position><WorldPosition x="0" y="0" h="0"/></Position></Vertex>
<Vertex><Position><WorldPosition x="10" y="0" h="0"/></Position></Vertex>
</Polyline></Shape></Trajectory><TimeReference><None/></TimeReference>
<TrajectoryFollowingMode followingMode="position"/></FollowTrajectoryAction></RoutingAction></PrivateAction>)";
  const Scenario s =
      load_scenario(dir.write("s.xosc", scenario("", world_teleport(0, 0, M_PI) + speed(-2) + trajectory)).string());
  const opendrive::RoadNetwork no_roads;
  StoryboardRuntime runtime(s, no_roads);
  orch::test::run_until(runtime, 2.0);
  const EntityState& a = runtime.entities().at("A");
  EXPECT_NEAR(a.pose.x, 2 * runtime.time(), 0.11);  // backing towards +x along the path
  EXPECT_NEAR(std::cos(a.pose.heading), -1.0, 1e-6);  // facing -x
  orch::test::run_until(runtime, 8.0);
  EXPECT_NEAR(runtime.entities().at("A").pose.x, 10.0, 1e-6);
  EXPECT_EQ(runtime.entities().at("A").speed, 0.0);
}

// On a road network that has roads, a position on none of its lanes (a camera beside the
// road) is placed there by its pose alone, on no road, as in a scenario without one.
TEST(OpenScenarioWithoutRoad, AWorldPositionOffTheLanesOfARealRoadStandsThere) {
  TempDir dir;
  dir.write("road.xodr", orch::test::kStraightTwoLaneRoad);
  const Scenario s = load_scenario(
      dir.write("s.xosc", scenario("", world_teleport(10, 500, 0), R"(<LogicFile filepath="road.xodr"/>)")).string());
  const opendrive::RoadNetwork roads = opendrive::read_xodr_file((dir / "road.xodr").string());
  StoryboardRuntime runtime(s, roads);
  runtime.step(0.05);
  const EntityState& a = runtime.entities().at("A");
  EXPECT_TRUE(a.placed);
  EXPECT_TRUE(a.road_id.empty());
  EXPECT_NEAR(a.pose.x, 10.0, 1e-9);
  EXPECT_NEAR(a.pose.y, 500.0, 1e-9);
}

}  // namespace
}  // namespace orch::openscenario

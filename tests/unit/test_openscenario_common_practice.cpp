// Elements of the standard that real files use often (CARLA ScenarioRunner's, ASAM's own
// examples, other players'): actors selected by their triggering entities, followingMode on
// TransitionDynamics, routingAlgorithm, and the actions that run with no effect on motion (custom
// commands, controller overrides, animations, lights, visibility, controllers' lighting and
// animation domains). The files in tests/data/openscenario/ run in the storyboard (no
// simulator); broken variants are written here.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "core/errors.hpp"
#include "opendrive/xodr_reader.hpp"
#include "openscenario/storyboard_runtime.hpp"
#include "openscenario/xosc_reader.hpp"
#include "support/cli_runner.hpp"
#include "unit/openscenario_snippets.hpp"

namespace orch::openscenario {
namespace {

const std::string kData = std::string(ORCH_SOURCE_DIR) + "/tests/data/openscenario/";

std::string warnings_of(const Scenario& s) {
  std::string all;
  for (const Diagnostic& d : s.warnings.items()) all += d.format() + "\n";
  return all;
}

// Steps the storyboard of `scenario` until it ends.
void run_to_end(StoryboardRuntime& runtime) {
  while (!runtime.finished() && runtime.time() < 60) runtime.step(0.05);
}

TEST(OpenScenarioCommonPractice, TriggeringEntitiesAreTheActorsAndVisualActionsChangeNoMotion) {
  const Scenario scenario = load_scenario(kData + "common_practice.xosc");
  const std::string warnings = warnings_of(scenario);
  // What runs as something less than the standard's full meaning is said at load, with the line.
  EXPECT_NE(warnings.find("common_practice.xosc:78: warning"), std::string::npos) << warnings;  // followingMode
  EXPECT_NE(warnings.find("followingMode=\"follow\""), std::string::npos) << warnings;
  EXPECT_NE(warnings.find("CustomCommandAction type=\"python\" runs with no effect"), std::string::npos) << warnings;
  EXPECT_NE(warnings.find("CustomCommandAction type=\"log\" runs with no effect"), std::string::npos) << warnings;
  EXPECT_NE(warnings.find("OverrideControllerValueAction runs with no effect on motion"), std::string::npos) << warnings;
  EXPECT_NE(warnings.find("AnimationAction runs with no effect"), std::string::npos) << warnings;
  EXPECT_NE(warnings.find("activateLighting=\"true\""), std::string::npos) << warnings;

  const auto roads = opendrive::read_xodr_file(scenario.road_file);
  StoryboardRuntime runtime(scenario, roads);
  run_to_end(runtime);
  ASSERT_TRUE(runtime.finished());
  // Ego is within 40 m of Lead (60 m, closing at 5 m/s) at t = 4 s, Other only at 6 s.
  const auto act = test::transition_times(runtime, "CloseOnLead", "startTransition");
  ASSERT_EQ(act.size(), 1u);
  EXPECT_NEAR(act.front(), 4.0, 0.051);
  // The group's only actor is Ego, the entity that triggered the Act: it slows to 10 m/s in
  // 2 s (followingMode follow runs as position: the linear shape exactly), Other does not.
  EXPECT_NEAR(runtime.entities().at("Ego").speed, 10.0, 1e-9);
  EXPECT_NEAR(runtime.entities().at("Other").speed, 15.0, 1e-9);
  // Every action of the event ran and ended, the no-effect ones at once.
  for (const char* action : {"SlowDownAction", "BrakeOverride", "BrakeLights", "MirrorFold", "HideFromSensors", "Notify"})
    EXPECT_EQ(test::transition_times(runtime, action, "endTransition").size(), 1u) << action;
  EXPECT_NEAR(test::transition_times(runtime, "SlowDownAction", "endTransition").front() -
                  test::transition_times(runtime, "SlowDownAction", "startTransition").front(),
              2.0, 0.051);
  EXPECT_FALSE(runtime.entities().at("Ego").visibility.sensors);
  EXPECT_TRUE(runtime.entities().at("Other").visibility.sensors);  // not an actor
  EXPECT_EQ(runtime.entities().at("Other").controller, "LightsOnly");
  EXPECT_FALSE(runtime.entities().at("Other").controller_active);  // lighting is no motion domain
}

// Without selectTriggeringEntities the same file's group has no actor at all; with both an
// EntityRef and the flag, the named actor and the triggering one act.
TEST(OpenScenarioCommonPractice, NamedActorsAndTriggeringEntitiesTogether) {
  std::string text = orch::test::slurp(kData + "common_practice.xosc");
  const std::string actors = R"(<Actors selectTriggeringEntities="true"/>)";
  text.replace(text.find(actors), actors.size(),
               R"(<Actors selectTriggeringEntities="true"><EntityRef entityRef="Lead"/><EntityRef entityRef="Ego"/></Actors>)");
  const std::string road = "../../../scenarios/openscenario/roads/";
  text.replace(text.find(road), road.size(), std::string(ORCH_SOURCE_DIR) + "/scenarios/openscenario/roads/");
  orch::test::TempDir dir;
  const Scenario scenario = load_scenario(dir.write("s.xosc", text).string());
  const auto roads = opendrive::read_xodr_file(scenario.road_file);
  StoryboardRuntime runtime(scenario, roads);
  run_to_end(runtime);
  EXPECT_NEAR(runtime.entities().at("Ego").speed, 10.0, 1e-9);   // named and triggering: once
  EXPECT_NEAR(runtime.entities().at("Lead").speed, 10.0, 1e-9);  // named
  EXPECT_NEAR(runtime.entities().at("Other").speed, 15.0, 1e-9);
  EXPECT_FALSE(runtime.entities().at("Lead").visibility.sensors);
  EXPECT_TRUE(runtime.entities().at("Other").visibility.sensors);
}

class CommonPracticeErrors : public ::testing::Test {
 protected:
  // The load error of common_practice.xosc with `from` replaced by `to` ("" when it loads).
  std::string error_with(const std::string& from, const std::string& to) {
    std::string text = orch::test::slurp(kData + "common_practice.xosc");
    const auto at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at == std::string::npos) return "";
    text.replace(at, from.size(), to);
    const std::string road = "../../../scenarios/openscenario/roads/";
    text.replace(text.find(road), road.size(), std::string(ORCH_SOURCE_DIR) + "/scenarios/openscenario/roads/");
    try {
      (void)load_scenario(dir_.write("s.xosc", text).string());
    } catch (const ScenarioError& e) {
      return e.what();
    }
    return "";
  }
  orch::test::TempDir dir_;
};

TEST_F(CommonPracticeErrors, SelectingTriggeringEntitiesNeedsAnActStartedByEntities) {
  const std::string no_entities = error_with(
      R"(<ByEntityCondition>
              <TriggeringEntities triggeringEntitiesRule="any"><EntityRef entityRef="Ego"/><EntityRef entityRef="Other"/></TriggeringEntities>
              <EntityCondition><RelativeDistanceCondition entityRef="Lead" relativeDistanceType="longitudinal" coordinateSystem="road" freespace="false" value="40" rule="lessThan"/></EntityCondition>
            </ByEntityCondition>)",
      R"(<ByValueCondition><SimulationTimeCondition value="4" rule="greaterOrEqual"/></ByValueCondition>)");
  EXPECT_NE(no_entities.find("@selectTriggeringEntities: the actors are the entities that triggered the Act's "
                             "StartTrigger, which has no ByEntityCondition"),
            std::string::npos)
      << no_entities;
}

TEST_F(CommonPracticeErrors, FollowingModeAndOverridesAreCheckedAsTheSchemaHasThem) {
  EXPECT_NE(error_with(R"(followingMode="follow")", R"(followingMode="folow")").find("(did you mean \"follow\"?)"),
            std::string::npos);
  // followingMode="position" is what runs: no warning.
  EXPECT_EQ(error_with(R"(followingMode="follow")", R"(followingMode="position")"), "");
  // 1.0/1.1 overrides: a value on each (all six), read; a misspelt attribute is still an error.
  EXPECT_EQ(error_with(R"(<OverrideBrakeAction active="true"><BrakePercent value="0.3"/></OverrideBrakeAction>)",
                       R"(<OverrideThrottleAction active="false" value="0"/><OverrideBrakeAction active="true" value="0.3"/>
                          <OverrideClutchAction active="false" value="0"/><OverrideParkingBrakeAction active="false" value="0"/>
                          <OverrideSteeringWheelAction active="false" value="0"/><OverrideGearAction active="false" number="0"/>)"),
            "");
  EXPECT_NE(error_with(R"(<BrakePercent value="0.3"/>)", R"(<BrakePercent valeu="0.3"/>)").find("did you mean \"value\""),
            std::string::npos);
  EXPECT_NE(error_with(R"(<OverrideBrakeAction active="true"><BrakePercent value="0.3"/></OverrideBrakeAction>)", "")
                .find("an OverrideControllerValueAction needs at least one Override...Action"),
            std::string::npos);
  EXPECT_NE(error_with(R"(<CustomCommandAction type="log">)", "<CustomCommandAction>").find("@type: missing attribute"),
            std::string::npos);
  EXPECT_NE(error_with(R"(vehicleComponentType="sideMirrors")", "").find("missing attribute"), std::string::npos);
}

// OpenSCENARIO 1.0 wrote an AssignControllerAction and an OverrideControllerValueAction
// together in one ControllerAction (CARLA ScenarioRunner's files: six inactive overrides).
TEST_F(CommonPracticeErrors, OneZeroControllerActionWithAssignmentAndOverridesTogether) {
  const std::string assign = R"(<ControllerAction><AssignControllerAction activateLighting="true">
            <Controller name="LightsOnly"><Properties><Property name="module" value="lights"/></Properties></Controller>
          </AssignControllerAction>)";
  EXPECT_EQ(error_with(assign, R"(<ControllerAction><AssignControllerAction>
            <Controller name="LightsOnly"><Properties><Property name="module" value="lights"/></Properties></Controller>
          </AssignControllerAction><OverrideControllerValueAction>
            <OverrideThrottleAction value="0" active="false"/><OverrideBrakeAction value="0" active="false"/>
            <OverrideClutchAction value="0" active="false"/><OverrideParkingBrakeAction value="0" active="false"/>
            <OverrideSteeringWheelAction value="0" active="false"/><OverrideGearAction number="0" active="false"/>
          </OverrideControllerValueAction>)"),
            "");
  // Two assignments stay an error.
  EXPECT_NE(error_with(assign, assign + R"(<AssignControllerAction><Controller name="Second"/></AssignControllerAction>)")
                .find("ControllerAction holds exactly one of"),
            std::string::npos);
}

TEST_F(CommonPracticeErrors, RoutingAlgorithmIsReadOnTheDistanceConditions) {
  EXPECT_EQ(error_with(R"(coordinateSystem="road")", R"(coordinateSystem="road" routingAlgorithm="shortest")"), "");
  EXPECT_NE(error_with(R"(coordinateSystem="road")", R"(coordinateSystem="road" routingAlgorithm="shortst")")
                .find("(did you mean \"shortest\"?)"),
            std::string::npos);
}

}  // namespace
}  // namespace orch::openscenario

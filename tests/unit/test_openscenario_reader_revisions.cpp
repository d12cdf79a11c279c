// What OpenSCENARIO 1.1 to 1.3 files carry, read from small real snippets: schema attributes
// on the root, descriptive content, every revision's parameter types, ParameterDeclarations
// in Stories and Maneuvers (scoped), VariableDeclarations with their actions and condition,
// trailers, catalog folders that do not exist, pitch and roll, "$name" in a parameterRef.
#include <gtest/gtest.h>

#include <filesystem>

#include "core/errors.hpp"
#include "openscenario/xosc_reader.hpp"
#include "support/cli_runner.hpp"
#include "unit/openscenario_snippets.hpp"

namespace orch::openscenario {
namespace {

using orch::test::TempDir;

const char* kVehicles = R"(<?xml version="1.0"?>
<OpenSCENARIO xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance" xsi:noNamespaceSchemaLocation="OpenSCENARIO.xsd">
  <FileHeader revMajor="1" revMinor="3" date="2024-01-01T00:00:00" author="t" description="vehicles"/>
  <Catalog name="VehicleCatalog">
    <Vehicle name="tractor" vehicleCategory="truck">
      <ParameterDeclarations><ParameterDeclaration name="TrailerRef" parameterType="string" value=""/></ParameterDeclarations>
      <BoundingBox><Center x="2.2" y="0" z="1.6"/><Dimensions width="2.6" length="5.7" height="3.3"/></BoundingBox>
      <Performance maxSpeed="40" maxDeceleration="10" maxAcceleration="4"/>
      <Axles><FrontAxle maxSteering="0.5" wheelDiameter="0.8" trackWidth="1.68" positionX="2.98" positionZ="0.4"/>
        <RearAxle maxSteering="0" wheelDiameter="0.8" trackWidth="1.68" positionX="0" positionZ="0.4"/></Axles>
      <TrailerHitch dx="-1.0"/>
      <Trailer><TrailerRef entityRef="$TrailerRef"/></Trailer>
      <Properties><Property name="model" value="tractor"/></Properties>
    </Vehicle>
    <Vehicle name="trailer" vehicleCategory="trailer">
      <BoundingBox><Center x="3" y="0" z="1.5"/><Dimensions width="2.6" length="10" height="3.5"/></BoundingBox>
      <Performance maxSpeed="40" maxDeceleration="10" maxAcceleration="4"/>
      <Axles><RearAxle maxSteering="0" wheelDiameter="0.8" trackWidth="1.68" positionX="0" positionZ="0.4"/></Axles>
      <TrailerCoupler dx="7.0"/>
    </Vehicle>
  </Catalog>
</OpenSCENARIO>)";

// A 1.3 scenario: `entities` inside Entities, `init` inside Init/Actions, `story` as the Story's
// content after its name, and `extra` after the ParameterDeclarations.
std::string scenario(const std::string& entities, const std::string& init, const std::string& story,
                     const std::string& extra = "") {
  return R"(<?xml version="1.0"?>
<OpenSCENARIO xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance" xsi:noNamespaceSchemaLocation="OpenSCENARIO.xsd">
  <FileHeader revMajor="1" revMinor="3" date="2024-01-01T00:00:00" author="t" description="1.3">
    <License name="MPL-2.0" resource="https://mozilla.org/MPL/2.0/" spdxId="MPL-2.0"/>
  </FileHeader>
  <ParameterDeclarations>
    <ParameterDeclaration name="Speed" parameterType="double" value="10"/>
    <ParameterDeclaration name="Count" parameterType="int" value="3"/>
    <ParameterDeclaration name="Small" parameterType="unsignedShort" value="7"/>
    <ParameterDeclaration name="When" parameterType="dateTime" value="2024-01-01T10:00:00"/>
  </ParameterDeclarations>)" +
         extra + R"(
  <CatalogLocations><VehicleCatalog><Directory path="./catalogs"/></VehicleCatalog></CatalogLocations>
  <RoadNetwork><LogicFile filepath="./road.xodr"/></RoadNetwork>
  <Entities>)" +
         entities + R"(</Entities>
  <Storyboard>
    <Init><Actions>)" +
         init + R"(</Actions></Init>
    <Story name="S">)" +
         story + R"(</Story>
    <StopTrigger/>
  </Storyboard>
</OpenSCENARIO>)";
}

std::string time_trigger(const std::string& name, double at) {
  return R"(<StartTrigger><ConditionGroup><Condition name=")" + name +
         R"(" delay="0" conditionEdge="none"><ByValueCondition><SimulationTimeCondition value=")" +
         std::to_string(at) + R"(" rule="greaterOrEqual"/></ByValueCondition></Condition></ConditionGroup></StartTrigger>)";
}

// An Act with one maneuver group (actor A) holding `maneuver_content` in maneuver M.
std::string act(const std::string& maneuver_content, const std::string& maneuver_extra = "") {
  return R"(<Act name="Act"><ManeuverGroup name="G" maximumExecutionCount="1">
    <Actors selectTriggeringEntities="false"><EntityRef entityRef="A"/></Actors>
    <Maneuver name="M">)" +
         maneuver_extra + maneuver_content + R"(</Maneuver></ManeuverGroup>)" + time_trigger("ActStart", 0) + "</Act>";
}

std::string speed_event(const std::string& name, const std::string& value) {
  return R"(<Event name=")" + name + R"(" priority="overwrite"><Action name=")" + name +
         R"(Action"><PrivateAction><LongitudinalAction><SpeedAction>
    <SpeedActionDynamics dynamicsShape="step" dynamicsDimension="time" value="0"/>
    <SpeedActionTarget><AbsoluteTargetSpeed value=")" +
         value + R"("/></SpeedActionTarget></SpeedAction></LongitudinalAction></PrivateAction></Action>)" +
         time_trigger(name + "Start", 1) + "</Event>";
}

class XoscRevisions : public ::testing::Test {
 protected:
  XoscRevisions() {
    std::filesystem::create_directories(dir_ / "catalogs");
    dir_.write("catalogs/vehicles.xosc", kVehicles);
    dir_.write("road.xodr", test::kStraightTwoLaneRoad);
  }
  Scenario load(const std::string& text) { return load_scenario(dir_.write("s.xosc", text).string()); }
  std::string error(const std::string& text) {
    try {
      (void)load(text);
    } catch (const ScenarioError& e) {
      return e.what();
    }
    return "no error";
  }
  Scenario simple(const std::string& story, const std::string& extra = "") {
    return load(scenario(test::vehicle("A"), test::place("A", 10, -1, 10), story, extra));
  }
  TempDir dir_;
};

TEST_F(XoscRevisions, ReadsARevisionOneThreeFileWithSchemaAttributesAndLicense) {
  const Scenario s = simple(act(speed_event("Go", "$Speed")));
  EXPECT_EQ(s.rev_minor, 3);
  EXPECT_EQ(s.description, "1.3");
  ASSERT_EQ(s.parameters.size(), 4u);
  EXPECT_EQ(s.parameters[1].type, "integer");  // 1.2's "int" is the same type as "integer"
  EXPECT_EQ(s.parameters[2].type, "unsignedShort");
  EXPECT_EQ(s.parameters[3].type, "dateTime");
  std::string later = scenario(test::vehicle("A"), "", act(speed_event("Go", "1")));
  later.replace(later.find("revMinor=\"3\""), 12, "revMinor=\"4\"");
  EXPECT_NE(error(later).find("OpenSCENARIO 1.4 is not supported: this reads 1.0 to 1.3"), std::string::npos)
      << error(later);
}

TEST_F(XoscRevisions, ParameterTypesOfEveryRevisionAreCheckedByTheirRange) {
  const std::string base = scenario(test::vehicle("A"), test::place("A", 10, -1, 10), act(speed_event("Go", "1")));
  std::string bad = base;
  bad.replace(bad.find("value=\"7\""), 9, "value=\"70000\"");
  EXPECT_NE(error(bad).find("70000 is outside [0, 65535]"), std::string::npos) << error(bad);
  bad = base;
  bad.replace(bad.find("parameterType=\"int\""), 19, "parameterType=\"itn\"");
  EXPECT_NE(error(bad).find("did you mean \"int\""), std::string::npos) << error(bad);
}

TEST_F(XoscRevisions, StoryAndManeuverParametersAreScopedAndKeyed) {
  const std::string story = R"(<ParameterDeclarations>
      <ParameterDeclaration name="Speed" parameterType="double" value="20"/>
      <ParameterDeclaration name="Twice" parameterType="double" value="${$Speed * 2}"/>
    </ParameterDeclarations>)" +
                            act(speed_event("Go", "$Twice") + speed_event("Again", "$Local"),
                                R"(<ParameterDeclarations><ParameterDeclaration name="Local" parameterType="double" value="${$Speed + 1}"/></ParameterDeclarations>)");
  const Scenario s = simple(story);
  const auto& events = s.storyboard.stories.at(0).acts.at(0).groups.at(0).maneuvers.at(0).events;
  // The Story's Speed hides the scenario's; its Twice sees it; the Maneuver sees both.
  EXPECT_DOUBLE_EQ(std::get<AbsoluteTargetSpeed>(std::get<SpeedAction>(events.at(0).actions.at(0).action).target).value, 40);
  EXPECT_DOUBLE_EQ(std::get<AbsoluteTargetSpeed>(std::get<SpeedAction>(events.at(1).actions.at(0).action).target).value, 21);
  std::vector<std::string> keys;
  for (const Parameter& p : s.local_parameters) keys.push_back(p.name);
  EXPECT_EQ(keys, (std::vector<std::string>{"S/Speed", "S/Twice", "M/Local"}));
  EXPECT_EQ(s.parameters.at(0).value, "10");  // the scenario's own is unchanged

  // Outside the Story its parameters do not exist.
  std::string text = scenario(test::vehicle("A"), test::place("A", 10, -1, 10), story);
  text.replace(text.find("<StopTrigger/>"), 14,
               R"(<StopTrigger><ConditionGroup><Condition name="End" delay="0" conditionEdge="none"><ByValueCondition><SimulationTimeCondition value="$Twice" rule="greaterOrEqual"/></ByValueCondition></Condition></ConditionGroup></StopTrigger>)");
  EXPECT_NE(error(text).find("unknown parameter \"Twice\""), std::string::npos) << error(text);
}

TEST_F(XoscRevisions, ParameterActionsAndConditionsOnAStoryParameterUseItsKey) {
  const std::string set = R"(<Event name="Set" priority="overwrite"><Action name="SetIt"><GlobalAction>
      <ParameterAction parameterRef="Mode"><SetAction value="fast"/></ParameterAction></GlobalAction></Action>)" +
                          time_trigger("SetStart", 1) + "</Event>";
  const std::string story = R"(<ParameterDeclarations><ParameterDeclaration name="Mode" parameterType="string" value="slow"/></ParameterDeclarations>)" +
                            act(set + R"(<Event name="Watch" priority="parallel"><Action name="WatchAction"><PrivateAction><LongitudinalAction><SpeedAction>
    <SpeedActionDynamics dynamicsShape="step" dynamicsDimension="time" value="0"/>
    <SpeedActionTarget><AbsoluteTargetSpeed value="20"/></SpeedActionTarget></SpeedAction></LongitudinalAction></PrivateAction></Action>
    <StartTrigger><ConditionGroup><Condition name="Fast" delay="0" conditionEdge="none"><ByValueCondition>
      <ParameterCondition parameterRef="Mode" rule="equalTo" value="fast"/></ByValueCondition></Condition></ConditionGroup></StartTrigger></Event>)");
  const Scenario s = simple(story);
  const auto& events = s.storyboard.stories.at(0).acts.at(0).groups.at(0).maneuvers.at(0).events;
  EXPECT_EQ(std::get<ParameterSetAction>(events.at(0).actions.at(0).action).parameter, "S/Mode");
  EXPECT_EQ(std::get<ParameterCondition>(events.at(1).start_trigger->groups.at(0).at(0).kind).parameter, "S/Mode");
}

TEST_F(XoscRevisions, VariablesAreDeclaredSetModifiedAndCompared) {
  const std::string variables = R"(
  <VariableDeclarations>
    <VariableDeclaration name="Counter" variableType="int" value="0"/>
    <VariableDeclaration name="Phase" variableType="string" value="start"/>
  </VariableDeclarations>)";
  const std::string actions = R"(<Event name="Count" priority="overwrite">
      <Action name="Add"><GlobalAction><VariableAction variableRef="Counter"><ModifyAction><Rule><AddValue value="2"/></Rule></ModifyAction></VariableAction></GlobalAction></Action>
      <Action name="Rename"><GlobalAction><VariableAction variableRef="Phase"><SetAction value="end"/></VariableAction></GlobalAction></Action>)" +
                              time_trigger("CountStart", 1) + R"(</Event>
    <Event name="Check" priority="parallel"><Action name="CheckAction"><PrivateAction><LongitudinalAction><SpeedAction>
      <SpeedActionDynamics dynamicsShape="step" dynamicsDimension="time" value="0"/>
      <SpeedActionTarget><AbsoluteTargetSpeed value="0"/></SpeedActionTarget></SpeedAction></LongitudinalAction></PrivateAction></Action>
      <StartTrigger><ConditionGroup><Condition name="Two" delay="0" conditionEdge="none"><ByValueCondition>
        <VariableCondition variableRef="Counter" rule="greaterOrEqual" value="2"/></ByValueCondition></Condition></ConditionGroup></StartTrigger></Event>)";
  const Scenario s = simple(act(actions), variables);
  ASSERT_EQ(s.variables.size(), 2u);
  EXPECT_EQ(s.variables[0].type, "integer");
  const auto& events = s.storyboard.stories.at(0).acts.at(0).groups.at(0).maneuvers.at(0).events;
  const auto& add = std::get<VariableModifyAction>(events.at(0).actions.at(0).action);
  EXPECT_EQ(add.variable, "Counter");
  EXPECT_FALSE(add.multiply);
  EXPECT_DOUBLE_EQ(add.value, 2);
  EXPECT_EQ(std::get<VariableSetAction>(events.at(0).actions.at(1).action).value, "end");
  EXPECT_EQ(std::get<VariableCondition>(events.at(1).start_trigger->groups.at(0).at(0).kind).variable, "Counter");

  std::string unknown = scenario(test::vehicle("A"), test::place("A", 10, -1, 10), act(actions), variables);
  unknown.replace(unknown.find("variableRef=\"Counter\""), 21, "variableRef=\"Countr\"");
  EXPECT_NE(error(unknown).find("no variable \"Countr\" is declared (VariableDeclarations) (did you mean \"Counter\"?)"),
            std::string::npos)
      << error(unknown);
  std::string wrong_type = scenario(test::vehicle("A"), test::place("A", 10, -1, 10), act(actions), variables);
  wrong_type.replace(wrong_type.find("<AddValue value=\"2\"/>"), 21, "<AddValue value=\"x\"/>");
  EXPECT_NE(error(wrong_type).find("expected a number"), std::string::npos) << error(wrong_type);
}

TEST_F(XoscRevisions, TrailersByReferenceInlineAndByAction) {
  const std::string entities = R"(
    <ScenarioObject name="Trailer"><CatalogReference catalogName="VehicleCatalog" entryName="trailer"/></ScenarioObject>
    <ScenarioObject name="A"><CatalogReference catalogName="VehicleCatalog" entryName="tractor">
      <ParameterAssignments><ParameterAssignment parameterRef="$TrailerRef" value="Trailer"/></ParameterAssignments>
    </CatalogReference></ScenarioObject>
    <ScenarioObject name="B"><Vehicle name="car" vehicleCategory="car">
      <BoundingBox><Center x="1.5" y="0" z="0.9"/><Dimensions width="2" length="5" height="1.8"/></BoundingBox>
      <Performance maxSpeed="70" maxDeceleration="10" maxAcceleration="10"/>
      <Axles><FrontAxle maxSteering="0.5" wheelDiameter="0.8" trackWidth="1.68" positionX="3" positionZ="0.4"/>
        <RearAxle maxSteering="0" wheelDiameter="0.8" trackWidth="1.68" positionX="0" positionZ="0.4"/></Axles>
      <TrailerHitch dx="-1.2"/>
      <Trailer><Trailer name="small"><CatalogReference catalogName="VehicleCatalog" entryName="trailer"/></Trailer></Trailer>
    </Vehicle></ScenarioObject>)";
  const std::string actions = R"(<Event name="Off" priority="overwrite"><Action name="Disconnect"><PrivateAction><TrailerAction><DisconnectTrailerAction/></TrailerAction></PrivateAction></Action>)" +
                              time_trigger("OffStart", 1) + R"(</Event>
    <Event name="On" priority="parallel"><Action name="Connect"><PrivateAction><TrailerAction><ConnectTrailerAction trailerRef="Trailer"/></TrailerAction></PrivateAction></Action>)" +
                              time_trigger("OnStart", 2) + "</Event>";
  const Scenario s = load(scenario(entities, test::place("A", 30, -1, 10), act(actions)));
  ASSERT_EQ(s.entities.size(), 4u);
  const Entity& tractor = *s.entity("A");
  EXPECT_EQ(tractor.trailer, "Trailer");
  EXPECT_DOUBLE_EQ(*tractor.trailer_hitch_dx, -1.0);
  EXPECT_EQ(tractor.properties.at("model"), "tractor");
  EXPECT_TRUE(tractor.front_axle.has_value());
  const Entity& trailer = *s.entity("Trailer");
  EXPECT_TRUE(trailer.trailer.empty());  // the catalog's default "" is no trailer
  EXPECT_DOUBLE_EQ(*trailer.trailer_coupler_dx, 7.0);
  EXPECT_FALSE(trailer.front_axle.has_value());  // a trailer has no front axle
  ASSERT_NE(s.entity("B+"), nullptr);            // an inline trailer is an entity of its own, as in esmini
  EXPECT_EQ(s.entity("B")->trailer, "B+");
  const auto& events = s.storyboard.stories.at(0).acts.at(0).groups.at(0).maneuvers.at(0).events;
  EXPECT_TRUE(std::holds_alternative<DisconnectTrailerAction>(events.at(0).actions.at(0).action));
  EXPECT_EQ(std::get<ConnectTrailerAction>(events.at(1).actions.at(0).action).entity, "Trailer");

  std::string missing = scenario(entities, "", act(actions));
  missing.replace(missing.find("value=\"Trailer\""), 15, "value=\"Trailr\"");
  EXPECT_NE(error(missing).find("the trailer of \"A\" is no entity: \"Trailr\" (did you mean \"Trailer\"?)"),
            std::string::npos)
      << error(missing);
  std::string bad_action = scenario(entities, "", act(actions));
  bad_action.replace(bad_action.find("trailerRef=\"Trailer\""), 20, "trailerRef=\"Nobody\"");
  EXPECT_NE(error(bad_action).find("no entity named \"Nobody\""), std::string::npos) << error(bad_action);
}

TEST_F(XoscRevisions, AMissingCatalogDirectoryIsAWarningAndAReferenceIntoItTheError) {
  std::string text = scenario(test::vehicle("A"), test::place("A", 10, -1, 10), act(speed_event("Go", "1")));
  text.replace(text.find("<CatalogLocations>"), 18,
               R"(<CatalogLocations><ControllerCatalog><Directory path="./no_such_folder"/></ControllerCatalog>)");
  const Scenario s = load(text);
  ASSERT_EQ(s.warnings.warning_count(), 1);
  EXPECT_NE(s.warnings.items()[0].message.find("no_such_folder (ControllerCatalog)"), std::string::npos)
      << s.warnings.format();
  std::string uses = text;
  uses.replace(uses.find("</Entities>"), 0,
               R"(<ScenarioObject name="X"><CatalogReference catalogName="ControllerCatalog" entryName="c"/></ScenarioObject>)");
  // The reference names the folder that does not exist.
  const std::string message = error(uses);
  EXPECT_NE(message.find("no catalog named \"ControllerCatalog\""), std::string::npos) << message;
  EXPECT_NE(message.find("the ControllerCatalog directory"), std::string::npos) << message;
}

TEST_F(XoscRevisions, PitchAndRollAreReadNotRefused) {
  std::string init = test::place("A", 10, -1, 10);
  init.replace(init.find("offset=\"0\"/>"), 12, R"(offset="0"><Orientation type="relative" h="0" p="0.05" r="-0.02"/></LanePosition>)");
  EXPECT_EQ(error(scenario(test::vehicle("A"), init, act(speed_event("Go", "1")))), "no error");
  init.replace(init.find("p=\"0.05\""), 8, "p=\"up\"");
  EXPECT_NE(error(scenario(test::vehicle("A"), init, act(speed_event("Go", "1")))).find("expected a number"),
            std::string::npos);
}

}  // namespace
}  // namespace orch::openscenario

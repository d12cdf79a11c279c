// The .xosc reader: a small scenario with a catalog and a road written to a temporary
// folder, read into the model; then one broken variant per kind of error.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include "core/errors.hpp"
#include "openscenario/xosc_reader.hpp"
#include "support/cli_runner.hpp"

namespace orch::openscenario {
namespace {

using orch::test::TempDir;

const char* kCatalog = R"(<?xml version="1.0"?>
<OpenSCENARIO>
  <FileHeader revMajor="1" revMinor="1" date="2024-01-01T00:00:00" author="t" description="cat"/>
  <Catalog name="vehicles">
    <Vehicle name="car" vehicleCategory="car">
      <ParameterDeclarations>
        <ParameterDeclaration name="Length" parameterType="double" value="5.0"/>
      </ParameterDeclarations>
      <BoundingBox><Center x="1.4" y="0" z="0.9"/><Dimensions width="2.0" length="$Length" height="1.8"/></BoundingBox>
      <Performance maxSpeed="70" maxDeceleration="10" maxAcceleration="10"/>
      <Axles>
        <FrontAxle maxSteering="0.5" wheelDiameter="0.8" trackWidth="1.68" positionX="2.98" positionZ="0.4"/>
        <RearAxle maxSteering="0" wheelDiameter="0.8" trackWidth="1.68" positionX="0" positionZ="0.4"/>
      </Axles>
      <Properties><Property name="type" value="ego_vehicle"/></Properties>
    </Vehicle>
  </Catalog>
</OpenSCENARIO>)";

const char* kRoad = R"(<OpenDRIVE><header revMajor="1" revMinor="6"/>
<road id="0" length="100" junction="-1"><planView><geometry s="0" x="0" y="0" hdg="0" length="100"><line/></geometry></planView>
<lanes><laneSection s="0"><right><lane id="-1" type="driving"><width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane></right></laneSection></lanes></road>
</OpenDRIVE>)";

const char* kScenario = R"(<?xml version="1.0" encoding="utf-8"?>
<OpenSCENARIO>
  <FileHeader revMajor="1" revMinor="1" date="2024-01-01T00:00:00" author="t" description="cut in"/>
  <ParameterDeclarations>
    <ParameterDeclaration name="Speed_kph" parameterType="double" value="60.0">
      <ConstraintGroup>
        <ValueConstraint rule="greaterThan" value="0.0"/>
        <ValueConstraint rule="lessOrEqual" value="60.0"/>
      </ConstraintGroup>
    </ParameterDeclaration>
    <ParameterDeclaration name="Lane" parameterType="integer" value="-1"/>
    <ParameterDeclaration name="Model" parameterType="string" value="car"/>
  </ParameterDeclarations>
  <CatalogLocations><VehicleCatalog><Directory path="./catalogs"/></VehicleCatalog></CatalogLocations>
  <RoadNetwork><LogicFile filepath="./road.xodr"/></RoadNetwork>
  <Entities>
    <ScenarioObject name="Ego">
      <CatalogReference catalogName="vehicles" entryName="$Model">
        <ParameterAssignments><ParameterAssignment parameterRef="Length" value="4.5"/></ParameterAssignments>
      </CatalogReference>
      <ObjectController><Controller name="ALKSController"><Properties/></Controller></ObjectController>
    </ScenarioObject>
    <ScenarioObject name="Other">
      <CatalogReference catalogName="vehicles" entryName="car"/>
    </ScenarioObject>
  </Entities>
  <Storyboard>
    <Init><Actions>
      <Private entityRef="Ego">
        <PrivateAction><TeleportAction><Position><LanePosition roadId="0" laneId="$Lane" offset="0.0" s="5.0"/></Position></TeleportAction></PrivateAction>
        <PrivateAction><LongitudinalAction><SpeedAction>
          <SpeedActionDynamics dynamicsShape="step" dynamicsDimension="time" value="0"/>
          <SpeedActionTarget><AbsoluteTargetSpeed value="${$Speed_kph / 3.6}"/></SpeedActionTarget>
        </SpeedAction></LongitudinalAction></PrivateAction>
      </Private>
      <Private entityRef="Other">
        <PrivateAction><TeleportAction><Position><RelativeLanePosition entityRef="Ego" dLane="0" ds="${20 + 10}" offset="0"/></Position></TeleportAction></PrivateAction>
      </Private>
    </Actions></Init>
    <Story name="S">
      <Act name="A">
        <ManeuverGroup maximumExecutionCount="1" name="G">
          <Actors selectTriggeringEntities="false"><EntityRef entityRef="Other"/></Actors>
          <Maneuver name="M">
            <Event name="E" priority="overwrite">
              <Action name="Brake">
                <PrivateAction><LongitudinalAction><SpeedAction>
                  <SpeedActionDynamics dynamicsShape="linear" dynamicsDimension="rate" value="2"/>
                  <SpeedActionTarget><RelativeTargetSpeed entityRef="Ego" value="-5" speedTargetValueType="delta" continuous="false"/></SpeedActionTarget>
                </SpeedAction></LongitudinalAction></PrivateAction>
              </Action>
              <StartTrigger><ConditionGroup>
                <Condition name="Near" delay="0" conditionEdge="rising"><ByEntityCondition>
                  <TriggeringEntities triggeringEntitiesRule="any"><EntityRef entityRef="Ego"/></TriggeringEntities>
                  <EntityCondition><RelativeDistanceCondition entityRef="Other" relativeDistanceType="longitudinal" value="20" freespace="true" rule="lessThan" coordinateSystem="entity"/></EntityCondition>
                </ByEntityCondition></Condition>
              </ConditionGroup></StartTrigger>
            </Event>
          </Maneuver>
        </ManeuverGroup>
        <StartTrigger><ConditionGroup><Condition name="T0" delay="0" conditionEdge="none"><ByValueCondition><SimulationTimeCondition value="0" rule="greaterThan"/></ByValueCondition></Condition></ConditionGroup></StartTrigger>
      </Act>
    </Story>
    <StopTrigger><ConditionGroup><Condition name="Done" delay="1.5" conditionEdge="rising"><ByValueCondition>
      <StoryboardElementStateCondition storyboardElementType="action" storyboardElementRef="Brake" state="completeState"/>
    </ByValueCondition></Condition></ConditionGroup></StopTrigger>
  </Storyboard>
</OpenSCENARIO>)";

class XoscReader : public ::testing::Test {
 protected:
  XoscReader() {
    std::filesystem::create_directories(dir_ / "catalogs");
    dir_.write("catalogs/vehicles.xosc", kCatalog);
    dir_.write("road.xodr", kRoad);
  }
  // Writes the scenario with `from` replaced by `to` and loads it.
  Scenario load(const std::string& from = "", const std::string& to = "", const LoadOptions& options = {}) {
    std::string text = kScenario;
    if (!from.empty()) {
      const auto at = text.find(from);
      EXPECT_NE(at, std::string::npos) << from;
      text.replace(at, from.size(), to);
    }
    return load_scenario(dir_.write("s.xosc", text).string(), options);
  }
  std::string error(const std::string& from, const std::string& to, const LoadOptions& options = {}) {
    try {
      (void)load(from, to, options);
    } catch (const ScenarioError& e) {
      return e.what();
    }
    return "no error";
  }
  TempDir dir_;
};

TEST_F(XoscReader, ReadsTheModelWithParametersAndCatalogs) {
  const Scenario s = load();
  EXPECT_EQ(s.rev_minor, 1);
  ASSERT_EQ(s.entities.size(), 2u);
  const Entity& ego = s.entities[0];
  EXPECT_EQ(ego.object_name, "car");
  EXPECT_DOUBLE_EQ(ego.box.length, 4.5);  // the assignment replaces the entry's default
  EXPECT_DOUBLE_EQ(s.entities[1].box.length, 5.0);
  EXPECT_DOUBLE_EQ(ego.box.center_x, 1.4);
  ASSERT_TRUE(ego.controller.has_value());
  EXPECT_EQ(ego.controller->name, "ALKSController");
  EXPECT_EQ(ego.properties.at("type"), "ego_vehicle");
  EXPECT_EQ(std::filesystem::path(s.road_file).filename(), "road.xodr");

  ASSERT_EQ(s.storyboard.init.size(), 3u);
  const auto& teleport = std::get<TeleportAction>(s.storyboard.init[0].action);
  EXPECT_EQ(std::get<LanePosition>(teleport.position).lane_id, -1);
  const auto& speed = std::get<SpeedAction>(s.storyboard.init[1].action);
  EXPECT_NEAR(std::get<AbsoluteTargetSpeed>(speed.target).value, 60.0 / 3.6, 1e-12);
  const auto& relative = std::get<TeleportAction>(s.storyboard.init[2].action);
  EXPECT_DOUBLE_EQ(std::get<RelativeLanePosition>(relative.position).ds, 30.0);

  const Act& act = s.storyboard.stories.at(0).acts.at(0);
  const Event& event = act.groups.at(0).maneuvers.at(0).events.at(0);
  EXPECT_EQ(event.actions.at(0).actors, std::vector<std::string>{"Other"});
  const auto& brake = std::get<SpeedAction>(event.actions.at(0).action);
  EXPECT_EQ(brake.dynamics.dimension, DynamicsDimension::Rate);
  EXPECT_EQ(std::get<RelativeTargetSpeed>(brake.target).entity, "Ego");
  const Condition& near = event.start_trigger->groups.at(0).at(0);
  EXPECT_EQ(near.edge, Edge::Rising);
  const auto& by = std::get<ByEntityCondition>(near.kind);
  EXPECT_TRUE(std::get<RelativeDistanceCondition>(by.condition).freespace);
  const Condition& done = s.storyboard.stop_trigger->groups.at(0).at(0);
  EXPECT_DOUBLE_EQ(done.delay, 1.5);
  EXPECT_EQ(std::get<StoryboardElementStateCondition>(done.kind).state, "completeState");
}

TEST_F(XoscReader, ByteOrderMarkIsFine) {
  std::string text = "\xEF\xBB\xBF" + std::string(kScenario);
  EXPECT_EQ(load_scenario(dir_.write("bom.xosc", text).string()).entities.size(), 2u);
}

TEST_F(XoscReader, ParamOverridesAndConstraints) {
  LoadOptions options;
  options.parameter_overrides["Speed_kph"] = "36";
  const Scenario s = load("", "", options);
  const auto& speed = std::get<SpeedAction>(s.storyboard.init[1].action);
  EXPECT_NEAR(std::get<AbsoluteTargetSpeed>(speed.target).value, 10.0, 1e-12);

  options.parameter_overrides["Speed_kph"] = "80";
  EXPECT_NE(error("", "", options).find("parameter \"Speed_kph\" = 80 violates its constraints (lessOrEqual 60.0"),
            std::string::npos);
  options.parameter_overrides.clear();
  options.parameter_overrides["Sped_kph"] = "30";
  EXPECT_NE(error("", "", options).find("no parameter \"Sped_kph\" (did you mean \"Speed_kph\"?)"), std::string::npos);
  options.parameter_overrides.clear();
  options.parameter_overrides["Lane"] = "x";
  EXPECT_NE(error("", "", options).find("not a whole number"), std::string::npos);
}

TEST_F(XoscReader, MisspeltElementsAndAttributesGetSuggestions) {
  const std::string element = error("<TeleportAction><Position><LanePosition roadId=\"0\" laneId=\"$Lane\" offset=\"0.0\" s=\"5.0\"/></Position></TeleportAction>",
                                    "<TeleprtAction/>");
  EXPECT_NE(element.find("s.xosc:"), std::string::npos) << element;
  EXPECT_NE(element.find("/OpenSCENARIO/Storyboard/Init/Actions/Private[1]/PrivateAction[1]/TeleprtAction"),
            std::string::npos)
      << element;
  EXPECT_NE(element.find("did you mean \"TeleportAction\""), std::string::npos) << element;
  const std::string attribute = error("conditionEdge=\"rising\">", "conditionEgde=\"rising\">");
  EXPECT_NE(attribute.find("did you mean \"conditionEdge\""), std::string::npos) << attribute;
  const std::string value = error("priority=\"overwrite\"", "priority=\"overwrit\"");
  EXPECT_NE(value.find("did you mean \"overwrite\""), std::string::npos) << value;
}

TEST_F(XoscReader, StandardElementsNotRunAreNamed) {
  // A standard element where the orchestrator reads none of its kind is named as such, never
  // "unknown" with a "did you mean".
  const std::string message =
      error("<LanePosition roadId=\"0\" laneId=\"$Lane\" offset=\"0.0\" s=\"5.0\"/>",
            "<LanePosition roadId=\"0\" laneId=\"$Lane\" offset=\"0.0\" s=\"5.0\"><Waypoint/></LanePosition>");
  EXPECT_NE(message.find("Waypoint in LanePosition is an OpenSCENARIO element the orchestrator does not run there"),
            std::string::npos)
      << message;
}

TEST_F(XoscReader, ParameterConditionsAreCheckedAgainstTheDeclaration) {
  const std::string time = "<SimulationTimeCondition value=\"0\" rule=\"greaterThan\"/>";
  EXPECT_EQ(error(time, "<ParameterCondition parameterRef=\"Lane\" value=\"-1\" rule=\"equalTo\"/>"), "no error");
  EXPECT_NE(error(time, "<ParameterCondition parameterRef=\"Lane\" value=\"left\" rule=\"equalTo\"/>")
                .find("\"left\" is not a whole number (integer parameter Lane)"),
            std::string::npos);
  EXPECT_NE(error(time, "<ParameterCondition parameterRef=\"Lan\" value=\"1\" rule=\"equalTo\"/>")
                .find("no parameter \"Lan\" is declared"),
            std::string::npos);
}

TEST_F(XoscReader, RevisionsOtherThanOneZeroToOneTwoAreErrors) {
  EXPECT_NE(error("revMajor=\"1\" revMinor=\"1\" date=\"2024-01-01T00:00:00\" author=\"t\" description=\"cut in\"",
                  "revMajor=\"2\" revMinor=\"0\" date=\"2024-01-01T00:00:00\" author=\"t\" description=\"cut in\"")
                .find("OpenSCENARIO 2.0 is not supported"),
            std::string::npos);
  EXPECT_EQ(error("revMinor=\"1\" date=\"2024-01-01T00:00:00\" author=\"t\" description=\"cut in\"",
                  "revMinor=\"2\" date=\"2024-01-01T00:00:00\" author=\"t\" description=\"cut in\""),
            "no error");
}

TEST_F(XoscReader, ReferencesAreCheckedAtLoad) {
  EXPECT_NE(error("<EntityRef entityRef=\"Other\"/></Actors>", "<EntityRef entityRef=\"Othr\"/></Actors>")
                .find("no entity named \"Othr\" (did you mean \"Other\"?)"),
            std::string::npos);
  EXPECT_NE(error("storyboardElementRef=\"Brake\"", "storyboardElementRef=\"Brak\"")
                .find("no action named \"Brak\" in the storyboard (did you mean \"Brake\"?)"),
            std::string::npos);
  EXPECT_NE(error("entryName=\"car\"/>", "entryName=\"cr\"/>").find("catalog \"vehicles\" has no entry \"cr\""),
            std::string::npos);
  EXPECT_NE(error("<RelativeTargetSpeed entityRef=\"Ego\"", "<RelativeTargetSpeed entityRef=\"Eg\"")
                .find("no entity named \"Eg\""),
            std::string::npos);
  EXPECT_NE(error("./road.xodr", "./missing.xodr").find("no OpenDRIVE file"), std::string::npos);
  EXPECT_NE(error("value=\"${$Speed_kph / 3.6}\"", "value=\"${$Speed_kph / }\"").find("expected a value"),
            std::string::npos);
}

// Every warning the reader gave, formatted, in one text.
std::string warnings_of(const Scenario& s) {
  std::string all;
  for (const Diagnostic& d : s.warnings.items()) all += d.format() + "\n";
  return all;
}

// Real files (esmini's examples) write decelerations as negative rates; the standard's range is
// [0..inf[: the magnitude is run, with a warning that says so. A negative time stays an error.
TEST_F(XoscReader, ANegativeRateIsRunByItsMagnitudeWithAWarning) {
  const Scenario s = load("dynamicsDimension=\"rate\" value=\"2\"", "dynamicsDimension=\"rate\" value=\"-2\"");
  const Event& event = s.storyboard.stories.at(0).acts.at(0).groups.at(0).maneuvers.at(0).events.at(0);
  EXPECT_DOUBLE_EQ(std::get<SpeedAction>(event.actions.at(0).action).dynamics.value, 2.0);
  const std::string warnings = warnings_of(s);
  EXPECT_NE(warnings.find("a negative rate (-2): the standard gives TransitionDynamics value the range [0..inf["),
            std::string::npos)
      << warnings;
  EXPECT_NE(error("dynamicsShape=\"step\" dynamicsDimension=\"time\" value=\"0\"",
                  "dynamicsShape=\"step\" dynamicsDimension=\"time\" value=\"-1\"")
                .find("a transition's time or distance cannot be negative"),
            std::string::npos);
}

// One parameter declared twice in the scenario's ParameterDeclarations: the same declaration
// again changes nothing (a warning); a different one is ambiguous (an error naming the first).
TEST_F(XoscReader, AParameterDeclaredTwice) {
  const std::string lane = "<ParameterDeclaration name=\"Lane\" parameterType=\"integer\" value=\"-1\"/>";
  const Scenario s = load(lane, lane + lane);
  EXPECT_EQ(std::count_if(s.parameters.begin(), s.parameters.end(), [](const Parameter& p) { return p.name == "Lane"; }),
            1);
  EXPECT_NE(warnings_of(s).find("parameter \"Lane\" is declared a second time, as at line 11"), std::string::npos)
      << warnings_of(s);
  EXPECT_NE(error(lane, lane + "<ParameterDeclaration name=\"Lane\" parameterType=\"integer\" value=\"-2\"/>")
                .find("parameter \"Lane\" is declared twice, differently (first at line 11)"),
            std::string::npos);
}

// catalogName is the Catalog's name (here "vehicles"). A name no catalog has, where exactly one
// catalog holds an entry of that name and kind, takes that entry (as esmini, which looks entries
// up by kind), with a warning; an entry no catalog holds stays the error.
TEST_F(XoscReader, ACatalogNamedLooselyIsFoundByItsEntry) {
  const std::string other = "<CatalogReference catalogName=\"vehicles\" entryName=\"car\"/>";
  const Scenario s = load(other, "<CatalogReference catalogName=\"VehicleCatalog\" entryName=\"car\"/>");
  EXPECT_DOUBLE_EQ(s.entities.at(1).box.length, 5.0);
  EXPECT_NE(warnings_of(s).find("no catalog named \"VehicleCatalog\" (the standard resolves catalogName by the "
                                "Catalog's name); its entry \"car\" is taken from catalog \"vehicles\""),
            std::string::npos)
      << warnings_of(s);
  EXPECT_NE(error(other, "<CatalogReference catalogName=\"VehicleCatalog\" entryName=\"truck\"/>")
                .find("no catalog named \"VehicleCatalog\" in the CatalogLocations"),
            std::string::npos);
}

}  // namespace
}  // namespace orch::openscenario

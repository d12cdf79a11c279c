// OpenSCENARIO's TimeOfDayCondition (against the Environment's TimeOfDay, animated or not),
// the 1.3 monitors (MonitorDeclarations, SetMonitorAction), the refusal of
// UserDefinedValueCondition, and xsd:dateTime reading.
#include <gtest/gtest.h>

#include "core/errors.hpp"
#include "opendrive/xodr_reader.hpp"
#include "openscenario/date_time.hpp"
#include "openscenario/storyboard_runtime.hpp"
#include "openscenario/xosc_reader.hpp"
#include "run/run_result.hpp"
#include "support/cli_runner.hpp"
#include "unit/openscenario_snippets.hpp"

namespace orch::openscenario {
namespace {

using test::kStraightTwoLaneRoad;
using test::place;
using test::run_until;
using test::transition_times;
using test::vehicle;

std::string environment(const std::string& date_time, bool animation) {
  return R"(<GlobalAction><EnvironmentAction><Environment name="Env"><TimeOfDay animation=")" +
         std::string(animation ? "true" : "false") + R"(" dateTime=")" + date_time +
         R"("/><Weather cloudState="free"/><RoadCondition frictionScaleFactor="1"/></Environment></EnvironmentAction></GlobalAction>)";
}

std::string simulation_time(double at) {
  return R"(<StartTrigger><ConditionGroup><Condition name="At" delay="0" conditionEdge="none"><ByValueCondition>
<SimulationTimeCondition value=")" + std::to_string(at) + R"(" rule="greaterOrEqual"/></ByValueCondition></Condition></ConditionGroup></StartTrigger>)";
}

std::string value_event(const std::string& event, const std::string& action, const std::string& condition) {
  return R"(<Event name=")" + event + R"(" priority="parallel"><Action name=")" + event + R"(Action">)" + action +
         R"(</Action><StartTrigger><ConditionGroup><Condition name=")" + event +
         R"(Condition" delay="0" conditionEdge="none"><ByValueCondition>)" + condition +
         R"(</ByValueCondition></Condition></ConditionGroup></StartTrigger></Event>)";
}

const std::string kSpeedUp = R"(<PrivateAction><LongitudinalAction><SpeedAction><SpeedActionDynamics dynamicsShape="step" dynamicsDimension="time" value="0"/>
<SpeedActionTarget><AbsoluteTargetSpeed value="30"/></SpeedActionTarget></SpeedAction></LongitudinalAction></PrivateAction>)";

class TimeAndMonitors : public ::testing::Test {
 protected:
  void load(const std::string& init, const std::string& events, const std::string& declarations = "") {
    const std::string text = R"(<?xml version="1.0"?><OpenSCENARIO>
<FileHeader revMajor="1" revMinor="3" date="2024-01-01T00:00:00" author="t" description="time"/>)" + declarations +
                             R"(<RoadNetwork><LogicFile filepath="road.xodr"/></RoadNetwork>
<Entities>)" + vehicle("A") + R"(</Entities>
<Storyboard><Init><Actions>)" + init + place("A", 10, -1, 10) + R"(</Actions></Init>
<Story name="S"><Act name="Act"><ManeuverGroup name="G" maximumExecutionCount="1">
<Actors selectTriggeringEntities="false"><EntityRef entityRef="A"/></Actors><Maneuver name="M">)" + events +
                             R"(</Maneuver></ManeuverGroup>)" + simulation_time(0) + R"(</Act></Story>
<StopTrigger/></Storyboard></OpenSCENARIO>)";
    dir_.write("road.xodr", kStraightTwoLaneRoad);
    scenario_ = load_scenario(dir_.write("s.xosc", text).string());
    roads_ = opendrive::read_xodr_file((dir_ / "road.xodr").string());
    runtime_ = std::make_unique<StoryboardRuntime>(scenario_, roads_);
  }
  std::string load_error(const std::string& init, const std::string& events, const std::string& declarations = "") {
    try {
      load(init, events, declarations);
    } catch (const ScenarioError& e) {
      return e.what();
    }
    return "";
  }
  [[nodiscard]] double started(const std::string& event) const {
    const auto times = transition_times(*runtime_, event, "startTransition");
    return times.empty() ? -1 : times.front();
  }
  test::TempDir dir_;
  Scenario scenario_;
  opendrive::RoadNetwork roads_;
  std::unique_ptr<StoryboardRuntime> runtime_;
};

TEST(DateTime, ReadsTheSchemaFormWithFractionsAndZones) {
  EXPECT_EQ(*parse_date_time("1970-01-01T00:00:00"), 0.0);
  EXPECT_EQ(*parse_date_time("1970-01-02T00:00:01Z"), 86401.0);
  // 2000-03-01 follows a leap day: 30 years and 60 days after 1970, 7 of those years leap.
  EXPECT_EQ(*parse_date_time("2000-03-01T00:00:00"), (30.0 * 365 + 7 + 31 + 29) * 86400);
  EXPECT_NEAR(*parse_date_time("2025-06-13T12:00:00.250+02:00"), *parse_date_time("2025-06-13T10:00:00Z") + 0.25, 1e-6);
  EXPECT_EQ(*parse_date_time("2025-06-13T12:00:00-01:30"), *parse_date_time("2025-06-13T13:30:00"));
  for (const char* bad : {"2025-06-13", "2025-06-13 12:00:00", "2025-13-01T00:00:00", "2023-02-29T00:00:00",
                          "2025-06-13T25:00:00", "2025-06-13T12:00:00+2", "2025-06-13T12:00:00.", "12:00:00"})
    EXPECT_FALSE(parse_date_time(bad).has_value()) << bad;
}

TEST_F(TimeAndMonitors, AnimatedTimeOfDayRunsOnWithSimulationTime) {
  load(environment("2025-06-13T12:00:00", true),
       value_event("Later", kSpeedUp, R"(<TimeOfDayCondition rule="greaterOrEqual" dateTime="2025-06-13T12:00:02"/>)"));
  run_until(*runtime_, 4);
  EXPECT_NEAR(started("Later"), 2.0, 0.05 + 1e-9);
}

TEST_F(TimeAndMonitors, TimeOfDayWithoutAnimationStays) {
  load(environment("2025-06-13T12:00:00", false),
       value_event("Later", kSpeedUp, R"(<TimeOfDayCondition rule="greaterOrEqual" dateTime="2025-06-13T12:00:02"/>)") +
           value_event("Noon", kSpeedUp, R"(<TimeOfDayCondition rule="equalTo" dateTime="2025-06-13T12:00:00"/>)"));
  run_until(*runtime_, 4);
  EXPECT_EQ(started("Later"), -1.0);
  EXPECT_GE(started("Noon"), 0.0);
}

TEST_F(TimeAndMonitors, TimeOfDayIsUnsetUntilAnEnvironmentActionSetsIt) {
  // No TimeOfDay until the event at 1 s sets one (animated, 11:59:59): the condition
  // "after 11:00" is false before, true once set.
  load("",
       value_event("SetTime", environment("2025-06-13T11:59:59", true), R"(<SimulationTimeCondition value="1" rule="greaterOrEqual"/>)") +
           value_event("Later", kSpeedUp, R"(<TimeOfDayCondition rule="greaterThan" dateTime="2025-06-13T11:00:00"/>)"));
  run_until(*runtime_, 3);
  const double set = started("SetTime");
  ASSERT_GE(set, 1.0);
  EXPECT_GE(started("Later"), set);
  EXPECT_LE(started("Later"), set + 0.05 + 1e-9);
}

TEST_F(TimeAndMonitors, ReaderChecksDateTimes) {
  EXPECT_NE(load_error("", value_event("E", kSpeedUp, R"(<TimeOfDayCondition rule="equalTo" dateTime="noon"/>)"))
                .find("xsd:dateTime"),
            std::string::npos);
  EXPECT_NE(load_error(environment("13.6.2025 12:00", false), "").find("dateTime"), std::string::npos);
}

TEST_F(TimeAndMonitors, DateTimeParametersCompareAsInstantsNotTexts) {
  // 12:00:00+02:00 is 10:00:00Z; 11:30:00+02:00 is 09:30:00Z, earlier although its text sorts
  // after "10:00".
  const std::string declarations =
      R"(<ParameterDeclarations><ParameterDeclaration name="When" parameterType="dateTime" value="2024-01-01T10:00:00Z"/></ParameterDeclarations>)";
  load("",
       value_event("Same", kSpeedUp, R"(<ParameterCondition parameterRef="When" rule="equalTo" value="2024-01-01T12:00:00+02:00"/>)") +
           value_event("Before", kSpeedUp, R"(<ParameterCondition parameterRef="When" rule="lessThan" value="2024-01-01T11:30:00+02:00"/>)") +
           value_event("After", kSpeedUp, R"(<ParameterCondition parameterRef="When" rule="greaterThan" value="2024-01-01T11:30:00+02:00"/>)"),
       declarations);
  run_until(*runtime_, 1);
  EXPECT_GE(started("Same"), 0.0);
  EXPECT_EQ(started("Before"), -1.0);
  EXPECT_GE(started("After"), 0.0);
  const std::string bad =
      R"(<ParameterDeclarations><ParameterDeclaration name="When" parameterType="dateTime" value="noon"/></ParameterDeclarations>)";
  EXPECT_NE(load_error("", "", bad).find("\"noon\" is no xsd:dateTime"), std::string::npos) << load_error("", "", bad);
}

TEST_F(TimeAndMonitors, UserDefinedValueConditionIsAnErrorNamingTheValue) {
  const std::string message =
      load_error("", value_event("E", kSpeedUp, R"(<UserDefinedValueCondition name="RainSensor" rule="greaterThan" value="0.5"/>)"));
  EXPECT_NE(message.find("UserDefinedValueCondition"), std::string::npos) << message;
  EXPECT_NE(message.find("RainSensor"), std::string::npos) << message;
  EXPECT_NE(message.find("no source"), std::string::npos) << message;
}

TEST_F(TimeAndMonitors, SetMonitorActionChangesTheDeclaredMonitor) {
  const std::string monitors = R"(<MonitorDeclarations><MonitorDeclaration name="KeepsDistance" value="true"/>
<MonitorDeclaration name="Reached" value="false"/></MonitorDeclarations>)";
  load("",
       value_event("Fail", R"(<GlobalAction><SetMonitorAction monitorRef="KeepsDistance" value="false"/></GlobalAction>)",
                   R"(<SimulationTimeCondition value="1" rule="greaterOrEqual"/>)"),
       monitors);
  EXPECT_TRUE(runtime_->monitors().at("KeepsDistance"));
  EXPECT_FALSE(runtime_->monitors().at("Reached"));
  run_until(*runtime_, 0.5);
  EXPECT_TRUE(runtime_->monitors().at("KeepsDistance"));
  run_until(*runtime_, 2);
  EXPECT_FALSE(runtime_->monitors().at("KeepsDistance"));
  EXPECT_FALSE(runtime_->monitors().at("Reached"));
}

TEST_F(TimeAndMonitors, MonitorsAreCheckedAtLoad) {
  const std::string monitors = R"(<MonitorDeclarations><MonitorDeclaration name="KeepsDistance" value="true"/></MonitorDeclarations>)";
  const std::string message = load_error(
      "", value_event("Fail", R"(<GlobalAction><SetMonitorAction monitorRef="KeepDistance" value="false"/></GlobalAction>)",
                      R"(<SimulationTimeCondition value="1" rule="greaterOrEqual"/>)"),
      monitors);
  EXPECT_NE(message.find("no monitor named \"KeepDistance\""), std::string::npos) << message;
  EXPECT_NE(message.find("KeepsDistance"), std::string::npos) << message;  // did you mean
  EXPECT_NE(load_error("", "",
                       R"(<MonitorDeclarations><MonitorDeclaration name="M" value="true"/><MonitorDeclaration name="M" value="false"/></MonitorDeclarations>)")
                .find("declared twice"),
            std::string::npos);
}

TEST(MonitorResults, ResultJsonHasEachMonitorsFinalValueOrNull) {
  test::TempDir dir;
  RunResult r;
  write_result(dir.path(), r);
  EXPECT_TRUE(test::read_json(dir / "result.json")["monitors"].is_null());
  r.monitors = {{"KeepsDistance", false}, {"Reached", true}};
  write_result(dir.path(), r);
  const auto j = test::read_json(dir / "result.json");
  EXPECT_FALSE(j["monitors"]["KeepsDistance"].get<bool>());
  EXPECT_TRUE(j["monitors"]["Reached"].get<bool>());
}

}  // namespace
}  // namespace orch::openscenario

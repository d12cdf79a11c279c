// SynchronizeAction read and run by the storyboard on a straight road (no simulator): A
// arrives at its target when the master B arrives at its own, at the final speed; bad
// content is an error naming the line.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "core/errors.hpp"
#include "opendrive/xodr_reader.hpp"
#include "openscenario/scenario_check.hpp"
#include "openscenario/storyboard_runtime.hpp"
#include "openscenario/synchronize_targets.hpp"
#include "openscenario/xosc_reader.hpp"
#include "support/cli_runner.hpp"
#include "unit/openscenario_snippets.hpp"

namespace orch::openscenario {
namespace {

std::string synchronize(const std::string& attributes, const std::string& final_speed) {
  return R"(<SynchronizeAction masterEntityRef="B" )" + attributes + R"(>
<TargetPositionMaster><LanePosition roadId="0" laneId="-2" s="300" offset="0"/></TargetPositionMaster>
<TargetPosition><LanePosition roadId="0" laneId="-1" s="400" offset="0"/></TargetPosition>)" +
         final_speed + "</SynchronizeAction>";
}

std::string scenario(const std::string& action) {
  return R"(<?xml version="1.0"?><OpenSCENARIO>
<FileHeader revMajor="1" revMinor="3" date="2024-01-01T00:00:00" author="t" description="synchronize"/>
<RoadNetwork><LogicFile filepath="road.xodr"/></RoadNetwork>
<Entities>)" + test::vehicle("A") + test::vehicle("B") + R"(</Entities>
<Storyboard><Init><Actions>)" + test::place("A", 100, -1, 10) + test::place("B", 100, -2, 10) + R"(</Actions></Init>
<Story name="S"><Act name="Act"><ManeuverGroup name="G" maximumExecutionCount="1">
<Actors selectTriggeringEntities="false"><EntityRef entityRef="A"/></Actors><Maneuver name="M">
<Event name="E" priority="parallel"><Action name="Sync"><PrivateAction>)" + action + R"(</PrivateAction></Action>
<StartTrigger><ConditionGroup><Condition name="c" delay="0" conditionEdge="none"><ByValueCondition>
<SimulationTimeCondition value="0" rule="greaterOrEqual"/></ByValueCondition></Condition></ConditionGroup></StartTrigger></Event>
</Maneuver></ManeuverGroup></Act></Story>
<StopTrigger><ConditionGroup><Condition name="stop" delay="0" conditionEdge="none"><ByValueCondition>
<SimulationTimeCondition value="60" rule="greaterOrEqual"/></ByValueCondition></Condition></ConditionGroup></StopTrigger>
</Storyboard></OpenSCENARIO>)";
}

class Synchronize : public ::testing::Test {
 protected:
  void load(const std::string& action) {
    dir_.write("road.xodr", test::kStraightTwoLaneRoad);
    scenario_ = load_scenario(dir_.write("s.xosc", scenario(action)).string());
    roads_ = opendrive::read_xodr_file((dir_ / "road.xodr").string());
    runtime_ = std::make_unique<StoryboardRuntime>(scenario_, roads_);
  }
  std::string load_error(const std::string& action) {
    try {
      load(action);
    } catch (const ScenarioError& e) {
      return e.what();
    }
    return "";
  }
  // Runs until the action ends; its end time (-1: never).
  double run_to_end() {
    while (runtime_->time() < 59 && !runtime_->finished()) {
      runtime_->step(0.05);
      if (!test::transition_times(*runtime_, "Sync", "endTransition").empty()) return runtime_->time();
    }
    return -1;
  }
  const EntityState& entity(const std::string& name) const { return runtime_->entities().at(name); }

  orch::test::TempDir dir_;
  Scenario scenario_;
  opendrive::RoadNetwork roads_;
  std::unique_ptr<StoryboardRuntime> runtime_;
};

TEST_F(Synchronize, ArrivesWhenTheMasterArrives) {
  // B needs 20 s for its 200 m; A has 300 m: it speeds up and arrives with B.
  load(synchronize(R"(targetTolerance="0" targetToleranceMaster="0")", ""));
  const double end = run_to_end();
  EXPECT_NEAR(end, 20.0, 0.1);
  EXPECT_NEAR(entity("A").s, 400.0, 1.0);
  EXPECT_NEAR(entity("B").s, 300.0, 1.0);
}

TEST_F(Synchronize, AbsoluteFinalSpeedIsTakenOnArrival) {
  load(synchronize("", R"(<FinalSpeed><AbsoluteSpeed value="12"/></FinalSpeed>)"));
  EXPECT_NEAR(run_to_end(), 20.0, 0.1);
  EXPECT_NEAR(entity("A").s, 400.0, 1.0);
  EXPECT_DOUBLE_EQ(entity("A").speed, 12.0);
}

TEST_F(Synchronize, RelativeFinalSpeedFollowsTheMaster) {
  load(synchronize("", R"(<FinalSpeed><RelativeSpeedToMaster value="3" speedTargetValueType="delta">
<TargetTimeSteadyState time="2"/></RelativeSpeedToMaster></FinalSpeed>)"));
  EXPECT_NEAR(run_to_end(), 20.0, 0.1);
  EXPECT_NEAR(entity("A").s, 400.0, 1.0);
  EXPECT_DOUBLE_EQ(entity("A").speed, 13.0);  // B's 10 m/s + 3
}

TEST_F(Synchronize, BadContentNamesTheLine) {
  const std::string negative = load_error(synchronize(R"(targetTolerance="-1")", ""));
  EXPECT_NE(negative.find("s.xosc:"), std::string::npos) << negative;
  EXPECT_NE(negative.find("SynchronizeAction/@targetTolerance: a tolerance cannot be negative"), std::string::npos)
      << negative;
  EXPECT_NE(load_error(synchronize("", R"(<FinalSpeed><AbsoluteSpeed value="5"><TargetDistanceSteadyState distance="3"/>
<TargetTimeSteadyState time="1"/></AbsoluteSpeed></FinalSpeed>)")).find("give one steady state"),
            std::string::npos);
  EXPECT_NE(load_error(R"(<SynchronizeAction masterEntityRef="C"><TargetPositionMaster><LanePosition roadId="0" laneId="-2" s="300" offset="0"/></TargetPositionMaster>
<TargetPosition><LanePosition roadId="0" laneId="-1" s="400" offset="0"/></TargetPosition></SynchronizeAction>)")
                .find("\"C\""),
            std::string::npos);
}

TEST_F(Synchronize, ATargetPastTheRoadsEndIsTruncatedWithAWarningAsThePeerDoes) {
  // Road 0 is 2000 m long; the target at s = 2500 (esmini's ltap-od-relative-speed.xosc has one).
  const std::string action = R"(<SynchronizeAction masterEntityRef="B">
<TargetPositionMaster><LanePosition roadId="0" laneId="-2" s="300" offset="0"/></TargetPositionMaster>
<TargetPosition><LanePosition roadId="0" laneId="-1" s="2500" offset="0"/></TargetPosition></SynchronizeAction>)";
  dir_.write("road.xodr", test::kStraightTwoLaneRoad);
  scenario_ = load_scenario(dir_.write("s.xosc", scenario(action)).string());
  roads_ = opendrive::read_xodr_file((dir_ / "road.xodr").string());
  const Diagnostics warnings = truncate_synchronize_targets(scenario_, roads_);
  ASSERT_EQ(warnings.warning_count(), 1) << warnings.format();
  const std::string text = warnings.items().front().format();
  EXPECT_NE(text.find("s.xosc:"), std::string::npos) << text;
  EXPECT_NE(text.find("TargetPosition: s=2500 is beyond the end of road 0 (length 2000.00); truncated to 2000.00"),
            std::string::npos)
      << text;
  const auto& sync = std::get<SynchronizeAction>(scenario_.storyboard.stories[0].acts[0].groups[0].maneuvers[0]
                                                     .events[0].actions[0].action);
  EXPECT_EQ(std::get<LanePosition>(sync.position).s, 2000.0);
  EXPECT_EQ(std::get<LanePosition>(sync.master_position).s, 300.0);  // within its road: unchanged
  runtime_ = std::make_unique<StoryboardRuntime>(scenario_, roads_);  // the action starts at 0 s: it runs
  EXPECT_GT(run_to_end(), 0.0);
  // `validate` says the same, as a warning: the file is valid.
  const Diagnostics checked = check_scenario_file((dir_ / "s.xosc").string());
  EXPECT_FALSE(checked.has_errors()) << checked.format();
  EXPECT_EQ(checked.warning_count(), 1);
}

}  // namespace
}  // namespace orch::openscenario

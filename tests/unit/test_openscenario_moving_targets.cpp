// Transitions whose end moves while they run, in the storyboard runtime (no simulator): a
// SpeedAction with a RelativeTargetSpeed follows the reference entity's speed during the
// transition, continuous or not (as esmini; the standard gives the target relative to the
// reference's speed, not when it is taken), and a continuous one keeps following it after the
// transition; a LaneChangeAction by distance runs over the distance travelled, however the
// speed changes on the way.
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "opendrive/xodr_reader.hpp"
#include "openscenario/storyboard_runtime.hpp"
#include "openscenario/xosc_reader.hpp"
#include "support/cli_runner.hpp"
#include "unit/openscenario_snippets.hpp"

namespace orch::openscenario {
namespace {

std::string at_time(double at) {
  return R"(<StartTrigger><ConditionGroup><Condition name="c" delay="0" conditionEdge="none"><ByValueCondition><SimulationTimeCondition value=")" +
         std::to_string(at) + R"(" rule="greaterOrEqual"/></ByValueCondition></Condition></ConditionGroup></StartTrigger>)";
}

std::string speed_event(const std::string& name, const std::string& dynamics, const std::string& target, double at) {
  return R"(<Event name=")" + name + R"(" priority="parallel"><Action name=")" + name +
         R"(Action"><PrivateAction><LongitudinalAction><SpeedAction>)" + dynamics + "<SpeedActionTarget>" + target +
         "</SpeedActionTarget></SpeedAction></LongitudinalAction></PrivateAction></Action>" + at_time(at) + "</Event>";
}

std::string group(const std::string& actor, const std::string& events) {
  return R"(<ManeuverGroup name="G)" + actor + R"(" maximumExecutionCount="1"><Actors selectTriggeringEntities="false"><EntityRef entityRef=")" +
         actor + R"("/></Actors><Maneuver name="M)" + actor + R"(">)" + events + "</Maneuver></ManeuverGroup>";
}

class RelativeSpeed : public ::testing::Test {
 protected:
  // A (20 m/s) goes to B's speed + 0 linearly in 4 s from 1 s; B (10 m/s) jumps to 6 m/s
  // at 2 s and to 8 m/s at 6 s.
  void load(bool continuous, const std::string& a_more = "") {
    const std::string step = R"(<SpeedActionDynamics dynamicsShape="step" dynamicsDimension="time" value="0"/>)";
    const std::string a_events = speed_event(
        "Follow", R"(<SpeedActionDynamics dynamicsShape="linear" dynamicsDimension="time" value="4"/>)",
        std::string(R"(<RelativeTargetSpeed entityRef="B" value="0" speedTargetValueType="delta" continuous=")") +
            (continuous ? "true" : "false") + R"("/>)",
        1) + a_more;
    const std::string b_events = speed_event("Slow", step, R"(<AbsoluteTargetSpeed value="6"/>)", 2) +
                                 speed_event("Faster", step, R"(<AbsoluteTargetSpeed value="8"/>)", 6);
    const std::string text = R"(<?xml version="1.0"?><OpenSCENARIO>
<FileHeader revMajor="1" revMinor="2" date="2024-01-01T00:00:00" author="t" description="relative speed"/>
<RoadNetwork><LogicFile filepath="road.xodr"/></RoadNetwork>
<Entities>)" + test::vehicle("A") + test::vehicle("B") +
                             R"(</Entities>
<Storyboard><Init><Actions>)" + test::place("A", 10, -1, 20) + test::place("B", 200, -1, 10) +
                             R"(</Actions></Init>
<Story name="S"><Act name="Act">)" + group("A", a_events) + group("B", b_events) + at_time(0) +
                             R"(</Act></Story><StopTrigger/></Storyboard></OpenSCENARIO>)";
    dir_.write("road.xodr", std::string(test::kStraightTwoLaneRoad));
    scenario_ = load_scenario(dir_.write("s.xosc", text).string());
    roads_ = opendrive::read_xodr_file((dir_ / "road.xodr").string());
    runtime_ = std::make_unique<StoryboardRuntime>(scenario_, roads_);
  }
  [[nodiscard]] double speed(const std::string& name) const { return runtime_->entities().at(name).speed; }

  orch::test::TempDir dir_;
  Scenario scenario_;
  opendrive::RoadNetwork roads_;
  std::unique_ptr<StoryboardRuntime> runtime_;
};

TEST_F(RelativeSpeed, TheTargetFollowsTheReferenceDuringTheTransition) {
  load(false);
  test::run_until(*runtime_, 3);
  // Half-way through the line from 20 m/s towards B's 6 m/s now (a target taken at the start
  // would be half-way to 10 m/s: 15).
  EXPECT_NEAR(speed("A"), 20 + (6 - 20) * 0.5, 1e-9);
  test::run_until(*runtime_, 7);
  EXPECT_NEAR(speed("A"), 6, 1e-9);  // reached at 5 s, and kept: not continuous
  const auto ended = test::transition_times(*runtime_, "FollowAction", "endTransition");
  ASSERT_EQ(ended.size(), 1u);
  EXPECT_NEAR(ended[0], 5, 1e-9);
}

TEST_F(RelativeSpeed, AContinuousOneKeepsFollowingAfterTheTransition) {
  load(true);
  test::run_until(*runtime_, 3);
  EXPECT_NEAR(speed("A"), 13, 1e-9);
  test::run_until(*runtime_, 5);
  EXPECT_NEAR(speed("A"), 6, 1e-9);  // no jump at the transition's end
  test::run_until(*runtime_, 7);
  EXPECT_NEAR(speed("A"), 8, 1e-9);
  EXPECT_TRUE(test::transition_times(*runtime_, "FollowAction", "endTransition").empty());
}

// A's lane change to lane -2 (sinusoidal over 50 m) starts at 1 s at 20 m/s, and A then slows
// towards B: it takes the 50 m, not the 2.5 s the start speed gave.
TEST_F(RelativeSpeed, ALaneChangeByDistanceRunsOverTheDistanceTravelled) {
  load(false, R"(<Event name="Change" priority="parallel"><Action name="ChangeAction"><PrivateAction><LateralAction>
<LaneChangeAction><LaneChangeActionDynamics dynamicsShape="sinusoidal" dynamicsDimension="distance" value="50"/>
<LaneChangeTarget><AbsoluteTargetLane value="-2"/></LaneChangeTarget></LaneChangeAction></LateralAction></PrivateAction></Action>)" +
                  at_time(1) + "</Event>");
  const auto odometer = [&] { return runtime_->entities().at("A").odometer; };
  test::run_until(*runtime_, 1);
  const double start = odometer();
  while (odometer() - start < 25 - 1e-9) runtime_->step(0.05);
  // Half-way along the 50 m (within a step's travel): half-way across, from -1.75 to -5.25.
  EXPECT_NEAR(runtime_->entities().at("A").t, -3.5, 0.2);
  EXPECT_GT(runtime_->time(), 1 + 1.25 + 0.05);  // later than at 20 m/s
  test::run_until(*runtime_, 10);
  const auto ended = test::transition_times(*runtime_, "ChangeAction", "endTransition");
  ASSERT_EQ(ended.size(), 1u);
  EXPECT_GT(ended[0], 1 + 2.5 + 0.5);
  EXPECT_NEAR(runtime_->entities().at("A").t, -5.25, 1e-9);
}

}  // namespace
}  // namespace orch::openscenario

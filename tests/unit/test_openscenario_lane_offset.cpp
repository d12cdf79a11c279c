// LaneOffsetAction in the storyboard runtime (no simulator): the target of a
// RelativeTargetLaneOffset and the sinusoidal shape under maxLateralAcc.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "opendrive/xodr_reader.hpp"
#include "openscenario/lane_offset.hpp"
#include "openscenario/storyboard_runtime.hpp"
#include "openscenario/xosc_reader.hpp"
#include "support/cli_runner.hpp"
#include "unit/openscenario_snippets.hpp"

namespace orch::openscenario {
namespace {

using test::kStraightTwoLaneRoad;
using test::place;
using test::vehicle;

std::string at_time(const std::string& name, double at) {
  return R"(<Condition name=")" + name + R"(" delay="0" conditionEdge="none"><ByValueCondition><SimulationTimeCondition value=")" +
         std::to_string(at) + R"(" rule="greaterOrEqual"/></ByValueCondition></Condition>)";
}

// A LaneOffsetAction event: `target` is the LaneOffsetTarget's content.
std::string offset_event(const std::string& name, const std::string& target, double max_acc, const std::string& condition) {
  return R"(<Event name=")" + name + R"(" priority="parallel"><Action name=")" + name + R"(Action"><PrivateAction><LateralAction>
    <LaneOffsetAction continuous="false"><LaneOffsetActionDynamics maxLateralAcc=")" + std::to_string(max_acc) +
         R"(" dynamicsShape="sinusoidal"/><LaneOffsetTarget>)" + target +
         R"(</LaneOffsetTarget></LaneOffsetAction></LateralAction></PrivateAction></Action><StartTrigger><ConditionGroup>)" +
         condition + "</ConditionGroup></StartTrigger></Event>";
}

// A (lane -1, centre y = -1.75, s 10) and B (lane -2, centre y = -5.25, s 10), both 10 m/s;
// A's maneuver holds `events`.
class LaneOffset : public ::testing::Test {
 protected:
  void load(const std::string& events) {
    const std::string text = R"(<?xml version="1.0"?><OpenSCENARIO>
<FileHeader revMajor="1" revMinor="2" date="2024-01-01T00:00:00" author="t" description="lane offset"/>
<RoadNetwork><LogicFile filepath="road.xodr"/></RoadNetwork>
<Entities>)" + vehicle("A") + vehicle("B") + R"(</Entities>
<Storyboard><Init><Actions>)" + place("A", 10, -1, 10) + place("B", 10, -2, 10) + R"(</Actions></Init>
<Story name="S"><Act name="Act"><ManeuverGroup name="G" maximumExecutionCount="1">
<Actors selectTriggeringEntities="false"><EntityRef entityRef="A"/></Actors><Maneuver name="M">)" + events +
                             R"(</Maneuver></ManeuverGroup><StartTrigger><ConditionGroup>)" + at_time("ActStart", 0) +
                             R"(</ConditionGroup></StartTrigger></Act></Story>
<StopTrigger><ConditionGroup>)" + at_time("Stop", 100) + R"(</ConditionGroup></StopTrigger></Storyboard></OpenSCENARIO>)";
    dir_.write("road.xodr", kStraightTwoLaneRoad);
    scenario_ = load_scenario(dir_.write("s.xosc", text).string());
    roads_ = opendrive::read_xodr_file((dir_ / "road.xodr").string());
    runtime_ = std::make_unique<StoryboardRuntime>(scenario_, roads_);
  }
  const EntityState& a() const { return runtime_->entities().at("A"); }

  orch::test::TempDir dir_;
  Scenario scenario_;
  opendrive::RoadNetwork roads_;
  std::unique_ptr<StoryboardRuntime> runtime_;
};

// OSC-ALKS 4.6_2: the side vehicle's target is "-1.75 relative to the ego": 1.75 m to the
// ego's right, next to it, not 1.75 m right of the side vehicle's own lane centre.
TEST_F(LaneOffset, RelativeTargetIsBesideTheReferenceEntity) {
  load(offset_event("Approach", R"(<RelativeTargetLaneOffset entityRef="B" value="1.75"/>)", 0.5, at_time("T", 1.0)));
  // B's reference point is at y = -5.25; 1.75 m to its left is y = -3.5: A moves 1.75 m right.
  const double duration = std::numbers::pi * std::sqrt(1.75 / (2 * 0.5));
  test::run_until(*runtime_, 1.0 + duration + 0.5);
  EXPECT_EQ(a().lane, -1);
  EXPECT_NEAR(a().offset, -1.75, 1e-9);
  EXPECT_NEAR(a().pose.y, -3.5, 1e-9);
  EXPECT_EQ(test::transition_times(*runtime_, "ApproachAction", "endTransition").size(), 1u);
}

// OSC-ALKS 4.1_2's swerve: 1.5 m to the left, sinusoidal, maxLateralAcc 0.3 m/s^2. The
// standard's sinusoidal shape has zero slope at both ends (f = A sin(x) + B over half a
// period): the offset is 1.5 (1 - cos(pi tau / T)) / 2, whose peak lateral acceleration
// 1.5 / 2 (pi / T)^2 is maxLateralAcc, so T = pi sqrt(1.5 / 0.6) = 4.967 s. The shape runs
// one step behind the action's start, as esmini steps it (LateralProfile::lane_offset): the
// first step keeps the offset it starts from.
TEST_F(LaneOffset, SinusoidalShapeReachesMaxLateralAccelerationOnce) {
  load(offset_event("Swerve", R"(<AbsoluteTargetLaneOffset value="1.5"/>)", 0.3, at_time("T", 10.0)));
  const double duration = std::numbers::pi * std::sqrt(1.5 / (2 * 0.3));
  std::vector<double> y;  // every step from the start, to differentiate
  test::run_until(*runtime_, 10.0);
  while (runtime_->time() < 10.0 + duration + 0.2) {
    y.push_back(a().pose.y);
    runtime_->step(0.05);
  }
  for (std::size_t i = 0; i < y.size(); ++i) {
    const double tau = std::clamp(0.05 * (static_cast<double>(i) - 1), 0.0, duration);
    EXPECT_NEAR(y[i], -1.75 + 1.5 * 0.5 * (1 - std::cos(std::numbers::pi * tau / duration)), 1e-9) << "tau " << tau;
  }
  double peak = 0;  // second difference: the lateral acceleration
  for (std::size_t i = 1; i + 1 < y.size(); ++i) peak = std::max(peak, std::abs(y[i + 1] - 2 * y[i] + y[i - 1]) / 0.0025);
  EXPECT_NEAR(peak, 0.3, 0.01);
  // Ends at the first step at or after T, one step late: 10 + 0.05 + 4.967 -> 15.05.
  EXPECT_EQ(test::transition_times(*runtime_, "SwerveAction", "endTransition"), std::vector<double>{15.05});
  // Along its lane at its full 10 m/s all the while (the lateral motion on top, as in esmini).
  EXPECT_NEAR(a().s, 10.0 + 10.0 * runtime_->time(), 1e-6);
}

// The value is in the reference entity's coordinate system: positive is to its left, which
// is -t when it faces against the road's s.
TEST(RelativeLaneOffset, PositiveIsTheReferenceEntitysLeft) {
  const opendrive::RoadNetwork roads = opendrive::read_xodr_text(kStraightTwoLaneRoad, "road.xodr");
  EntityState side, reference;
  side.road_id = reference.road_id = "0";
  side.s = reference.s = 100;
  side.lane = -1;  // centre t = -1.75
  reference.lane = -2;
  reference.t = -5.25;
  reference.pose = {100, -5.25, 0.0};  // along +s: its left is +t
  EXPECT_NEAR(relative_lane_offset(side, reference, 1.75, roads), -1.75, 1e-12);   // t = -3.5
  EXPECT_NEAR(relative_lane_offset(side, reference, -1.75, roads), -5.25, 1e-12);  // t = -7.0
  reference.pose.heading = std::numbers::pi;  // facing against s: its left is -t
  EXPECT_NEAR(relative_lane_offset(side, reference, -1.75, roads), -1.75, 1e-12);
}

}  // namespace
}  // namespace orch::openscenario

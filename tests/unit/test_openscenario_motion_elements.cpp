// OpenSCENARIO 1.2/1.3 motion elements run by the storyboard on a straight road (no
// simulator): SpeedProfileAction in both following modes, RelativeClearanceCondition,
// ClothoidSpline trajectories, and a catalog Maneuver used twice that names its own event.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <memory>

#include "core/errors.hpp"
#include "opendrive/xodr_reader.hpp"
#include "openscenario/storyboard_runtime.hpp"
#include "openscenario/trajectory_motion.hpp"
#include "openscenario/xosc_reader.hpp"
#include "support/cli_runner.hpp"
#include "unit/openscenario_snippets.hpp"

namespace orch::openscenario {
namespace {

std::string time_trigger(double t) {
  return R"(<StartTrigger><ConditionGroup><Condition name="c" delay="0" conditionEdge="none"><ByValueCondition>
<SimulationTimeCondition value=")" + std::to_string(t) + R"(" rule="greaterOrEqual"/></ByValueCondition></Condition></ConditionGroup></StartTrigger>)";
}

// A does `action` (started by `trigger`); B is placed by `b_place`.
std::string scenario(const std::string& action, const std::string& trigger, const std::string& a_place,
                     const std::string& b_place, const std::string& catalogs = "",
                     const std::string& groups = "") {
  return R"(<?xml version="1.0"?><OpenSCENARIO>
<FileHeader revMajor="1" revMinor="3" date="2024-01-01T00:00:00" author="t" description="motion"/>)" + catalogs +
         R"(<RoadNetwork><LogicFile filepath="road.xodr"/></RoadNetwork>
<Entities>)" + test::vehicle("A") + test::vehicle("B") + R"(</Entities>
<Storyboard><Init><Actions>)" + a_place + b_place + R"(</Actions></Init>
<Story name="S"><Act name="Act">)" +
         (groups.empty() ? R"(<ManeuverGroup name="G" maximumExecutionCount="1">
<Actors selectTriggeringEntities="false"><EntityRef entityRef="A"/></Actors><Maneuver name="M">
<Event name="E" priority="parallel"><Action name="Go"><PrivateAction>)" + action + R"(</PrivateAction></Action>)" +
                               trigger + R"(</Event></Maneuver></ManeuverGroup>)"
                         : groups) +
         R"(</Act></Story>
<StopTrigger><ConditionGroup><Condition name="stop" delay="0" conditionEdge="none"><ByValueCondition>
<SimulationTimeCondition value="60" rule="greaterOrEqual"/></ByValueCondition></Condition></ConditionGroup></StopTrigger>
</Storyboard></OpenSCENARIO>)";
}

class MotionElements : public ::testing::Test {
 protected:
  void load(const std::string& text) {
    dir_.write("road.xodr", test::kStraightTwoLaneRoad);
    scenario_ = load_scenario(dir_.write("s.xosc", text).string());
    roads_ = opendrive::read_xodr_file((dir_ / "road.xodr").string());
    runtime_ = std::make_unique<StoryboardRuntime>(scenario_, roads_);
  }
  std::string load_error(const std::string& text) {
    try {
      load(text);
    } catch (const ScenarioError& e) {
      return e.what();
    }
    return "";
  }
  const EntityState& entity(const std::string& name) const { return runtime_->entities().at(name); }

  orch::test::TempDir dir_;
  Scenario scenario_;
  opendrive::RoadNetwork roads_;
  std::unique_ptr<StoryboardRuntime> runtime_;
};

std::string speed_profile(const std::string& mode, const std::string& constraints) {
  return R"(<LongitudinalAction><SpeedProfileAction followingMode=")" + mode + R"(">)" + constraints +
         R"(<SpeedProfileEntry time="0" speed="0"/><SpeedProfileEntry time="4" speed="10"/>
<SpeedProfileEntry time="4" speed="4"/><SpeedProfileEntry time="2" speed="8"/></SpeedProfileAction></LongitudinalAction>)";
}

TEST_F(MotionElements, SpeedProfilePositionModeIsLinearFromEntryToEntry) {
  load(scenario(speed_profile("position", ""), time_trigger(2), test::place("A", 10, -1, 0), test::place("B", 10, -2, 0)));
  // Each entry's time counts from the entry before: 10 m/s at 6 s, 4 m/s at 10 s, 8 m/s at 12 s.
  const std::vector<std::pair<double, double>> expected = {{2, 0}, {4, 5}, {6, 10}, {8, 7}, {10, 4}, {11, 6}, {12, 8}};
  for (const auto& [t, speed] : expected) {
    test::run_until(*runtime_, t);
    EXPECT_NEAR(entity("A").speed, speed, 1e-6) << "at " << t << " s";
  }
  test::run_until(*runtime_, 13);
  const std::vector<double> end = test::transition_times(*runtime_, "Go", "endTransition");
  ASSERT_EQ(end.size(), 1U);
  EXPECT_NEAR(end.front(), 12.0, 0.051);
  EXPECT_NEAR(entity("A").speed, 8.0, 1e-9);
}

TEST_F(MotionElements, SpeedProfileFollowModeKeepsItsConstraints) {
  load(scenario(speed_profile("follow", R"(<DynamicConstraints maxAcceleration="2" maxDeceleration="3"
 maxAccelerationRate="4" maxDecelerationRate="3" maxSpeed="20"/>)"),
                time_trigger(2), test::place("A", 10, -1, 0), test::place("B", 10, -2, 0)));
  double speed = entity("A").speed, acceleration = 0, top = 0;
  while (runtime_->time() < 30) {
    runtime_->step(0.05);
    if (!test::transition_times(*runtime_, "Go", "endTransition").empty()) break;  // its last step lands on 8 m/s
    const double a = (entity("A").speed - speed) / 0.05;
    EXPECT_LE(a, 2 + 1e-9) << runtime_->time();
    EXPECT_GE(a, -3 - 1e-9) << runtime_->time();
    EXPECT_LE(a - acceleration, 4 * 0.05 + 1e-9) << runtime_->time();  // rates: per step
    EXPECT_GE(a - acceleration, -3 * 0.05 - 1e-9) << runtime_->time();
    top = std::max(top, entity("A").speed);
    acceleration = a;
    speed = entity("A").speed;
  }
  EXPECT_LE(top, 10 + 1e-9);  // smoothed, never above the profile's top
  EXPECT_GT(top, 7.0);         // it did go for the 10 m/s entry
  ASSERT_EQ(test::transition_times(*runtime_, "Go", "endTransition").size(), 1U);
  EXPECT_NEAR(entity("A").speed, 8.0, 1e-9);
}

std::string clearance(const std::string& range) {
  return R"(<StartTrigger><ConditionGroup><Condition name="clear" delay="0" conditionEdge="none"><ByEntityCondition>
<TriggeringEntities triggeringEntitiesRule="any"><EntityRef entityRef="A"/></TriggeringEntities><EntityCondition>
<RelativeClearanceCondition distanceForward="40" distanceBackward="20" freeSpace="false" oppositeLanes="false">)" +
         range + R"(</RelativeClearanceCondition></EntityCondition></ByEntityCondition></Condition></ConditionGroup></StartTrigger>)";
}
const char* kKeepSpeed = R"(<LongitudinalAction><SpeedAction><SpeedActionDynamics dynamicsShape="step" dynamicsDimension="time" value="0"/>
<SpeedActionTarget><AbsoluteTargetSpeed value="10"/></SpeedActionTarget></SpeedAction></LongitudinalAction>)";

TEST_F(MotionElements, RelativeClearanceHoldsOnceTheLaneBesideIsFree) {
  // A in lane -2 at 10 m/s, B 20 m ahead in lane -1 (to A's left) at 20 m/s: lane -1 is
  // free 40 m ahead of A once B is more than 40 m ahead, at 2 s.
  load(scenario(kKeepSpeed, clearance(R"(<RelativeLaneRange from="1" to="1"/>)"), test::place("A", 100, -2, 10),
                test::place("B", 120, -1, 20)));
  test::run_until(*runtime_, 5);
  const std::vector<double> start = test::transition_times(*runtime_, "E", "startTransition");
  ASSERT_EQ(start.size(), 1U);
  EXPECT_NEAR(start.front(), 2.0, 0.051);
}

TEST_F(MotionElements, RelativeClearanceIsFalseWithoutALaneToCheck) {
  // Two lanes to A's left of lane -2 is beyond the road: nothing is clear there.
  load(scenario(kKeepSpeed, clearance(R"(<RelativeLaneRange from="2" to="2"/>)"), test::place("A", 100, -2, 10),
                test::place("B", 300, -1, 20)));
  test::run_until(*runtime_, 3);
  EXPECT_TRUE(test::transition_times(*runtime_, "E", "startTransition").empty());
}

TEST_F(MotionElements, RelativeClearanceOnlyCountsTheListedEntities) {
  // B is in the lane but not listed: the lane counts as clear from the start.
  load(scenario(kKeepSpeed,
                clearance(R"(<RelativeLaneRange from="1" to="1"/><EntityRef entityRef="A"/>)"),
                test::place("A", 100, -2, 10), test::place("B", 110, -1, 10)));
  test::run_until(*runtime_, 1);
  EXPECT_EQ(test::transition_times(*runtime_, "E", "startTransition").size(), 1U);
}

TEST(ClothoidSpline, SegmentsJoinEndToStartAndTurnByTheirOffsets) {
  ClothoidSplineShape spline;
  spline.segments.push_back({std::nullopt, 0.01, 0.01, 15, 0, std::nullopt});  // arc of radius 100
  spline.segments.push_back({std::nullopt, 0.0, 0.0, 5, 0, std::nullopt});     // then straight on
  const std::vector<PathPoint> points = clothoid_spline_points(spline, {std::nullopt, std::nullopt}, {10, 20, 0});
  const double turn = 0.15;  // 15 m at 1/100 m
  const double x = 10 + 100 * std::sin(turn) + 5 * std::cos(turn);
  const double y = 20 + 100 * (1 - std::cos(turn)) + 5 * std::sin(turn);
  EXPECT_NEAR(points.back().x, x, 1e-6);
  EXPECT_NEAR(points.back().y, y, 1e-6);
  for (std::size_t i = 1; i < points.size(); ++i)  // no repeated joint point
    EXPECT_GT(std::hypot(points[i].x - points[i - 1].x, points[i].y - points[i - 1].y), 1e-3);
  // An entity on it faces along the curve's tangent, not a chord's: at the arc's end, 0.15
  // rad (a chord of the last piece is half that piece's turn short of it).
  const PathMotion path = make_path(points, false);
  EXPECT_NEAR(path.pose_at(15.0).heading, turn, 1e-9);
  EXPECT_NEAR(path.pose_at(path.length()).heading, turn, 1e-9);
  EXPECT_NEAR(path.pose_at(7.5).heading, 0.075, 1e-4);
  const PathMotion arc = make_path(clothoid_points({0, 0, 0}, 0.01, 0, 15), false);
  EXPECT_NEAR(arc.pose_at(arc.length()).heading, turn, 1e-9);  // where the entity leaves it

  // A PositionStart places its segment; hOffset turns it.
  spline.segments[1].heading_offset = 0.5;
  const std::vector<PathPoint> moved =
      clothoid_spline_points(spline, {std::nullopt, opendrive::Pose2{0, 0, 0.2}}, {10, 20, 0});
  EXPECT_NEAR(moved.back().x, 5 * std::cos(0.7), 1e-6);
  EXPECT_NEAR(moved.back().y, 5 * std::sin(0.7), 1e-6);
}

TEST_F(MotionElements, ClothoidSplineTrajectoryIsFollowedFromTheEntity) {
  load(scenario(R"(<RoutingAction><FollowTrajectoryAction><TrajectoryRef><Trajectory name="T" closed="false"><Shape><ClothoidSpline>
<ClothoidSplineSegment curvatureStart="0" curvatureEnd="0" length="20"/>
<ClothoidSplineSegment curvatureStart="0" curvatureEnd="0" length="10" hOffset="1.5707963267948966"/>
</ClothoidSpline></Shape></Trajectory></TrajectoryRef><TimeReference><None/></TimeReference>
<TrajectoryFollowingMode followingMode="position"/></FollowTrajectoryAction></RoutingAction>)",
                time_trigger(0), test::place("A", 100, -1, 10), test::place("B", 300, -2, 0)));
  test::run_until(*runtime_, 2.5);  // 25 m: 20 along x from (100, -1.75), then 5 up
  EXPECT_NEAR(entity("A").pose.x, 120.0, 0.05);
  EXPECT_NEAR(entity("A").pose.y, -1.75 + 5.0, 0.05);
  EXPECT_NE(load_error(scenario(R"(<RoutingAction><FollowTrajectoryAction><TrajectoryRef><Trajectory name="T" closed="false"><Shape><ClothoidSpline>
<ClothoidSplineSegment curvatureStart="0" curvatureEnd="0" length="-2"/></ClothoidSpline></Shape></Trajectory></TrajectoryRef>
<TimeReference><None/></TimeReference><TrajectoryFollowingMode followingMode="position"/></FollowTrajectoryAction></RoutingAction>)",
                                time_trigger(0), test::place("A", 100, -1, 10), test::place("B", 300, -2, 0)))
                .find("ClothoidSplineSegment/@length"),
            std::string::npos);
}

TEST(ClosedTrajectory, ReturnsToItsStartAtItsLastPiecesSpeed) {
  // Untimed: a segment back to the first point is added.
  std::vector<PathPoint> square{{0, 0, 0, std::nullopt, std::nullopt}, {10, 0, 0, std::nullopt, std::nullopt},
                                {10, 10, 0, std::nullopt, std::nullopt}};
  close_path(square);
  ASSERT_EQ(square.size(), 4u);
  EXPECT_EQ(square.back().x, 0.0);
  EXPECT_EQ(square.back().y, 0.0);
  EXPECT_FALSE(square.back().due);
  // Timed: the last piece runs at 10 m/s, so the 10 m back take 1 s.
  std::vector<PathPoint> timed{{0, 0, 0, 2.0, std::nullopt}, {10, 0, 0, 3.0, std::nullopt}};
  close_path(timed);
  ASSERT_EQ(timed.size(), 3u);
  EXPECT_DOUBLE_EQ(*timed.back().due, 4.0);
  // Already closed: nothing added.
  std::vector<PathPoint> loop{{0, 0, 0, std::nullopt, std::nullopt}, {10, 0, 0, std::nullopt, std::nullopt}, {0, 0, 0, std::nullopt, std::nullopt}};
  close_path(loop);
  EXPECT_EQ(loop.size(), 3u);
}

TEST_F(MotionElements, AClosedTrajectoryIsFollowedBackToItsStart) {
  // (100, -1.75) -> (120, -1.75) in 2 s -> (120, 8.25) in 1 s, then back to the start (22.36 m at
  // the last piece's 10 m/s: due at 5.24 s).
  load(scenario(R"(<RoutingAction><FollowTrajectoryAction><TrajectoryRef><Trajectory name="T" closed="true"><Shape><Polyline>
<Vertex time="0"><Position><WorldPosition x="100" y="-1.75" h="0"/></Position></Vertex>
<Vertex time="2"><Position><WorldPosition x="120" y="-1.75" h="0"/></Position></Vertex>
<Vertex time="3"><Position><WorldPosition x="120" y="8.25" h="0"/></Position></Vertex>
</Polyline></Shape></Trajectory></TrajectoryRef><TimeReference><Timing domainAbsoluteRelative="absolute" scale="1" offset="0"/></TimeReference>
<TrajectoryFollowingMode followingMode="position"/></FollowTrajectoryAction></RoutingAction>)",
                time_trigger(0), test::place("A", 100, -1, 10), test::place("B", 300, -2, 0)));
  test::run_until(*runtime_, 5.0);  // 2 s of the 2.236 s back: 0.894 of the way
  const double f = 2.0 / std::hypot(20.0, 10.0) * 10.0;
  EXPECT_NEAR(entity("A").pose.x, 120.0 - 20.0 * f, 0.05);
  EXPECT_NEAR(entity("A").pose.y, 8.25 - 10.0 * f, 0.05);
}

// A ManeuverCatalog entry whose second event waits for its first, by name alone.
const char* kManeuverCatalog = R"(<?xml version="1.0"?><OpenSCENARIO>
<FileHeader revMajor="1" revMinor="3" date="2024-01-01T00:00:00" author="t" description="c"/>
<Catalog name="Maneuvers"><Maneuver name="Twice">
<Event name="First" priority="parallel"><Action name="Slow"><PrivateAction><LongitudinalAction><SpeedAction>
<SpeedActionDynamics dynamicsShape="step" dynamicsDimension="time" value="0"/><SpeedActionTarget><AbsoluteTargetSpeed value="5"/></SpeedActionTarget>
</SpeedAction></LongitudinalAction></PrivateAction></Action></Event>
<Event name="Second" priority="parallel"><Action name="Fast"><PrivateAction><LongitudinalAction><SpeedAction>
<SpeedActionDynamics dynamicsShape="step" dynamicsDimension="time" value="0"/><SpeedActionTarget><AbsoluteTargetSpeed value="15"/></SpeedActionTarget>
</SpeedAction></LongitudinalAction></PrivateAction></Action>
<StartTrigger><ConditionGroup><Condition name="after" delay="1" conditionEdge="none"><ByValueCondition>
<StoryboardElementStateCondition storyboardElementType="event" storyboardElementRef="First" state="endTransition"/>
</ByValueCondition></Condition></ConditionGroup></StartTrigger></Event>
</Maneuver></Catalog></OpenSCENARIO>)";

std::string group_using_catalog(const std::string& group, const std::string& actor) {
  return R"(<ManeuverGroup name=")" + group + R"(" maximumExecutionCount="1"><Actors selectTriggeringEntities="false">
<EntityRef entityRef=")" + actor + R"("/></Actors><CatalogReference catalogName="Maneuvers" entryName="Twice"/></ManeuverGroup>)";
}

TEST_F(MotionElements, CatalogManeuverUsedTwiceNamesItsOwnEvent) {
  std::filesystem::create_directories(dir_ / "catalogs");
  dir_.write("catalogs/maneuvers.xosc", kManeuverCatalog);
  load(scenario("", "", test::place("A", 100, -1, 10), test::place("B", 100, -2, 10),
                R"(<CatalogLocations><ManeuverCatalog><Directory path="./catalogs"/></ManeuverCatalog></CatalogLocations>)",
                group_using_catalog("GA", "A") + group_using_catalog("GB", "B")));
  // Each instance's "First" is its own: both Second events start 1 s after the start.
  for (const ManeuverGroup& g : scenario_.storyboard.stories[0].acts[0].groups) {
    const Condition& c = g.maneuvers[0].events[1].start_trigger->groups[0][0];
    const std::string& key = std::get<StoryboardElementStateCondition>(c.kind).key;
    EXPECT_EQ(key.rfind(g.key + "::", 0), 0U) << key << " is not inside " << g.key;
  }
  test::run_until(*runtime_, 2);
  EXPECT_EQ(test::transition_times(*runtime_, "Second", "startTransition").size(), 2U);
  EXPECT_NEAR(entity("A").speed, 15.0, 1e-9);
  EXPECT_NEAR(entity("B").speed, 15.0, 1e-9);
}

}  // namespace
}  // namespace orch::openscenario

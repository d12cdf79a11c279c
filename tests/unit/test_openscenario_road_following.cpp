// Storyboard entities driving on through OpenDRIVE links: across a road end (also where the
// direction flips), through a junction straight on by default or as the route plans, lane
// sections renumbering lanes, dead ends (EndOfRoadCondition), AcquirePosition and routes in
// a scenario, and the SUMO-bound lanes ahead.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>

#include "core/errors.hpp"
#include "opendrive/xodr_reader.hpp"
#include "openscenario/road_following.hpp"
#include "openscenario/route_plan.hpp"
#include "openscenario/storyboard_runtime.hpp"
#include "openscenario/xosc_reader.hpp"
#include "support/cli_runner.hpp"
#include "unit/openscenario_snippets.hpp"
#include "unit/xodr_network_snippets.hpp"

namespace orch::openscenario {
namespace {

constexpr double kPi = std::numbers::pi;

EntityState on_lane(const opendrive::RoadNetwork& roads, const std::string& road, int lane, double s, double speed) {
  EntityState state;
  state.placed = true;
  state.road_id = road;
  state.lane = lane;
  state.s = s;
  state.speed = speed;
  update_pose(state, roads);
  return state;
}

// Steps of 0.05 s for `seconds` at constant speed.
void drive(EntityState& state, const opendrive::RoadNetwork& roads, double seconds) {
  double t = 0;
  for (int i = 0; i < static_cast<int>(std::lround(seconds / 0.05)); ++i) {
    t += 0.05;
    advance(state, roads, t, 0.05);
  }
}

std::vector<std::string> roads_of(const std::vector<opendrive::LaneEntry>& entries) {
  std::vector<std::string> out;
  for (const auto& e : entries) out.push_back(e.road_id);
  return out;
}

TEST(RoadFollowing, DrivesOnAcrossARoadEndWithTheRemainingDistance) {
  const auto roads = opendrive::read_xodr_text(test::xodr_two_in_a_row(), "row.xodr");
  EntityState car = on_lane(roads, "1", -1, 95, 10);
  drive(car, roads, 1.0);
  EXPECT_EQ(car.road_id, "2");
  EXPECT_EQ(car.lane, -1);
  EXPECT_NEAR(car.s, 5.0, 1e-9);
  EXPECT_NEAR(car.pose.x, 105.0, 1e-9);
  EXPECT_NEAR(car.pose.y, -1.75, 1e-9);
  EXPECT_NEAR(car.odometer, 10.0, 1e-9);
}

// The traveled distance is the sum of the straight steps between successive positions (as
// esmini's odometer): on a curve of radius 20 m each 0.5 m step along the lane is a chord
// L^3 / (24 R^2) = 1.3e-5 m shorter, so 10 steps at 10 m/s fall short of 5 m and a
// TraveledDistanceCondition of 5 m fires a step later (esmini's pedestrian.xosc).
TEST(RoadFollowing, TheOdometerAddsTheStraightStepsBetweenPositions) {
  test::XodrRoad curve;
  curve.id = "1";
  curve.curvature = 0.05;
  const auto roads = opendrive::read_xodr_text(test::xodr_file(test::xodr_road(curve)), "curve.xodr");
  EntityState car = on_lane(roads, "1", -1, 10, 10);
  drive(car, roads, 0.5);
  const double step = 10.0 * 0.05;  // along the lane
  const double radius = 20.0 + 1.75;  // lane -1's centre, on the outside of the left curve
  const double chord = 2 * radius * std::sin(step / (2 * radius));
  EXPECT_NEAR(car.odometer, 10 * chord, 1e-6);
  EXPECT_LT(car.odometer, 5.0 - 1e-6);
  drive(car, roads, 0.05);
  EXPECT_GT(car.odometer, 5.0);
}

// A lane that narrows to width 0 within its section (no lane section of its own where it
// ends): the entity on it goes on in the nearest lane of its type that has a width, in the
// step the width reaches 0 (as esmini: trailers.xosc on multi_intersections.xodr road 209).
TEST(RoadFollowing, AnEntityOnALaneNarrowedToNothingGoesOnInTheNearestLane) {
  const std::string road = R"(<road id="1" length="100" junction="-1"><link/>
<planView><geometry s="0" x="0" y="0" hdg="0" length="100"><line/></geometry></planView>
<lanes><laneSection s="0"><center><lane id="0" type="none"/></center><right>
<lane id="-1" type="driving"><width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane>
<lane id="-2" type="driving"><width sOffset="0" a="3.5" b="0" c="0" d="0"/><width sOffset="50" a="0" b="0" c="0" d="0"/></lane>
<lane id="-3" type="sidewalk"><width sOffset="0" a="2" b="0" c="0" d="0"/></lane>
</right></laneSection></lanes></road>)";
  const auto roads = opendrive::read_xodr_text(test::xodr_file(road), "narrowing.xodr");
  EntityState car = on_lane(roads, "1", -2, 40, 10);
  drive(car, roads, 0.95);
  EXPECT_EQ(car.lane, -2);
  EXPECT_NEAR(car.pose.y, -5.25, 1e-9);
  drive(car, roads, 0.1);  // past s = 50
  EXPECT_EQ(car.lane, -1);  // not the sidewalk, whose centre is nearer
  EXPECT_NEAR(car.pose.y, -1.75, 1e-9);
}

TEST(RoadFollowing, AStandingEntityKeepsTheHeadingItWasPlacedWithUntilItDrivesOff) {
  const auto roads = opendrive::read_xodr_text(test::xodr_two_in_a_row(), "row.xodr");
  EntityState car = on_lane(roads, "1", -1, 50, 0);
  car.pose.heading = kPi / 2;  // parked across its lane (a position's Orientation)
  drive(car, roads, 1.0);
  EXPECT_NEAR(car.pose.heading, kPi / 2, 1e-12);
  EXPECT_NEAR(car.pose.x, 50.0, 1e-9);
  car.speed = 5;  // drives off: along its lane
  drive(car, roads, 0.05);
  EXPECT_NEAR(car.pose.heading, 0.0, 1e-9);
}

TEST(RoadFollowing, AContactPointEndFlipsTheDirectionAndThePoseStaysContinuous) {
  const auto roads = opendrive::read_xodr_text(test::xodr_contact_end(), "flip.xodr");
  EntityState car = on_lane(roads, "1", -1, 95, 10);
  car.offset = 0.3;  // 0.3 m left of the lane centre, i.e. towards +y on road 1
  update_pose(car, roads);
  drive(car, roads, 1.0);
  EXPECT_EQ(car.road_id, "3");
  EXPECT_EQ(car.lane, 1);
  EXPECT_NEAR(car.s, 45.0, 1e-9);  // road 3 runs back: s falls as the car goes on
  EXPECT_NEAR(car.pose.x, 105.0, 1e-9);
  EXPECT_NEAR(car.pose.y, -1.75 + 0.3, 1e-9);  // still 0.3 m to its left: the offset flipped sign on road 3
  EXPECT_NEAR(car.offset, -0.3, 1e-12);
  EXPECT_NEAR(car.pose.heading, 0.0, 1e-9);
  drive(car, roads, 5.0);  // 45 m more: road 3's lane 1 ends at s = 0 onto road 1's lane 1... which drives back
  EXPECT_EQ(car.road_id, "3");
  EXPECT_NEAR(car.s, 0.0, 1e-12);  // road 3's start has no link: the car stays at the end
  EXPECT_TRUE(at_dead_end(car, roads));
}

TEST(RoadFollowing, AtAJunctionWithoutARouteTheCarGoesStraightOn) {
  const auto roads = opendrive::read_xodr_text(test::xodr_three_way(), "junction.xodr");
  EntityState car = on_lane(roads, "1", -1, 90, 10);
  drive(car, roads, 2.0);  // 10 m to the junction, 10 m on connecting road 10
  EXPECT_EQ(car.road_id, "10");
  EXPECT_NEAR(car.s, 10.0, 1e-9);
  drive(car, roads, 2.0);
  EXPECT_EQ(car.road_id, "2");
  EXPECT_NEAR(car.pose.x, 130.0, 1e-9);
  EXPECT_NEAR(car.pose.y, -1.75, 1e-9);
  EXPECT_FALSE(at_dead_end(car, roads));
}

TEST(RoadFollowing, TheRoutePlanTurnsAtTheJunction) {
  const auto roads = opendrive::read_xodr_text(test::xodr_three_way(), "junction.xodr");
  EntityState car = on_lane(roads, "1", -1, 90, 10);
  car.route = {{"3", 50, -1}};
  plan_entity_route(car, roads, {{car.route[0], opendrive::RouteStrategy::Shortest, "waypoint 1"}}, false);
  ASSERT_EQ(roads_of(car.route_plan), (std::vector<std::string>{"11", "3"}));
  drive(car, roads, 4.0);  // 10 m, the turn, then up road 3
  EXPECT_EQ(car.road_id, "3");
  EXPECT_EQ(car.route_plan_next, 2u);
  // Lane -1 runs 1.75 m outside the turn's reference line (radius 10): its path is 1.175
  // times as long as the 15.71 m of s; the 40 m driven are measured along the car's path.
  const double on_turn = 10 * kPi / 2 * 1.175;
  EXPECT_NEAR(car.s, 40.0 - 10.0 - on_turn, 1e-6);
  EXPECT_NEAR(car.pose.x, 111.75, 1e-9);
  EXPECT_NEAR(car.pose.heading, kPi / 2, 1e-9);
}

TEST(RoadFollowing, LaneLinksRenumberTheLaneBetweenSections) {
  const std::string road = R"(<OpenDRIVE><header revMajor="1" revMinor="6"/><road id="1" length="100" junction="-1">
<planView><geometry s="0" x="0" y="0" hdg="0" length="100"><line/></geometry></planView>
<lanes><laneSection s="0"><center><lane id="0" type="none"/></center>
<right><lane id="-1" type="driving"><link><successor id="-2"/></link><width sOffset="0" a="3.5"/></lane></right></laneSection>
<laneSection s="60"><center><lane id="0" type="none"/></center>
<right><lane id="-1" type="driving"><width sOffset="0" a="3.0"/></lane>
<lane id="-2" type="driving"><link><predecessor id="-1"/></link><width sOffset="0" a="3.5"/></lane></right></laneSection></lanes></road></OpenDRIVE>)";
  const auto roads = opendrive::read_xodr_text(road, "sections.xodr");
  EntityState car = on_lane(roads, "1", -1, 50, 10);
  drive(car, roads, 2.0);
  EXPECT_EQ(car.lane, -2);
  EXPECT_NEAR(car.pose.y, -3.0 - 1.75, 1e-9);  // outside the new 3 m inner lane
  drive(car, roads, 4.0);
  EXPECT_NEAR(car.s, 100.0, 1e-12);
  EXPECT_TRUE(at_dead_end(car, roads));
}

TEST(RoutePlan, ClosedRoutesLoopAndLanesAheadContinueStraightOn) {
  const auto roads = opendrive::read_xodr_text(test::xodr_three_way(), "junction.xodr");
  EntityState car = on_lane(roads, "2", 1, 50, 10);  // lane 1 of road 2 drives back to the junction
  // Without a route: back over connecting road 10 onto road 1's lane 1, then road 1's start ends it.
  EXPECT_EQ(roads_of(lanes_ahead(car, roads)), (std::vector<std::string>{"10", "1"}));
  // A route onto road 1 and back is unreachable: road 1's lane 1 has nowhere to turn.
  car.route = {{"1", 50, 1}, {"2", 50, -1}};
  try {
    plan_entity_route(car, roads,
                      {{car.route[0], opendrive::RouteStrategy::Shortest, "waypoint 1 of route \"R\""},
                       {car.route[1], opendrive::RouteStrategy::Shortest, "waypoint 2 of route \"R\""}},
                      true);
    FAIL() << "expected an error";
  } catch (const MapError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("waypoint 2 of route \"R\" (road 2, lane -1, s 50.00) cannot be reached from road 1, lane 1"),
              std::string::npos)
        << what;
  }
}

TEST(RoutePlan, AParkedEntityOrOneInTheOncomingLaneStartsItsRouteFromALaneGoingThere) {
  // One road along +x, lane 1 (driving against s, to the road's start) and lane -1.
  const auto roads = opendrive::read_xodr_text(R"(<OpenDRIVE><header revMajor="1" revMinor="6"/>
<road id="0" length="100" junction="-1"><planView><geometry s="0" x="0" y="0" hdg="0" length="100"><line/></geometry></planView>
<lanes><laneSection s="0"><left><lane id="1" type="driving"><width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane></left>
<right><lane id="-1" type="driving"><width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane></right></laneSection></lanes></road></OpenDRIVE>)",
                                               "one.xodr");
  const auto plan = [&](double heading, int direction = 0) {
    EntityState car = on_lane(roads, "0", 1, 50, 0);
    car.pose.heading = heading;
    car.direction = direction;
    car.route = {{"0", 80, -1}};
    plan_entity_route(car, roads, {{car.route[0], opendrive::RouteStrategy::Shortest, "waypoint 1"}}, false);
    return car.route_plan;
  };
  // Facing along its lane (against s), s = 80 is behind it: no route.
  EXPECT_THROW(plan(kPi), MapError);
  EXPECT_THROW(plan(kPi / 4), MapError);  // 45 degrees off the road: still driving its lane's way
  // Parked across the road (esmini's parking_demo.xosc): planned from lane -1, the nearest lane going there.
  EXPECT_NO_THROW(plan(kPi / 2));
  EXPECT_NO_THROW(plan(-kPi / 2));
  // In the oncoming lane but driving along s (it keeps its way): from a lane driving its way.
  EXPECT_NO_THROW(plan(0, 1));
}

TEST(RoutePlan, AClosedRouteRepeatsItsLoop) {
  // A ring: road 1 -> road 2 -> road 1 (both ends linked).
  const std::string ring = test::xodr_file(test::xodr_road({"1", 0, 0, 0, 100, "road 2 end", "road 2 start"}) +
                                           test::xodr_road({"2", 100, 0, kPi, 100, "road 1 end", "road 1 start"}));
  const auto roads = opendrive::read_xodr_text(ring, "ring.xodr");
  EntityState car = on_lane(roads, "1", -1, 10, 10);
  car.route = {{"1", 50, -1}, {"2", 50, -1}};
  plan_entity_route(car, roads,
                    {{car.route[0], opendrive::RouteStrategy::Shortest, "w1"},
                     {car.route[1], opendrive::RouteStrategy::Shortest, "w2"}},
                    true);
  EXPECT_EQ(roads_of(car.route_plan), (std::vector<std::string>{"2", "1"}));
  ASSERT_TRUE(car.route_plan_loop);
  EXPECT_EQ(*car.route_plan_loop, 0u);
  EXPECT_EQ(roads_of(lanes_ahead(car, roads)), (std::vector<std::string>{"2", "1", "2", "1", "2", "1"}));
  drive(car, roads, 25.0);  // 250 m: road 1 (90), road 2 (100), road 1 again (60)
  EXPECT_EQ(car.road_id, "1");
  EXPECT_NEAR(car.s, 60.0, 1e-6);
  EXPECT_EQ(car.route_plan_next, 0u);  // wrapped round to the loop's start
}

// A scenario on the three-way junction: A's route turns left onto road 3, B goes straight
// on; C acquires a position on road 3.
class JunctionScenario : public ::testing::Test {
 protected:
  void load(const std::string& a_events, const std::string& init_extra = "", const std::string& route_catalog = "",
            const std::string& init_first = "") {
    const auto teleport = [](const std::string& name, double s, double speed) {
      return R"(<Private entityRef=")" + name + R"("><PrivateAction><TeleportAction><Position><LanePosition roadId="1" laneId="-1" s=")" +
             std::to_string(s) + R"(" offset="0"/></Position></TeleportAction></PrivateAction>
  <PrivateAction><LongitudinalAction><SpeedAction><SpeedActionDynamics dynamicsShape="step" dynamicsDimension="time" value="0"/>
  <SpeedActionTarget><AbsoluteTargetSpeed value=")" + std::to_string(speed) + R"("/></SpeedActionTarget></SpeedAction></LongitudinalAction></PrivateAction></Private>)";
    };
    const std::string text = R"(<?xml version="1.0"?><OpenSCENARIO>
<FileHeader revMajor="1" revMinor="2" date="2024-01-01T00:00:00" author="t" description="junction"/>
<CatalogLocations><RouteCatalog><Directory path="./catalogs"/></RouteCatalog></CatalogLocations>
<RoadNetwork><LogicFile filepath="road.xodr"/></RoadNetwork>
<Entities>)" + test::vehicle("A") + test::vehicle("B") + R"(</Entities>
<Storyboard><Init><Actions>)" + init_first + teleport("A", 50, 10) + teleport("B", 30, 10) + init_extra + R"(</Actions></Init>
<Story name="S"><Act name="Act"><ManeuverGroup name="G" maximumExecutionCount="1">
<Actors selectTriggeringEntities="false"><EntityRef entityRef="A"/></Actors><Maneuver name="M">)" + a_events +
                             R"(</Maneuver></ManeuverGroup><StartTrigger><ConditionGroup><Condition name="c" delay="0" conditionEdge="none"><ByValueCondition><SimulationTimeCondition value="0" rule="greaterOrEqual"/></ByValueCondition></Condition>
</ConditionGroup></StartTrigger></Act></Story>
<StopTrigger><ConditionGroup><Condition name="stop" delay="0" conditionEdge="none"><ByValueCondition><SimulationTimeCondition value="100" rule="greaterOrEqual"/></ByValueCondition></Condition></ConditionGroup></StopTrigger></Storyboard></OpenSCENARIO>)";
    dir_.write("road.xodr", test::xodr_three_way());
    std::filesystem::create_directories(dir_ / "catalogs");
    dir_.write("catalogs/routes.xosc", R"(<?xml version="1.0"?><OpenSCENARIO>
<FileHeader revMajor="1" revMinor="2" date="2024-01-01T00:00:00" author="t" description="routes"/>
<Catalog name="routes">)" + route_catalog + "</Catalog></OpenSCENARIO>");
    scenario_ = load_scenario(dir_.write("s.xosc", text).string());
    roads_ = opendrive::read_xodr_file((dir_ / "road.xodr").string());
    runtime_ = std::make_unique<StoryboardRuntime>(scenario_, roads_);
  }
  static std::string event(const std::string& name, const std::string& body, double at) {
    return R"(<Event name=")" + name + R"(" priority="parallel"><Action name=")" + name + R"(Action"><PrivateAction>)" + body +
           R"(</PrivateAction></Action><StartTrigger><ConditionGroup><Condition name="c" delay="0" conditionEdge="none"><ByValueCondition><SimulationTimeCondition value=")" +
           std::to_string(at) + R"(" rule="greaterOrEqual"/></ByValueCondition></Condition></ConditionGroup></StartTrigger></Event>)";
  }
  static std::string lane_position(const std::string& road, double s, int lane) {
    return R"(<Position><LanePosition roadId=")" + road + R"(" laneId=")" + std::to_string(lane) + R"(" s=")" +
           std::to_string(s) + R"(" offset="0"/></Position>)";
  }
  const EntityState& entity(const std::string& name) const { return runtime_->entities().at(name); }

  orch::test::TempDir dir_;
  Scenario scenario_;
  opendrive::RoadNetwork roads_;
  std::unique_ptr<StoryboardRuntime> runtime_;
};

TEST_F(JunctionScenario, TheRoutedEntityTurnsAndTheOtherGoesStraightOn) {
  load(event("Route",
             R"(<RoutingAction><AssignRouteAction><Route name="Left" closed="false"><Waypoint routeStrategy="shortest">)" +
                 lane_position("1", 60, -1) + R"(</Waypoint><Waypoint routeStrategy="shortest">)" +
                 lane_position("3", 60, -1) + "</Waypoint></Route></AssignRouteAction></RoutingAction>",
             1));
  test::run_until(*runtime_, 15);
  EXPECT_EQ(entity("A").road_id, "3");
  EXPECT_NEAR(entity("A").pose.x, 111.75, 1e-6);
  EXPECT_NEAR(entity("A").s, 150.0 - 50.0 - 10 * kPi / 2 * 1.175, 1e-6);
  EXPECT_EQ(entity("A").route_passed, 2u);  // s = 81.5 > 60 on road 3
  EXPECT_EQ(entity("B").road_id, "2");
  EXPECT_NEAR(entity("B").pose.y, -1.75, 1e-6);
}

// esmini's routing-test.xosc assigns the route in Init before the TeleportAction places the
// entity: Init actions all take effect at 0 s, so the route is planned from where the entity
// is placed (before, it was planned from no position: no plan, and B went straight on).
TEST_F(JunctionScenario, ARouteAssignedInInitBeforeTheTeleportTurns) {
  load(event("Route", R"(<RoutingAction><AssignRouteAction><CatalogReference catalogName="routes" entryName="Left"/></AssignRouteAction></RoutingAction>)", 1),
       "",
       R"(<Route name="Left" closed="false"><Waypoint routeStrategy="shortest">)" + lane_position("1", 60, -1) +
           R"(</Waypoint><Waypoint routeStrategy="shortest">)" + lane_position("3", 60, -1) + "</Waypoint></Route>",
       R"(<Private entityRef="B"><PrivateAction><RoutingAction><AssignRouteAction><CatalogReference catalogName="routes" entryName="Left"/></AssignRouteAction></RoutingAction></PrivateAction></Private>)");
  EXPECT_FALSE(entity("B").route_plan.empty());
  test::run_until(*runtime_, 15);
  EXPECT_EQ(entity("B").road_id, "3");
}

TEST_F(JunctionScenario, ARouteFromTheRouteCatalogTurnsToo) {
  load(event("Route", R"(<RoutingAction><AssignRouteAction><CatalogReference catalogName="routes" entryName="Left"/></AssignRouteAction></RoutingAction>)", 1),
       "",
       R"(<Route name="Left" closed="false"><Waypoint routeStrategy="leastIntersections">)" + lane_position("1", 60, -1) +
           R"(</Waypoint><Waypoint routeStrategy="leastIntersections">)" + lane_position("3", 60, -1) + "</Waypoint></Route>");
  test::run_until(*runtime_, 15);
  EXPECT_EQ(entity("A").road_id, "3");
  EXPECT_EQ(entity("B").road_id, "2");
}

TEST_F(JunctionScenario, AcquirePositionPlansThroughTheJunctionAndEndsThere) {
  load(event("Acquire", "<RoutingAction><AcquirePositionAction>" + lane_position("3", 20, -1) +
                            "</AcquirePositionAction></RoutingAction>",
             1));
  test::run_until(*runtime_, 12);
  const auto ends = test::transition_times(*runtime_, "AcquireAction", "endTransition");
  ASSERT_EQ(ends.size(), 1u);
  // 50 m to the junction, 18.46 m of turn (lane -1's path), 20 m on road 3: 88.46 m at 10 m/s.
  EXPECT_NEAR(ends[0], 8.85, 0.05 + 1e-9);
  EXPECT_EQ(entity("A").road_id, "3");
}

TEST_F(JunctionScenario, AnUnreachableWaypointIsAnErrorNamingItsElement) {
  // Road 2's lane 1 drives away from road 2's end: a waypoint there cannot be reached by A.
  load(event("Route",
             R"(<RoutingAction><AssignRouteAction><Route name="Back" closed="false"><Waypoint routeStrategy="shortest">)" +
                 lane_position("1", 60, -1) + R"(</Waypoint><Waypoint routeStrategy="fastest">)" +
                 lane_position("2", 60, 1) + "</Waypoint></Route></AssignRouteAction></RoutingAction>",
             1));
  try {
    test::run_until(*runtime_, 2);
    FAIL() << "expected an error";
  } catch (const MapError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("waypoint 2 of route \"Back\" of \"A\" (/OpenSCENARIO/Storyboard/"), std::string::npos) << what;
    EXPECT_NE(what.find("/Waypoint[2], line 22)"), std::string::npos) << what;
    EXPECT_NE(what.find("cannot be reached"), std::string::npos) << what;
  }
}

TEST(RoadFollowing, EndOfRoadHoldsOnlyAtADeadEndInTheDirectionOfTravel) {
  const auto roads = opendrive::read_xodr_text(test::xodr_three_way(), "junction.xodr");
  EXPECT_FALSE(at_dead_end(on_lane(roads, "1", -1, 0, 10), roads));    // s = 0 is behind it
  EXPECT_FALSE(at_dead_end(on_lane(roads, "1", -1, 100, 10), roads));  // into the junction
  EXPECT_TRUE(at_dead_end(on_lane(roads, "1", 1, 0, 10), roads));      // lane 1 ends at road 1's start
  EXPECT_TRUE(at_dead_end(on_lane(roads, "2", -1, 100, 10), roads));
  EXPECT_FALSE(at_dead_end(on_lane(roads, "2", -1, 99, 10), roads));
}

// At a dead end the car stops, but not in the step it gets there: an action the arrival
// triggers (a TeleportAction on EndOfRoadCondition, esmini's lane_change_simple.xosc) finds
// the speed it came with; a step later, still at the end, it stands.
TEST(RoadFollowing, ACarArrivingAtADeadEndKeepsItsSpeedForThatStepThenStands) {
  const auto roads = opendrive::read_xodr_text(test::xodr_three_way(), "junction.xodr");
  EntityState car = on_lane(roads, "2", -1, 99.7, 10);
  advance(car, roads, 0.05, 0.05);  // 0.5 m: past the end
  EXPECT_DOUBLE_EQ(car.s, 100.0);
  EXPECT_DOUBLE_EQ(car.speed, 10.0);
  EXPECT_TRUE(at_dead_end(car, roads));
  advance(car, roads, 0.10, 0.05);
  EXPECT_DOUBLE_EQ(car.s, 100.0);
  EXPECT_DOUBLE_EQ(car.speed, 0.0);
}

}  // namespace
}  // namespace orch::openscenario

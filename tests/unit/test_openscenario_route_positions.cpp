// RoutePosition (map/route_path.hpp, map/position_resolver.hpp): the path of a route through
// its waypoints and the places along it by pathS, each InRoutePosition kind by hand on two
// roads where the second is driven against its s; and the reader's side: a RoutePosition
// in a file, Init positions relative to entities placed further down, alongRoute.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>

#include "core/errors.hpp"
#include "map/position_resolver.hpp"
#include "map/route_path.hpp"
#include "opendrive/xodr_reader.hpp"
#include "openscenario/storyboard_runtime.hpp"
#include "openscenario/xosc_reader.hpp"
#include "support/cli_runner.hpp"
#include "unit/openscenario_snippets.hpp"
#include "unit/xodr_network_snippets.hpp"

namespace orch::position {
namespace {

using opendrive::Pose2;
using opendrive::RoutePoint;
using opendrive::RouteStrategy;

// Road 1: (0,0) -> (100,0). Road 3: (150,0) -> (100,0) (heading pi), its end meets road 1's
// end; lane -1 of road 1 continues on lane 1 of road 3, against road 3's s.
class RoutePositions : public ::testing::Test {
 protected:
  RoutePositions() : roads_(opendrive::read_xodr_text(test::xodr_contact_end(), "flip.xodr")), resolver_(roads_) {
    auto route = std::make_shared<RouteWaypoints>();
    route->name = "R";
    route->waypoints.push_back({LanePosition{"1", -1, 60.0, 0.0, std::nullopt}, RouteStrategy::Shortest});
    route->waypoints.push_back({LanePosition{"3", 1, 20.0, 0.0, std::nullopt}, RouteStrategy::Shortest});
    route_ = route;
  }
  ResolvedPosition resolve(const Position& p) {
    return resolver_.resolve(p, [&](const std::string& name) -> std::optional<Pose2> {
      if (name == "Ego") return Pose2{30.0, -1.75, 0.0};
      return std::nullopt;
    });
  }
  ResolvedPosition on_lane(double path_s, int lane, double offset) {
    return resolve(RoutePosition{route_, InRouteFromLane{path_s, lane, offset}, std::nullopt});
  }
  opendrive::RoadNetwork roads_;
  PositionResolver resolver_;
  std::shared_ptr<const RouteWaypoints> route_;
};

TEST_F(RoutePositions, ThePathRunsFromTheFirstWaypointToTheLastRoadByRoad) {
  const RoutePath path = route_path(roads_, {RoutePoint{"1", 60.0, -1}, RoutePoint{"3", 20.0, 1}},
                                    {RouteStrategy::Shortest, RouteStrategy::Shortest}, "R");
  ASSERT_EQ(path.pieces.size(), 2u);
  EXPECT_EQ(path.pieces[0].road_id, "1");
  EXPECT_DOUBLE_EQ(path.pieces[0].s_begin, 60.0);
  EXPECT_DOUBLE_EQ(path.pieces[0].s_end, 100.0);
  EXPECT_EQ(path.pieces[1].road_id, "3");
  EXPECT_DOUBLE_EQ(path.pieces[1].s_begin, 50.0);  // entered at its end
  EXPECT_DOUBLE_EQ(path.pieces[1].s_end, 20.0);
  EXPECT_EQ(path.pieces[1].direction(), -1);
  EXPECT_DOUBLE_EQ(path.length(), 40.0 + 30.0);
  const PathPlace at = place_on_path(path, 55.0, "R");
  EXPECT_EQ(at.road_id, "3");
  EXPECT_DOUBLE_EQ(at.s, 35.0);
  EXPECT_THROW((void)place_on_path(path, 70.5, "R"), MapError);
  // Two waypoints on one road: one piece between them.
  const RoutePath same = route_path(roads_, {RoutePoint{"1", 10.0, -1}, RoutePoint{"1", 90.0, -1}},
                                    {RouteStrategy::Shortest, RouteStrategy::Shortest}, "R");
  ASSERT_EQ(same.pieces.size(), 1u);
  EXPECT_DOUBLE_EQ(same.length(), 80.0);
}

TEST_F(RoutePositions, FromLaneCoordinatesIsOnTheLaneAtPathS) {
  const ResolvedPosition first = on_lane(10.0, -1, 0.0);  // road 1, s 70
  EXPECT_NEAR(first.pose.x, 70.0, 1e-9);
  EXPECT_NEAR(first.pose.y, -1.75, 1e-9);
  EXPECT_NEAR(first.pose.heading, 0.0, 1e-9);
  EXPECT_EQ(first.lane, -1);
  // pathS 55: 15 m into road 3 from its end, s 35, x 150 - 35; lane 1 (t 1.75) + 0.5 lies on
  // road 3's left, -y; facing the route's way, against road 3's heading pi: heading 0 (2 pi).
  const ResolvedPosition second = on_lane(55.0, 1, 0.5);
  EXPECT_NEAR(second.pose.x, 115.0, 1e-9);
  EXPECT_NEAR(second.pose.y, -2.25, 1e-9);
  EXPECT_NEAR(std::cos(second.pose.heading), 1.0, 1e-9);
  EXPECT_EQ(second.road->road_id, "3");
  EXPECT_NEAR(second.road->s, 35.0, 1e-9);
  EXPECT_EQ(second.lane, 1);
  EXPECT_THROW((void)on_lane(71.0, -1, 0.0), MapError);
}

TEST_F(RoutePositions, FromRoadCoordinatesAndFromCurrentEntity) {
  const ResolvedPosition road = resolve(RoutePosition{route_, InRouteFromRoad{40.0, -1.0}, std::nullopt});
  EXPECT_NEAR(road.pose.x, 100.0, 1e-9);  // the end of road 1
  EXPECT_NEAR(road.pose.y, -1.0, 1e-9);
  const ResolvedPosition turned =
      resolve(RoutePosition{route_, InRouteFromRoad{20.0, 0.0}, Orientation{true, 0.25}});
  EXPECT_NEAR(turned.pose.x, 80.0, 1e-9);
  EXPECT_NEAR(turned.pose.heading, 0.25, 1e-9);
  const ResolvedPosition current = resolve(RoutePosition{route_, InRouteFromEntity{"Ego"}, std::nullopt});
  EXPECT_NEAR(current.pose.x, 30.0, 1e-9);
  EXPECT_EQ(current.lane, -1);
  EXPECT_THROW((void)resolve(RoutePosition{route_, InRouteFromEntity{"Nobody"}, std::nullopt}), MapError);
}

TEST_F(RoutePositions, AnUnreachableWaypointIsAnErrorNamingTheRoute) {
  auto backwards = std::make_shared<RouteWaypoints>();
  backwards->name = "Back";
  backwards->waypoints.push_back({LanePosition{"3", 1, 20.0, 0.0, std::nullopt}, RouteStrategy::Shortest});
  backwards->waypoints.push_back({LanePosition{"1", -1, 60.0, 0.0, std::nullopt}, RouteStrategy::Shortest});
  try {
    (void)resolve(RoutePosition{backwards, InRouteFromLane{0.0, 1, 0.0}, std::nullopt});
    FAIL() << "expected an error";
  } catch (const MapError& e) {
    EXPECT_NE(std::string(e.what()).find("route \"Back\""), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace orch::position

namespace orch::openscenario {
namespace {

using test::place;
using test::vehicle;

std::string scenario_text(const std::string& init, const std::string& condition = "") {
  const std::string stop = condition.empty()
                               ? R"(<Condition name="Stop" delay="0" conditionEdge="rising"><ByValueCondition>
<SimulationTimeCondition value="5" rule="greaterOrEqual"/></ByValueCondition></Condition>)"
                               : condition;
  return R"(<?xml version="1.0"?><OpenSCENARIO>
<FileHeader revMajor="1" revMinor="0" date="2024-01-01T00:00:00" author="t" description="route positions"/>
<RoadNetwork><LogicFile filepath="road.xodr"/></RoadNetwork>
<Entities>)" + vehicle("A") + vehicle("B") + R"(</Entities>
<Storyboard><Init><Actions>)" + init + R"(</Actions></Init>
<StopTrigger><ConditionGroup>)" + stop + R"(</ConditionGroup></StopTrigger></Storyboard></OpenSCENARIO>)";
}

std::string relative_to(const std::string& name, const std::string& other, double ds) {
  return R"(<Private entityRef=")" + name + R"("><PrivateAction><TeleportAction><Position>
<RelativeLanePosition entityRef=")" + other + R"(" dLane="0" ds=")" + std::to_string(ds) +
         R"("/></Position></TeleportAction></PrivateAction></Private>)";
}

class RouteScenario : public ::testing::Test {
 protected:
  Scenario load(const std::string& text) {
    dir_.write("road.xodr", test::kStraightTwoLaneRoad);
    return load_scenario(dir_.write("s.xosc", text).string());
  }
  orch::test::TempDir dir_;
};

TEST_F(RouteScenario, ARoutePositionInAFileIsPlacedAlongItsRoute) {
  const std::string route_position = R"(<Private entityRef="A"><PrivateAction><TeleportAction><Position>
<RoutePosition><RouteRef><Route name="Along" closed="false">
<Waypoint routeStrategy="shortest"><Position><LanePosition roadId="0" laneId="-1" s="100" offset="0"/></Position></Waypoint>
<Waypoint routeStrategy="fastest"><Position><LanePosition roadId="0" laneId="-1" s="900" offset="0"/></Position></Waypoint>
</Route></RouteRef><InRoutePosition><FromLaneCoordinates pathS="250" laneId="-2" laneOffset="0.5"/></InRoutePosition>
</RoutePosition></Position></TeleportAction></PrivateAction></Private>)";
  const Scenario scenario = load(scenario_text(route_position + place("B", 10, -1, 0)));
  const opendrive::RoadNetwork roads = opendrive::read_xodr_file((dir_ / "road.xodr").string());
  const StoryboardRuntime runtime(scenario, roads);
  const EntityState& a = runtime.entities().at("A");
  EXPECT_NEAR(a.pose.x, 350.0, 1e-9);
  EXPECT_NEAR(a.pose.y, -5.25 + 0.5, 1e-9);
  EXPECT_EQ(a.lane, -2);
}

TEST_F(RouteScenario, InitPositionsRelativeToAnEntityPlacedLaterAreResolvedAfterIt) {
  // A is placed relative to B, which the file places after it.
  const Scenario scenario = load(scenario_text(relative_to("A", "B", 30) + place("B", 100, -1, 5)));
  const opendrive::RoadNetwork roads = opendrive::read_xodr_file((dir_ / "road.xodr").string());
  const StoryboardRuntime runtime(scenario, roads);
  EXPECT_NEAR(runtime.entities().at("A").pose.x, 130.0, 1e-9);
  EXPECT_NEAR(runtime.entities().at("B").pose.x, 100.0, 1e-9);
}

TEST_F(RouteScenario, InitPositionsRelativeToEachOtherAreAnErrorNamingBoth) {
  try {
    (void)load(scenario_text(relative_to("A", "B", 30) + relative_to("B", "A", -30)));
    FAIL() << "expected an error";
  } catch (const ScenarioError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("\"A\", \"B\""), std::string::npos) << what;
    EXPECT_NE(what.find("cycle"), std::string::npos) << what;
  }
}

TEST_F(RouteScenario, AlongRouteMeasuresOnTheRoad) {
  const std::string condition = R"(<Condition name="Stop" delay="0" conditionEdge="none"><ByEntityCondition>
<TriggeringEntities triggeringEntitiesRule="any"><EntityRef entityRef="A"/></TriggeringEntities><EntityCondition>
<TimeHeadwayCondition entityRef="B" value="2" freespace="false" alongRoute="true" rule="lessThan"/>
</EntityCondition></ByEntityCondition></Condition>)";
  const Scenario scenario = load(scenario_text(place("A", 10, -1, 10) + place("B", 50, -2, 0), condition));
  const auto& group = scenario.storyboard.stop_trigger->groups.at(0);
  const auto& by = std::get<ByEntityCondition>(group.at(0).kind);
  const auto& headway = std::get<TimeHeadwayCondition>(by.condition);
  EXPECT_EQ(headway.coordinate_system, "road");
}

}  // namespace
}  // namespace orch::openscenario

// OpenSCENARIO 1.3's traffic additions: TrafficAreaAction (read, its area's places, its
// vehicles kept in the area on SUMO commands without a simulator), TrafficDistribution (the
// vehicle templates' shares and sizes) on swarms, sources and areas, the source's `speed`, and
// RandomRouteAction (a random walk over the lane graph, the same for the same seed and entity). The
// runs on real SUMO are tests/integration/test_openscenario_traffic.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <set>
#include <string>
#include <vector>

#include "core/errors.hpp"
#include "opendrive/xodr_reader.hpp"
#include "openscenario/random_route.hpp"
#include "openscenario/storyboard_runtime.hpp"
#include "openscenario/xosc_reader.hpp"
#include "run/openscenario_traffic.hpp"
#include "run/traffic_area.hpp"
#include "support/cli_runner.hpp"
#include "unit/openscenario_snippets.hpp"
#include "unit/openscenario_traffic_snippets.hpp"
#include "unit/xodr_network_snippets.hpp"

namespace orch::openscenario {
namespace {

std::string vehicle_template(const std::string& category, double length, double weight) {
  return R"(<EntityDistributionEntry weight=")" + std::to_string(weight) + R"("><ScenarioObjectTemplate>
<Vehicle name=")" + category + R"(" vehicleCategory=")" + category + R"(">
<BoundingBox><Center x="1.5" y="0" z="0.9"/><Dimensions width="2.1" length=")" + std::to_string(length) + R"(" height="2"/></BoundingBox>
<Performance maxSpeed="40" maxDeceleration="8" maxAcceleration="3"/>
<Axles><RearAxle maxSteering="0" wheelDiameter="0.8" trackWidth="1.68" positionX="0" positionZ="0.4"/></Axles>
</Vehicle></ScenarioObjectTemplate></EntityDistributionEntry>)";
}

// Entry weights 3 and 1: a van and a truck (1 : 1) in the first, a car in the second.
const std::string kDistribution = R"(<TrafficDistribution><TrafficDistributionEntry weight="3"><EntityDistribution>)" +
                                  vehicle_template("van", 5.5, 1) + vehicle_template("truck", 11, 1) +
                                  R"(</EntityDistribution></TrafficDistributionEntry>
<TrafficDistributionEntry weight="1"><EntityDistribution>)" + vehicle_template("car", 4.2, 5) +
                                  R"(</EntityDistribution><Properties><Property name="p" value="1"/></Properties></TrafficDistributionEntry></TrafficDistribution>)";

// Road 0's lane -1 from s = 200 to s = 500.
std::string road_range_area(int entities, bool continuous, const std::string& distribution = kDistribution) {
  return R"(<TrafficAction trafficName="Zone"><TrafficAreaAction numberOfEntities=")" + std::to_string(entities) +
         R"(" continuous=")" + (continuous ? "true" : "false") + R"(">)" + distribution + R"(<TrafficArea><RoadRange>
<RoadCursor roadId="0" s="200"><Lane id="-1"/></RoadCursor><RoadCursor roadId="0" s="500"/></RoadRange></TrafficArea>
</TrafficAreaAction></TrafficAction>)";
}

using test::kRoadZeroNet;

template <class T>
const T* init_action(const Scenario& s) {
  for (const InitAction& a : s.storyboard.init)
    if (const auto* found = std::get_if<T>(&a.action)) return found;
  return nullptr;
}

class TrafficArea13 : public ::testing::Test {
 protected:
  // A on road 0 at s = 1000, lane -1; `global` in Init's GlobalAction; `private_actions` A's.
  Scenario load(const std::string& global, const std::string& private_actions = "") {
    const std::string text = R"(<?xml version="1.0"?><OpenSCENARIO>
<FileHeader revMajor="1" revMinor="3" date="2024-01-01T00:00:00" author="t" description="traffic 1.3"/>
<RoadNetwork><LogicFile filepath="road.xodr"/></RoadNetwork>
<Entities>)" + test::vehicle("A") + R"(</Entities>
<Storyboard><Init><Actions>)" + (global.empty() ? "" : "<GlobalAction>" + global + "</GlobalAction>") +
                             test::place("A", 1000, -1, 10) +
                             (private_actions.empty() ? "" : R"(<Private entityRef="A">)" + private_actions + "</Private>") +
                             R"(</Actions></Init><StopTrigger/></Storyboard></OpenSCENARIO>)";
    dir_.write("road.xodr", test::kStraightTwoLaneRoad);
    return load_scenario(dir_.write("s.xosc", text).string());
  }
  std::string error(const std::string& global) {
    try {
      load(global);
    } catch (const ScenarioError& e) {
      return e.what();
    }
    return "";
  }
  test::TempDir dir_;
};

TEST_F(TrafficArea13, AnAreaIsReadWithItsRoadRangeAndItsDistributionsShares) {
  const Scenario s = load(road_range_area(4, true));
  const auto* area = init_action<TrafficAreaAction>(s);
  ASSERT_NE(area, nullptr);
  EXPECT_EQ(area->name, "Zone");
  EXPECT_EQ(area->entities, 4);
  EXPECT_TRUE(area->continuous);
  EXPECT_TRUE(area->polygon.empty());
  ASSERT_EQ(area->road_ranges.size(), 1u);
  ASSERT_EQ(area->road_ranges[0].cursors.size(), 2u);
  EXPECT_EQ(area->road_ranges[0].cursors[0].lanes, std::vector<int>{-1});
  EXPECT_EQ(area->road_ranges[0].cursors[1].s, 500.0);
  // Shares: entry weight / 4 x template weight / its distribution's sum.
  ASSERT_EQ(area->categories.size(), 3u);
  EXPECT_EQ(area->categories[0].category, "van");
  EXPECT_NEAR(area->categories[0].weight, 0.375, 1e-12);
  EXPECT_EQ(area->categories[1].category, "truck");
  EXPECT_NEAR(area->categories[1].weight, 0.375, 1e-12);
  EXPECT_EQ(area->categories[2].category, "car");
  EXPECT_NEAR(area->categories[2].weight, 0.25, 1e-12);
  EXPECT_EQ(area->categories[1].length, 11.0);
  EXPECT_EQ(area->categories[1].width, 2.1);
}

TEST_F(TrafficArea13, SwarmsAndSourcesTakeATrafficDistributionAndASourceIts13Speed) {
  const Scenario s = load(R"(<TrafficAction><TrafficSwarmAction innerRadius="10" semiMajorAxis="100" semiMinorAxis="10" numberOfVehicles="3" offset="0">
<CentralObject entityRef="A"/>)" + kDistribution + R"(</TrafficSwarmAction></TrafficAction></GlobalAction><GlobalAction>
<TrafficAction><TrafficSourceAction radius="5" rate="0.5" speed="12"><Position><LanePosition roadId="0" laneId="-2" s="100" offset="0"/></Position>)" +
                          kDistribution + R"(</TrafficSourceAction></TrafficAction>)");
  const auto* swarm = init_action<TrafficSwarmAction>(s);
  ASSERT_NE(swarm, nullptr);
  EXPECT_EQ(swarm->categories.size(), 3u);
  const auto* source = init_action<TrafficSourceAction>(s);
  ASSERT_NE(source, nullptr);
  EXPECT_EQ(source->speed, 12.0);
  EXPECT_EQ(source->categories.size(), 3u);
}

TEST_F(TrafficArea13, BadAreasAndDistributionsAreErrorsNamingWhatWasExpected) {
  const std::string corners = error(R"(<TrafficAction><TrafficAreaAction numberOfEntities="2" continuous="false">)" + kDistribution +
                                    R"(<TrafficArea><Polygon><Position><WorldPosition x="0" y="0"/></Position>
<Position><WorldPosition x="10" y="0"/></Position></Polygon></TrafficArea></TrafficAreaAction></TrafficAction>)");
  EXPECT_NE(corners.find("s.xosc:"), std::string::npos) << corners;
  EXPECT_NE(corners.find("a Polygon needs at least 3 Positions, it has 2"), std::string::npos) << corners;
  const std::string cursors = error(R"(<TrafficAction><TrafficAreaAction numberOfEntities="2" continuous="false">)" + kDistribution +
                                    R"(<TrafficArea><RoadRange><RoadCursor roadId="0"/></RoadRange></TrafficArea></TrafficAreaAction></TrafficAction>)");
  EXPECT_NE(cursors.find("a RoadRange needs at least 2 RoadCursors"), std::string::npos) << cursors;
  const std::string pedestrian = error(road_range_area(2, false, R"(<TrafficDistribution><TrafficDistributionEntry weight="1"><EntityDistribution>
<EntityDistributionEntry weight="1"><ScenarioObjectTemplate><Pedestrian name="p" mass="80" pedestrianCategory="pedestrian">
<BoundingBox><Center x="0" y="0" z="0.9"/><Dimensions width="0.5" length="0.5" height="1.8"/></BoundingBox></Pedestrian>
</ScenarioObjectTemplate></EntityDistributionEntry></EntityDistribution></TrafficDistributionEntry></TrafficDistribution>)"));
  EXPECT_NE(pedestrian.find("template is not a Vehicle"), std::string::npos) << pedestrian;
  const std::string zero = error(road_range_area(2, false, R"(<TrafficDistribution><TrafficDistributionEntry weight="0"><EntityDistribution>)" +
                                                               vehicle_template("car", 4, 1) +
                                                               R"(</EntityDistribution></TrafficDistributionEntry></TrafficDistribution>)"));
  EXPECT_NE(zero.find("the weights of all TrafficDistributionEntries are 0"), std::string::npos) << zero;
  const std::string both = error(R"(<TrafficAction><TrafficSourceAction radius="5" rate="1" speed="3" velocity="3">
<Position><LanePosition roadId="0" laneId="-2" s="100" offset="0"/></Position></TrafficSourceAction></TrafficAction>)");
  EXPECT_NE(both.find("speed (1.3) and velocity (its deprecated name) are both given"), std::string::npos) << both;
}

TEST(TrafficAreaPlaces, ARoadRangeRunsFromCursorToCursorOverRoadsAndStopsAtItsLength) {
  TrafficAreaRoadRange range;
  range.cursors = {{"1", 60.0, {-1}}, {"2", std::nullopt, {}}, {"2", 30.0, {}}};
  const auto parts = area_parts(range, {100, 50, 50});
  ASSERT_EQ(parts.size(), 3u);
  EXPECT_EQ(parts[0].road, "1");  // road 1 from its cursor to its end, lane -1 only
  EXPECT_EQ(parts[0].from, 60.0);
  EXPECT_EQ(parts[0].to, 100.0);
  EXPECT_EQ(parts[0].lanes, std::vector<int>{-1});
  EXPECT_EQ(parts[1].road, "2");  // road 2 up to its cursor without s: the whole road
  EXPECT_EQ(parts[1].to, 50.0);
  EXPECT_EQ(parts[2].from, 30.0);  // then on road 2 between its two cursors
  EXPECT_EQ(parts[2].to, 50.0);
  range.length = 50;  // 40 m on road 1, then 10 m of road 2
  const auto capped = area_parts(range, {100, 50, 50});
  ASSERT_EQ(capped.size(), 2u);
  EXPECT_EQ(capped[1].to, 10.0);
  EXPECT_TRUE(in_parts({"1", -1, 70, {0, 0}}, capped));
  EXPECT_FALSE(in_parts({"1", 1, 70, {0, 0}}, capped));  // another lane
  EXPECT_FALSE(in_parts({"2", -1, 20, {0, 0}}, capped));  // past the length
  // A polygon: even-odd inside test.
  const std::vector<Vec2> square{{0, 0}, {10, 0}, {10, 10}, {0, 10}};
  EXPECT_TRUE(inside_polygon({5, 5}, square));
  EXPECT_FALSE(inside_polygon({15, 5}, square));
  EXPECT_FALSE(inside_polygon({5, 5}, {{0, 0}, {10, 0}}));
}

TEST_F(TrafficArea13, AnAreaSpawnsItsVehiclesInItsAreaOnRoutesThatStayThereTheSameForTheSameSeed) {
  const Scenario s = load(road_range_area(5, true));
  const opendrive::RoadNetwork roads = opendrive::read_xodr_file((dir_.path() / "road.xodr").string());
  const opendrive::SumoLaneIndex lanes{roads, dir_.write("n.net.xml", kRoadZeroNet).string()};
  StoryboardRuntime runtime(s, roads);
  const auto spawns = [&](long long seed) { return test::first_step_spawns(lanes, runtime, seed); };
  const auto first = spawns(3);
  ASSERT_EQ(first.size(), 5u);
  std::set<std::string> categories;
  for (const auto& c : first) {
    EXPECT_TRUE(c.traffic);
    EXPECT_FALSE(c.scripted);
    EXPECT_EQ(c.edge, "-0");
    EXPECT_EQ(c.lane, 1);  // lane -1 only
    EXPECT_GE(c.lane_pos, 200.0 - 1e-9);
    EXPECT_LE(c.lane_pos, 500.0 + 1e-9);
    EXPECT_EQ(c.route, std::vector<std::string>{"-0"});
    categories.insert(c.model.id);
    if (c.model.id == "truck") {
      EXPECT_EQ(c.model.length, 11.0);  // the template's size
    }
  }
  const auto again = spawns(3);
  for (std::size_t i = 0; i < first.size(); ++i) EXPECT_EQ(again[i].lane_pos, first[i].lane_pos);
}

TEST_F(TrafficArea13, AContinuousAreaReplacesAVehicleThatLeftItAndAOnceFilledAreaDoesNot) {
  const opendrive::RoadNetwork roads = opendrive::read_xodr_text(test::kStraightTwoLaneRoad, "road.xodr");
  const opendrive::SumoLaneIndex lanes{roads, dir_.write("n.net.xml", kRoadZeroNet).string()};
  for (const bool continuous : {true, false}) {
    const Scenario s = load(road_range_area(3, continuous));
    StoryboardRuntime runtime(s, roads);
    OpenScenarioTraffic traffic(lanes, 1);
    std::vector<sim::NearbyVehicle> seen;
    for (auto& c : traffic.update(runtime.traffic(), runtime.entities(), {}, 0.0, 0.05)) {
      const auto& spawn = std::get<sim::SpawnVehicle>(c);
      seen.push_back({spawn.actor.sumo_id, {spawn.lane_pos, -1.75}, 0, 10, 4.5, 1.8});
    }
    ASSERT_EQ(seen.size(), 3u);
    seen.front().position = {650, -1.75};  // past s = 500 (and kPlaceStep beyond): out of the area
    const std::string gone = seen.front().sumo_id;
    const auto commands = traffic.update(runtime.traffic(), runtime.entities(), seen, 0.05, 0.05);
    ASSERT_FALSE(commands.empty());
    EXPECT_EQ(std::get<sim::RemoveActor>(commands.front()).sumo_id, gone);
    EXPECT_EQ(commands.size(), continuous ? 2u : 1u) << "continuous " << continuous;
    EXPECT_EQ(traffic.count(1), continuous ? 3 : 2);
    const auto record = traffic_record(runtime.traffic().all().front(), traffic);
    EXPECT_EQ(record.kind, "area");
    EXPECT_EQ(record.spawned, continuous ? 4 : 3);
    EXPECT_EQ(record.removed, 1);
  }
}

TEST_F(TrafficArea13, APolygonAreaSpawnsInsideItsCornersAsResolvedWhenItStarts) {
  // A rectangle 40 m ahead of A (x 1040..1240), over both lanes, given relative to A.
  const Scenario s = load(R"(<TrafficAction><TrafficAreaAction numberOfEntities="20" continuous="false">)" + kDistribution +
                          R"(<TrafficArea><Polygon>
<Position><RelativeWorldPosition entityRef="A" dx="40" dy="5"/></Position>
<Position><RelativeWorldPosition entityRef="A" dx="240" dy="5"/></Position>
<Position><RelativeWorldPosition entityRef="A" dx="240" dy="-10"/></Position>
<Position><RelativeWorldPosition entityRef="A" dx="40" dy="-10"/></Position></Polygon></TrafficArea></TrafficAreaAction></TrafficAction>)");
  const opendrive::RoadNetwork roads = opendrive::read_xodr_file((dir_.path() / "road.xodr").string());
  const opendrive::SumoLaneIndex lanes{roads, dir_.write("n.net.xml", kRoadZeroNet).string()};
  StoryboardRuntime runtime(s, roads);
  ASSERT_EQ(runtime.traffic().all().front().polygon.size(), 4u);
  OpenScenarioTraffic traffic(lanes, 5);
  const auto commands = traffic.update(runtime.traffic(), runtime.entities(), {}, 0.0, 0.05);
  // 200 m x 2 lanes with kSpacing (20 m) between vehicles: fewer than the 20 asked fit.
  ASSERT_FALSE(commands.empty());
  EXPECT_LT(commands.size(), 20u);
  for (const auto& c : commands) {
    const auto& spawn = std::get<sim::SpawnVehicle>(c);
    EXPECT_GT(spawn.lane_pos, 1040.0 - 1e-9);
    EXPECT_LT(spawn.lane_pos, 1240.0 + 1e-9);
  }
}

// RandomRouteAction: a walk over the lane graph whose forks the run's seed and the entity's
// name decide.
EntityState on_road_1_before_the_junction() {
  EntityState state;
  state.placed = true;
  state.road_id = "1";
  state.lane = -1;
  state.s = 20;
  return state;
}

std::vector<std::string> planned_roads(const EntityState& state) {
  std::vector<std::string> roads;
  for (const opendrive::LaneEntry& entry : state.route_plan) roads.push_back(entry.road_id);
  return roads;
}

TEST(RandomRoute, AForkIsTakenEachWayByTheHashOfTheEntityTheSameEveryTime) {
  const opendrive::RoadNetwork roads = opendrive::read_xodr_text(test::xodr_three_way(), "three_way.xodr");
  std::set<std::string> first_roads;
  for (int i = 0; i < 16; ++i) {
    EntityState state = on_road_1_before_the_junction();
    const std::string name = "Car" + std::to_string(i);
    plan_random_route(state, roads, name, 42);
    ASSERT_FALSE(state.route_plan.empty()) << name;
    first_roads.insert(state.route_plan.front().road_id);
    EntityState again = state;
    plan_random_route(again, roads, name, 42);
    EXPECT_EQ(planned_roads(again), planned_roads(state)) << name;
    EXPECT_EQ(again.route_version, state.route_version + 1);  // a new plan
  }
  EXPECT_EQ(first_roads, (std::set<std::string>{"10", "11"}));  // both ways out of the junction
}

// The run's --seed reaches the walk: one entity takes both ways out of the junction over 16
// seeds, and the same seed gives it the same route every time.
TEST(RandomRoute, TheRunsSeedDecidesTheForksTheSameSeedTheSameRoute) {
  const opendrive::RoadNetwork roads = opendrive::read_xodr_text(test::xodr_three_way(), "three_way.xodr");
  std::set<std::string> first_roads;
  for (std::uint64_t seed = 1; seed <= 16; ++seed) {
    EntityState state = on_road_1_before_the_junction();
    plan_random_route(state, roads, "Wanderer", seed);
    ASSERT_FALSE(state.route_plan.empty()) << seed;
    first_roads.insert(state.route_plan.front().road_id);
    EntityState again = on_road_1_before_the_junction();
    plan_random_route(again, roads, "Wanderer", seed);
    EXPECT_EQ(planned_roads(again), planned_roads(state)) << seed;
  }
  EXPECT_EQ(first_roads, (std::set<std::string>{"10", "11"}));
}

TEST_F(TrafficArea13, ARandomRouteActionIsReadAndPlansFromTheEntitysLane) {
  const Scenario s = load("", R"(<PrivateAction><RoutingAction><RandomRouteAction/></RoutingAction></PrivateAction>)");
  bool found = false;
  for (const InitAction& a : s.storyboard.init) found = found || std::holds_alternative<RandomRouteAction>(a.action);
  EXPECT_TRUE(found);
  const opendrive::RoadNetwork roads = opendrive::read_xodr_file((dir_.path() / "road.xodr").string());
  StoryboardRuntime runtime(s, roads);
  test::run_until(runtime, 1);
  EXPECT_NEAR(runtime.entities().at("A").s, 1010.0, 1e-6);  // no fork on road 0: it drives on
}

}  // namespace
}  // namespace orch::openscenario

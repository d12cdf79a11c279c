// TrafficActions (GlobalAction/TrafficAction): read and checked (bad input is an error naming
// the file, the line and what was expected), kept by the storyboard (traffic_book.hpp: started
// at their time, ended by a TrafficStopAction), and turned into SUMO commands without a
// simulator (run/openscenario_traffic.hpp: spawns in the swarm's annulus, the same for the
// same seed). The runs on real SUMO are tests/integration/test_openscenario_traffic.cpp.
#include <gtest/gtest.h>

#include <cmath>

#include "core/errors.hpp"
#include "opendrive/xodr_reader.hpp"
#include "openscenario/storyboard_runtime.hpp"
#include "openscenario/xosc_reader.hpp"
#include "run/openscenario_traffic.hpp"
#include "support/cli_runner.hpp"
#include "unit/openscenario_snippets.hpp"
#include "unit/openscenario_traffic_snippets.hpp"

namespace orch::openscenario {
namespace {

const char* kSwarm = R"(<TrafficAction trafficName="Crowd"><TrafficSwarmAction innerRadius="50" semiMajorAxis="300" semiMinorAxis="20" numberOfVehicles="8" velocity="20" offset="0">
<CentralObject entityRef="A"/></TrafficSwarmAction></TrafficAction>)";

std::string stop_event(const std::string& name, double at) {
  return R"(<Event name="StopIt" priority="parallel"><Action name="StopItAction"><GlobalAction><TrafficAction trafficName=")" + name +
         R"("><TrafficStopAction/></TrafficAction></GlobalAction></Action><StartTrigger><ConditionGroup>
<Condition name="c" delay="0" conditionEdge="none"><ByValueCondition><SimulationTimeCondition value=")" +
         std::to_string(at) + R"(" rule="greaterOrEqual"/></ByValueCondition></Condition></ConditionGroup></StartTrigger></Event>)";
}

// An event no test reaches (a Maneuver needs one).
const std::string kLaterEvent = R"(<Event name="Later" priority="parallel"><Action name="LaterAction"><PrivateAction>
<LongitudinalAction><SpeedAction><SpeedActionDynamics dynamicsShape="step" dynamicsDimension="time" value="0"/>
<SpeedActionTarget><AbsoluteTargetSpeed value="5"/></SpeedActionTarget></SpeedAction></LongitudinalAction></PrivateAction></Action>
<StartTrigger><ConditionGroup><Condition name="c" delay="0" conditionEdge="none"><ByValueCondition>
<SimulationTimeCondition value="1000" rule="greaterOrEqual"/></ByValueCondition></Condition></ConditionGroup></StartTrigger></Event>)";

// The first Init action of type T (nullptr: none).
template <class T>
const T* init_action(const Scenario& s) {
  for (const InitAction& a : s.storyboard.init)
    if (const auto* found = std::get_if<T>(&a.action)) return found;
  return nullptr;
}

class TrafficActions : public ::testing::Test {
 protected:
  // A on road 0 (test::kStraightTwoLaneRoad) at s = 1000, lane -1, 10 m/s; `global` in Init's
  // GlobalAction (each element its own GlobalAction), `events` in A's maneuver.
  std::string text(const std::string& global, const std::string& events = "") {
    return R"(<?xml version="1.0"?><OpenSCENARIO>
<FileHeader revMajor="1" revMinor="2" date="2024-01-01T00:00:00" author="t" description="traffic"/>
<RoadNetwork><LogicFile filepath="road.xodr"/></RoadNetwork>
<Entities>)" + test::vehicle("A") + R"(</Entities>
<Storyboard><Init><Actions>)" + (global.empty() ? "" : "<GlobalAction>" + global + "</GlobalAction>") +
           test::place("A", 1000, -1, 10) + R"(</Actions></Init>
<Story name="S"><Act name="Act"><ManeuverGroup name="G" maximumExecutionCount="1">
<Actors selectTriggeringEntities="false"><EntityRef entityRef="A"/></Actors><Maneuver name="M">)" +
           (events.empty() ? kLaterEvent : events) + R"(</Maneuver></ManeuverGroup></Act></Story>
<StopTrigger><ConditionGroup><Condition name="end" delay="0" conditionEdge="none"><ByValueCondition>
<SimulationTimeCondition value="100" rule="greaterOrEqual"/></ByValueCondition></Condition></ConditionGroup></StopTrigger>
</Storyboard></OpenSCENARIO>)";
  }
  Scenario load(const std::string& global, const std::string& events = "") {
    dir_.write("road.xodr", test::kStraightTwoLaneRoad);
    return load_scenario(dir_.write("s.xosc", text(global, events)).string());
  }
  std::string error(const std::string& global, const std::string& events = "") {
    try {
      load(global, events);
    } catch (const ScenarioError& e) {
      return e.what();
    }
    return "";
  }
  test::TempDir dir_;
};

TEST_F(TrafficActions, ASwarmIsReadWithItsCentreAndShape) {
  const Scenario s = load(kSwarm);
  const auto* swarm = init_action<TrafficSwarmAction>(s);
  ASSERT_NE(swarm, nullptr);
  EXPECT_EQ(swarm->name, "Crowd");
  EXPECT_EQ(swarm->entity, "A");
  EXPECT_EQ(swarm->inner_radius, 50);
  EXPECT_EQ(swarm->semi_major, 300);
  EXPECT_EQ(swarm->semi_minor, 20);
  EXPECT_EQ(swarm->vehicles, 8);
  EXPECT_EQ(swarm->speed, 20.0);
}

TEST_F(TrafficActions, SourcesAndSinksAreReadWithTheirDefinition) {
  const Scenario s = load(R"(<TrafficAction trafficName="In"><TrafficSourceAction radius="5" rate="0.5">
<Position><LanePosition roadId="0" laneId="-2" s="100" offset="0"/></Position>
<TrafficDefinition name="mix"><VehicleCategoryDistribution><VehicleCategoryDistributionEntry category="car" weight="3"/>
<VehicleCategoryDistributionEntry category="truck" weight="1"/></VehicleCategoryDistribution>
<ControllerDistribution><ControllerDistributionEntry weight="1"><Controller name="c"/></ControllerDistributionEntry></ControllerDistribution>
</TrafficDefinition><InitialSpeedRange lowerLimit="15" upperLimit="25"/></TrafficSourceAction></TrafficAction></GlobalAction>
<GlobalAction><TrafficAction><TrafficSinkAction radius="20"><Position><LanePosition roadId="0" laneId="-2" s="900" offset="0"/></Position>
</TrafficSinkAction></TrafficAction>)");
  const auto* source = init_action<TrafficSourceAction>(s);
  ASSERT_NE(source, nullptr);
  EXPECT_EQ(source->rate, 0.5);
  ASSERT_EQ(source->categories.size(), 2u);
  EXPECT_EQ(source->categories[1].category, "truck");
  ASSERT_TRUE(source->speed_range);
  EXPECT_EQ(source->speed_range->second, 25.0);
  const auto* sink = init_action<TrafficSinkAction>(s);
  ASSERT_NE(sink, nullptr);
  EXPECT_EQ(sink->name, "");
  EXPECT_FALSE(sink->rate);  // every vehicle in the radius at once
}

TEST_F(TrafficActions, BadTrafficIsAnErrorNamingFileLineAndWhatWasExpected) {
  // A negative radius: the standard's range is [0..inf[.
  const std::string negative = error(R"(<TrafficAction><TrafficSinkAction radius="-5"><Position><LanePosition roadId="0" laneId="-1" s="9" offset="0"/></Position></TrafficSinkAction></TrafficAction>)");
  EXPECT_NE(negative.find("s.xosc:"), std::string::npos) << negative;
  EXPECT_NE(negative.find("/TrafficSinkAction/@radius: radius cannot be negative"), std::string::npos) << negative;
  // The swarm's centre is required.
  EXPECT_NE(error(R"(<TrafficAction><TrafficSwarmAction innerRadius="1" semiMajorAxis="2" semiMinorAxis="2" numberOfVehicles="1"/></TrafficAction>)")
                .find("CentralObject"),
            std::string::npos);
  // ... and must name an entity.
  EXPECT_NE(error(R"(<TrafficAction><TrafficSwarmAction innerRadius="1" semiMajorAxis="2" semiMinorAxis="2" numberOfVehicles="1"><CentralObject entityRef="B"/></TrafficSwarmAction></TrafficAction>)")
                .find("\"B\""),
            std::string::npos);
  // A TrafficStopAction names the traffic it stops, one the file starts.
  const std::string unknown = error(kSwarm, stop_event("Crowed", 5));
  EXPECT_NE(unknown.find("s.xosc:"), std::string::npos) << unknown;
  EXPECT_NE(unknown.find("stops traffic \"Crowed\", which no TrafficAction of the file starts (did you mean \"Crowd\"?)"),
            std::string::npos)
      << unknown;
  EXPECT_NE(error(kSwarm, stop_event("", 5)).find("needs the TrafficAction's trafficName"), std::string::npos);
  // A misspelt attribute: "did you mean".
  EXPECT_NE(error(R"(<TrafficAction><TrafficSinkAction radiuss="5"><Position><LanePosition roadId="0" laneId="-1" s="9" offset="0"/></Position></TrafficSinkAction></TrafficAction>)")
                .find("did you mean \"radius\""),
            std::string::npos);
  // A TrafficAreaAction (1.3) needs its area and its distribution (test_openscenario_traffic_area.cpp).
  EXPECT_NE(error(R"(<TrafficAction><TrafficAreaAction continuous="true" numberOfEntities="3"/></TrafficAction>)").find("TrafficArea"),
            std::string::npos);
}

TEST_F(TrafficActions, TheStoryboardKeepsTrafficUntilATrafficStopActionEndsIt) {
  const Scenario s = load(kSwarm, stop_event("Crowd", 5));
  const opendrive::RoadNetwork roads = opendrive::read_xodr_file((dir_.path() / "road.xodr").string());
  StoryboardRuntime runtime(s, roads);
  ASSERT_EQ(runtime.traffic().all().size(), 1u);
  const Traffic& swarm = runtime.traffic().all().front();
  EXPECT_EQ(swarm.started, 0.0);
  EXPECT_FALSE(swarm.stopped);
  test::run_until(runtime, 4.9);
  EXPECT_FALSE(runtime.traffic().all().front().stopped);
  test::run_until(runtime, 5.5);
  ASSERT_TRUE(runtime.traffic().all().front().stopped);
  EXPECT_NEAR(*runtime.traffic().all().front().stopped, 5.0, 1e-9);
  // The stop action takes no simulation time: it ends as it starts.
  EXPECT_EQ(test::transition_times(runtime, "StopItAction", "startTransition"),
            test::transition_times(runtime, "StopItAction", "endTransition"));
}

using test::kRoadZeroNet;

TEST_F(TrafficActions, ASwarmSpawnsInItsAnnulusTheSameWayForTheSameSeed) {
  const Scenario s = load(kSwarm);
  const opendrive::RoadNetwork roads = opendrive::read_xodr_file((dir_.path() / "road.xodr").string());
  const opendrive::SumoLaneIndex lanes{roads, dir_.write("n.net.xml", kRoadZeroNet).string()};
  StoryboardRuntime runtime(s, roads);
  const auto spawns = [&](long long seed) { return test::first_step_spawns(lanes, runtime, seed); };
  const auto first = spawns(7);
  ASSERT_EQ(first.size(), 8u);  // numberOfVehicles, room enough on 2 x 600 m of lanes
  const opendrive::Pose2 a = runtime.entities().at("A").pose;
  for (const auto& c : first) {
    EXPECT_TRUE(c.traffic);
    EXPECT_FALSE(c.scripted);  // SUMO's driver drives it
    EXPECT_EQ(c.max_speed, 20.0);
    EXPECT_EQ(c.edge, "-0");
    // Lane positions along road 0 (along +x): the annulus is 50 m < |dx| <= 300 m (the
    // ellipse is 20 m wide across, the road narrower).
    const double dx = c.lane_pos - a.x;
    EXPECT_GE(std::abs(dx), 50.0 - 1e-9) << c.actor.sumo_id;
    EXPECT_LE(std::abs(dx), 300.0 + 1e-9) << c.actor.sumo_id;
  }
  // No two closer than kSpacing (SUMO lane 1 is lane -1 at y = -1.75, lane 0 is -2 at -5.25).
  const auto y = [](const sim::SpawnVehicle& c) { return c.lane == 1 ? -1.75 : -5.25; };
  for (std::size_t i = 0; i < first.size(); ++i)
    for (std::size_t j = i + 1; j < first.size(); ++j)
      EXPECT_GE(std::hypot(first[i].lane_pos - first[j].lane_pos, y(first[i]) - y(first[j])),
                OpenScenarioTraffic::kSpacing);
  const auto again = spawns(7), other = spawns(8);
  ASSERT_EQ(again.size(), first.size());
  bool all_same = true;
  for (std::size_t i = 0; i < first.size(); ++i) {
    EXPECT_EQ(again[i].lane_pos, first[i].lane_pos);
    EXPECT_EQ(again[i].lane, first[i].lane);
    all_same = all_same && other[i].lane_pos == first[i].lane_pos;
  }
  EXPECT_FALSE(all_same);  // another seed, other places
}

TEST_F(TrafficActions, ASwarmRemovesItsVehiclesOutsideTheEllipse) {
  const Scenario s = load(kSwarm);
  const opendrive::RoadNetwork roads = opendrive::read_xodr_file((dir_.path() / "road.xodr").string());
  const opendrive::SumoLaneIndex lanes{roads, dir_.write("n.net.xml", kRoadZeroNet).string()};
  StoryboardRuntime runtime(s, roads);
  OpenScenarioTraffic traffic(lanes, 1);
  std::vector<sim::NearbyVehicle> seen;
  for (auto& c : traffic.update(runtime.traffic(), runtime.entities(), {}, 0.0, 0.05)) {
    const auto& spawn = std::get<sim::SpawnVehicle>(c);
    seen.push_back({spawn.actor.sumo_id, {spawn.lane_pos, -1.75}, 0, 20, 4.5, 1.8});
  }
  ASSERT_FALSE(seen.empty());
  seen.front().position = {1400, -1.75};  // 400 m ahead of A: outside the 300 m ellipse
  const std::string gone = seen.front().sumo_id;
  const auto commands = traffic.update(runtime.traffic(), runtime.entities(), seen, 0.05, 0.05);
  ASSERT_FALSE(commands.empty());
  const auto* remove = std::get_if<sim::RemoveActor>(&commands.front());
  ASSERT_NE(remove, nullptr);
  EXPECT_EQ(remove->sumo_id, gone);
  // ... and one is spawned in its stead: the count is kept.
  ASSERT_EQ(commands.size(), 2u);
  EXPECT_TRUE(std::holds_alternative<sim::SpawnVehicle>(commands[1]));
  EXPECT_EQ(traffic.count(1), 8);
  // result.json's counts: 9 spawned, 1 removed, 8 there.
  const OpenScenarioTraffic::Tally tally = traffic.tally(1);
  EXPECT_EQ(tally.spawned, 9);
  EXPECT_EQ(tally.removed, 1);
  EXPECT_EQ(tally.left + tally.not_inserted, 0);
  EXPECT_EQ(traffic.removed_total(), 1);
}

// The standard's sink removes every traffic participant in its radius: the background
// vehicles (--traffic) near the entities too, each once when two sinks reach it.
TEST_F(TrafficActions, ASinkRemovesBackgroundVehiclesInItsRadiusOnce) {
  const std::string sink = R"(<TrafficAction trafficName="Out"><TrafficSinkAction radius="15"><Position>
<LanePosition roadId="0" laneId="-1" s="1050" offset="0"/></Position></TrafficSinkAction></TrafficAction>)";
  const std::string other = R"(<TrafficAction trafficName="Out2"><TrafficSinkAction radius="15"><Position>
<LanePosition roadId="0" laneId="-1" s="1060" offset="0"/></Position></TrafficSinkAction></TrafficAction>)";
  const Scenario s = load(sink + "</GlobalAction><GlobalAction>" + other);
  const opendrive::RoadNetwork roads = opendrive::read_xodr_file((dir_.path() / "road.xodr").string());
  const opendrive::SumoLaneIndex lanes{roads, dir_.write("n.net.xml", kRoadZeroNet).string()};
  StoryboardRuntime runtime(s, roads);
  OpenScenarioTraffic traffic(lanes, 1);
  const std::vector<sim::NearbyVehicle> background{{"bg.inside_both", {1055, -1.75}, 0, 20, 4.5, 1.8},
                                                   {"bg.outside", {1200, -1.75}, 0, 20, 4.5, 1.8}};
  const auto commands = traffic.update(runtime.traffic(), runtime.entities(), {}, 0.0, 0.05, background);
  ASSERT_EQ(commands.size(), 1u);
  EXPECT_EQ(std::get<sim::RemoveActor>(commands.front()).sumo_id, "bg.inside_both");
  EXPECT_EQ(traffic.tally(1).removed, 1);
  EXPECT_EQ(traffic.tally(1).removed_background, 1);
  EXPECT_EQ(traffic.tally(2).removed, 0);
  EXPECT_EQ(traffic.removed_total(), 1);
}

}  // namespace
}  // namespace orch::openscenario

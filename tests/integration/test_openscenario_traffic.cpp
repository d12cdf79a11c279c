// The storyboard's TrafficActions on real SUMO (libsumo): the storyboard, the entities and the
// traffic (run/openscenario_traffic.hpp) step as the run loop steps them, and what SUMO reports
// of the traffic vehicles (WorldSnapshot::traffic) is checked: a swarm's vehicles appear inside
// its annulus, are removed outside its ellipse and their number is kept; a source injects at
// its rate; a sink removes the vehicles that reach it; a TrafficAreaAction (1.3) keeps its
// vehicles, of its TrafficDistribution's kinds and sizes, in its area.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>

#include "opendrive/sumo_lanes.hpp"
#include "opendrive/sumo_net.hpp"
#include "opendrive/xodr_reader.hpp"
#include "openscenario/storyboard_runtime.hpp"
#include "openscenario/xosc_reader.hpp"
#include "run/openscenario_traffic.hpp"
#include "run/openscenario_world.hpp"
#include "sumo/sumo_simulator.hpp"
#include "support/cli_runner.hpp"
#include "unit/openscenario_snippets.hpp"

namespace orch {
namespace {

constexpr double kStep = 0.05;

// A on road 0 (2 km, two lanes along +x) at `s` on `lane` at `speed`; `global` in Init.
std::string scenario_text(const std::string& global, double s, int lane, double speed) {
  return R"(<?xml version="1.0"?><OpenSCENARIO>
<FileHeader revMajor="1" revMinor="2" date="2024-01-01T00:00:00" author="t" description="traffic"/>
<RoadNetwork><LogicFile filepath="road.xodr"/></RoadNetwork>
<Entities>)" + test::vehicle("A") + R"(</Entities>
<Storyboard><Init><Actions>)" + global + test::place("A", s, lane, speed) + R"(</Actions></Init>
<StopTrigger><ConditionGroup><Condition name="end" delay="0" conditionEdge="none"><ByValueCondition>
<SimulationTimeCondition value="100" rule="greaterOrEqual"/></ByValueCondition></Condition></ConditionGroup></StopTrigger>
</Storyboard></OpenSCENARIO>)";
}

// One run: the storyboard, its entities on SUMO and its traffic, stepped as run/openscenario_format.cpp does.
class TrafficRun {
 public:
  TrafficRun(const std::string& global, double s, int lane, double speed)
      : scenario_(load(global, s, lane, speed)),
        roads_(opendrive::read_xodr_file((dir_.path() / "road.xodr").string())),
        net_(opendrive::convert_to_sumo_net(dir_.path() / "road.xodr", dir_.path() / "cache")),
        lanes_(roads_, net_.net_file.string()),
        runtime_(scenario_, roads_),
        actors_(scenario_, lanes_, "", EgoDrive::Storyboard),
        traffic_(lanes_, 42),
        sim_(make_libsumo_simulator()) {
    SimulatorConfig config;
    config.net_file = net_.net_file.string();
    config.step = kStep;
    config.log_file = (dir_.path() / "sumo.log").string();
    sim_->start(config);
    sim_->apply(commands({}));
  }
  ~TrafficRun() { sim_->close(); }

  // One step: SUMO moves, the storyboard advances, the next commands go to SUMO.
  const sim::WorldSnapshot& step() {
    sim_->advance();
    snap_ = sim_->read(actors_.tracked());
    runtime_.step(kStep);
    last_ = commands(snap_.traffic);
    sim_->apply(last_);
    return snap_;
  }
  [[nodiscard]] const std::vector<sim::Command>& last_commands() const { return last_; }
  [[nodiscard]] const openscenario::EntityState& a() const { return runtime_.entities().at("A"); }
  [[nodiscard]] const OpenScenarioTraffic& traffic() const { return traffic_; }

 private:
  openscenario::Scenario load(const std::string& global, double s, int lane, double speed) {
    dir_.write("road.xodr", test::kStraightTwoLaneRoad);
    return openscenario::load_scenario(dir_.write("s.xosc", scenario_text(global, s, lane, speed)).string());
  }
  std::vector<sim::Command> commands(const std::vector<sim::NearbyVehicle>& seen) {
    auto out = actors_.place(runtime_.entities());
    for (auto& c : traffic_.update(runtime_.traffic(), runtime_.entities(), seen, runtime_.time(), kStep))
      out.push_back(std::move(c));
    return out;
  }

  test::TempDir dir_;
  openscenario::Scenario scenario_;
  opendrive::RoadNetwork roads_;
  opendrive::SumoNet net_;
  opendrive::SumoLaneIndex lanes_;
  openscenario::StoryboardRuntime runtime_;
  OpenScenarioActors actors_;
  OpenScenarioTraffic traffic_;
  std::unique_ptr<Simulator> sim_;
  sim::WorldSnapshot snap_;
  std::vector<sim::Command> last_;
};

// <= 1 inside the ellipse around `pose` (semi-axis a along its heading, b across).
double ellipse_value(const Vec2& p, const opendrive::Pose2& pose, double a, double b) {
  const double dx = p.x() - pose.x, dy = p.y() - pose.y;
  const double x = dx * std::cos(pose.heading) + dy * std::sin(pose.heading);
  const double y = -dx * std::sin(pose.heading) + dy * std::cos(pose.heading);
  return (x / a) * (x / a) + (y / b) * (y / b);
}

}  // namespace

TEST(OpenScenarioTraffic, ASwarmKeepsItsVehiclesInTheAnnulusAroundItsCentralEntity) {
  TrafficRun run(R"(<GlobalAction><TrafficAction trafficName="Crowd"><TrafficSwarmAction innerRadius="30" semiMajorAxis="200"
semiMinorAxis="15" numberOfVehicles="10" velocity="20" offset="0"><CentralObject entityRef="A"/></TrafficSwarmAction>
</TrafficAction></GlobalAction>)",
                 500, -1, 10);
  std::set<std::string> known;
  std::size_t most = 0, checked_spawns = 0, checked_removals = 0;
  for (int step = 1; step <= 600; ++step) {
    const opendrive::Pose2 centre = run.a().pose;  // where the swarm's centre was when SUMO stepped
    const sim::WorldSnapshot& snap = run.step();
    most = std::max(most, snap.traffic.size());
    std::map<std::string, Vec2> where;
    for (const auto& v : snap.traffic) {
      where[v.sumo_id] = v.position;
      if (!known.insert(v.sumo_id).second) continue;
      // First seen one step after its spawn, having moved at most 1 m (20 m/s), the centre 0.5 m:
      // inside the annulus, with that margin.
      const Vec2 at{centre.x, centre.y};
      EXPECT_GE((v.position - at).norm(), 30.0 - 2.0) << v.sumo_id << " at step " << step;
      EXPECT_LE(ellipse_value(v.position, centre, 202.0, 17.0), 1.0) << v.sumo_id << " at step " << step;
      ++checked_spawns;
    }
    // Each removal is of a vehicle outside the ellipse around the centre it was judged by.
    for (const auto& c : run.last_commands())
      if (const auto* remove = std::get_if<sim::RemoveActor>(&c); remove && where.count(remove->sumo_id)) {
        EXPECT_GT(ellipse_value(where[remove->sumo_id], run.a().pose, 200.0, 15.0), 1.0) << remove->sumo_id;
        ++checked_removals;
      }
  }
  EXPECT_EQ(most, 10u);  // numberOfVehicles, never more
  EXPECT_EQ(run.traffic().count(1), 10);  // and kept: the removed ones were replaced
  EXPECT_GT(checked_spawns, 10u);
  EXPECT_GT(checked_removals, 0u);  // the faster vehicles ahead left the ellipse
  // Every vehicle spawned is accounted for (result.json's storyboard_traffic).
  const OpenScenarioTraffic::Tally tally = run.traffic().tally(1);
  EXPECT_EQ(tally.spawned, run.traffic().spawned_total());
  EXPECT_EQ(tally.spawned, 10 + tally.removed + tally.left + tally.not_inserted);
  EXPECT_EQ(tally.removed, run.traffic().removed_total());
}

TEST(OpenScenarioTraffic, ASourceInjectsAtItsRateAndASinkRemovesWhatReachesIt) {
  TrafficRun run(R"(<GlobalAction><TrafficAction trafficName="In"><TrafficSourceAction radius="0" rate="1" velocity="25">
<Position><LanePosition roadId="0" laneId="-1" s="100" offset="0"/></Position></TrafficSourceAction></TrafficAction></GlobalAction>
<GlobalAction><TrafficAction><TrafficSinkAction radius="15"><Position><LanePosition roadId="0" laneId="-1" s="400" offset="0"/></Position>
</TrafficSinkAction></TrafficAction></GlobalAction>)",
                 1500, -2, 0);
  std::set<std::string> known;
  for (int step = 1; step <= 400; ++step) {  // 20 s
    const sim::WorldSnapshot& snap = run.step();
    for (const auto& v : snap.traffic) {
      // Never past the sink's circle (a step's travel, 1.25 m, after entering it).
      EXPECT_LE(v.position.x(), 400.0 + 15.0 + 1.5) << v.sumo_id << " at step " << step;
      if (known.insert(v.sumo_id).second) {
        EXPECT_NEAR(v.position.x(), 100.0 + 1.25, 1.5) << v.sumo_id;  // at the source, one step on
        EXPECT_NEAR(v.position.y(), -1.75, 0.3) << v.sumo_id;
      }
    }
  }
  // One vehicle a second from t = 0 (21 due by 20 s); one waits while the one before is within
  // kSpacing (20 m, 0.8 s at 25 m/s), so at most a few fewer.
  EXPECT_LE(run.traffic().spawned_total(), 21);
  EXPECT_GE(run.traffic().spawned_total(), 15);
  // Those that reached the sink (300 m at 25 m/s: 12 s) are gone.
  EXPECT_GE(run.traffic().removed_total(), 5);
  EXPECT_LE(run.traffic().count(1), 15);
  // The sink (traffic 2) removed what the source (traffic 1) lost: no background here.
  EXPECT_EQ(run.traffic().tally(2).removed, run.traffic().tally(1).removed);
  EXPECT_EQ(run.traffic().tally(2).removed_background, 0);
}

// TrafficAreaAction (1.3): road 0's lane -1 from s = 200 to 600, 4 vehicles, continuous, of a
// TrafficDistribution (a 5.5 m van or an 11 m truck). SUMO drives them out of the area's end;
// each is removed there and replaced, so the area holds 4 again.
TEST(OpenScenarioTraffic, AnAreaKeepsItsVehiclesOfItsDistributionInsideItOnRealSumo) {
  const auto vehicle = [](const std::string& category, double length) {
    return R"(<EntityDistributionEntry weight="1"><ScenarioObjectTemplate><Vehicle name=")" + category +
           R"(" vehicleCategory=")" + category + R"("><BoundingBox><Center x="0" y="0" z="1"/><Dimensions width="2.2" length=")" +
           std::to_string(length) + R"(" height="2.5"/></BoundingBox><Performance maxSpeed="30" maxDeceleration="8" maxAcceleration="3"/>
<Axles><RearAxle maxSteering="0" wheelDiameter="0.8" trackWidth="1.8" positionX="0" positionZ="0.4"/></Axles></Vehicle>
</ScenarioObjectTemplate></EntityDistributionEntry>)";
  };
  TrafficRun run(R"(<GlobalAction><TrafficAction trafficName="Zone"><TrafficAreaAction numberOfEntities="4" continuous="true">
<TrafficDistribution><TrafficDistributionEntry weight="1"><EntityDistribution>)" +
                     vehicle("van", 5.5) + vehicle("truck", 11) + R"(</EntityDistribution></TrafficDistributionEntry></TrafficDistribution>
<TrafficArea><RoadRange><RoadCursor roadId="0" s="200"><Lane id="-1"/></RoadCursor><RoadCursor roadId="0" s="600"/></RoadRange></TrafficArea>
</TrafficAreaAction></TrafficAction></GlobalAction>)",
                 1500, -2, 0);
  std::set<std::string> known;
  std::set<double> lengths;
  std::size_t most = 0;
  double moved = 0;
  std::map<std::string, double> first_x;
  for (int step = 1; step <= 1200; ++step) {  // 60 s
    const sim::WorldSnapshot& snap = run.step();
    most = std::max(most, snap.traffic.size());
    for (const auto& v : snap.traffic) {
      // In the area (its lane, s 200..600), a vehicle's length and a step's travel (2 m) past its
      // places' kPlaceStep at most (it is removed then); a lane change onto lane -2 (y = -5.25)
      // takes it out once kAreaHalfWidth (2 m) off lane -1's centre.
      EXPECT_GT(v.position.y(), -3.5 - 0.5) << v.sumo_id << " at step " << step;
      EXPECT_LT(v.position.y(), -1.75 + 0.3) << v.sumo_id << " at step " << step;
      EXPECT_GE(v.position.x(), 200.0 - 12.0) << v.sumo_id << " at step " << step;
      EXPECT_LE(v.position.x(), 600.0 + OpenScenarioTraffic::kPlaceStep + 2.0) << v.sumo_id << " at step " << step;
      lengths.insert(v.length);
      if (known.insert(v.sumo_id).second) first_x[v.sumo_id] = v.position.x();
      moved = std::max(moved, v.position.x() - first_x[v.sumo_id]);
    }
  }
  EXPECT_EQ(most, 4u);                  // numberOfEntities, never more
  EXPECT_EQ(run.traffic().count(1), 4);  // and kept
  EXPECT_GT(moved, 50.0);               // SUMO's driver drives them
  const OpenScenarioTraffic::Tally tally = run.traffic().tally(1);
  EXPECT_GT(tally.removed, 0);  // those that drove out of the area's end
  EXPECT_EQ(tally.spawned, 4 + tally.removed + tally.left + tally.not_inserted);
  for (const double l : lengths) EXPECT_TRUE(std::abs(l - 5.5) < 1e-6 || std::abs(l - 11.0) < 1e-6) << l;
}

}  // namespace orch

// Traffic signals on real SUMO, on esmini's fabriksgatan_traffic_lights.xodr: netconvert
// makes OpenDRIVE signal 1 (road 3, before junction 4) part of SUMO's traffic light "4". A
// car SUMO drives (--ego) stops at the light while the storyboard's controller holds it red
// and drives through once the controller's phase turns it green; SUMO's own program (green
// for the first 42 s) would have let it through at once. And esmini's traffic_lights.xosc
// runs: its events wait for the signal states its actions set. A phase's
// TrafficSignalGroupState (1.2) holds the light red the same way, through the road's signal
// group (an OpenDRIVE <controller> added to a copy of the road).
#include <gtest/gtest.h>

#include <cmath>

#include "support/cli_runner.hpp"
#include "support/trace_csv.hpp"

using namespace orch::test;

namespace {

const std::string kRoad = std::string(ORCH_SHARED_DATA_DIR) + "/esmini_examples/xodr/fabriksgatan_traffic_lights.xodr";

std::string scenario(const std::string& phases, const std::string& road = kRoad) {
  return R"(<?xml version="1.0"?><OpenSCENARIO>
<FileHeader revMajor="1" revMinor="3" date="2024-01-01T00:00:00" author="t" description="a red light on SUMO"/>
<RoadNetwork><LogicFile filepath=")" + road + R"("/><TrafficSignals>
 <TrafficSignalController name="Junction4">)" + phases + R"(</TrafficSignalController></TrafficSignals></RoadNetwork>
<Entities><ScenarioObject name="Ego"><Vehicle name="car" vehicleCategory="car">
  <BoundingBox><Center x="1.4" y="0" z="0.8"/><Dimensions width="2" length="5" height="1.5"/></BoundingBox>
  <Performance maxSpeed="70" maxDeceleration="10" maxAcceleration="5"/>
  <Axles><FrontAxle maxSteering="0.5" wheelDiameter="0.8" trackWidth="1.68" positionX="2.98" positionZ="0.4"/>
  <RearAxle maxSteering="0" wheelDiameter="0.8" trackWidth="1.68" positionX="0" positionZ="0.4"/></Axles>
</Vehicle></ScenarioObject></Entities>
<Storyboard><Init><Actions><Private entityRef="Ego">
  <PrivateAction><TeleportAction><Position><LanePosition roadId="3" laneId="-1" offset="0" s="10"/></Position></TeleportAction></PrivateAction>
  <PrivateAction><RoutingAction><AssignRouteAction><Route name="R" closed="false">
    <Waypoint routeStrategy="shortest"><Position><LanePosition roadId="3" laneId="-1" offset="0" s="11"/></Position></Waypoint>
    <Waypoint routeStrategy="shortest"><Position><LanePosition roadId="2" laneId="1" offset="0" s="200"/></Position></Waypoint>
  </Route></AssignRouteAction></RoutingAction></PrivateAction>
  <PrivateAction><LongitudinalAction><SpeedAction><SpeedActionDynamics dynamicsShape="step" dynamicsDimension="time" value="0"/>
    <SpeedActionTarget><AbsoluteTargetSpeed value="10"/></SpeedActionTarget></SpeedAction></LongitudinalAction></PrivateAction>
</Private></Actions></Init>
<StopTrigger><ConditionGroup><Condition name="End" delay="0" conditionEdge="none"><ByValueCondition>
  <SimulationTimeCondition value="35" rule="greaterThan"/></ByValueCondition></Condition></ConditionGroup></StopTrigger>
</Storyboard></OpenSCENARIO>)";
}

const std::string kRed20 = R"(<Phase name="red" duration="20"><TrafficSignalState trafficSignalId="1" state="on;off;off"/></Phase>
  <Phase name="green" duration="100"><TrafficSignalState trafficSignalId="1" state="off;off;on"/></Phase>)";
const std::string kGreen = R"(<Phase name="green" duration="100"><TrafficSignalState trafficSignalId="1" state="off;off;on"/></Phase>)";

// The run's trace (the car SUMO drives through the storyboard's lights).
Trace run_with(const TempDir& dir, const std::string& name, const std::string& phases,
               const std::string& road = kRoad) {
  const auto file = dir.write(name + ".xosc", scenario(phases, road));
  const auto out = dir / name;
  const auto r = run_cli({"run", file.string(), "--ego", "Ego", "--out", out.string(), "-q", "--no-report"});
  EXPECT_EQ(r.exit_code, 0) << r.output;
  const std::string log = slurp(out / "run.log");
  EXPECT_EQ(log.find("has a state but no SUMO traffic light"), std::string::npos) << log;
  return Trace(out / "trace.csv");
}

}  // namespace

TEST(EsminiTrafficSignals, ASumoDrivenCarGoesThroughTheStoryboardsGreen) {
  TempDir dir;
  const Trace trace = run_with(dir, "green", kGreen);
  std::string edge_at_15;
  for (const auto& row : trace.rows())
    if (row.str("actor_id") == "Ego" && std::abs(row.num("time") - 15.0) < 1e-6) edge_at_15 = row.str("edge");
  EXPECT_EQ(edge_at_15, "2");  // through junction 4 onto road 2 (SUMO's program alone: waiting on -3)
}

TEST(EsminiTrafficSignals, ASumoDrivenCarWaitsAtTheStoryboardsRedAndGoesOnGreen) {
  TempDir dir;
  const Trace trace = run_with(dir, "red_then_green", kRed20);
  double speed_at_19 = -1, x_at_19 = 0, y_at_19 = 0, x_at_34 = 0, y_at_34 = 0;
  int rows = 0;
  for (const auto& row : trace.rows()) {
    if (row.str("actor_id") != "Ego") continue;
    ++rows;
    const double t = row.num("time");
    if (std::abs(t - 19.0) < 1e-6) speed_at_19 = row.num("speed"), x_at_19 = row.num("x"), y_at_19 = row.num("y");
    if (std::abs(t - 34.0) < 1e-6) x_at_34 = row.num("x"), y_at_34 = row.num("y");
    if (t <= 20.0) {
      EXPECT_NE(row.str("edge").rfind(":4", 0), 0u) << "in junction 4 on red at " << t;
    }
  }
  ASSERT_GT(rows, 600);
  EXPECT_NEAR(speed_at_19, 0.0, 0.05);  // standing at the red light
  EXPECT_GT(std::hypot(x_at_34 - x_at_19, y_at_34 - y_at_19), 50.0);  // 14 s of green: through the junction and on
}

// The controller "Junction4" names the road's signal group of that id (signal 1): its phases'
// group states set signal 1 as the TrafficSignalStates above do.
TEST(EsminiTrafficSignals, AGroupStateHoldsTheRoadsSignalGroupRedOnSumo) {
  TempDir dir;
  std::string road = slurp(kRoad);
  const auto end = road.rfind("</OpenDRIVE>");
  ASSERT_NE(end, std::string::npos);
  road.insert(end, R"(<controller id="Junction4" name="j4"><control signalId="1" type="0"/></controller>)");
  const auto copy = dir.write("fabriksgatan_grouped.xodr", road);
  const Trace trace = run_with(dir, "group_red_then_green", R"(<Phase name="red" duration="20"><TrafficSignalGroupState state="on;off;off"/></Phase>
  <Phase name="green" duration="100"><TrafficSignalGroupState state="off;off;on"/></Phase>)", copy.string());
  double speed_at_19 = -1, x_at_19 = 0, y_at_19 = 0, x_at_34 = 0, y_at_34 = 0;
  for (const auto& row : trace.rows()) {
    if (row.str("actor_id") != "Ego") continue;
    const double t = row.num("time");
    if (std::abs(t - 19.0) < 1e-6) speed_at_19 = row.num("speed"), x_at_19 = row.num("x"), y_at_19 = row.num("y");
    if (std::abs(t - 34.0) < 1e-6) x_at_34 = row.num("x"), y_at_34 = row.num("y");
    if (t <= 20.0) {
      EXPECT_NE(row.str("edge").rfind(":4", 0), 0u) << "in junction 4 on red at " << t;
    }
  }
  EXPECT_NEAR(speed_at_19, 0.0, 0.05);  // standing at the group's red
  EXPECT_GT(std::hypot(x_at_34 - x_at_19, y_at_34 - y_at_19), 50.0);  // and on once it is green
}

TEST(EsminiTrafficSignals, EsminisTrafficLightsFileRunsItsSignalEvents) {
  TempDir out;
  const std::string file = std::string(ORCH_SHARED_DATA_DIR) + "/esmini_examples/xosc/traffic_lights.xosc";
  const auto r = run_cli({"run", file, "--out", out.path().string(), "-q", "--no-report"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(read_json(out / "result.json")["verdict"], "success");
  const std::string log = slurp(out / "run.log");
  // Each event waits for the state an earlier one set (yellow, then red after 3 s, ...).
  for (const char* event : {"StopLightEvent2", "StopLightEvent3", "PedestrianLightEvent", "PedestrianLightEvent2",
                            "DriveOnGreenEvent", "WalkOnGreenEvent1", "WalkOnGreenEvent2"})
    EXPECT_NE(log.find(std::string("event ") + event + " startTransition"), std::string::npos) << event << "\n" << log;
}

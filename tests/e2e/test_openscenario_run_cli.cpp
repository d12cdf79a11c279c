// `orchestrator run FILE.xosc` with the real CLI on the repository's own sample (no
// ../shared needed): to the StopTrigger on SUMO, and clear errors for a bad --ego or file.
#include <gtest/gtest.h>

#include <cctype>
#include <fstream>
#include <map>
#include <unistd.h>

#include "support/cli_runner.hpp"
#include "support/trace_csv.hpp"

using namespace orch::test;

namespace {

// The car of the inline scenarios: 5 m long, its reference point on the rear axle.
const std::string kCar = R"(<Vehicle name="car" vehicleCategory="car">
<BoundingBox><Center x="1.5" y="0" z="0.9"/><Dimensions width="2" length="5" height="1.8"/></BoundingBox>
<Performance maxSpeed="70" maxDeceleration="10" maxAcceleration="10"/>
<Axles><FrontAxle maxSteering="0.5" wheelDiameter="0.8" trackWidth="1.68" positionX="3" positionZ="0.4"/>
<RearAxle maxSteering="0" wheelDiameter="0.8" trackWidth="1.68" positionX="0" positionZ="0.4"/></Axles>
</Vehicle>)";

const std::string kOvertaking = std::string(ORCH_SOURCE_DIR) + "/scenarios/openscenario/overtaking.xosc";

TEST(OpenScenarioRunCli, OvertakingRunsToItsStopTriggerWithEveryEntityTraced) {
  TempDir out;
  const auto r = run_cli({"run", kOvertaking, "--out", out.path().string(), "-q"});
  const auto result = read_json(out / "result.json");
  ASSERT_EQ(result["verdict"], "success") << result["reason"] << "\n" << r.output;
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(result["reason"].get<std::string>().find("StopTrigger"), std::string::npos);
  EXPECT_EQ(result["map_id"], "motorway_3_lanes");
  EXPECT_GT(result["wall_time_s"].get<double>(), 0.0);  // the report's "wall time"
  const Trace trace(out / "trace.csv");
  bool ego = false, overtaker = false;
  for (const auto& row : trace.rows()) {
    ego |= row.str("actor_id") == "Ego";
    overtaker |= row.str("actor_id") == "Overtaker";
    EXPECT_FALSE(row.str("edge").empty()) << row.str("actor_id") << " @" << row.str("time");
  }
  EXPECT_TRUE(ego && overtaker);
}

TEST(OpenScenarioRunCli, ReportShowsTheEntitiesByNameWithTheEgo) {
  TempDir out;
  const auto r = run_cli({"run", std::string(ORCH_SOURCE_DIR) + "/scenarios/openscenario/cut_in_traffic.xosc", "--out",
                          out.path().string(), "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(r.output.find("no report.html"), std::string::npos) << r.output;
  ASSERT_TRUE(std::filesystem::exists(out / "report.html")) << r.output;
  // result.json names the entities and which one is the ego (the ALKSController one).
  const auto result = read_json(out / "result.json");
  std::map<std::string, bool> ego_of;
  for (const auto& a : result["actors"]) ego_of[a["sumo_id"].get<std::string>()] = a["ego"].get<bool>();
  EXPECT_EQ(ego_of, (std::map<std::string, bool>{{"CutIn", false}, {"Ego", true}}));
  // The report's actors are the trace's entity names.
  const std::string page = slurp(out / "report.html");
  EXPECT_NE(page.find("\"actor_id\":\"CutIn\""), std::string::npos);
  EXPECT_NE(page.find("\"actor_id\":\"Ego\""), std::string::npos);
}

TEST(OpenScenarioRunCli, UnknownEgoIsAnErrorWithASuggestion) {
  TempDir out;
  const auto r = run_cli({"run", kOvertaking, "--ego", "Egoo", "--out", out.path().string(), "-q"});
  const auto result = read_json(out / "result.json");
  EXPECT_EQ(result["verdict"], "error");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(result["reason"].get<std::string>().find("did you mean \"Ego\""), std::string::npos) << result["reason"];
}

TEST(OpenScenarioRunCli, AMisspeltAttributeIsAnErrorNamingTheFileAndLine) {
  TempDir out;
  std::string text = slurp(kOvertaking);
  const auto at = text.find("conditionEdge");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, 13, "conditionEgde");
  // Beside the original so that its relative road and catalog paths still resolve.
  const auto bad = std::filesystem::path(kOvertaking).parent_path() / ("bad_" + std::to_string(::getpid()) + ".xosc");
  { std::ofstream(bad) << text; }
  const auto r = run_cli({"run", bad.string(), "--out", out.path().string(), "-q"});
  std::filesystem::remove(bad);
  const auto result = read_json(out / "result.json");
  EXPECT_EQ(result["verdict"], "error");
  const std::string reason = result["reason"];
  const auto name_at = reason.find(bad.filename().string() + ":");
  ASSERT_NE(name_at, std::string::npos) << reason;
  EXPECT_TRUE(std::isdigit(static_cast<unsigned char>(reason[name_at + bad.filename().string().size() + 1])))
      << "no line number: " << reason;
  EXPECT_NE(reason.find("did you mean \"conditionEdge\""), std::string::npos) << reason;
}

}  // namespace

// A StopTrigger that never fires (esmini's cut-in_cr.xosc waits for a continuous action to
// end) ran for ever: 58,835 s simulated and a 3.5-million-line trace before it was killed.
// Without --max-time a run now ends at kDefaultMaxTimeS (7,200 s), with a reason that says so.
TEST(OpenScenarioRunCli, AStopTriggerThatNeverFiresEndsAtTheDefaultLimit) {
  TempDir dir;
  const auto file = dir.write("never_stops.xosc", R"(<?xml version="1.0"?><OpenSCENARIO>
<FileHeader revMajor="1" revMinor="3" date="2024-01-01T00:00:00" author="t" description="never stops"/>
<RoadNetwork/>
<Entities><ScenarioObject name="Car">)" + kCar + R"(</ScenarioObject></Entities>
<Storyboard><Init><Actions><Private entityRef="Car">
<PrivateAction><TeleportAction><Position><WorldPosition x="1.8" y="-358" z="0" h="1.5707963"/></Position></TeleportAction></PrivateAction>
</Private></Actions></Init>
<StopTrigger><ConditionGroup><Condition name="Stop" delay="0" conditionEdge="none"><ByValueCondition>
<SimulationTimeCondition value="9000" rule="greaterOrEqual"/></ByValueCondition></Condition></ConditionGroup></StopTrigger>
</Storyboard></OpenSCENARIO>)");
  TempDir out;
  const auto r = run_cli({"run", file.string(), "--out", out.path().string(), "-q", "--no-report", "--step", "1"});
  EXPECT_EQ(r.exit_code, 1) << r.output;
  const auto result = read_json(out / "result.json");
  EXPECT_EQ(result["verdict"], "failure");
  EXPECT_NEAR(result["sim_time"].get<double>(), 7200.0, 1e-6);
  const std::string reason = result["reason"];
  EXPECT_NE(reason.find("the limit without --max-time"), std::string::npos) << reason;
  EXPECT_TRUE(result["max_time"].is_null());  // the user gave none
}

// Entities placed off every lane of a road network (a camera, an object beside the road:
// esmini's parking_demo.xosc) were refused ("on no lane of the road network"); now they stand
// at their world position off the lanes (SUMO's vehicle entered on a lane near them and moved
// there), an OffroadCondition fires for them and not for an entity on a lane.
TEST(OpenScenarioRunCli, AnEntityOffEveryLaneOfTheRoadsStandsWhereItIsPlaced) {
  TempDir dir;
  const std::string road = std::string(ORCH_SOURCE_DIR) + "/scenarios/openscenario/roads/rural_2_lanes_600m.xodr";
  const std::string car = kCar;
  const auto off_road_event = [](const std::string& entity) {
    return "<Event name=\"Off" + entity + "\" priority=\"parallel\"><Action name=\"Set" + entity +
           "\"><GlobalAction><ParameterAction parameterRef=\"p\"><SetAction value=\"1\"/></ParameterAction></GlobalAction>"
           "</Action><StartTrigger><ConditionGroup><Condition name=\"c" + entity +
           "\" delay=\"0\" conditionEdge=\"none\"><ByEntityCondition><TriggeringEntities triggeringEntitiesRule=\"any\">"
           "<EntityRef entityRef=\"" + entity + "\"/></TriggeringEntities><EntityCondition><OffroadCondition duration=\"0.2\"/>"
           "</EntityCondition></ByEntityCondition></Condition></ConditionGroup></StartTrigger></Event>";
  };
  const auto file = dir.write("off_lanes.xosc", std::string(R"(<?xml version="1.0"?><OpenSCENARIO>
<FileHeader revMajor="1" revMinor="3" date="2024-01-01T00:00:00" author="t" description="off the lanes"/>
<ParameterDeclarations><ParameterDeclaration name="p" parameterType="double" value="0"/></ParameterDeclarations>
<RoadNetwork><LogicFile filepath=")") + road + R"("/></RoadNetwork>
<Entities><ScenarioObject name="Camera">)" + car + R"(</ScenarioObject><ScenarioObject name="Car">)" + car +
                                                   R"(</ScenarioObject></Entities>
<Storyboard><Init><Actions>
<Private entityRef="Camera"><PrivateAction><TeleportAction><Position><WorldPosition x="100" y="25" z="0" h="0"/></Position></TeleportAction></PrivateAction></Private>
<Private entityRef="Car"><PrivateAction><TeleportAction><Position><LanePosition roadId="1" laneId="-1" s="50" offset="0"/></Position></TeleportAction></PrivateAction></Private>
</Actions></Init>
<Story name="S"><Act name="A"><ManeuverGroup maximumExecutionCount="1" name="G"><Actors selectTriggeringEntities="false"/><Maneuver name="M">)" +
                                                   off_road_event("Camera") + off_road_event("Car") + R"(</Maneuver></ManeuverGroup>
<StartTrigger><ConditionGroup><Condition name="go" delay="0" conditionEdge="none"><ByValueCondition><SimulationTimeCondition value="0" rule="greaterOrEqual"/></ByValueCondition></Condition></ConditionGroup></StartTrigger></Act></Story>
<StopTrigger><ConditionGroup><Condition name="Stop" delay="0" conditionEdge="none"><ByValueCondition>
<SimulationTimeCondition value="1" rule="greaterOrEqual"/></ByValueCondition></Condition></ConditionGroup></StopTrigger>
</Storyboard></OpenSCENARIO>)");
  TempDir out;
  const auto r = run_cli({"run", file.string(), "--out", out.path().string(), "-q", "--no-report"});
  const auto result = read_json(out / "result.json");
  ASSERT_EQ(result["verdict"], "success") << result["reason"] << "\n" << r.output;
  const std::string log = slurp(out / "run.log");
  EXPECT_NE(log.find("event OffCamera startTransition"), std::string::npos) << log;
  EXPECT_EQ(log.find("event OffCar startTransition"), std::string::npos) << log;
  const Trace trace(out / "trace.csv");
  int rows = 0;
  for (const auto& row : trace.rows()) {
    if (row.str("actor_id") != "Camera") continue;
    ++rows;
    EXPECT_NEAR(row.num("x"), 100.0, 0.01) << "@" << row.str("time");
    EXPECT_NEAR(row.num("y"), 25.0, 0.01) << "@" << row.str("time");
    EXPECT_EQ(row.str("edge"), "") << "@" << row.str("time");  // off the lanes
  }
  EXPECT_GT(rows, 10);
}

// A scenario without a road (no LogicFile, as the standard allows): SUMO runs on a generated
// parking road and the car is where the storyboard puts it by world position, off every lane,
// moving straight on along its heading (north here) at its SpeedAction's speed.
TEST(OpenScenarioRunCli, AScenarioWithoutARoadRunsWithEntitiesAtTheirWorldPositions) {
  TempDir dir;
  const auto file = dir.write("no_road.xosc", R"(<?xml version="1.0"?><OpenSCENARIO>
<FileHeader revMajor="1" revMinor="3" date="2024-01-01T00:00:00" author="t" description="no road"/>
<RoadNetwork/>
<Entities><ScenarioObject name="Car">)" + kCar + R"(</ScenarioObject></Entities>
<Storyboard><Init><Actions><Private entityRef="Car">
<PrivateAction><TeleportAction><Position><WorldPosition x="1.8" y="-358" z="0" h="1.5707963"/></Position></TeleportAction></PrivateAction>
<PrivateAction><LongitudinalAction><SpeedAction><SpeedActionDynamics dynamicsShape="step" dynamicsDimension="time" value="0"/>
<SpeedActionTarget><AbsoluteTargetSpeed value="5"/></SpeedActionTarget></SpeedAction></LongitudinalAction></PrivateAction>
</Private></Actions></Init>
<StopTrigger><ConditionGroup><Condition name="Stop" delay="0" conditionEdge="none"><ByValueCondition>
<SimulationTimeCondition value="3" rule="greaterOrEqual"/></ByValueCondition></Condition></ConditionGroup></StopTrigger>
</Storyboard></OpenSCENARIO>)");
  TempDir out;
  const auto r = run_cli({"run", file.string(), "--out", out.path().string(), "-q"});
  const auto result = read_json(out / "result.json");
  ASSERT_EQ(result["verdict"], "success") << result["reason"] << "\n" << r.output;
  EXPECT_EQ(result["map_id"], "none");
  const Trace trace(out / "trace.csv");
  int rows = 0;
  for (const auto& row : trace.rows()) {
    if (row.str("actor_id") != "Car") continue;
    ++rows;
    EXPECT_NEAR(row.num("x"), 1.8, 0.01) << "@" << row.str("time");
    EXPECT_NEAR(row.num("y"), -358 + 5 * row.num("time"), 0.01) << "@" << row.str("time");
    EXPECT_EQ(row.str("driver"), "script");
  }
  EXPECT_GT(rows, 50);
}

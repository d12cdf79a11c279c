// Overtaking through the lane of the opposite direction on a two-lane, two-way road: a map
// built from a waypoint file written here, a lane_change onto the other direction's route,
// and back.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "support/cli_runner.hpp"
#include "support/trace_csv.hpp"

using namespace orch::test;

namespace {

// RoadEditor coordinates: map y = -z. "East" runs along +x at map y = 0, "West" back
// along -x at map y = 3.5 (to the left of East).
std::string two_way_road() {
  std::string east, west;
  for (int i = 0; i <= 1000; ++i) {
    east += (i ? "," : "") + std::string(R"({"x":)") + std::to_string(i) + R"(,"y":0,"z":0,"v":60})";
    west += (i ? "," : "") + std::string(R"({"x":)") + std::to_string(1000 - i) + R"(,"y":0,"z":-3.5,"v":60})";
  }
  return R"({"id":"WayPoint_TwoWay","mapId":"TwoWay","waypoints":[{"id":"East","points":[)" + east +
         R"(]},{"id":"West","points":[)" + west + R"(]}],"properties":[]})";
}

const char* kOvertake = R"({
  "map_id": "TwoWay",
  "actors": {"ego": {"actor_id": 0, "model_id": "vehicle.toyota.prius"},
             "others": [{"actor_id": 1, "model_id": "vehicle.volkswagen.t2", "description": "Slow van"},
                        {"actor_id": 2, "model_id": "vehicle.audi.tt", "description": "Overtaker"}]},
  "scenario": {
    "opening_scene": {
      "ego": {"start_position": {"wp_id": "East", "wp_idx": 5}, "end_position": {"wp_id": "East", "wp_idx": 60}},
      "others": [
        {"actor_id": 1, "start_position": {"type": "waypoint", "wp_id": "East", "wp_idx": 200},
         "start_speed": {"type": "absolute", "value": 30}},
        {"actor_id": 2, "start_position": {"type": "waypoint", "wp_id": "East", "wp_idx": 150},
         "start_speed": {"type": "absolute", "value": 60}}],
      "next_scenes": [1]},
    "scenes": [
      {"scene_id": 1, "description": "Close behind the van: pull out into the oncoming lane",
       "conditions": {"and": [{"distance": {"actor_id": 2, "target_actor_id": 1, "comparison": "<", "value": 35}}]},
       "actions": [{"lane_change": {"actor_id": 2, "type": "lane", "wp_id": "West", "time": 2}}],
       "next_scenes": [2]},
      {"scene_id": 2, "description": "Past the van: back into the own lane",
       "conditions": {"and": [{"distance": {"actor_id": 2, "target_actor_id": 1, "comparison": "<", "value": -15}}]},
       "actions": [{"lane_change": {"actor_id": 2, "type": "lane", "wp_id": "East", "time": 3}}],
       "duration": 0, "next_scenes": [3]}],
    "ending_scenes": [{"scene_id": 3, "conditions": {"and": [{"simulation_time": {"comparison": ">=", "value": 40}}]}}]},
  "stop_conditions": {"or": [{"simulation_time": {"comparison": ">=", "value": 60}}]}
})";

}  // namespace

TEST(OppositeLane, OvertakeThroughTheOncomingLaneAndBack) {
  TempDir dir;
  const auto wps = dir.write("two_way.waypoint.json", two_way_road());
  const auto maps = dir / "maps";
  const auto built = run_cli({"map", "build", "--waypoints", wps.string(), "--id", "TwoWay", "--out",
                              (maps / "TwoWay").string()});
  ASSERT_EQ(built.exit_code, 0) << built.output;
  const auto scenario = dir.write("overtake.json", kOvertake);
  const auto r = run_cli({"run", scenario.string(), "--maps", maps.string(), "--out", (dir / "out").string(), "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto result = read_json(dir / "out" / "result.json");
  ASSERT_EQ(result["scenes"].size(), 4u) << result.dump(2);
  const double out_at = result["scenes"][1]["enter_time"], back_at = result["scenes"][2]["enter_time"];
  EXPECT_TRUE(result["collisions"].empty()) << result["collisions"].dump();

  Trace trace(dir / "out" / "trace.csv");
  std::string east_edge, west_edge;
  bool was_on_west = false;
  double previous_x = -1;
  for (const auto& row : trace.actor(2)) {
    const double t = row.num("time");
    // Always eastbound: x grows and the car points east, also in the oncoming lane.
    EXPECT_GT(row.num("x"), previous_x) << "t=" << t;
    EXPECT_NEAR(std::cos(row.num("heading")), 1.0, 0.02) << "t=" << t;
    previous_x = row.num("x");
    if (t < out_at) east_edge = row.str("edge");
    if (t > out_at + 2.05 && t < back_at) {
      EXPECT_NEAR(row.num("y"), 3.5, 0.01) << "t=" << t;  // on the West lane's centre
      west_edge = row.str("edge");
      was_on_west = true;
    }
    if (t > back_at + 3.05) {
      EXPECT_NEAR(row.num("y"), 0.0, 0.01) << "t=" << t;
    }
  }
  EXPECT_TRUE(was_on_west);
  // SUMO had it on the West edges (the other direction's) while overtaking.
  EXPECT_NE(west_edge.find("West"), std::string::npos) << west_edge;
  EXPECT_EQ(west_edge.find("East"), std::string::npos) << west_edge;
  EXPECT_NE(east_edge.find("East"), std::string::npos) << east_edge;
}

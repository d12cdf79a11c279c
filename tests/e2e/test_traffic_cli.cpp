// `orchestrator run --traffic` end to end: background traffic from the map folder, seeded,
// counted every step, traced only on request, living around the scripted actors.
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "support/cli_runner.hpp"
#include "support/trace_csv.hpp"

using namespace orch::test;

namespace {

// A construction sign standing in the middle lane of the highway, the ego passing on the
// left lane, dense traffic all around.
std::string obstacle_on_the_highway() {
  return R"({
  "title": "Obstacle in the middle lane",
  "map_id": "highway",
  "actors": {
    "ego": {"actor_id": 0, "model_id": "vehicle.toyota.prius"},
    "others": [{"actor_id": 1, "model_id": "static.prop.warningconstruction"}]
  },
  "scenario": {
    "opening_scene": {
      "ego": {"start_position": {"wp_id": "Waypoint01", "wp_idx": 100},
              "end_position": {"wp_id": "Waypoint01", "wp_idx": 1800}},
      "others": [{"actor_id": 1, "start_position": {"type": "waypoint", "wp_id": "Waypoint02", "wp_idx": 500}}],
      "next_scenes": [1]
    },
    "scenes": [],
    "ending_scenes": [{"scene_id": 1, "description": "One minute",
                       "conditions": {"and": [{"simulation_time": {"comparison": ">=", "value": 60}}]}}]
  }
})";
}

}  // namespace

TEST(TrafficCli, CountsEveryStepAndBackgroundRowsOnlyWhenAsked) {
  TempDir plain, traced;
  const std::string scenario = source_path("scenarios/highway_cut_in.json");
  ASSERT_EQ(run_scenario(scenario, plain, {"--traffic", "dense", "--max-time", "15"}).exit_code, 1);
  ASSERT_EQ(run_scenario(scenario, traced, {"--traffic", "dense", "--max-time", "15", "--trace-background"}).exit_code, 1);

  EXPECT_FALSE(std::filesystem::exists(plain / "background.csv"));
  // The flag only writes: what happened is the same.
  EXPECT_EQ(slurp(plain / "trace.csv"), slurp(traced / "trace.csv"));
  EXPECT_EQ(slurp(plain / "counts.csv"), slurp(traced / "counts.csv"));

  const auto result = read_json(plain / "result.json");
  EXPECT_EQ(result["traffic"], "dense");
  const std::string file = result["inputs"]["traffic"]["path"];
  EXPECT_NE(file.find("sumo_nets/highway/traffic/dense.rou.xml"), std::string::npos) << file;
  EXPECT_EQ(result["inputs"]["traffic"]["sha256"].get<std::string>().size(), 64u);

  Trace counts(plain / "counts.csv");
  ASSERT_EQ(static_cast<long long>(counts.rows().size()), result["steps"].get<long long>());
  EXPECT_EQ(counts.header(), "time,background_vehicles,nearby_vehicles,waiting_over_60s");
  EXPECT_EQ(counts.rows().front().integer("background_vehicles"), 0);  // traffic starts at t=1 s
  EXPECT_GT(counts.rows().back().integer("background_vehicles"), 100);  // 2 x 3 lanes x 2 km, dense
  int most_nearby = 0;
  for (const auto& r : counts.rows()) most_nearby = std::max(most_nearby, r.integer("nearby_vehicles"));
  EXPECT_GT(most_nearby, 0);

  Trace background(traced / "background.csv");
  ASSERT_FALSE(background.rows().empty());
  std::set<std::string> ids;
  for (const auto& r : background.rows()) {
    const std::string id = r.str("vehicle_id");
    EXPECT_EQ(id.rfind("bg", 0), 0u) << id;  // never "ego" or "actor<N>"
    EXPECT_NEAR(r.num("length"), 5.0, 1e-9);  // SUMO's default passenger car
    ids.insert(id);
  }
  EXPECT_GT(ids.size(), 10u);
  // One row per nearby vehicle and step: the counts say how many.
  long long nearby_total = 0;
  for (const auto& r : counts.rows()) nearby_total += r.integer("nearby_vehicles");
  EXPECT_EQ(static_cast<long long>(background.rows().size()), nearby_total);
}

TEST(TrafficCli, SameSeedSameTrafficOtherSeedOtherTraffic) {
  TempDir a, b, c;
  const std::string scenario = source_path("scenarios/highway_cut_in.json");
  const std::vector<std::string> opts{"--traffic", "dense", "--max-time", "10", "--trace-background"};
  auto with_seed = [&](const char* seed) {
    auto o = opts;
    o.insert(o.end(), {"--seed", seed});
    return o;
  };
  ASSERT_EQ(run_scenario(scenario, a, with_seed("7")).exit_code, 1);
  ASSERT_EQ(run_scenario(scenario, b, with_seed("7")).exit_code, 1);
  ASSERT_EQ(run_scenario(scenario, c, with_seed("8")).exit_code, 1);
  EXPECT_EQ(slurp(a / "trace.csv"), slurp(b / "trace.csv"));
  EXPECT_EQ(slurp(a / "counts.csv"), slurp(b / "counts.csv"));
  EXPECT_EQ(slurp(a / "background.csv"), slurp(b / "background.csv"));
  EXPECT_GT(slurp(a / "background.csv").size(), 1000u);
  EXPECT_NE(slurp(a / "background.csv"), slurp(c / "background.csv"));
}

TEST(TrafficCli, BackgroundCarsStopForAScriptedObstacleInsteadOfHittingIt) {
  TempDir out;
  const auto file = out.write("obstacle.json", obstacle_on_the_highway());
  const auto r = run_scenario(file.string(), out, {"--traffic", "dense", "--trace-background"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  Trace trace(out / "trace.csv");
  const auto sign = trace.actor(1);
  ASSERT_FALSE(sign.empty());
  const double sx = sign.back().num("x");
  const double sy = sign.back().num("y");
  const double heading = sign.back().num("heading");
  const double ux = std::cos(heading);
  const double uy = std::sin(heading);
  constexpr double kSignLength = 0.8;  // catalog: static.prop.warningconstruction
  constexpr double kSignWidth = 2.0;
  bool queued_behind = false;
  const Trace background(out / "background.csv");
  for (const auto& row : background.rows()) {
    const double dx = row.num("x") - sx;
    const double dy = row.num("y") - sy;
    const double along = dx * ux + dy * uy;  // + = ahead of the sign
    const double across = -dx * uy + dy * ux;
    const bool overlaps = std::abs(along) < (row.num("length") + kSignLength) / 2 &&
                          std::abs(across) < (row.num("width") + kSignWidth) / 2;
    EXPECT_FALSE(overlaps) << row.str("vehicle_id") << " at t=" << row.str("time") << " overlaps the sign";
    if (std::abs(across) < 1.0 && along < 0 && along > -30 && row.num("speed") < 1.0) queued_behind = true;
  }
  EXPECT_TRUE(queued_behind) << "no background car waited behind the sign";
}

TEST(TrafficCli, ScenarioMayNameItsOwnTrafficFile) {
  TempDir out;
  std::string text = slurp(source_path("scenarios/highway_cut_in.json"));
  text.replace(text.find("\"map_id\""), 8, "\"traffic\": \"mine.rou.xml\", \"map_id\"");
  const auto scenario = out.write("own_traffic.json", text);
  out.write("mine.rou.xml",
            "<routes>\n  <vType id=\"orch.background\" vClass=\"passenger\"/>\n"
            "  <flow id=\"mine\" type=\"orch.background\" begin=\"1\" end=\"100\" period=\"1\" "
            "from=\"Waypoint03+Waypoint02+Waypoint01#0\" to=\"Waypoint03+Waypoint02+Waypoint01#7\" "
            "departLane=\"2\" departPos=\"base\" departSpeed=\"max\"/>\n</routes>\n");
  TempDir own, none;
  ASSERT_EQ(run_scenario(scenario.string(), own, {"--max-time", "10"}).exit_code, 1);
  ASSERT_EQ(run_scenario(scenario.string(), none, {"--max-time", "10", "--traffic", "none"}).exit_code, 1);
  const auto result = read_json(own / "result.json");
  EXPECT_NE(result["traffic"].get<std::string>().find("mine.rou.xml"), std::string::npos);
  EXPECT_GE(Trace(own / "counts.csv").rows().back().integer("background_vehicles"), 5);  // one a second from t=1
  EXPECT_EQ(Trace(none / "counts.csv").rows().back().integer("background_vehicles"), 0);
  EXPECT_TRUE(read_json(none / "result.json")["inputs"]["traffic"].is_null());
}

TEST(TrafficCli, UnknownTrafficLevelIsAnError) {
  TempDir out;
  const auto r = run_scenario(source_path("scenarios/highway_cut_in.json"), out, {"--traffic", "heavy"});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  const auto result = read_json(out / "result.json");
  EXPECT_EQ(result["verdict"], "error");
  EXPECT_NE(result["reason"].get<std::string>().find("heavy"), std::string::npos);
}

TEST(TrafficCli, BackgroundCarInTheWayOfTheCutInIsRecordedAsAConflict) {
  // Dense traffic, seed 1: a background car drives in the target lane close ahead while the
  // cut-in car changes lanes (found by running it; the seed makes it repeatable).
  TempDir out;
  const auto r = run_scenario(source_path("scenarios/highway_cut_in.json"), out,
                              {"--traffic", "dense", "--seed", "1", "--trace-background"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto result = read_json(out / "result.json");
  const auto& conflicts = result["lane_change_conflicts"];
  ASSERT_FALSE(conflicts.empty()) << result.dump(1);
  double lane_change_start = -1;
  for (const auto& s : result["scenes"])
    if (s["scene_id"] == 3) lane_change_start = s["enter_time"].get<double>();  // "Cut in over 3 s"
  ASSERT_GT(lane_change_start, 0);
  Trace background(out / "background.csv");
  for (const auto& c : conflicts) {
    const double t = c["time"].get<double>();
    EXPECT_EQ(c["actor"], 1);
    EXPECT_EQ(c["target_route"], "Waypoint02");
    EXPECT_GE(t, lane_change_start);
    EXPECT_LE(t, lane_change_start + 3.0 + 1e-9);
    EXPECT_TRUE(c["gap"].get<double>() < 2.0 || c["time_gap"].get<double>() < 1.0) << c.dump();
    // The vehicle is a background car, and it was where the conflict says in that step.
    const std::string vehicle = c["vehicle"];
    EXPECT_EQ(vehicle.rfind("bg", 0), 0u) << vehicle;
    bool seen = false;
    for (const auto& row : background.rows())
      if (row.str("vehicle_id") == vehicle && std::abs(row.num("time") - t) < 1e-6) {
        seen = true;
        EXPECT_NEAR(row.num("x"), c["positions"][1][0].get<double>(), 1e-3);
        EXPECT_NEAR(row.num("y"), c["positions"][1][1].get<double>(), 1e-3);
      }
    EXPECT_TRUE(seen) << vehicle << " at " << t;
  }
  // The run log says it too, and the lane change itself went ahead as written.
  bool logged = false;
  for (const auto& e : result["events"])
    logged |= e["text"].get<std::string>().rfind("lane change conflict: actor 1 changing to Waypoint02", 0) == 0;
  EXPECT_TRUE(logged);
  // The scripted car neither brakes nor steers for traffic: here it runs into the slower car
  // it cut in ahead of, and that contact is a collision like any other.
  bool contact = false;
  for (const auto& c : result["collisions"])
    contact |= c["between"][0] == 1 && c["between"][1] == conflicts[0]["vehicle"] && c["source"] == "geometry";
  EXPECT_TRUE(contact) << result["collisions"].dump();
}

// The map builder's property test, scripted half (docs/maps.md, "Generated maps"): on a
// generated city map every route is driven end to end by an orchestrator-scripted actor, in a
// ScenarioExecutor-JSON scenario run by the real `orchestrator run` on libsumo. One actor per
// route, all at once, each on a `route_move` through its own waypoints (a leg every 40 points
// and its last one) timed so that every actor reaches its last waypoint at the same moment T
// (speed = route length / T, at most 10 m/s), when the ending scene ends the run; "reaches": its
// front at the last waypoint (SUMO places a vehicle by its front bumper, and the front of a car
// centred on the last waypoint of a route ending inside a junction, on a dead-end lane that
// ends there, would be on no lane of its route: seed 13). Holds: the run reaches its ending
// scene; the engine's own check of where SUMO put each scripted actor ("SUMO placed actor ...
// instead of its route's lane", every step) never fires; every actor ends where it was sent. SUMO-driven vehicles along every route are the other
// test's (test_generated_city_maps.cpp). The seeds: a few of that test's CI set (this costs
// a run of `orchestrator` per map); ORCH_CITY_SEEDS replaces them (scripts/map_soak.py
// --scripted runs both tests on every seed).
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>

#include "integration/city_maps.hpp"
#include "support/trace_csv.hpp"

using namespace orch;
using namespace orch::test;

namespace {

// Seeds of the CI set with the kinds of routes the scripted actors must follow: 7 (3-lane
// edges, lanes of 3 routes), 13 (a route ending inside a junction on a dead-end lane of its
// own), 62 (a route ending inside a junction on another route's connection), 113 (a detour
// lane on a closed route), 152 (a closed route), 459 (a dead-end lane curving back beside its
// junction, a 0.2 m stub before fix H). Not yet: maps where a scripted actor passes a merge or
// a branch whose two connections coincide there (SUMO's free placement puts it on the other
// one; docs/maps.md, "Generated maps"), about half of the CI set (8, 23, ...).
constexpr int kScriptedSeeds[] = {7, 13, 62, 113, 152, 459};

constexpr double kMaxSpeed = 10.0;    // m/s: the longest route's actor
constexpr std::size_t kLegPoints = 40;  // waypoints per route_move leg
constexpr double kStep = 0.05;        // s: `orchestrator run`'s default step
constexpr double kCarLength = 3.71;   // m: vehicle.audi.a2 in the model catalog

// The route's fractional wp_idx at arc length s.
double index_at(const Polyline& line, double s) {
  std::size_t i = 0;
  while (i + 2 < line.size() && line.s_at_index(i + 1) <= s) ++i;
  const double seg = line.s_at_index(i + 1) - line.s_at_index(i);
  return static_cast<double>(i) + (seg > 0 ? std::clamp((s - line.s_at_index(i)) / seg, 0.0, 1.0) : 0.0);
}

// Where route r's actor is sent: its centre half a car length before the last waypoint.
double arrival_s(const WaypointRoute& r) { return std::max(0.0, r.line.length() - kCarLength / 2); }

// The scenario: the ego (SUMO-driven) along the first route, actor i + 1 scripted along route i.
nlohmann::json scenario(const BuiltMap& m, double& end_time) {
  double longest = 0;
  for (const WaypointRoute& r : m.waypoints.routes) longest = std::max(longest, r.line.length());
  end_time = std::ceil(longest / kMaxSpeed) + 1.0;
  nlohmann::json others = nlohmann::json::array();
  nlohmann::json starts = nlohmann::json::array();
  nlohmann::json actions = nlohmann::json::array();
  for (std::size_t i = 0; i < m.waypoints.routes.size(); ++i) {
    const WaypointRoute& r = m.waypoints.routes[i];
    const int id = static_cast<int>(i) + 1;
    others.push_back({{"actor_id", id}, {"model_id", "vehicle.audi.a2"}});
    starts.push_back({{"actor_id", id},
                      {"start_position", {{"type", "waypoint"}, {"wp_id", r.id}, {"wp_idx", 0}}},
                      {"start_speed", {{"type", "absolute"}, {"value", 0}}}});
    // The legs start a step after the opening scene; they end together at end_time.
    const double arrival = arrival_s(r);
    const double speed = arrival / (end_time - kStep);
    nlohmann::json legs = nlohmann::json::array();
    double prev_s = 0;
    for (std::size_t k = kLegPoints; prev_s < arrival; k += kLegPoints) {
      const bool last = k >= r.line.size() - 1 || r.line.s_at_index(k) >= arrival;
      const double s = last ? arrival : r.line.s_at_index(k);
      if (!last && s - prev_s < 1.0) continue;  // (repeated points: no leg of no length)
      const double idx = last ? index_at(r.line, arrival) : static_cast<double>(k);
      legs.push_back({{"wp_id", r.id}, {"wp_idx", idx}, {"time", (s - prev_s) / speed}});
      prev_s = s;
    }
    actions.push_back({{"route_move", {{"actor_id", id}, {"type", "waypoint"}, {"route", legs}}}});
  }
  const WaypointRoute& first = m.waypoints.routes.front();
  return {
      {"title", "Every route driven by a scripted actor"},
      {"description", "Generated city map: one scripted actor per route from its first waypoint to its last"},
      {"map_id", m.manifest.id},
      {"actors", {{"ego", {{"actor_id", 0}, {"model_id", "vehicle.toyota.prius"}}}, {"others", others}}},
      {"scenario",
       {{"opening_scene",
         {{"ego",
           {{"start_position", {{"wp_id", first.id}, {"wp_idx", 0}}},
            {"end_position", {{"wp_id", first.id}, {"wp_idx", first.line.size() - 1}}}}},
          {"others", starts},
          {"next_scenes", {1}}}},
        {"scenes", {{{"scene_id", 1}, {"description", "Drive"}, {"actions", actions}, {"next_scenes", {2}}}}},
        {"ending_scenes",
         {{{"scene_id", 2},
           {"description", "Every actor at its last waypoint"},
           {"conditions", {{"and", {{{"simulation_time", {{"comparison", ">="}, {"value", end_time}}}}}}}}}}}}},
      {"stop_conditions", {{"or", {{{"simulation_time", {{"comparison", ">="}, {"value", end_time + 10}}}}}}}}};
}

}  // namespace

class ScriptedCityDrives : public ::testing::TestWithParam<int> {};

TEST_P(ScriptedCityDrives, AScriptedActorDrivesEveryRouteEndToEnd) {
  const int seed = GetParam();
  SCOPED_TRACE(reproduce(seed));
  TempDir dir("city_scripted");
  BuiltMap m;
  try {
    m = generate_and_build(dir, seed);
  } catch (const MapError& e) {
    FAIL() << "seed " << seed << ": map build refused the map: " << e.what();
  }
  double end_time = 0;
  const auto file = dir.path() / "scripted.json";
  std::ofstream(file) << scenario(m, end_time).dump(1);
  const auto out = dir.path() / "run";
  const ProcessResult run = run_process(ORCH_BINARY, {"run", file.string(), "--maps", dir.path().string(), "--out",
                                                      out.string(), "-q", "--no-report"});
  const std::string log = read_file(out / "run.log");
  ASSERT_NE(log.find("ending scene 2"), std::string::npos)
      << "seed " << seed << ": orchestrator run exit " << run.exit_code << ": " << run.output << log;
  // The engine's every-step check that SUMO put each scripted actor on its route's lane.
  EXPECT_EQ(log.find("SUMO placed actor"), std::string::npos) << "seed " << seed << ": " << log;
  const Trace trace(out / "trace.csv");
  for (std::size_t i = 0; i < m.waypoints.routes.size(); ++i) {
    const WaypointRoute& r = m.waypoints.routes[i];
    const auto rows = trace.actor(static_cast<int>(i) + 1);
    ASSERT_FALSE(rows.empty()) << "seed " << seed << ": no trace of route " << r.id;
    const Vec2 end(rows.back().num("x"), rows.back().num("y"));
    // A step short of it at most (the trace's last row is the ending scene's step).
    const double speed = arrival_s(r) / (end_time - kStep);
    const Vec2 target = r.line.point_at(arrival_s(r));
    EXPECT_LT((end - target).norm(), speed * kStep + 0.1)
        << "seed " << seed << ": the actor of route " << r.id << " ends at (" << end.x() << ", " << end.y()
        << "), not at (" << target.x() << ", " << target.y() << ")";
  }
}

INSTANTIATE_TEST_SUITE_P(Scripted, ScriptedCityDrives,
                         ::testing::ValuesIn(city_seeds({std::begin(kScriptedSeeds), std::end(kScriptedSeeds)})),
                         [](const ::testing::TestParamInfo<int>& param) { return fmt::format("seed{}", param.param); });

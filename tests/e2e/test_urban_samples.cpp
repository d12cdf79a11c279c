// The urban samples (scenarios/urban_*.json on sumo_nets/urban, a map with junctions) run
// through the CLI on both backends: each reaches its ending scene, the traces are
// byte-identical, the scripted actors stay on their routes' lanes through the junctions,
// and SUMO's drivers keep the right of way rules towards them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "sim/box.hpp"
#include "support/cli_runner.hpp"
#include "support/trace_csv.hpp"

using namespace orch::test;

namespace {

double distance(const Trace::Row& a, const Trace::Row& b) {
  return std::hypot(a.num("x") - b.num("x"), a.num("y") - b.num("y"));
}

std::set<std::string> edges_of(const std::vector<Trace::Row>& rows) {
  std::set<std::string> out;
  for (const auto& r : rows) out.insert(r.str("edge"));
  return out;
}

bool drives_through(const std::vector<Trace::Row>& rows, const std::string& junction) {
  for (const auto& e : edges_of(rows))
    if (e.rfind(":" + junction + "_", 0) == 0) return true;
  return false;
}

// The actor's body at a trace row: the row's centre and heading, the size result.json records.
orch::sim::Box body(const Trace::Row& row, const nlohmann::json& result) {
  for (const auto& a : result["actors"])
    if (a["actor_id"].get<int>() == row.integer("actor_id"))
      return {{row.num("x"), row.num("y")}, row.num("heading"), a["length"].get<double>(), a["width"].get<double>()};
  ADD_FAILURE() << "no actor " << row.str("actor_id") << " in result.json";
  return {};
}

double point_to_segment(const orch::Vec2& p, const orch::Vec2& a, const orch::Vec2& b) {
  const orch::Vec2 ab = b - a;
  const double u = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (a + u * ab - p).norm();
}

// The gap between two bodies (0 when they touch): for rectangles apart, the nearest corner
// of one to an edge of the other.
double gap_between(const orch::sim::Box& a, const orch::sim::Box& b) {
  if (orch::sim::boxes_touch(a, b)) return 0.0;
  double gap = 1e9;
  for (const auto& [from, to] : {std::pair{a, b}, std::pair{b, a}}) {
    const auto corners = orch::sim::box_corners(from);
    const auto edges = orch::sim::box_corners(to);
    for (const auto& c : corners)
      for (std::size_t e = 0; e < 4; ++e) gap = std::min(gap, point_to_segment(c, edges[e], edges[(e + 1) % 4]));
  }
  return gap;
}

struct UrbanRun {
  TempDir out;
  CliResult cli;
  nlohmann::json result;
  UrbanRun(const std::string& sample, std::vector<std::string> extra = {}) {
    cli = run_scenario(source_path("scenarios/" + sample), out, std::move(extra));
    result = read_json(out / "result.json");
  }
};

}  // namespace

class UrbanSamples : public ::testing::TestWithParam<const char*> {};

TEST_P(UrbanSamples, ReachTheEndingSceneWithIdenticalTracesOnBothBackends) {
  UrbanRun libsumo(GetParam());
  UrbanRun traci(GetParam(), {"--backend", "traci"});
  ASSERT_EQ(libsumo.cli.exit_code, 0) << libsumo.cli.output;
  EXPECT_EQ(libsumo.result["verdict"], "success");
  ASSERT_EQ(traci.cli.exit_code, 0) << traci.cli.output;
  EXPECT_EQ(slurp(libsumo.out / "trace.csv"), slurp(traci.out / "trace.csv"));
  EXPECT_EQ(slurp(libsumo.out / "counts.csv"), slurp(traci.out / "counts.csv"));
  // Scripted vehicles were where the scenario put them on every step, junctions included.
  EXPECT_EQ(slurp(libsumo.out / "run.log").find("SUMO placed actor"), std::string::npos);
  EXPECT_TRUE(libsumo.result["collisions"].empty() ||
              libsumo.result["collisions"][0]["counted"] == false) << libsumo.result["collisions"].dump();
}

INSTANTIATE_TEST_SUITE_P(All, UrbanSamples,
                         ::testing::Values("urban_blind_corner.json", "urban_left_turn.json",
                                           "urban_pedestrian_junction.json", "urban_loop_follow.json"));

TEST(UrbanBehaviour, TheEgoWaitsForTheCarWithPriorityBeforeItTurnsAcrossItsPath) {
  UrbanRun run("urban_blind_corner.json");
  ASSERT_EQ(run.cli.exit_code, 0) << run.cli.output;
  Trace trace(run.out / "trace.csv");
  const auto ego = trace.actor(0);
  const auto car = trace.actor(1);
  ASSERT_EQ(ego.size(), car.size());
  // The ego comes to a stop while the car is still east of the side street, and only
  // crosses the westbound lane (y > 0) once the car is past it (x < 112: beyond the junction).
  bool stopped_before_car_passed = false;
  for (std::size_t i = 0; i < ego.size(); ++i) {
    if (ego[i].num("speed") < 0.5 && car[i].num("x") > 118) stopped_before_car_passed = true;
    if (ego[i].num("y") > 0) {
      EXPECT_LT(car[i].num("x"), 112.0) << "t=" << ego[i].str("time");
    }
  }
  EXPECT_TRUE(stopped_before_car_passed);
  EXPECT_TRUE(drives_through(ego, "J1"));
  EXPECT_TRUE(drives_through(car, "J1"));
}

// The ego turns left across the oncoming car's path (a permissive left turn): it stands in
// the junction until the car has gone through the point where their paths cross.
TEST(UrbanBehaviour, TheEgoTurningLeftWaitsInTheJunctionForTheOncomingCar) {
  UrbanRun run("urban_left_turn.json");
  ASSERT_EQ(run.cli.exit_code, 0) << run.cli.output;
  Trace trace(run.out / "trace.csv");
  const auto ego = trace.actor(0);
  const auto car = trace.actor(1);
  ASSERT_EQ(ego.size(), car.size());
  // Where the paths cross: the closest pair of their points, whenever each was there.
  std::size_t ego_there = 0, car_there = 0;
  double closest = 1e9;
  for (std::size_t i = 0; i < ego.size(); ++i)
    for (std::size_t j = 0; j < car.size(); ++j)
      if (const double d = distance(ego[i], car[j]); d < closest) closest = d, ego_there = i, car_there = j;
  ASSERT_LT(closest, 1.0);  // the paths do cross
  EXPECT_GT(ego[ego_there].num("time"), car[car_there].num("time") + 1.0) << "the car crosses first";
  // While the car comes, the ego stands inside the junction near the crossing, and keeps
  // clear of the car's body (0.66 m at the closest, as the car passes its front).
  bool waited_in_junction = false;
  for (std::size_t i = 0; i < car_there; ++i)
    waited_in_junction |= ego[i].num("speed") < 0.1 && ego[i].str("edge").rfind(":J", 0) == 0 &&
                          distance(ego[i], car[car_there]) < 12.0;
  EXPECT_TRUE(waited_in_junction);
  for (std::size_t i = 0; i < ego.size(); ++i)
    EXPECT_GT(gap_between(body(ego[i], run.result), body(car[i], run.result)), 0.3) << "t=" << ego[i].str("time");
}

TEST(UrbanBehaviour, TheEgoBrakesForThePedestrianCrossingPastTheJunction) {
  UrbanRun run("urban_pedestrian_junction.json");
  ASSERT_EQ(run.cli.exit_code, 0) << run.cli.output;
  Trace trace(run.out / "trace.csv");
  const auto ego = trace.actor(0);
  const auto walker = trace.actor(1);
  double slowest = 1e9;
  double nearest = 1e9;
  for (std::size_t i = 40; i < ego.size() && i < walker.size(); ++i) {
    slowest = std::min(slowest, ego[i].num("speed"));
    nearest = std::min(nearest, gap_between(body(ego[i], run.result), body(walker[i], run.result)));
  }
  EXPECT_LT(slowest, 6.0);  // from 50 km/h (13.9 m/s)
  EXPECT_GT(nearest, 1.0);  // no contact: a metre between the bodies at least
}

TEST(UrbanBehaviour, TheFollowerKeepsItsGapAroundTheLoopThroughEveryJunction) {
  UrbanRun run("urban_loop_follow.json");
  ASSERT_EQ(run.cli.exit_code, 0) << run.cli.output;
  Trace trace(run.out / "trace.csv");
  const auto ego = trace.actor(0);
  const auto car = trace.actor(1);
  for (const char* j : {"J0", "J1", "J2"}) {
    EXPECT_TRUE(drives_through(ego, j)) << j;
    EXPECT_TRUE(drives_through(car, j)) << j;
  }
  // After the first 20 s the follower is never nearer than 8 m nor (in a straight line)
  // farther than 25 m: it follows along the road through the turns.
  for (std::size_t i = 400; i < ego.size() && i < car.size(); ++i) {
    const double d = distance(ego[i], car[i]);
    EXPECT_GT(d, 8.0) << "t=" << ego[i].str("time");
    EXPECT_LT(d, 25.0) << "t=" << ego[i].str("time");
  }
}

class UrbanDenseTraffic : public ::testing::TestWithParam<const char*> {};

TEST_P(UrbanDenseTraffic, TheSampleStillEndsWellAndTheJunctionsKeepFlowing) {
  UrbanRun run(GetParam(), {"--traffic", "dense"});
  ASSERT_EQ(run.cli.exit_code, 0) << run.cli.output;
  EXPECT_EQ(run.result["verdict"], "success");
  Trace counts(run.out / "counts.csv");
  ASSERT_FALSE(counts.rows().empty());
  EXPECT_GT(counts.rows().back().integer("background_vehicles"), 30);
  // Nobody has been standing for a minute (these runs are shorter than two minutes).
  EXPECT_EQ(counts.rows().back().integer("waiting_over_60s"), 0);
}

INSTANTIATE_TEST_SUITE_P(All, UrbanDenseTraffic,
                         ::testing::Values("urban_blind_corner.json", "urban_left_turn.json",
                                           "urban_pedestrian_junction.json"));

TEST(UrbanDenseTrafficWaits, VehiclesStandingLongerThanAMinuteAreCounted) {
  // Dense traffic on the loop's way: queues form at the junctions (a saturated minor road
  // waits), and counts.csv says how many vehicles have been standing for over 60 s.
  UrbanRun run("urban_loop_follow.json", {"--traffic", "dense", "--max-time", "120"});
  ASSERT_TRUE(run.cli.exit_code == 0 || run.cli.exit_code == 1) << run.cli.output;
  Trace counts(run.out / "counts.csv");
  int most = 0;
  for (const auto& r : counts.rows()) {
    if (r.num("time") <= 60.0) {
      EXPECT_EQ(r.integer("waiting_over_60s"), 0) << r.str("time");
    }
    most = std::max(most, r.integer("waiting_over_60s"));
  }
  EXPECT_GT(most, 0);
  // ... but the junctions keep flowing: far fewer stand that long than are on the road.
  EXPECT_LT(counts.rows().back().integer("waiting_over_60s"), counts.rows().back().integer("background_vehicles") / 2);
}

class JunctionMapCli : public ::testing::TestWithParam<const char*> {};

TEST_P(JunctionMapCli, ATeamFixtureBecomesAMapThatPassesMapCheck) {
  // `map build --waypoints` on each of the team's own junction fixtures, as a new user would,
  // then `map check` on the new folder (a ring with no way out gets no background traffic).
  TempDir maps;
  const std::string file = source_path(std::string("tests/data/waypoints/") + GetParam() + ".waypoint.json");
  const CliResult built = run_cli({"map", "build", "--waypoints", file, "--maps", maps.path().string()});
  ASSERT_EQ(built.exit_code, 0) << built.output;
  EXPECT_NE(built.output.find("built"), std::string::npos) << built.output;
  const CliResult checked = run_cli({"map", "check", "--maps", maps.path().string()});
  EXPECT_EQ(checked.exit_code, 0) << checked.output;
  EXPECT_NE(checked.output.find(":J0_"), std::string::npos) << checked.output;  // junction interiors listed
}

INSTANTIATE_TEST_SUITE_P(Fixtures, JunctionMapCli, ::testing::Values("crossing", "branch_merge", "loop"));

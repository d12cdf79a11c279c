// The repository's own OpenSCENARIO samples through the real CLI on SUMO: the scenario that
// uses every condition (each fires its event; libsumo and libtraci give the same trace
// bytes) and the cut-in with background traffic (the car cuts into the ego's lane, is
// handed to SUMO's driver, and the SUMO-driven ego slows behind it).
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>

#include "support/cli_runner.hpp"
#include "support/trace_csv.hpp"

using namespace orch::test;

namespace {

const std::string kSamples = std::string(ORCH_SOURCE_DIR) + "/scenarios/openscenario/";

// The simulation time of the first run.log line that contains `text`, or -1.
double logged_at(const std::string& log, const std::string& text) {
  const auto at = log.find(text);
  if (at == std::string::npos) return -1;
  const auto line = log.rfind('\n', at);
  const auto t = log.find("t=", line == std::string::npos ? 0 : line);
  return t == std::string::npos || t > at ? -1 : std::stod(log.substr(t + 2, 10));
}

TEST(OpenScenarioSamplesCli, EveryConditionFiresItsEventOnBothBackendsWithTheSameTrace) {
  TempDir libsumo_out, traci_out;
  const std::string file = kSamples + "every_condition.xosc";
  const auto r = run_cli({"run", file, "--out", libsumo_out.path().string(), "-q"});
  const auto result = read_json(libsumo_out / "result.json");
  ASSERT_EQ(result["verdict"], "success") << result["reason"] << "\n" << r.output;
  const std::string log = slurp(libsumo_out / "run.log");
  // One event per condition (the comment at the top of the file tells the story).
  const std::vector<std::pair<std::string, std::string>> events = {
      {"AddObstacle", "SimulationTime"},          {"LeadSpeedsUp", "TraveledDistance"},
      {"MarkAccelerating", "Acceleration"},       {"FollowerChases", "Parameter"},
      {"CountFaster", "RelativeSpeed"},           {"FollowerChangesLane", "TimeHeadway"},
      {"DoubleAfterLaneChange", "RelativeDistance"}, {"WalkerStepsAside", "TimeToCollision"},
      {"WalkerStops", "ReachPosition"},           {"MarkOffRoad", "Offroad"},
      {"FollowerStops", "Collision (ByType)"},    {"ClearObstacle", "Collision (EntityRef)"},
      {"MarkStopped", "StandStill"},              {"LeadToTheEnd", "Distance"},
      {"EndReached", "EndOfRoad"}};
  for (const auto& [event, condition] : events)
    EXPECT_GE(logged_at(log, "event " + event + " startTransition"), 0.0) << condition << " did not start " << event;
  // The story's order: time-to-collision before the collision, the collision before standing still.
  EXPECT_LT(logged_at(log, "event WalkerStepsAside startTransition"), logged_at(log, "event FollowerStops startTransition"));
  EXPECT_DOUBLE_EQ(logged_at(log, "event FollowerStops startTransition"), logged_at(log, "event ClearObstacle startTransition"));
  EXPECT_NEAR(logged_at(log, "event MarkStopped startTransition"),
              logged_at(log, "event FollowerStops startTransition") + 1.0, 0.051);
  EXPECT_GT(logged_at(log, "storyboard  stopTransition"), logged_at(log, "event EndReached startTransition"));

  // The obstacle is in SUMO from t = 1 s until the collision deletes it; the walker ends off the road.
  const Trace trace(libsumo_out / "trace.csv");
  double first_obstacle = std::numeric_limits<double>::infinity(), last_obstacle = -1, walker_y = 0;
  for (const auto& row : trace.rows()) {
    if (row.str("actor_id") == "Obstacle") {
      first_obstacle = std::min(first_obstacle, row.num("time"));
      last_obstacle = std::max(last_obstacle, row.num("time"));
    }
    if (row.str("actor_id") == "Walker") walker_y = row.num("y");
  }
  EXPECT_NEAR(first_obstacle, 1.05, 0.051);
  EXPECT_NEAR(last_obstacle, logged_at(log, "event ClearObstacle startTransition"), 0.051);
  EXPECT_NEAR(walker_y, -16.0, 0.5);  // the shoulder ends at y = -10

  const auto t = run_cli({"run", file, "--backend", "traci", "--out", traci_out.path().string(), "-q"});
  ASSERT_EQ(read_json(traci_out / "result.json")["verdict"], "success") << t.output;
  EXPECT_TRUE(slurp(libsumo_out / "trace.csv") == slurp(traci_out / "trace.csv"))
      << "libsumo and libtraci traces differ";
}

TEST(OpenScenarioSamplesCli, CutInWithBackgroundTrafficHandsTheCarToSumo) {
  TempDir out;
  const auto r = run_cli({"run", kSamples + "cut_in_traffic.xosc", "--traffic", "medium", "--out", out.path().string(), "-q"});
  const auto result = read_json(out / "result.json");
  ASSERT_EQ(result["verdict"], "success") << result["reason"] << "\n" << r.output;
  const std::string log = slurp(out / "run.log");
  const double cut_in = logged_at(log, "action CutInLaneChange endTransition");
  const double hand_over = logged_at(log, "action HandToSumo endTransition");
  ASSERT_GT(cut_in, 0);
  ASSERT_GT(hand_over, cut_in);
  const auto background = log.find("background vehicles in SUMO at the end");
  ASSERT_NE(background, std::string::npos);
  const auto line = log.rfind('\n', background);  // "N background vehicles in SUMO at the end"
  EXPECT_GT(std::stoi(log.substr(line == std::string::npos ? 0 : line + 1)), 0) << log;

  const Trace trace(out / "trace.csv");
  std::string first_cut_in_lane, last_cut_in_lane, ego_lane;
  std::string driver_before, driver_after;
  double ego_min_speed_after = 1e9;
  for (const auto& row : trace.rows()) {
    const double time = row.num("time");
    if (row.str("actor_id") == "CutIn") {
      if (first_cut_in_lane.empty()) first_cut_in_lane = row.str("lane");
      last_cut_in_lane = row.str("lane");
      (time < hand_over ? driver_before : driver_after) = row.str("driver");
    } else if (row.str("actor_id") == "Ego") {
      ego_lane = row.str("lane");
      if (time > cut_in) ego_min_speed_after = std::min(ego_min_speed_after, row.num("speed"));
    }
  }
  EXPECT_NE(first_cut_in_lane, ego_lane);  // it started in the lane to the left
  EXPECT_EQ(last_cut_in_lane, ego_lane);   // and ended in the ego's
  EXPECT_EQ(driver_before, "script");
  EXPECT_EQ(driver_after, "sumo");
  EXPECT_LT(ego_min_speed_after, 24.9);  // the SUMO-driven ego slowed behind the 24 m/s car
}

}  // namespace

// `orchestrator run` of the OpenSCENARIO 1.3 traffic sample, scenarios/openscenario/traffic_area.xosc
// (a T junction: a TrafficAreaAction on road 44, continuous, 3 vehicles of a car/van
// TrafficDistribution; one over a polygon around roads 40 and 43 filled once with 4 cars; a
// RandomRouteAction for the one entity), on real SUMO with the real CLI: result.json's
// storyboard_traffic has both areas, their vehicles stay in their areas in traffic_actions.csv,
// the random route leaves the junction on one of its two roads, and the same seed gives the
// same bytes. Also: `validate` of a TrafficSignalGroupState whose road has no signal group.
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "support/cli_runner.hpp"
#include "support/trace_csv.hpp"

using namespace orch::test;

namespace {

const std::string kSample = std::string(ORCH_SOURCE_DIR) + "/scenarios/openscenario/traffic_area.xosc";

const std::filesystem::path& area_run() {
  static TempDir root;
  static const std::filesystem::path out = [] {
    const auto r = run_cli({"run", kSample, "--seed", "7", "--out", (root / "run").string(), "-q"});
    if (r.exit_code != 0) throw std::runtime_error(r.output);
    return root / "run";
  }();
  return out;
}

}  // namespace

TEST(OpenScenarioTrafficAreaCli, BothAreasRunAndTheirVehiclesStayInside) {
  const auto result = read_json(area_run() / "result.json");
  ASSERT_EQ(result["verdict"], "success") << result["reason"];
  EXPECT_EQ(result["ego_model"], "none") << "the file has no ego: nothing is said to drive one";
  const auto& traffic = result["storyboard_traffic"];
  ASSERT_TRUE(traffic.is_object()) << result.dump(1);
  ASSERT_EQ(traffic["actions"].size(), 2u);
  const auto& south = traffic["actions"][0];
  const auto& east = traffic["actions"][1];
  EXPECT_EQ(south["kind"], "area");
  EXPECT_EQ(south["name"], "SouthApproach");
  EXPECT_EQ(east["kind"], "area");
  for (const auto* a : {&south, &east})
    EXPECT_EQ((*a)["spawned"].get<int>(), (*a)["active_at_end"].get<int>() + (*a)["removed"].get<int>() +
                                               (*a)["left"].get<int>() + (*a)["not_inserted"].get<int>())
        << a->dump();
  // The continuous area on road 44 (s 20..180 at SUMO's speed) is refilled as its vehicles
  // reach its end; the polygon is filled once with at most its 4.
  EXPECT_GT(south["spawned"].get<int>(), 3);
  EXPECT_LE(east["spawned"].get<int>() - east["not_inserted"].get<int>(), 4);
  EXPECT_GT(east["spawned"].get<int>(), 0);

  // traffic_actions.csv: road 44 runs along x = 1.6 from y = -200 to -7.2 (s 20..180: y
  // -180..-20); the polygon is x 40..190, |y| <= 10. A vehicle is taken out within a step of
  // leaving (its centre a few m past the area's end: half its length, a step's travel).
  const Trace vehicles(area_run() / "traffic_actions.csv");
  std::set<std::string> south_ids;
  for (const auto& row : vehicles.rows()) {
    const double x = row.num("x"), y = row.num("y");
    if (row.integer("traffic") == 1) {
      south_ids.insert(row.str("vehicle_id"));
      EXPECT_NEAR(x, 1.6, 0.5) << row.str("vehicle_id");
      EXPECT_GE(y, -180.0 - 4.0) << row.str("vehicle_id");
      EXPECT_LE(y, -20.0 + 10.0 + 4.0) << row.str("vehicle_id");
    } else {
      EXPECT_GE(x, 40.0 - 4.0) << row.str("vehicle_id");
      EXPECT_LE(x, 190.0 + 4.0) << row.str("vehicle_id");
      EXPECT_LE(std::abs(y), 10.0) << row.str("vehicle_id");
    }
  }
  EXPECT_GT(south_ids.size(), 3u);
}

TEST(OpenScenarioTrafficAreaCli, TheRandomRouteLeavesTheJunctionOnOneOfItsRoadsTheSameEveryRun) {
  const Trace trace(area_run() / "trace.csv");
  double x = 0, y = 0;
  for (const auto& row : trace.rows())
    if (row.str("actor_id") == "Wanderer") {
      x = row.num("x");
      y = row.num("y");
    }
  // From road 45 (W to C) at 8 m/s for 30 s: past C, either east on road 40 (y = -1.6) or
  // south on road 41 (x = -1.6).
  const bool east = x > 20 && std::abs(y + 1.6) < 0.5;
  const bool south = y < -20 && std::abs(x + 1.6) < 0.5;
  EXPECT_TRUE(east || south) << x << ", " << y;

  TempDir again;
  const auto r = run_cli({"run", kSample, "--seed", "7", "--out", again.path().string(), "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* file : {"trace.csv", "traffic_actions.csv"})
    EXPECT_TRUE(slurp(area_run() / file) == slurp(again / file)) << file << " differs for the same seed";
}

TEST(OpenScenarioTrafficAreaCli, AGroupStateWithoutTheRoadsSignalGroupIsAValidationError) {
  TempDir dir;
  std::string text = slurp(kSample);
  const std::string network = "<RoadNetwork><LogicFile filepath=\"./roads/town_t_junction.xodr\"/></RoadNetwork>";
  const auto at = text.find(network);
  ASSERT_NE(at, std::string::npos);
  text.replace(at, network.size(),
               "<RoadNetwork><LogicFile filepath=\"" + std::string(ORCH_SOURCE_DIR) +
                   "/scenarios/openscenario/roads/town_t_junction.xodr\"/><TrafficSignals><TrafficSignalController name=\"C\">"
                   "<Phase name=\"all_red\" duration=\"5\"><TrafficSignalGroupState state=\"on;off;off\"/></Phase>"
                   "</TrafficSignalController></TrafficSignals></RoadNetwork>");
  const auto file = dir.write("group.xosc", text);
  const auto r = run_cli({"validate", file.string()});
  EXPECT_NE(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("TrafficSignalGroupState of phase \"all_red\" of TrafficSignalController \"C\""), std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("the road network defines none"), std::string::npos) << r.output;
}

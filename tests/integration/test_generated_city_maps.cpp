// The map builder's property test (docs/maps.md, "Generated maps"): city-like RoadEditor
// waypoint files drawn at random by scripts/city_waypoints.py, one per seed of a fixed set.
// For every map: `map build` succeeds (or names the waypoint that makes the map impossible);
// every waypoint lies within 0.10 m of the lane its route drives, junction interiors
// included; every route is one connected path through SUMO's lane graph in drawn order; a
// SUMO vehicle drives each route end to end without teleport; rebuilding gives the same
// bytes. ORCH_CITY_SEEDS ("7", "1-50", "3,9,12") replaces the fixed set (scripts/map_soak.py).
#include <gtest/gtest.h>
#include <pugixml.hpp>

#include <fmt/format.h>

#include <cstdlib>
#include <sstream>

#include "core/errors.hpp"
#include "core/process.hpp"
#include "integration/city_maps.hpp"

using namespace orch;
using namespace orch::test;

namespace {

// The CI set: the 42 seeds of 1-91 that passed first (39 now, below), and more (the failing
// seeds and why are listed in docs/maps.md, "Generated maps"; they stay open until the builder
// handles them, and then join this set as regression fixtures).
// 28, 55, 64: routes ending (starting) inside a junction, continued on the lane they end on.
// 10, 11, 33, 34, 40, 57, 76, 82, 85: a route ending (starting) inside a junction with no lane
// continuing it keeps its own lane as a dead end; 13, 60: on a lane other routes drive, it
// gets a dead-end lane of its own for half its passage.
// 7, 12, 14, 16, 21, 27, 38, 49, 50, 65, 66, 69, 70, 75, 77: junction shapes that cut none of
// their lanes; 84: a stub under 5 m is no neighbouring lane; 48: a dead-end lane is a lane of
// its own (fixtures of these three fixes: test_junction_maps.cpp, CityMapRegressions).
// Joined later (of the 44 more of 1-300 that pass since, the cheapest that fit the test's
// budget of ~90 s on 2 cores): 15, 32, 41, 58, 118, 151, 155, 158, 195, 205, 207, 218 (and
// 3, 24, 56 until fix G): the uncut tree as junction shape;
// 6: a dead-end lane wholly inside a junction shape; 184: the tree across a lane ending on the
// next one's start; 138: the tree around a curving lane through the grid; 8: routes
// drawn together from a point inside a junction continue their shared lane; 152: the first
// lane of a route that ends where it began.
// 23, 35, 113, 127: a second route through a junction between the same two lanes along
// another path gets a detour lane of its own (23: its path parts from the first only 10 m
// into the junction, so `map check` tells the two apart over a longer stretch; 113: on a
// closed route).
// Then (the failures other than a second path between the same lanes): 143: a route's end
// direction over 2 m, not its last 3 cm segment; 165: a route ending beside a neighbour's
// dead-end lane continues on it; 208: a lane goes on to a loose route's end when no route on
// it goes on; 150 (start), 229 (end): a route starting or ending a metre or two inside a
// junction on other routes' connection lies on that internal lane; 263: connections that run
// together and part are told apart over their whole internal lane; 90: a lane ending inside a
// 180-degree spike; 246: a dead-end node with lanes ending far apart cuts none; 133: was
// netconvert's "Could not insert connection".
// Then (routes drawn a little apart along one lane or one turn, "waypoints off" by 0.10-0.25 m):
// 42, 46: a shared lane is the best fit of every route on it (42: four routes, 46: three);
// 1, 19: routes drawn 0.22-0.24 m apart through one turn get a junction there, the second a
// detour lane.
// Then (the kinds other than routes drawn apart on one shared lane): 5: a route ending 0.20 m
// beside the lane it would join gets a dead-end lane of its own; 9: a lane ending at a junction
// is not extended straight 1.6 m to its neighbour's cut on a curve; 116: was 0.61 m off.
// Then (the 13 failures left of 1-300): 92, 171, 257: a lane never ends before its route's last
// waypoint (routes ending together, a noisy last segment); 190: a free end whose extension
// cuts a neighbour out of order is not extended (was refused); 239: a lane ending at a
// junction reaches at most 0.3 m straight to the cut (regressed with the best fit); 62: a
// route ending inside a junction ends on the connection its last waypoints lie on; 225, 286:
// dead-end lanes from a 1.4 m passage; 278: routes drawn too far apart for one lane get their
// junction at a route's own start too.
// Then (fix F, three of the four failures left of 1-300): 137: a 180-degree spike across a
// lane's end (the waypoint after the tip lies back on the lane before); 142: a connection keeps
// a waypoint just past a lane end that lies beside the route; 154: a shared lane's averaged
// line is judged without the points netconvert drops (under 0.1 m apart).
// Then (fix G): 200, 582: two lanes of one road whose connections cross no longer yield to
// each other (a SUMO deadlock); 383: a route starting inside a junction off every path along
// its lane gets a dead-end lane of its own from a 0.8 m passage.
// To keep the set's time (~70 s), three of the 42 first seeds tied to no fix left it (26, 36,
// 43: 9.6 s), and for the nine above eight more (17, 20, 30, 59, 63, 72, 79, 81); for fix G's
// three, three of the fifteen seeds of the uncut tree (3, 24, 56: the slowest of them);
// scripts/map_soak.py --seeds 1-400 still runs them.
// Then (fix H): 459, 892: a lane whose straight extension beyond its far end crosses its
// junction's shape overlaps that shape 5 cm (it was cut to a 0.2 m stub); 449: the same, and
// links of a priority junction that yielded to each other in a cycle (a deadlock). For them
// three more of the uncut tree's seeds left (118, 151, 205: 14.7 s, the three 7.1 s).
// Then (fix I): 479, 888: a route's first lane, tied with its later lap's lane along its first
// stretch, is told apart where they part; 480: successors still tied are told apart by the
// farthest waypoint; 734: a route starting inside a junction that its own later lap passes gets
// a dead-end lane of its own (its lane is not continued through a junction it ends at); 615: a
// route starting past a lane end, off every path from that lane, gets one too; 606: dead-end
// lanes from a 0.6 m passage; 831: the uncut tree's grid reaches round a lane bent in a U; 993:
// a route ending just inside a junction ends on the connection it lies nearest.
constexpr int kCiSeeds[] = {7,  10, 11, 12, 13, 14, 16, 21, 27, 28, 33, 34, 38, 40, 48,
                            49, 50, 55, 57, 60, 64, 65, 66, 69, 70, 75, 76, 77, 82, 84, 85,
                            6,  8,  15, 32, 41, 58, 138, 152, 155, 158, 184, 195,
                            207, 218, 23, 35, 113, 127, 90, 133, 143, 150, 165, 208, 229, 246, 263,
                            1,  19, 42, 46, 5, 9, 116,
                            92, 171, 257, 190, 239, 62, 225, 286, 278,
                            137, 142, 154,
                            200, 383, 582,
                            449, 459, 892,
                            479, 888, 480, 734, 615, 606, 831, 993};

constexpr double kTolerance = 0.10;  // m, as `map check`

// One SUMO vehicle per route along its normal edges, from its first waypoint to its last,
// departures 4 s apart; returns SUMO's statistics (pugixml) and its output.
struct DriveResult {
  int loaded = 0;
  int inserted = 0;
  int running = 0;
  int waiting = 0;
  int teleports = 0;
  std::string output;
};

DriveResult drive_every_route(const BuiltMap& m, const LaneMap& lanes) {
  std::string rou = "<routes>\n";
  int n = 0;
  for (const WaypointRoute& r : m.waypoints.routes) {
    const RouteLanes& rl = *lanes.route(r.id);
    std::vector<std::string> edges;
    for (const int l : rl.lanes)
      if (!lanes.lane(l).internal && (edges.empty() || edges.back() != lanes.lane(l).edge)) edges.push_back(lanes.lane(l).edge);
    const LanePlace& first = rl.points.front();
    const LanePlace& last = rl.points.back();
    const bool first_normal = !lanes.lane(first.lane).internal;
    const bool last_normal = !lanes.lane(last.lane).internal;
    std::string route_edges;
    for (const auto& e : edges) route_edges += (route_edges.empty() ? "" : " ") + e;
    rou += fmt::format(
        "  <vehicle id=\"v{}\" depart=\"{}\" departLane=\"{}\" departPos=\"{}\" arrivalPos=\"{}\">"
        "<route edges=\"{}\"/></vehicle>\n",
        n, 4 * n, first_normal ? std::to_string(lanes.lane(first.lane).index) : "best",
        first_normal ? fmt::format("{:.2f}", first.lane_pos) : "base",
        last_normal ? fmt::format("{:.2f}", last.lane_pos) : "max", route_edges);
    ++n;
  }
  rou += "</routes>\n";
  const auto rou_file = m.manifest.dir / "drive.rou.xml";
  write_file_atomically(rou_file, rou);
  const auto stats_file = m.manifest.dir / "drive.stats.xml";
  const ProcessResult sumo =
      run_process("sumo", {"-n", m.net(), "-r", rou_file.string(), "--end", "3600", "--time-to-teleport", "60",
                           "--no-step-log", "true", "--statistic-output", stats_file.string(), "--seed", "1"});
  DriveResult d;
  d.output = sumo.output;
  pugi::xml_document doc;
  if (sumo.exit_code != 0 || !doc.load_file(stats_file.c_str())) return d;
  const auto v = doc.child("statistics").child("vehicles");
  d.loaded = v.attribute("loaded").as_int();
  d.inserted = v.attribute("inserted").as_int();
  d.running = v.attribute("running").as_int();
  d.waiting = v.attribute("waiting").as_int();
  d.teleports = doc.child("statistics").child("teleports").attribute("total").as_int();
  return d;
}

}  // namespace

class GeneratedCityMaps : public ::testing::TestWithParam<int> {};

TEST_P(GeneratedCityMaps, BuildFitDriveAndRebuild) {
  const int seed = GetParam();
  SCOPED_TRACE(reproduce(seed));
  TempDir dir("city");
  BuiltMap m;
  try {
    m = generate_and_build(dir, seed);
  } catch (const MapError& e) {
    // A map may be impossible, but then the message must say which waypoint makes it so.
    const std::string what = e.what();
    EXPECT_NE(what.find("wp_idx"), std::string::npos) << "map build failed without naming a waypoint: " << what;
    FAIL() << "seed " << seed << ": map build refused the map: " << what;
  }
  LaneMap lanes;
  try {
    lanes = m.lanes();  // throws when a route is not one connected path through the lane graph
  } catch (const MapError& e) {
    FAIL() << "seed " << seed << ": " << e.what();
  }
  for (const auto& r : m.waypoints.routes) {
    const RouteLanes& rl = *lanes.route(r.id);
    for (std::size_t i = 0; i < rl.points.size(); ++i)
      if (rl.points[i].distance > kTolerance) {
        ADD_FAILURE() << "seed " << seed << ": route " << r.id << " wp_idx " << i << " lies "
                      << rl.points[i].distance << " m from lane " << lanes.lane(rl.points[i].lane).id;
        break;
      }
    for (std::size_t i = 0; i + 1 < rl.lanes.size(); ++i) {
      const auto& next = lanes.lane(rl.lanes[i]).next;
      EXPECT_NE(std::find(next.begin(), next.end(), rl.lanes[i + 1]), next.end())
          << "seed " << seed << ": " << r.id << ": " << lanes.lane(rl.lanes[i]).id << " -> "
          << lanes.lane(rl.lanes[i + 1]).id;
    }
  }
  for (const LaneInfo& l : lanes.lanes()) EXPECT_GT(l.length, 0.1) << "seed " << seed << ": lane " << l.id;

  const DriveResult d = drive_every_route(m, lanes);
  const int routes = static_cast<int>(m.waypoints.routes.size());
  EXPECT_EQ(d.loaded, routes) << d.output;
  EXPECT_EQ(d.inserted, routes) << d.output;
  EXPECT_EQ(d.running + d.waiting, 0) << d.output;
  EXPECT_EQ(d.teleports, 0) << d.output;

  const std::string net = read_file(m.manifest.net_path());
  build_net(m.manifest, m.waypoints);
  EXPECT_EQ(read_file(m.manifest.net_path()), net) << "seed " << seed << ": rebuilding changed the net";
}

INSTANTIATE_TEST_SUITE_P(Seeds, GeneratedCityMaps,
                         ::testing::ValuesIn(city_seeds({std::begin(kCiSeeds), std::end(kCiSeeds)})),
                         [](const ::testing::TestParamInfo<int>& param) { return fmt::format("seed{}", param.param); });

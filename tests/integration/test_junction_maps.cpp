// Junction maps built with the real netconvert from the team's own waypoint files: every
// waypoint, inside junctions too, lies on the lane (or SUMO internal lane) its route drives
// there; each route is one connected path through the lane graph; rebuilding gives the same
// bytes; a route that leaves the net is reported at the waypoint where it breaks.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "core/errors.hpp"
#include "integration/map_fixtures.hpp"

using namespace orch;
using namespace orch::test;

namespace {

BuiltMap build_fixture(const TempDir& dir, const std::string& name) {
  BuiltMap m;
  m.manifest.id = name;
  m.manifest.dir = dir.path() / name;
  m.manifest.max_edge_length = kDefaultMaxEdgeLength;
  std::filesystem::create_directories(m.manifest.dir);
  const auto source = std::filesystem::path(ORCH_SOURCE_DIR) / "tests/data/waypoints" / (name + ".waypoint.json");
  std::filesystem::copy_file(source, m.manifest.dir / source.filename());
  m.manifest.waypoint_file = source.filename().string();
  m.manifest.net_file = name + ".net.xml";
  save_map_manifest(m.manifest);
  m.waypoints = load_waypoint_file(m.manifest.waypoint_path().string());
  m.report = build_net(m.manifest, m.waypoints);
  return m;
}

int internal_lanes(const LaneMap& lanes, const RouteLanes& rl) {
  int n = 0;
  for (const int l : rl.lanes) n += lanes.lane(l).internal ? 1 : 0;
  return n;
}

}  // namespace

class JunctionMaps : public ::testing::TestWithParam<const char*> {};

TEST_P(JunctionMaps, EveryWaypointLiesOnItsLaneInsideJunctionsToo) {
  TempDir dir("junction_maps");
  const BuiltMap m = build_fixture(dir, GetParam());
  const LaneMap lanes = m.lanes();
  EXPECT_LE(max_waypoint_distance(lanes, m.waypoints), 0.10);
  for (const auto& r : m.waypoints.routes) {
    const RouteLanes& rl = *lanes.route(r.id);
    EXPECT_GE(internal_lanes(lanes, rl), 1) << r.id << " never drives through a junction";
    // Consecutive lanes of the sequence are connected in SUMO's lane graph.
    for (std::size_t i = 0; i + 1 < rl.lanes.size(); ++i) {
      const auto& next = lanes.lane(rl.lanes[i]).next;
      EXPECT_NE(std::find(next.begin(), next.end(), rl.lanes[i + 1]), next.end())
          << r.id << ": " << lanes.lane(rl.lanes[i]).id << " -> " << lanes.lane(rl.lanes[i + 1]).id;
    }
    // Waypoints inside a junction are placed on the internal lane with the route's own shape.
    for (std::size_t i = 0; i < rl.points.size(); ++i) {
      if (lanes.lane(rl.points[i].lane).internal) {
        EXPECT_LE(rl.points[i].distance, 0.05) << r.id << " wp " << i;
      }
    }
  }
}

TEST_P(JunctionMaps, RebuildingGivesTheSameBytes) {
  TempDir dir("junction_rebuild");
  const BuiltMap m = build_fixture(dir, GetParam());
  const std::string net = read_file(m.manifest.net_path());
  const std::string plain = read_file(m.manifest.dir / "plain" / (m.manifest.id + ".con.xml"));
  build_net(m.manifest, m.waypoints);
  EXPECT_EQ(read_file(m.manifest.net_path()), net);
  EXPECT_EQ(read_file(m.manifest.dir / "plain" / (m.manifest.id + ".con.xml")), plain);
}

INSTANTIATE_TEST_SUITE_P(Fixtures, JunctionMaps, ::testing::Values("crossing", "branch_merge", "loop"));

TEST(JunctionMapsShipped, TheUrbanMapFitsItsRoutesAndItsLoopIsDrivenAround) {
  const MapManifest m = load_map_manifest(shipped_map_dir("urban"));
  const WaypointFile wf = load_waypoint_file(m.waypoint_path().string());
  const LaneMap lanes = LaneMap::build(m.net_path().string(), wf);
  EXPECT_LE(max_waypoint_distance(lanes, wf), 0.10);
  // The loop closes: it ends on the lane it starts on, through three junctions.
  const RouteLanes& loop = *lanes.route("LOOP");
  EXPECT_EQ(loop.lanes.front(), loop.lanes.back());
  EXPECT_GE(internal_lanes(lanes, loop), 3);
  // Passing a place twice: the second lap's lanes are the first lap's.
  const RouteLanes& twice = *lanes.route("LOOP_then_east");
  EXPECT_GT(std::count(twice.lanes.begin(), twice.lanes.end(), twice.lanes.front()), 1);
  // The ego's SUMO route along the loop lists normal edges only, the first one again at the end.
  const auto edges = lanes.route_edges(*wf.find("LOOP"), 5.0, wf.find("LOOP")->line.length() - 5.0);
  ASSERT_GE(edges.size(), 4u);
  EXPECT_EQ(edges.front(), edges.back());
  for (const auto& e : edges) EXPECT_NE(e.front(), ':');
}

TEST(JunctionMapsShipped, ARouteThatLeavesTheNetIsReportedWhereItBreaks) {
  TempDir dir("junction_broken");
  const BuiltMap m = build_fixture(dir, "crossing");
  // The same routes, but "EB" swerves 4 m to the side from the junction on: no lane that
  // continues its lane into the junction follows it.
  nlohmann::json j = nlohmann::json::parse(read_file(m.manifest.waypoint_path()));
  for (auto& route : j["waypoints"])
    if (route["id"] == "EB")
      for (auto& p : route["points"])
        if (p["x"].get<double>() > -6.2) p["z"] = p["z"].get<double>() - 4.0;
  const auto broken = dir.path() / "broken.waypoint.json";
  std::ofstream(broken) << j.dump();
  const WaypointFile wf = load_waypoint_file(broken.string());
  try {
    LaneMap::build(m.net(), wf);
    FAIL() << "a broken route was accepted";
  } catch (const MapError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("route \"EB\" cannot be driven as one connected path"), std::string::npos) << what;
    EXPECT_NE(what.find("wp_idx 94"), std::string::npos) << what;  // x = -6: the first point past its lane's end
  }
}

// Junction maps built with the real netconvert from the team's own waypoint files: every
// waypoint, inside junctions too, lies on the lane (or SUMO internal lane) its route drives
// there; each route is one connected path through the lane graph; rebuilding gives the same
// bytes; a route that leaves the net is reported at the waypoint where it breaks.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <pugixml.hpp>
#include <sstream>

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

// Regression fixtures cut from generated city maps (scripts/city_waypoints.py --seed N: the
// routes' stretches within a square around the place that failed), one per builder fix:
//   city1_turn_beside_two_way_street  seed 1, 45 m around (200, 32): a route turns right out
//     of a junction into a two-way street, its lane leaving in the middle of the turn; the
//     junction's shape through the lane ends' corners crossed that lane 7.6 m along, and
//     netconvert cut it there (the route then left its internal lane onto no lane).
//   city84_stub_beside_lane  seed 84, 35 m around (71.7, 70): a route's 2 m stretch after a
//     junction lay beside another route's lane and became a lane of that road (the route
//     could not be followed off the junction).
//   city48_dead_end_beside_lanes  seed 48, 30 m around (72.9, 176.5): two routes end inside a
//     T junction; the dead-end lane made for one of them lay beside a road's lanes and became
//     one of them, ending nowhere near where that road's junction is.
class CityMapRegressions : public ::testing::TestWithParam<const char*> {};

TEST_P(CityMapRegressions, BuildsFitsAndEveryRouteIsOneConnectedPath) {
  TempDir dir("city_regressions");
  const BuiltMap m = build_fixture(dir, GetParam());
  LaneMap lanes;
  ASSERT_NO_THROW(lanes = m.lanes());  // throws where a route is not one connected path
  EXPECT_LE(max_waypoint_distance(lanes, m.waypoints), 0.10);
  for (const auto& r : m.waypoints.routes) {
    const RouteLanes& rl = *lanes.route(r.id);
    for (std::size_t i = 0; i + 1 < rl.lanes.size(); ++i) {
      const auto& next = lanes.lane(rl.lanes[i]).next;
      EXPECT_NE(std::find(next.begin(), next.end(), rl.lanes[i + 1]), next.end())
          << r.id << ": " << lanes.lane(rl.lanes[i]).id << " -> " << lanes.lane(rl.lanes[i + 1]).id;
    }
  }
  for (const LaneInfo& l : lanes.lanes()) EXPECT_GT(l.length, 0.1) << l.id;
}

// netconvert cuts a lane where its junction's shape crosses it: on the map whose lane leaves a
// junction in the middle of a turn, every lane of the net keeps the ends `map build` planned
// (plain XML), so the routes' waypoints stay on their lanes.
TEST(CityMapShapes, NoJunctionShapeCutsALaneLeavingInTheMiddleOfATurn) {
  TempDir dir("city_shapes");
  const BuiltMap m = build_fixture(dir, "city1_turn_beside_two_way_street");
  pugi::xml_document plain;
  pugi::xml_document net;
  ASSERT_TRUE(plain.load_file((m.manifest.dir / "plain" / (m.manifest.id + ".edg.xml")).c_str()));
  ASSERT_TRUE(net.load_file(m.manifest.net_path().c_str()));
  std::map<std::string, std::string> net_shapes;
  for (const auto e : net.child("net").children("edge"))
    for (const auto l : e.children("lane")) net_shapes[l.attribute("id").as_string()] = l.attribute("shape").as_string();
  const auto ends = [](const std::string& shape) {
    std::vector<Vec2> pts;
    std::stringstream in(shape);
    for (std::string xy; in >> xy;) pts.emplace_back(std::stod(xy), std::stod(xy.substr(xy.find(',') + 1)));
    return std::make_pair(pts.front(), pts.back());
  };
  int lanes = 0;
  for (const auto e : plain.child("edges").children("edge"))
    for (const auto l : e.children("lane")) {
      const std::string id = fmt::format("{}_{}", e.attribute("id").as_string(), l.attribute("index").as_int());
      ASSERT_TRUE(net_shapes.count(id)) << id;
      const auto [a0, a1] = ends(l.attribute("shape").as_string());
      const auto [b0, b1] = ends(net_shapes[id]);
      EXPECT_LE((a0 - b0).norm(), 0.10) << id << " start";
      EXPECT_LE((a1 - b1).norm(), 0.10) << id << " end";
      ++lanes;
    }
  EXPECT_GT(lanes, 0);
}

INSTANTIATE_TEST_SUITE_P(Seeds, CityMapRegressions,
                         ::testing::Values("city1_turn_beside_two_way_street", "city84_stub_beside_lane",
                                           "city48_dead_end_beside_lanes"));

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

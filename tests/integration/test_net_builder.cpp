// `map build` end to end with the real netconvert: synthetic roads of every kind the
// generic algorithm handles, reproducible output, the shipped nets, and the CLI.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cstdio>

#include "core/errors.hpp"
#include "integration/map_fixtures.hpp"

using namespace orch;
using orch::test::BuiltMap;
using orch::test::road_points;
using orch::test::RoadShape;
using orch::test::TempDir;

namespace {

pugi::xml_document load_net(const BuiltMap& m) {
  pugi::xml_document doc;
  EXPECT_TRUE(doc.load_file(m.net().c_str())) << m.net();
  return doc;
}

Vec2 lane_direction(const LaneInfo& lane) { return lane.shape.tangent_at(lane.shape.length() / 2); }

struct CliResult {
  int exit_code = -1;
  std::string output;
};

// Runs the orchestrator binary (arguments are plain paths and words, quoted for the shell).
CliResult run_cli(const std::vector<std::string>& args) {
  std::string command = std::string("'") + ORCH_BINARY + "'";
  for (const auto& a : args) command += " '" + a + "'";
  CliResult result;
  FILE* pipe = ::popen((command + " 2>&1").c_str(), "r");
  if (!pipe) return result;
  char buffer[4096];
  while (const std::size_t n = std::fread(buffer, 1, sizeof buffer, pipe)) result.output.append(buffer, n);
  const int status = ::pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

RoadShape curved_road() {
  RoadShape road;
  road.heading = -0.4;
  road.straight = 250;
  road.radius = -300;  // turning right
  road.arc_length = 450;
  return road;
}

}  // namespace

TEST(NetBuilder, StraightThreeLaneRoadIsOneEdgeOrderedRightToLeft) {
  TempDir dir("netbuild");
  RoadShape road;
  road.straight = 600;
  const BuiltMap m = test::build_synthetic(dir, "straight", {{"L", road_points(road, 3.5, 0, 600), 100},
                                                              {"M", road_points(road, 0, 0, 600), 80},
                                                              {"R", road_points(road, -3.5, 0, 600), 60}});
  const auto doc = load_net(m);
  const auto edges = test::normal_edges(doc);
  ASSERT_EQ(edges.size(), 1u);
  EXPECT_STREQ(edges[0].attribute("id").as_string(), "R+M+L#0");
  const LaneMap lanes = m.lanes();
  std::vector<std::string> order;
  double last_y = -1e9;
  for (const auto lane : edges[0].children("lane")) {
    order.push_back(lane.child("param").attribute("value").as_string());
    // Driving +x, left is +y: each lane lies left of the one before.
    const LaneInfo& info = lanes.lane(static_cast<int>(order.size() - 1));
    EXPECT_EQ(info.id, lane.attribute("id").as_string());
    EXPECT_GT(info.shape.point(0).y(), last_y);
    last_y = info.shape.point(0).y();
    // No allow/disallow: every class, pedestrians included, may use the lane.
    EXPECT_TRUE(lane.attribute("allow").empty());
    EXPECT_TRUE(lane.attribute("disallow").empty());
    EXPECT_DOUBLE_EQ(lane.attribute("width").as_double(), 3.5);
  }
  EXPECT_EQ(order, (std::vector<std::string>{"R", "M", "L"}));
  EXPECT_NEAR(edges[0].child("lane").attribute("speed").as_double(), 60 / 3.6, 1e-4);
  // Lanes reach 20 m beyond the first and last waypoint.
  EXPECT_NEAR(edges[0].child("lane").attribute("length").as_double(), 640.0, 1e-3);
  EXPECT_LE(test::max_waypoint_distance(lanes, m.waypoints), 0.10);
  EXPECT_EQ(m.report.corridors, 1);
  EXPECT_EQ(m.report.edges, 1);
  EXPECT_EQ(m.report.lanes, 3);
  // The plain XML is kept next to the net.
  EXPECT_TRUE(std::filesystem::exists(m.manifest.dir / "plain" / "straight.edg.xml"));
  EXPECT_TRUE(std::filesystem::exists(m.manifest.dir / "plain" / "straight.nod.xml"));
  EXPECT_TRUE(std::filesystem::exists(m.manifest.dir / "plain" / "straight.con.xml"));
}

TEST(NetBuilder, OppositeDirectionsGetEdgesOfTheirOwn) {
  TempDir dir("netbuild");
  RoadShape road;
  const BuiltMap m = test::build_synthetic(dir, "twoway", {{"east", road_points(road, -1.75, 0, 500)},
                                                            {"west", road_points(road, 1.75, 0, 500, 1.0, true)}});
  const auto doc = load_net(m);
  ASSERT_EQ(test::normal_edges(doc).size(), 2u);
  const LaneMap lanes = m.lanes();
  const auto& east = lanes.lane(lanes.route("east")->lanes.at(0));
  const auto& west = lanes.lane(lanes.route("west")->lanes.at(0));
  EXPECT_NE(east.edge, west.edge);
  EXPECT_LT(lane_direction(east).dot(lane_direction(west)), -0.99);
  EXPECT_GT(lane_direction(east).x(), 0.99);
  EXPECT_LE(test::max_waypoint_distance(lanes, m.waypoints), 0.10);
  EXPECT_TRUE(test::lane_connections(doc).empty());  // no U-turns (--no-turnarounds)
}

TEST(NetBuilder, CurvedRoadFollowsTheRoutes) {
  TempDir dir("netbuild");
  const RoadShape road = curved_road();
  const BuiltMap m = test::build_synthetic(dir, "curve", {{"a", road_points(road, 0, 0, 700)},
                                                           {"b", road_points(road, 3.75, 0, 700)}});
  const LaneMap lanes = m.lanes();
  ASSERT_EQ(lanes.lanes().size(), 2u);
  // Turning right, the left lane is the outer one: longer than the right one.
  EXPECT_GT(lanes.lane(1).shape.length(), lanes.lane(0).shape.length() + 1.0);
  // SUMO gives both lanes one length; positions map to the shapes through the factor.
  EXPECT_DOUBLE_EQ(lanes.lane(0).length, lanes.lane(1).length);
  EXPECT_GT(lanes.lane(1).geometry_factor(), 1.0);
  EXPECT_LT(lanes.lane(0).geometry_factor(), 1.0);
  EXPECT_DOUBLE_EQ(lanes.lane(0).width, 3.75);
  const double worst = test::max_waypoint_distance(lanes, m.waypoints);
  EXPECT_LE(worst, 0.10);
  EXPECT_GT(worst, 0.001);  // the shapes really were simplified
}

TEST(NetBuilder, LaneStartingLaterSplitsTheRoadWithConnectionsPerRoute) {
  TempDir dir("netbuild");
  const RoadShape road = curved_road();
  const BuiltMap m = test::build_synthetic(dir, "widening", {{"R1", road_points(road, 0, 0, 700)},
                                                              {"R2", road_points(road, 3.5, 0, 700)},
                                                              {"R3", road_points(road, 7.0, 200, 700)}});
  const auto doc = load_net(m);
  const auto edges = test::normal_edges(doc);
  ASSERT_EQ(edges.size(), 2u);
  EXPECT_STREQ(edges[0].attribute("id").as_string(), "R1+R2+R3#0");
  EXPECT_STREQ(edges[1].attribute("id").as_string(), "R1+R2+R3#1");
  EXPECT_STREQ(edges[0].attribute("to").as_string(), edges[1].attribute("from").as_string());
  // Each route continues on its own lane, and the new lane has no predecessor.
  EXPECT_EQ(test::lane_connections(doc),
            (std::vector<std::string>{"R1+R2+R3#0_0->R1+R2+R3#1_0", "R1+R2+R3#0_1->R1+R2+R3#1_1"}));
  const LaneMap lanes = m.lanes();
  EXPECT_LE(test::max_waypoint_distance(lanes, m.waypoints), 0.10);
  // netconvert kept the planned lane ends: consecutive lanes of a route meet without a gap.
  const auto& r1 = lanes.route("R1")->lanes;
  ASSERT_EQ(r1.size(), 2u);
  EXPECT_LT((lanes.lane(r1[0]).shape.points().back() - lanes.lane(r1[1]).shape.point(0)).norm(), 1e-3);
  EXPECT_EQ(lanes.route("R3")->lanes.size(), 1u);
  EXPECT_EQ(lanes.lane(lanes.route("R3")->lanes[0]).index, 2);
}

TEST(NetBuilder, EndingLaneGetsNoConnection) {
  TempDir dir("netbuild");
  const RoadShape road = curved_road();
  const BuiltMap m = test::build_synthetic(dir, "narrowing", {{"main", road_points(road, 0, 0, 700)},
                                                               {"drop", road_points(road, 3.6, 0, 400)}});
  const auto doc = load_net(m);
  ASSERT_EQ(test::normal_edges(doc).size(), 2u);
  EXPECT_EQ(test::lane_connections(doc), (std::vector<std::string>{"main+drop#0_0->main+drop#1_0"}));
  EXPECT_LE(test::max_waypoint_distance(m.lanes(), m.waypoints), 0.10);
}

TEST(NetBuilder, LonelyRouteIsASingleLaneEdge) {
  TempDir dir("netbuild");
  RoadShape road;
  road.radius = 150;
  road.arc_length = 100;
  const BuiltMap m = test::build_synthetic(dir, "solo", {{"only", road_points(road, 0, 0, 600)}});
  const auto doc = load_net(m);
  const auto edges = test::normal_edges(doc);
  ASSERT_EQ(edges.size(), 1u);
  EXPECT_DOUBLE_EQ(edges[0].child("lane").attribute("width").as_double(), 3.5);
  EXPECT_FALSE(m.report.notes.empty());
  EXPECT_LE(test::max_waypoint_distance(m.lanes(), m.waypoints), 0.10);
}

// Lane ends in curves are where netconvert is tempted to cut lanes at their junctions.
TEST(NetBuilder, NetconvertKeepsThePlannedLanesOnAnSCurve) {
  TempDir dir("netbuild");
  RoadShape road;
  road.straight = 200;
  road.radius = 300;
  road.arc_length = 300;
  road.radius2 = -200;
  road.arc_length2 = 300;
  const auto back = [&](double lateral) { return road_points(road, lateral, 0, 1000, 1.0, true); };
  const BuiltMap m = test::build_synthetic(dir, "scurve", {{"L1", road_points(road, 0, 0, 1000), 100},
                                                            {"L2", road_points(road, 3.6, 0, 1000), 100},
                                                            {"L3", road_points(road, 7.2, 0, 1000), 100},
                                                            {"L4", road_points(road, 10.8, 300, 600), 80},
                                                            {"L4b", road_points(road, 10.8, 630, 1000), 80},
                                                            {"R1", back(16.0), 100},
                                                            {"R2", back(19.6), 100}});
  const LaneMap lanes = m.lanes();
  // Simplification (0.02 m) and output precision only: nothing was cut off.
  EXPECT_LE(test::max_waypoint_distance(lanes, m.waypoints), 0.021);
  for (const auto& r : m.waypoints.routes) {
    const auto& own = lanes.route(r.id)->lanes;
    for (std::size_t k = 0; k + 1 < own.size(); ++k)
      EXPECT_LT((lanes.lane(own[k]).shape.points().back() - lanes.lane(own[k + 1]).shape.point(0)).norm(), 1e-3)
          << r.id << " between " << lanes.lane(own[k]).id << " and " << lanes.lane(own[k + 1]).id;
  }
  // L4 (a lane in the middle stretch only, ending in the curve) splits the road into three
  // edges; L4b goes on where L4 stops, 30 m later, on the same lane: the lanes connect.
  EXPECT_EQ(lanes.route("L1")->lanes.size(), 3u);
  EXPECT_EQ(lanes.route("R1")->lanes.size(), 1u);
  const LaneInfo& l4 = lanes.lane(lanes.route("L4")->lanes.back());
  const LaneInfo& l4b = lanes.lane(lanes.route("L4b")->lanes.front());
  EXPECT_LT((l4.shape.points().back() - l4b.shape.point(0)).norm(), 1e-3);
  EXPECT_EQ(l4.index, 3);
  EXPECT_EQ(l4b.index, 3);
  pugi::xml_document doc;
  ASSERT_TRUE(doc.load_file(m.net().c_str()));
  const auto connections = test::lane_connections(doc);
  EXPECT_NE(std::find(connections.begin(), connections.end(), l4.id + "->" + l4b.id), connections.end());
}

TEST(NetBuilder, SameInputsGiveByteIdenticalNets) {
  TempDir dir("netbuild");
  const RoadShape road = curved_road();
  const std::vector<test::SyntheticRoute> routes = {{"R1", road_points(road, 0, 0, 700)},
                                                    {"R2", road_points(road, 3.5, 100, 700)}};
  const BuiltMap first = test::build_synthetic(dir, "again", routes);
  const std::string bytes = read_file(first.net());
  EXPECT_EQ(bytes.find("generated on"), std::string::npos);  // the timestamp is gone
  build_net(first.manifest, first.waypoints);
  EXPECT_EQ(read_file(first.net()), bytes);
  // Another folder (another absolute path) gives the same bytes too.
  TempDir other("netbuild_other");
  const BuiltMap second = test::build_synthetic(other, "again", routes);
  EXPECT_EQ(read_file(second.net()), bytes);
}

TEST(NetBuilder, ShippedNetsEqualAFreshBuild) {
  for (const char* id : {"highway", "ALKS_Road", "ALKS_Road_Different_Curvatures", "urban"}) {
    SCOPED_TRACE(id);
    const MapManifest shipped = load_map_manifest(test::shipped_map_dir(id));
    TempDir dir("netbuild_shipped");
    MapManifest fresh = shipped;
    fresh.dir = dir.path();
    std::filesystem::copy_file(shipped.waypoint_path(), fresh.waypoint_path());
    build_net(fresh, load_waypoint_file(fresh.waypoint_path().string()));
    EXPECT_TRUE(read_file(fresh.net_path()) == read_file(shipped.net_path()))
        << "sumo_nets/" << id << " is stale: rebuild it with `orchestrator map build " << id << "`";
    for (const auto& entry : std::filesystem::directory_iterator(fresh.dir / "plain"))
      EXPECT_TRUE(read_file(entry.path()) == read_file(shipped.dir / "plain" / entry.path().filename()))
          << entry.path().filename();
  }
}

TEST(NetBuilder, NetconvertFailureCarriesItsMessage) {
  TempDir dir("netbuild");
  RoadShape road;
  BuiltMap m = test::build_synthetic(dir, "fails", {{"a", road_points(road, 0, 0, 100)}});
  m.manifest.net_file = "no_such_folder/fails.net.xml";
  try {
    build_net(m.manifest, m.waypoints);
    FAIL() << "expected a MapError";
  } catch (const MapError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("netconvert failed"), std::string::npos) << what;
    EXPECT_NE(what.find("Could not build output file"), std::string::npos) << what;
  }
}

// A map from user waypoints may take any id, a shipped map's too; a name is refused only
// where both maps would be loaded together, and the message says how to choose.
TEST(MapBuildCommand, AnyIdUnlessTwoMapsOfThatNameWouldLoadTogether) {
  TempDir dir("mapcli_id");
  RoadShape road;
  const auto source = test::write_waypoint_file(dir.path(), "Test.Road", {{"W1", road_points(road, 0, 0, 300)},
                                                                          {"W2", road_points(road, 3.5, 0, 300)}});
  // The shipped map's name, in a folder outside the maps folders: built.
  const auto own = dir.path() / "mine" / "urban";
  auto shipped_name = run_cli({"map", "build", "--waypoints", source.string(), "--id", "urban", "--out", own.string()});
  ASSERT_EQ(shipped_name.exit_code, 0) << shipped_name.output;
  EXPECT_EQ(load_map_manifest(own).id, "urban");
  // Two maps named "road" in one maps folder would load together: the second is refused.
  const auto maps = dir.path() / "maps";
  auto first = run_cli({"map", "build", "--waypoints", source.string(), "--id", "road", "--out",
                        (maps / "road").string(), "--maps", maps.string()});
  ASSERT_EQ(first.exit_code, 0) << first.output;
  auto second = run_cli({"map", "build", "--waypoints", source.string(), "--id", "road", "--out",
                         (maps / "road2").string(), "--maps", maps.string()});
  EXPECT_NE(second.exit_code, 0);
  EXPECT_NE(second.output.find("a map named \"road\" already exists"), std::string::npos) << second.output;
  EXPECT_NE(second.output.find("choose another --id"), std::string::npos) << second.output;
  EXPECT_FALSE(std::filesystem::exists(maps / "road2" / "road.net.xml"));
}

TEST(MapBuildCommand, CreatesAMapFolderFromAnyWaypointFile) {
  TempDir dir("mapcli");
  RoadShape road;
  const auto source = test::write_waypoint_file(dir.path(), "Test.Road", {{"W1", road_points(road, 0, 0, 300)},
                                                                          {"W2", road_points(road, 3.5, 0, 300)}});
  const auto maps = dir.path() / "maps";
  const auto out = maps / "test_road";
  auto build = run_cli({"map", "build", "--waypoints", source.string(), "--id", "test_road", "--alias",
                                    "scenario_name", "--out", out.string(), "--maps", maps.string()});
  ASSERT_EQ(build.exit_code, 0) << build.output;
  const MapManifest m = load_map_manifest(out);
  EXPECT_EQ(m.id, "test_road");
  EXPECT_EQ(m.aliases, (std::vector<std::string>{"scenario_name", "Test.Road", "WayPoint_Test.Road"}));
  EXPECT_EQ(m.waypoint_file, "Test.Road.waypoint.json");
  EXPECT_EQ(read_file(m.waypoint_path()), read_file(source));
  EXPECT_TRUE(std::filesystem::exists(out / "test_road.net.xml"));

  // The map is found by its alias, passes the check, and fails a tolerance below 0.
  auto check = run_cli({"map", "check", "Test.Road", "--maps", maps.string()});
  EXPECT_EQ(check.exit_code, 0) << check.output;
  EXPECT_NE(check.output.find("W1"), std::string::npos) << check.output;
  auto strict = run_cli({"map", "check", "--maps", maps.string(), "--tolerance", "-1"});
  EXPECT_EQ(strict.exit_code, 1) << strict.output;
  EXPECT_NE(strict.output.find("over tolerance"), std::string::npos) << strict.output;

  // Rebuilding by id gives the same net.
  const std::string before = read_file(out / "test_road.net.xml");
  auto rebuild = run_cli({"map", "build", "test_road", "--maps", maps.string()});
  ASSERT_EQ(rebuild.exit_code, 0) << rebuild.output;
  EXPECT_EQ(read_file(out / "test_road.net.xml"), before);
}

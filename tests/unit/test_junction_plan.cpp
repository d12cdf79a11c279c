// The junction step of `map build` on the team's own waypoint files (tests/data/waypoints,
// written by scripts/urban_waypoints.py), without SUMO: where the junctions are, which
// stretches become one lane for several routes, and that the lanes through a junction are
// the routes' own points.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "core/errors.hpp"
#include "map/junction_detours.hpp"
#include "map/junction_pieces.hpp"
#include "map/junction_plan.hpp"
#include "map/junction_zones.hpp"
#include "map/net_plan.hpp"
#include "map/waypoint_file.hpp"
#include "unit/synthetic_roads.hpp"

using namespace orch;

namespace {

WaypointFile fixture(const std::string& name) {
  return load_waypoint_file(std::string(ORCH_SOURCE_DIR) + "/tests/data/waypoints/" + name + ".waypoint.json");
}

WaypointFile urban() { return load_waypoint_file(std::string(ORCH_SOURCE_DIR) + "/sumo_nets/urban/urban.waypoint.json"); }

const PlannedLane* lane_of_routes(const NetPlan& plan, const std::set<std::string>& routes) {
  for (const auto& e : plan.edges)
    for (const auto& l : e.lanes) {
      const std::set<std::string> here(l.routes.begin(), l.routes.end());
      if (here == routes) return &l;
    }
  return nullptr;
}

std::set<std::string> junction_nodes(const NetPlan& plan) {
  std::set<std::string> ids;
  for (const auto& n : plan.nodes)
    if (!n.type.empty()) ids.insert(n.id);
  return ids;
}

// Largest distance from the route's waypoints to the nearest planned lane or connection
// shape: every waypoint, junction interiors included, must lie under the net.
double max_distance_to_plan(const NetPlan& plan, const WaypointRoute& route) {
  std::vector<Polyline> shapes;
  for (const auto& e : plan.edges)
    for (const auto& l : e.lanes) {
      const auto& ids = l.routes.empty() ? std::vector<std::string>{l.route_id} : l.routes;
      if (std::find(ids.begin(), ids.end(), route.id) != ids.end()) shapes.push_back(l.shape);
    }
  for (const auto& c : plan.connections)
    if (c.shape.size() >= 2) shapes.emplace_back(c.shape);
  double worst = 0;
  for (const Vec2& p : route.line.points()) {
    double best = 1e9;
    for (const auto& s : shapes) best = std::min(best, s.project(p).distance);
    worst = std::max(worst, best);
  }
  return worst;
}

}  // namespace

TEST(JunctionPlan, ACrossingOfTwoTwoWayStreetsIsOneJunctionWithStraightConnections) {
  const WaypointFile wf = fixture("crossing");
  const NetPlan plan = plan_net(wf, NetPlanSettings{});
  EXPECT_EQ(plan.junctions, 1);
  EXPECT_EQ(junction_nodes(plan), std::set<std::string>{"J0"});
  ASSERT_EQ(plan.connections.size(), 4u);  // one straight connection per direction
  for (const auto& c : plan.connections) {
    ASSERT_GE(c.shape.size(), 2u);
    const Vec2 d = c.shape.back() - c.shape.front();
    EXPECT_GT(d.norm(), 2 * kConflictReach) << c.from << " -> " << c.to;  // across the whole junction
  }
  // Each route: a lane into the junction and one out of it, nothing shared (no two routes
  // drive the same lane here).
  EXPECT_EQ(plan.edges.size(), 8u);
  for (const auto& r : wf.routes) EXPECT_LE(max_distance_to_plan(plan, r), 0.03) << r.id;
}

TEST(JunctionPlan, RoutesSharingTheirFirstStretchShareOneLaneUntilTheyBranch) {
  const WaypointFile wf = fixture("branch_merge");
  const NetPlan plan = plan_net(wf, NetPlanSettings{});
  // "exit" is drawn 3 cm beside "main" up to its right turn: one lane for both before it,
  // and after the junction "entry" joins "main" on one lane (a merge).
  EXPECT_NE(lane_of_routes(plan, {"main", "exit"}), nullptr);
  EXPECT_NE(lane_of_routes(plan, {"main", "entry"}), nullptr);
  EXPECT_NE(lane_of_routes(plan, {"exit"}), nullptr);
  EXPECT_NE(lane_of_routes(plan, {"entry"}), nullptr);
  EXPECT_EQ(lane_of_routes(plan, {"main"}), nullptr);  // "main" never has a lane of its own
  EXPECT_GE(plan.junctions, 1);
  for (const auto& r : wf.routes) EXPECT_LE(max_distance_to_plan(plan, r), 0.05) << r.id;
}

TEST(JunctionPlan, AClosedLoopBecomesACycleOfEdgesThroughTwoJunctions) {
  const WaypointFile wf = fixture("loop");
  ASSERT_TRUE(is_closed_route(wf.routes[0]));
  const NetPlan plan = plan_net(wf, NetPlanSettings{});
  EXPECT_EQ(plan.junctions, 2);
  // Every junction has exactly one lane in and one out, connected: the ring is closed.
  std::map<std::string, int> ins;
  std::map<std::string, int> outs;
  for (const auto& e : plan.edges) {
    ++outs[e.from];
    ++ins[e.to];
  }
  for (const auto& id : junction_nodes(plan)) {
    EXPECT_EQ(ins[id], 1) << id;
    EXPECT_EQ(outs[id], 1) << id;
  }
  EXPECT_EQ(plan.connections.size(), 2u);
  EXPECT_LE(max_distance_to_plan(plan, wf.routes[0]), 0.03);
}

TEST(JunctionPlan, TheUrbanGridHasItsThreeJunctionsAndEveryWaypointLiesUnderTheNet) {
  const WaypointFile wf = urban();
  const JunctionZones zones = find_junction_zones(wf);
  EXPECT_EQ(zones.count, 3);  // the 4-way, the T junction, the loop's junction on the cross street
  const NetPlan plan = plan_net(wf, NetPlanSettings{});
  EXPECT_EQ(plan.junctions, 3);
  // The loop overlaps the straight route in the middle (between the 4-way and the T) and
  // leaves it; the straight route's first stretch is shared with two turning routes.
  EXPECT_NE(lane_of_routes(plan, {"EB_left", "EB_straight", "T_in"}), nullptr);
  bool loop_shares_main_street = false;
  for (const auto& e : plan.edges)
    for (const auto& l : e.lanes)
      if (std::count(l.routes.begin(), l.routes.end(), "LOOP") && std::count(l.routes.begin(), l.routes.end(), "EB_straight"))
        loop_shares_main_street = true;
  EXPECT_TRUE(loop_shares_main_street);
  for (const auto& r : wf.routes) EXPECT_LE(max_distance_to_plan(plan, r), 0.10) << r.id;
}

TEST(JunctionPlan, PlanningIsDeterministic) {
  const WaypointFile wf = urban();
  const NetPlan a = plan_net(wf, NetPlanSettings{});
  const NetPlan b = plan_net(wf, NetPlanSettings{});
  ASSERT_EQ(a.edges.size(), b.edges.size());
  for (std::size_t i = 0; i < a.edges.size(); ++i) {
    EXPECT_EQ(a.edges[i].id, b.edges[i].id);
    ASSERT_EQ(a.edges[i].lanes.size(), b.edges[i].lanes.size());
    for (std::size_t l = 0; l < a.edges[i].lanes.size(); ++l)
      EXPECT_EQ(a.edges[i].lanes[l].shape.points(), b.edges[i].lanes[l].shape.points());
  }
  ASSERT_EQ(a.connections.size(), b.connections.size());
  for (std::size_t i = 0; i < a.connections.size(); ++i) EXPECT_EQ(a.connections[i].shape, b.connections[i].shape);
}

TEST(JunctionPlan, MapJsonSetsTheTypeAndTheRoadWithPriority) {
  const WaypointFile wf = fixture("crossing");
  JunctionSettings js;
  js.overrides.push_back({"", Vec2(1, 1), "allway_stop", {"NB", "SB"}});
  const NetPlan plan = plan_net(wf, NetPlanSettings{}, js);
  const auto node = std::find_if(plan.nodes.begin(), plan.nodes.end(), [](const auto& n) { return n.id == "J0"; });
  ASSERT_NE(node, plan.nodes.end());
  EXPECT_EQ(node->type, "allway_stop");
  for (const auto& e : plan.edges) {
    const bool cross_street = e.lanes.front().route_id == "NB" || e.lanes.front().route_id == "SB";
    EXPECT_EQ(e.priority > 100, cross_street) << e.id;
  }
  js.overrides = {{"J7", std::nullopt, "traffic_light", {}}};
  EXPECT_THROW(plan_net(wf, NetPlanSettings{}, js), MapError);  // no such junction
}

TEST(JunctionPlan, RoadsWithoutJunctionsArePlannedAsBefore) {
  // A plain two-lane road: no zones, no shared lanes, no junction nodes, no shapes.
  test::RoadShape road;
  std::vector<test::SyntheticRoute> routes = {{"right", test::road_points(road, 0, 0, 300)},
                                              {"left", test::road_points(road, 3.5, 0, 300)}};
  test::TempDir dir("junction_none");
  const WaypointFile wf = load_waypoint_file(test::write_waypoint_file(dir.path(), "plain", routes).string());
  EXPECT_TRUE(find_junction_zones(wf).empty());
  const NetPlan plan = plan_net(wf, NetPlanSettings{});
  EXPECT_EQ(plan.junctions, 0);
  EXPECT_TRUE(junction_nodes(plan).empty());
  for (const auto& c : plan.connections) EXPECT_TRUE(c.shape.empty());
}

namespace {

// East along y = 0, a right turn of radius `radius` onto x = 0, south to y = -60 (1 m points;
// the straights are drawn the same for any radius, so two such routes share them as one lane).
std::vector<Vec2> right_turn(double radius) {
  std::vector<Vec2> pts;
  for (double x = -60; x < -radius - 1e-9; x += 1.0) pts.emplace_back(x, 0);
  const int n = static_cast<int>(std::ceil(radius * M_PI / 2));
  for (int i = 0; i <= n; ++i) {
    const double a = M_PI / 2 * i / n;  // from north of the centre round to its east
    pts.emplace_back(-radius + radius * std::sin(a), -radius + radius * std::cos(a));
  }
  for (double y = -std::ceil(radius + 1e-9); y >= -60; y -= 1.0) pts.emplace_back(0, y);
  return pts;
}

}  // namespace

TEST(JunctionPlan, TwoTurnsOfDifferentRadiiBetweenTheSameLanesEachGetAPathOfTheirOwn) {
  // A RoadEditor user can draw this (the same turn once tight, once wide). SUMO has one
  // connection per pair of lanes, so the wide turn gets a detour lane of its own in the middle
  // of its turn (junction_detours.hpp): shared lane -> detour -> shared lane are pairs of lanes
  // of its own, connected along its own points, and every waypoint of both lies under the net.
  std::vector<test::SyntheticRoute> routes = {{"tight", right_turn(8)}, {"wide", right_turn(15)}};
  test::TempDir dir("junction_two_radii");
  const WaypointFile wf = load_waypoint_file(test::write_waypoint_file(dir.path(), "two_radii", routes).string());
  const NetPlan plan = plan_net(wf, NetPlanSettings{});
  EXPECT_NE(lane_of_routes(plan, {"tight", "wide"}), nullptr);  // the shared straights
  const PlannedLane* detour = lane_of_routes(plan, {"wide"});
  ASSERT_NE(detour, nullptr);
  EXPECT_LE(detour->shape.length(), kDetourLength / 2 + 0.01);  // cut in the middle by a node of its own
  EXPECT_EQ(plan.junctions, 1);
  EXPECT_EQ(plan.connections.size(), 4u);  // tight's, into the detour, between its halves, out of it
  EXPECT_LE(max_distance_to_plan(plan, wf.routes[0]), 0.05);
  EXPECT_LE(max_distance_to_plan(plan, wf.routes[1]), 0.05);  // the wide turn lay up to 2.9 m off tight's
  for (const auto& n : plan.notes) EXPECT_EQ(n.find("along different paths"), std::string::npos) << n;
  // A third route drawn along the wide turn drives its detour lane.
  routes.push_back({"wide_too", right_turn(15)});
  for (auto& p : routes.back().points) p.y() += 0.03;
  const WaypointFile wf3 = load_waypoint_file(test::write_waypoint_file(dir.path(), "three", routes).string());
  const NetPlan plan3 = plan_net(wf3, NetPlanSettings{});
  EXPECT_NE(lane_of_routes(plan3, {"wide", "wide_too"}), nullptr);
  EXPECT_LE(max_distance_to_plan(plan3, wf3.routes[2]), 0.05);
}

TEST(JunctionPlan, ARouteLeaningOffASharedLaneAndBackGetsADetourLane) {
  // The generator's shallow-angle touch (scripts/city_waypoints.py, bulge): two routes drawn
  // along one lane, the second leaning 2.6 m over 40 m towards the neighbouring lane (3.5 m to
  // the left) and back. It comes within a metre of that lane, so branch, touch and merge are
  // one junction between the shared lane before and the shared lane after; the leaning route
  // gets a detour lane of its own there (it drove the straight route's connection, 2.6 m off).
  std::vector<Vec2> straight;
  std::vector<Vec2> leaning;
  std::vector<Vec2> neighbour;
  for (double x = 0; x <= 200 + 1e-9; x += 1.0) {
    straight.emplace_back(x, 0);
    neighbour.emplace_back(x, 3.5);
    const double u = (x - 100) / 20;
    leaning.emplace_back(x, std::abs(u) < 1 ? 2.6 * (0.5 + 0.5 * std::cos(M_PI * u)) : 0.0);
  }
  std::vector<test::SyntheticRoute> routes = {{"straight", straight}, {"leaning", leaning}, {"neighbour", neighbour}};
  test::TempDir dir("junction_leaning");
  const WaypointFile wf = load_waypoint_file(test::write_waypoint_file(dir.path(), "leaning", routes).string());
  const NetPlan plan = plan_net(wf, NetPlanSettings{});
  EXPECT_EQ(plan.junctions, 1);
  EXPECT_NE(lane_of_routes(plan, {"straight", "leaning"}), nullptr);  // the shared lane before and after
  const PlannedLane* detour = lane_of_routes(plan, {"leaning"});
  ASSERT_NE(detour, nullptr);
  EXPECT_NEAR(detour->shape.point(0).y(), 2.6, 0.1);  // at the far side of the lean
  for (const WaypointRoute& r : wf.routes) EXPECT_LE(max_distance_to_plan(plan, r), 0.10) << r.id;  // `map check`'s tolerance
  for (const auto& n : plan.notes) EXPECT_EQ(n.find("along different paths"), std::string::npos) << n;
}

namespace {

// East along y = 0 to a right turn of radius `radius` about the corner (0, 0), then south,
// points `spacing` metres apart from x = -60 + `phase` (two routes with different phases lie
// between each other's points).
std::vector<Vec2> sparse_right_turn(double radius, double spacing, double phase) {
  std::vector<Vec2> pts;
  const double arc = radius * M_PI / 2;
  const double straight = 60 - radius;
  for (double s = phase; s <= 2 * straight + arc + 1e-9; s += spacing) {
    if (s < straight) {
      pts.emplace_back(-60 + s, 0);
    } else if (s < straight + arc) {
      const double a = (s - straight) / radius;
      pts.emplace_back(-radius + radius * std::sin(a), -radius + radius * std::cos(a));
    } else {
      pts.emplace_back(0, -radius - (s - straight - arc));
    }
  }
  return pts;
}

}  // namespace

TEST(JunctionPlan, RoutesDrawnALittleApartAlongOneLaneShareItsBestFit) {
  // The same turn of 6 m drawn twice along one lane, 2 m between points, 1 m out of step:
  // between two points of one, the other lies a chord's sagitta (0.08 m) off its line, and a
  // lane through the first one's points (averaged with the feet on the other) left the second
  // 0.12 m off. The shared lane is the best fit of both: every waypoint within
  // kPlannedLaneMiss of it, and no junction.
  std::vector<Vec2> again = sparse_right_turn(6.0, 2.0, 1.0);
  again.pop_back();  // ends before the first one's end, so that it lies along it
  const std::vector<test::SyntheticRoute> routes = {{"first", sparse_right_turn(6.0, 2.0, 0.0)}, {"again", again}};
  test::TempDir dir("junction_best_fit");
  const WaypointFile wf = load_waypoint_file(test::write_waypoint_file(dir.path(), "best_fit", routes).string());
  const NetPlan plan = plan_net(wf, NetPlanSettings{});
  EXPECT_EQ(plan.junctions, 0);
  EXPECT_NE(lane_of_routes(plan, {"first", "again"}), nullptr);
  for (const WaypointRoute& r : wf.routes) EXPECT_LE(max_distance_to_plan(plan, r), kPlannedLaneMiss) << r.id;
}

TEST(JunctionPlan, RoutesDrawnTooFarApartForOneLaneGetPathsOfTheirOwnThere) {
  // The same turn drawn with radii 10 and 10.6 m: 0.25 m apart at its middle (drawn "on one
  // lane", closer than kSameLaneDistance), so one lane in the middle left each 0.125 m off.
  // Farther apart than kMaxSameLaneSpread, the turn is a junction in which the second gets a
  // detour lane; the straights before and after stay one shared lane.
  const std::vector<test::SyntheticRoute> routes = {{"tight", sparse_right_turn(10.0, 1.0, 0.0)},
                                                    {"wide", sparse_right_turn(10.6, 1.0, 0.5)}};
  test::TempDir dir("junction_spread");
  const WaypointFile wf = load_waypoint_file(test::write_waypoint_file(dir.path(), "spread", routes).string());
  const NetPlan plan = plan_net(wf, NetPlanSettings{});
  EXPECT_EQ(plan.junctions, 1);
  EXPECT_NE(lane_of_routes(plan, {"tight", "wide"}), nullptr);
  EXPECT_NE(lane_of_routes(plan, {"wide"}), nullptr);  // its detour lane
  for (const WaypointRoute& r : wf.routes) EXPECT_LE(max_distance_to_plan(plan, r), kPlannedLaneMiss) << r.id;
}

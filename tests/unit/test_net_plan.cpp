// The network planner of `map build` on synthetic roads, without SUMO: which routes become
// lanes of one edge, in which order, where the road is split, and the lane geometry.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/errors.hpp"
#include "map/net_plan.hpp"
#include "map/route_corridors.hpp"
#include "map/waypoint_file.hpp"
#include "unit/synthetic_roads.hpp"

using namespace orch;
using orch::test::road_points;
using orch::test::RoadShape;
using orch::test::SyntheticRoute;

namespace {

struct Planned {
  WaypointFile waypoints;
  NetPlan plan;
};

Planned plan_routes(const std::vector<SyntheticRoute>& routes) {
  test::TempDir dir("netplan");
  Planned p;
  p.waypoints = load_waypoint_file(test::write_waypoint_file(dir.path(), "synthetic", routes).string());
  p.plan = plan_net(p.waypoints, NetPlanSettings{});
  return p;
}

std::vector<std::string> lane_routes(const PlannedEdge& e) {
  std::vector<std::string> out;
  for (const auto& l : e.lanes) out.push_back(l.route_id);
  return out;
}

// Largest distance from a waypoint of `route` to the planned lanes of that route.
double max_distance_to_own_lanes(const Planned& p, const std::string& route) {
  double worst = 0;
  for (const Vec2& pt : p.waypoints.find(route)->line.points()) {
    double best = 1e9;
    for (const auto& e : p.plan.edges)
      for (const auto& l : e.lanes)
        if (l.route_id == route) best = std::min(best, l.shape.project(pt).distance);
    worst = std::max(worst, best);
  }
  return worst;
}

RoadShape curved_road() {
  RoadShape road;
  road.heading = 0.3;
  road.straight = 300;
  road.radius = 250;
  road.arc_length = 400;
  return road;
}

}  // namespace

TEST(NetPlan, ParallelRoutesBecomeLanesOrderedRightToLeft) {
  RoadShape road;
  // File order deliberately not the lateral order: lane 0 must be the rightmost (lateral -3.5).
  const auto p = plan_routes({{"middle", road_points(road, 0, 0, 500), 80},
                              {"left", road_points(road, 3.5, 0, 500), 100},
                              {"right", road_points(road, -3.5, 0, 500), 60}});
  EXPECT_EQ(p.plan.corridors, 1);
  ASSERT_EQ(p.plan.edges.size(), 1u);
  const auto& e = p.plan.edges[0];
  EXPECT_EQ(lane_routes(e), (std::vector<std::string>{"right", "middle", "left"}));
  EXPECT_EQ(e.id, "right+middle+left#0");
  EXPECT_EQ(e.from, "right+middle+left@0");
  EXPECT_EQ(e.to, "right+middle+left@1");
  for (const auto& l : e.lanes) EXPECT_NEAR(l.width, 3.5, 1e-9);
  EXPECT_NEAR(e.lanes[0].speed, 60 / 3.6, 1e-9);
  EXPECT_NEAR(e.lanes[2].speed, 100 / 3.6, 1e-9);
  // Straight lanes simplify to their two ends, 20 m beyond the first and last waypoint.
  const auto& shape = e.lanes[0].shape;
  ASSERT_EQ(shape.size(), 2u);
  EXPECT_TRUE(shape.point(0).isApprox(Vec2(-20, -3.5), 1e-9));
  EXPECT_TRUE(shape.point(1).isApprox(Vec2(520, -3.5), 1e-9));
  EXPECT_TRUE(p.plan.connections.empty());
  ASSERT_EQ(p.plan.nodes.size(), 2u);
  // The junction shape passes through the lane ends (netconvert then keeps the lanes whole).
  for (const auto& l : e.lanes) {
    const auto& ns = p.plan.nodes[0].shape;
    EXPECT_NE(std::find_if(ns.begin(), ns.end(), [&](const Vec2& q) { return q.isApprox(l.shape.point(0)); }), ns.end());
  }
}

TEST(NetPlan, LaneWidthIsTheSpacingOfNeighbouringRoutes) {
  RoadShape road;
  const auto p = plan_routes({{"a", road_points(road, 0, 0, 300)},
                              {"b", road_points(road, 3.0, 0, 300)},
                              {"c", road_points(road, 7.0, 0, 300)}});
  ASSERT_EQ(p.plan.edges.size(), 1u);
  const auto& lanes = p.plan.edges[0].lanes;
  EXPECT_NEAR(lanes[0].width, 3.0, 1e-9);
  EXPECT_NEAR(lanes[1].width, 3.5, 1e-9);  // between 3 m and 4 m neighbours
  EXPECT_NEAR(lanes[2].width, 4.0, 1e-9);
}

TEST(NetPlan, OppositeDirectionsBecomeSeparateEdges) {
  RoadShape road;
  const auto p = plan_routes({{"east1", road_points(road, -1.75, 0, 400)},
                              {"east2", road_points(road, 1.75, 0, 400)},
                              {"west1", road_points(road, 5.25, 0, 400, 1.0, true)},
                              {"west2", road_points(road, 8.75, 0, 400, 1.0, true)}});
  EXPECT_EQ(p.plan.corridors, 2);
  ASSERT_EQ(p.plan.edges.size(), 2u);
  EXPECT_EQ(lane_routes(p.plan.edges[0]), (std::vector<std::string>{"east1", "east2"}));
  // Driving west, the right-hand side is +y: west2 (y = 8.75) is lane 0.
  EXPECT_EQ(lane_routes(p.plan.edges[1]), (std::vector<std::string>{"west2", "west1"}));
  const Vec2 east = p.plan.edges[0].lanes[0].shape.tangent_at(10);
  const Vec2 west = p.plan.edges[1].lanes[0].shape.tangent_at(10);
  EXPECT_LT(east.dot(west), -0.99);
}

TEST(NetPlan, LaneStartingLaterSplitsTheRoadAndConnectsEachRoute) {
  const RoadShape road = curved_road();
  const auto p = plan_routes({{"R1", road_points(road, 0, 0, 700)},
                              {"R2", road_points(road, 3.5, 0, 700)},
                              {"R3", road_points(road, 7.0, 200, 700)}});
  ASSERT_EQ(p.plan.edges.size(), 2u);
  const auto& first = p.plan.edges[0];
  const auto& second = p.plan.edges[1];
  EXPECT_EQ(lane_routes(first), (std::vector<std::string>{"R1", "R2"}));
  EXPECT_EQ(lane_routes(second), (std::vector<std::string>{"R1", "R2", "R3"}));
  EXPECT_EQ(first.to, second.from);
  EXPECT_EQ(first.id, "R1+R2+R3#0");
  EXPECT_EQ(second.id, "R1+R2+R3#1");
  // The new lane starts lane_extension (20 m) before its first waypoint: the cut is there.
  EXPECT_NEAR(second.lanes[2].shape.point(0).x(), road.at(180, 7.0).x(), 1e-6);
  EXPECT_NEAR(second.lanes[2].shape.point(0).y(), road.at(180, 7.0).y(), 1e-6);
  // Consecutive lanes of one route meet exactly.
  EXPECT_TRUE(first.lanes[0].shape.points().back().isApprox(second.lanes[0].shape.point(0), 1e-12));
  ASSERT_EQ(p.plan.connections.size(), 2u);
  for (int lane = 0; lane < 2; ++lane) {
    EXPECT_EQ(p.plan.connections[lane].from, first.id);
    EXPECT_EQ(p.plan.connections[lane].to, second.id);
    EXPECT_EQ(p.plan.connections[lane].from_lane, lane);
    EXPECT_EQ(p.plan.connections[lane].to_lane, lane);
  }
  for (const char* r : {"R1", "R2", "R3"}) EXPECT_LE(max_distance_to_own_lanes(p, r), 0.02 + 1e-9) << r;
}

TEST(NetPlan, CurvedLanesStayWithinTheSimplificationTolerance) {
  const RoadShape road = curved_road();
  const auto p = plan_routes({{"in", road_points(road, 3.5, 0, 700)}, {"out", road_points(road, 0, 0, 700)}});
  ASSERT_EQ(p.plan.edges.size(), 1u);
  EXPECT_EQ(lane_routes(p.plan.edges[0]), (std::vector<std::string>{"out", "in"}));
  // The arc needs more than two points, but far fewer than the 701 waypoints.
  EXPECT_GT(p.plan.edges[0].lanes[0].shape.size(), 10u);
  EXPECT_LT(p.plan.edges[0].lanes[0].shape.size(), 200u);
  EXPECT_LE(max_distance_to_own_lanes(p, "in"), 0.02 + 1e-9);
  EXPECT_LE(max_distance_to_own_lanes(p, "out"), 0.02 + 1e-9);
}

TEST(NetPlan, LonelyRouteIsASingleLaneRoad) {
  RoadShape road;
  const auto p = plan_routes({{"solo", road_points(road, 0, 0, 100)}});
  ASSERT_EQ(p.plan.edges.size(), 1u);
  ASSERT_EQ(p.plan.edges[0].lanes.size(), 1u);
  EXPECT_EQ(p.plan.edges[0].id, "solo#0");
  EXPECT_DOUBLE_EQ(p.plan.edges[0].lanes[0].width, kDefaultLaneWidth);
  EXPECT_NEAR(p.plan.edges[0].lanes[0].shape.length(), 140, 1e-9);
  EXPECT_NE(std::find_if(p.plan.notes.begin(), p.plan.notes.end(),
                         [](const std::string& n) { return n.find("\"solo\" has no parallel route") != std::string::npos; }),
            p.plan.notes.end());
}

TEST(NetPlan, RoutesTooFarApartAreSeparateRoads) {
  RoadShape road;
  const auto p = plan_routes({{"a", road_points(road, 0, 0, 300)}, {"b", road_points(road, 9, 0, 300)}});
  EXPECT_EQ(p.plan.corridors, 2);
  EXPECT_EQ(p.plan.edges.size(), 2u);
}

TEST(NetPlan, ZeroSpeedFallsBackAndIsReported) {
  RoadShape road;
  const auto p = plan_routes({{"stop", road_points(road, 0, 0, 100), 0}});
  EXPECT_DOUBLE_EQ(p.plan.edges[0].lanes[0].speed, kFallbackLaneSpeed);
  EXPECT_NE(std::find_if(p.plan.notes.begin(), p.plan.notes.end(),
                         [](const std::string& n) { return n.find("no positive target speed") != std::string::npos; }),
            p.plan.notes.end());
}

TEST(NetPlan, IdsAreMadeSafeForSumo) {
  EXPECT_EQ(sumo_safe_id("lane 1;a,b"), "lane_1_a_b");
  EXPECT_EQ(sumo_safe_id(":x"), "_x");
  RoadShape road;
  const auto p = plan_routes({{"my route", road_points(road, 0, 0, 100)}});
  EXPECT_EQ(p.plan.edges[0].id, "my_route#0");
  EXPECT_EQ(p.plan.edges[0].lanes[0].route_id, "my route");  // the param keeps the real id
}

TEST(RouteRelation, DistinguishesNeighboursFromOtherRoads) {
  RoadShape road;
  const Polyline base(road_points(road, 0, 0, 400));
  const auto rel = [&](const std::vector<Vec2>& pts) { return relate_routes(Polyline(pts), base); };
  using Kind = RouteRelation::Kind;

  const auto left = rel(road_points(road, 3.5, 100, 300));
  EXPECT_EQ(left.kind, Kind::Parallel);
  EXPECT_NEAR(left.lateral, 3.5, 1e-6);
  EXPECT_NEAR(left.overlap, 200, 2.5);
  EXPECT_EQ(rel(road_points(road, -4, 0, 400)).kind, Kind::Parallel);
  EXPECT_EQ(rel(road_points(road, 0.3, 0, 400)).kind, Kind::Coincident);
  EXPECT_EQ(rel(road_points(road, 3.5, 0, 400, 1.0, true)).kind, Kind::None);  // opposite direction
  EXPECT_EQ(rel(road_points(road, 12, 0, 400)).kind, Kind::None);              // another road

  // A route crossing the road at an angle, and one that drifts away like an exit lane.
  std::vector<Vec2> crossing;
  for (int i = 0; i <= 100; ++i) crossing.emplace_back(150 + i, -50 + i);
  EXPECT_EQ(rel(crossing).kind, Kind::None);
  std::vector<Vec2> exit;
  for (int i = 0; i <= 300; ++i) exit.emplace_back(50 + i, 3.5 + (i > 100 ? 0.05 * (i - 100) : 0.0));
  EXPECT_EQ(rel(exit).kind, Kind::None);
}

TEST(RouteCorridors, CoincidentRoutesAreNotStackedIntoOneRoad) {
  RoadShape road;
  test::TempDir dir("corridors");
  // "b" and "b_copy" are drawn along the same lane next to "a".
  const auto wf = load_waypoint_file(test::write_waypoint_file(dir.path(), "stack",
                                                               {{"a", road_points(road, 0, 0, 300)},
                                                                {"b", road_points(road, 3.5, 0, 300)},
                                                                {"b_copy", road_points(road, 3.6, 0, 300)}})
                                         .string());
  std::vector<std::string> notes;
  const auto corridors = find_corridors(wf, notes);
  ASSERT_EQ(corridors.size(), 2u);
  EXPECT_EQ(corridors[0].size(), 2u);
  EXPECT_EQ(corridors[1].size(), 1u);
  EXPECT_NE(std::find_if(notes.begin(), notes.end(),
                         [](const std::string& n) { return n.find("run along the same lane") != std::string::npos; }),
            notes.end());
}

TEST(NetPlan, LaneDrawnAsConsecutiveRoutesIsConnected) {
  const RoadShape road = curved_road();
  // "B" and "C" are one lane drawn in two pieces, 6 m apart, beside "A".
  const auto p = plan_routes({{"A", road_points(road, 0, 0, 700)},
                              {"B", road_points(road, 3.5, 0, 400)},
                              {"C", road_points(road, 3.5, 406, 700)}});
  ASSERT_EQ(p.plan.edges.size(), 2u);
  EXPECT_EQ(p.plan.edges[0].id, "A+B+C#0");
  EXPECT_EQ(lane_routes(p.plan.edges[0]), (std::vector<std::string>{"A", "B"}));
  EXPECT_EQ(lane_routes(p.plan.edges[1]), (std::vector<std::string>{"A", "C"}));
  // The pieces meet halfway between B's last and C's first waypoint, and B leads into C.
  const Vec2 meet = road.at(403, 3.5);
  EXPECT_LT((p.plan.edges[0].lanes[1].shape.points().back() - meet).norm(), 0.05);
  EXPECT_LT((p.plan.edges[1].lanes[1].shape.point(0) - meet).norm(), 0.05);
  ASSERT_EQ(p.plan.connections.size(), 2u);
  EXPECT_EQ(p.plan.connections[1].from_lane, 1);
  EXPECT_EQ(p.plan.connections[1].to_lane, 1);
  for (const char* r : {"A", "B", "C"}) EXPECT_LE(max_distance_to_own_lanes(p, r), 0.02 + 1e-9) << r;
}

TEST(NetPlan, ClosedLoopBecomesARingOfEdges) {
  // A ring road drawn as one route ending on its first point: the lane cannot close on
  // itself in one node, so the junction step splits it at two plain junctions.
  std::vector<Vec2> ring;
  for (int i = 0; i <= 600; ++i) ring.emplace_back(100 * std::cos(i * 2 * std::numbers::pi / 600), 100 * std::sin(i * 2 * std::numbers::pi / 600));
  const Planned p = plan_routes({{"ring", ring}});
  EXPECT_EQ(p.plan.junctions, 2);
  ASSERT_GE(p.plan.edges.size(), 2u);
  for (const auto& e : p.plan.edges) EXPECT_NE(e.from, e.to);
  EXPECT_EQ(p.plan.connections.size(), p.plan.edges.size());  // every edge leads on to the next
  // Every waypoint lies on a lane or on a junction's connection (the ring's own points).
  for (const Vec2& pt : p.waypoints.find("ring")->line.points()) {
    double best = 1e9;
    for (const auto& e : p.plan.edges) best = std::min(best, e.lanes.front().shape.project(pt).distance);
    for (const auto& c : p.plan.connections) best = std::min(best, Polyline(c.shape).project(pt).distance);
    EXPECT_LE(best, 0.05);
  }
}

TEST(RouteRelation, ShortStretchOnTheSameLaneIsCoincident) {
  RoadShape road;
  const Polyline base(road_points(road, 0, 0, 400));
  // A 10 m route: on the same lane it is coincident (two lanes cannot share even 10 m); one
  // lane over it is a neighbour (a short route needs only half its length beside the other).
  EXPECT_EQ(relate_routes(Polyline(road_points(road, 0.2, 390, 400)), base).kind, RouteRelation::Kind::Coincident);
  EXPECT_EQ(relate_routes(Polyline(road_points(road, 3.5, 390, 400)), base).kind, RouteRelation::Kind::Parallel);
  // A long route that runs beside the base for only its last 10 m is neither.
  std::vector<Vec2> joining = road_points(road, 3.5, 390, 400);
  for (int i = 1; i <= 100; ++i) joining.insert(joining.begin(), Vec2(390 - i * 0.7, 3.5 + i * 0.7));
  EXPECT_EQ(relate_routes(Polyline(joining), base).kind, RouteRelation::Kind::None);
}

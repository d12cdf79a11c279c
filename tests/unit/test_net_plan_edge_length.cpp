// `map build` cuts long stretches into edges no longer than max_edge_length (net_plan.hpp:
// SUMO's sublane model costs O(n^2) per lane), without changing where the lanes lie.
#include <gtest/gtest.h>

#include <cmath>

#include "map/net_plan.hpp"
#include "map/waypoint_file.hpp"
#include "unit/synthetic_roads.hpp"

using namespace orch;
using orch::test::road_points;
using orch::test::RoadShape;

namespace {

NetPlan plan(const std::vector<test::SyntheticRoute>& routes, double max_edge_length, WaypointFile* out = nullptr) {
  test::TempDir dir("netplan_length");
  WaypointFile wf = load_waypoint_file(test::write_waypoint_file(dir.path(), "synthetic", routes).string());
  NetPlanSettings settings;
  settings.max_edge_length = max_edge_length;
  NetPlan p = plan_net(wf, settings);
  if (out) *out = std::move(wf);
  return p;
}

RoadShape curved() {
  RoadShape road;
  road.straight = 300;
  road.radius = 400;
  road.arc_length = 600;
  return road;
}

}  // namespace

TEST(NetPlanEdgeLength, LongRoadIsCutIntoEqualEdgesNoLongerThanTheLimit) {
  const RoadShape road = curved();
  const auto p = plan({{"right", road_points(road, -3.5, 0, 900)}, {"left", road_points(road, 0, 0, 900)}}, 250);
  // 900 m of waypoints + 2 x 20 m extension = 940 m: four pieces of 235 m.
  ASSERT_EQ(p.edges.size(), 4u);
  for (std::size_t i = 0; i < p.edges.size(); ++i) {
    SCOPED_TRACE(i);
    EXPECT_EQ(p.edges[i].id, "right+left#" + std::to_string(i));
    ASSERT_EQ(p.edges[i].lanes.size(), 2u);
    for (const auto& lane : p.edges[i].lanes) {
      EXPECT_LE(lane.shape.length(), 250.0 + 1.0);
      EXPECT_GT(lane.shape.length(), 200.0);
    }
  }
  // Every lane continues on its own route across each cut, end to start.
  ASSERT_EQ(p.connections.size(), 6u);
  for (const auto& c : p.connections) EXPECT_EQ(c.from_lane, c.to_lane);
  for (std::size_t i = 0; i + 1 < p.edges.size(); ++i)
    for (std::size_t l = 0; l < 2; ++l)
      EXPECT_LT((p.edges[i].lanes[l].shape.points().back() - p.edges[i + 1].lanes[l].shape.point(0)).norm(), 0.01);
}

TEST(NetPlanEdgeLength, CutsDoNotMoveTheLanes) {
  const RoadShape road = curved();
  WaypointFile wf;
  const auto p = plan({{"r", road_points(road, -3.5, 0, 900)}, {"l", road_points(road, 0, 0, 900)}}, 250, &wf);
  for (const auto& route : wf.routes) {
    double worst = 0;
    for (const Vec2& pt : route.line.points()) {
      double best = 1e9;
      for (const auto& e : p.edges)
        for (const auto& l : e.lanes)
          if (l.route_id == route.id) best = std::min(best, l.shape.project(pt).distance);
      worst = std::max(worst, best);
    }
    EXPECT_LT(worst, 0.03) << route.id;
  }
}

TEST(NetPlanEdgeLength, ZeroKeepsOneEdgePerStretch) {
  const RoadShape road = curved();
  EXPECT_EQ(plan({{"a", road_points(road, 0, 0, 900)}}, 0).edges.size(), 1u);
  EXPECT_EQ(plan({{"a", road_points(road, 0, 0, 900)}}, 5000).edges.size(), 1u);
}

TEST(NetPlanEdgeLength, LaneEndsStillCutWhereTheyAre) {
  // A lane that starts 400 m in: the cut at its start stays, the stretches on either side
  // are cut by length on their own.
  RoadShape road;
  road.straight = 1200;
  const auto p = plan({{"main", road_points(road, 0, 0, 1000)}, {"added", road_points(road, 3.5, 400, 1000)}}, 300);
  std::size_t one_lane = 0;
  std::size_t two_lanes = 0;
  for (const auto& e : p.edges) {
    (e.lanes.size() == 1 ? one_lane : two_lanes)++;
    for (const auto& l : e.lanes) EXPECT_LE(l.shape.length(), 301.0);
  }
  EXPECT_EQ(one_lane, 2u);   // 0..380 m (20 m extension before "added" starts): 2 pieces
  EXPECT_EQ(two_lanes, 3u);  // 380..1020 m: 3 pieces
}

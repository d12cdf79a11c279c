// Along-road distance between actors on routes that only cross or join (route_crossing.hpp).
#include <gtest/gtest.h>

#include "scenario_executor_engine/route_crossing.hpp"
#include "map/waypoint_file.hpp"
#include "unit/synthetic_roads.hpp"

using namespace orch;
using namespace orch::engine;

namespace {

struct Routes {
  test::TempDir dir{"crossing"};
  WaypointFile file;
  const WaypointRoute& get(const std::string& id) const { return *file.find(id); }
};

std::vector<Vec2> line(Vec2 a, Vec2 b, double step = 1.0) {
  std::vector<Vec2> pts;
  const int n = static_cast<int>((b - a).norm() / step);
  for (int i = 0; i <= n; ++i) pts.push_back(a + (b - a) * (static_cast<double>(i) / n));
  return pts;
}

std::unique_ptr<Routes> routes() {
  auto r = std::make_unique<Routes>();
  // "east" along y = 0; "north" crosses it at x = 50; "merge" comes up from the south and
  // turns onto "east" at x = 70 (a right turn joining the lane); "beside" is the next lane.
  std::vector<Vec2> merge = line({70, -40}, {70, -0.5});
  for (const Vec2& p : line({70.5, 0}, {100, 0})) merge.push_back(p);
  const std::vector<test::SyntheticRoute> rs = {{"east", line({0, 0}, {100, 0})},
                                                {"north", line({50, -50}, {50, 50})},
                                                {"merge", merge},
                                                {"beside", line({0, 3.5}, {100, 3.5})}};
  r->file = load_waypoint_file(test::write_waypoint_file(r->dir.path(), "crossing", rs).string());
  return r;
}

}  // namespace

TEST(RouteCrossing, TheGapIsTheDifferenceOfTheDistancesToTheConflictPoint) {
  const auto r = routes();
  RouteMeetings meetings;
  // Actor 20 m before the crossing, target 10 m before it: the target is nearer, +10.
  auto gap = conflict_point_gap(r->get("east"), {30, 0}, r->get("north"), {50, -10}, meetings);
  ASSERT_TRUE(gap);
  EXPECT_NEAR(*gap, 10.0, 0.05);
  // The target 5 m past the crossing and the actor 20 m before it: 25 m "ahead".
  gap = conflict_point_gap(r->get("east"), {30, 0}, r->get("north"), {50, 5}, meetings);
  ASSERT_TRUE(gap);
  EXPECT_NEAR(*gap, 25.0, 0.05);
  // The actor nearer: negative.
  gap = conflict_point_gap(r->get("east"), {45, 0}, r->get("north"), {50, -30}, meetings);
  ASSERT_TRUE(gap);
  EXPECT_NEAR(*gap, -25.0, 0.05);
}

TEST(RouteCrossing, AJoiningRouteMeetsWhereItComesOntoTheLane) {
  const auto r = routes();
  RouteMeetings meetings;
  const auto& m = meetings.between(r->get("east"), r->get("merge"));
  ASSERT_EQ(m.size(), 1u);
  EXPECT_NEAR(m[0].s_route, 70.0, 0.6);
  const auto gap = conflict_point_gap(r->get("east"), {50, 0}, r->get("merge"), {70, -20}, meetings);
  ASSERT_TRUE(gap);
  EXPECT_NEAR(*gap, 0.0, 0.6);  // both 20 m from where the merge joins
}

TEST(RouteCrossing, TargetsOnOrBesideTheRouteUseTheOrdinaryAlongRoadDistance) {
  const auto r = routes();
  RouteMeetings meetings;
  EXPECT_FALSE(conflict_point_gap(r->get("east"), {30, 0}, r->get("beside"), {40, 3.5}, meetings));
  EXPECT_FALSE(conflict_point_gap(r->get("east"), {30, 0}, r->get("east"), {40, 0}, meetings));
  // A merging target already on the lane: beside the route, aligned.
  EXPECT_FALSE(conflict_point_gap(r->get("east"), {30, 0}, r->get("merge"), {80, 0}, meetings));
}

#include <gtest/gtest.h>

#include <cmath>

#include "scenario_executor_engine/motion.hpp"

using namespace orch;
using namespace orch::engine;

namespace {
WaypointRoute straight_route(const std::string& id, double y, double length) {
  WaypointRoute r;
  r.id = id;
  std::vector<Vec2> pts;
  for (int i = 0; i <= static_cast<int>(length); ++i) {
    r.points.push_back({static_cast<double>(i), y, 0, 80 / 3.6});
    pts.emplace_back(i, y);
  }
  r.line = Polyline(pts);
  return r;
}
constexpr double dt = 0.05;
}  // namespace

TEST(LateralMove, SmoothAndExactAtBothEnds) {
  LateralMove m{4.0, 0.0, 10.0, 3.0};
  EXPECT_DOUBLE_EQ(m.value_at(9.0), 4.0);
  EXPECT_DOUBLE_EQ(m.value_at(13.0), 0.0);
  EXPECT_NEAR(m.value_at(11.5), 2.0, 1e-12);  // symmetric profile: half way at half time
  EXPECT_DOUBLE_EQ(m.rate_at(10.0), 0.0);     // no lateral jerk at the start...
  EXPECT_DOUBLE_EQ(m.rate_at(13.0), 0.0);     // ...or the end
  EXPECT_NEAR(m.rate_at(11.5), -4.0 * 1.875 / 3.0, 1e-12);  // peak rate of the quintic
}

TEST(ScriptedMotion, AcceleratesAtTheGivenRateAndHolds) {
  auto route = straight_route("A", 0, 2000);
  ScriptedMotion m(route, 100, 0, 10.0, 0, 4.5, 20);
  m.set_desired(20.0, 2.0);
  double t = 0;
  for (int i = 0; i < 100; ++i, t += dt) m.advance(t, dt);  // 5 s
  EXPECT_NEAR(m.speed(), 20.0, 1e-9);
  // 10 -> 20 m/s at 2 m/s^2 takes 5 s and covers 75 m.
  EXPECT_NEAR(m.s(), 175.0, 1e-6);
  m.set_desired(5.0, 3.0);  // slowing down uses the same magnitude
  m.advance(t, dt);
  EXPECT_NEAR(m.speed(), 20.0 - 3.0 * dt, 1e-9);
  EXPECT_NEAR(m.accel(), -3.0, 1e-9);
}

TEST(ScriptedMotion, GodsHandIsInstant) {
  auto route = straight_route("A", 0, 500);
  ScriptedMotion m(route, 0, 0, 0.0, 0, 4.5, 20);
  m.set_desired(25.0, 0.0);
  m.advance(0, dt);
  EXPECT_DOUBLE_EQ(m.speed(), 25.0);
}

TEST(ScriptedMotion, ChangeRouteDriftsOntoTheNewLineInTheGivenTime) {
  auto left = straight_route("L", 4.0, 1000);
  auto right = straight_route("R", 0.0, 1000);
  ScriptedMotion m(left, 100, 0, 20.0, 0, 4.5, 20);
  m.set_desired(20.0, 0.0);
  m.change_route(right, 0.0, 10.0, 3.0);
  EXPECT_EQ(m.route().id, "R");
  EXPECT_NEAR(m.lateral(), 4.0, 1e-9);  // starts where it was, 4 m left of the new line
  double t = 10.0;
  double previous = m.lateral();
  for (int i = 0; i < 60; ++i, t += dt) {
    m.advance(t, dt);
    EXPECT_LE(m.lateral(), previous + 1e-12);  // monotone drift to the right
    previous = m.lateral();
  }
  EXPECT_NEAR(m.lateral(), 0.0, 1e-9);  // on the new lane's centre after exactly 3 s
  EXPECT_NEAR(m.position().y(), 0.0, 1e-9);
}

TEST(ScriptedMotion, LateralLegsRunInOrder) {
  auto route = straight_route("A", 0, 2000);
  ScriptedMotion m(route, 0, 0, 10.0, 0, 4.5, 20);
  m.set_desired(10.0, 0.0);
  m.plan_lateral({{1.0, 2.0}, {1.0, 5.0}, {-1.0, 2.0}}, 0.0);
  double t = 0;
  auto run_until = [&](double end) {
    while (t < end - 1e-9) {
      m.advance(t, dt);
      t += dt;
    }
  };
  run_until(2.0);
  EXPECT_NEAR(m.lateral(), 1.0, 1e-9);
  run_until(7.0);
  EXPECT_NEAR(m.lateral(), 1.0, 1e-9);
  run_until(8.0);
  EXPECT_NEAR(m.lateral(), 0.0, 1e-9);  // half way through the third leg
  run_until(9.0);
  EXPECT_NEAR(m.lateral(), -1.0, 1e-9);
  EXPECT_FALSE(m.lateral_busy());
}

TEST(ScriptedMotion, BrakesToStopAtTheEndOfItsLane) {
  auto route = straight_route("A", 0, 100);
  ScriptedMotion m(route, 0, 0, 20.0, 0, 4.0, 20);
  m.set_desired(20.0, 0.0);
  double t = 0;
  double hardest = 0;
  for (int i = 0; i < 400; ++i, t += dt) {
    m.advance(t, dt);
    hardest = std::min(hardest, m.accel());
  }
  // Braking started in time: about kEndOfLaneDecel, never an instant stop.
  EXPECT_GT(hardest, -ScriptedMotion::kEndOfLaneDecel * 1.2);
  EXPECT_TRUE(m.at_route_end());
  EXPECT_TRUE(m.running_out_of_road());
  EXPECT_DOUBLE_EQ(m.speed(), 0.0);
  EXPECT_NEAR(m.s(), 100 + 20 - 2.0, 1e-9);  // front at the end of the 20 m lane extension
}

TEST(ScriptedMotion, HeadingFollowsLateralMotion) {
  auto route = straight_route("A", 0, 1000);
  ScriptedMotion m(route, 0, 0, 20.0, 0, 4.5, 20);
  m.set_desired(20.0, 0.0);
  m.plan_lateral({{3.5, 3.0}}, 0.0);
  for (int i = 0; i < 30; ++i) m.advance(i * dt, dt);
  EXPECT_GT(m.heading(), 0.0);  // drifting left: pointing left of the road direction
  EXPECT_LT(m.heading(), 0.2);
}

TEST(ScriptedMotion, WalksStraightLegsAtDistanceOverTime) {
  auto route = straight_route("A", 0, 100);
  ScriptedMotion m(route, 50, -5, 0.0, 0, 0.4, 20);
  m.plan_walk({{Vec2(50, 5), 5.0}}, 0.0);  // 10 m across in 5 s
  double t = 0;
  for (int i = 0; i < 50; ++i, t += dt) m.advance(t, dt);
  EXPECT_NEAR(m.speed(), 2.0, 1e-9);
  EXPECT_NEAR(m.position().y(), 0.0, 1e-9);
  for (int i = 0; i < 60; ++i, t += dt) m.advance(t, dt);
  EXPECT_TRUE(m.position().isApprox(Vec2(50, 5)));
  EXPECT_NEAR(m.speed(), 0.0, 1e-9);
}

// FollowTrajectoryAction followingMode "follow": the pure-pursuit follower on a kinematic
// bicycle (openscenario/trajectory_follow.hpp), stepped directly on paths (no roads).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "openscenario/trajectory_follow.hpp"

namespace orch::openscenario {
namespace {

constexpr double kDt = 0.05;

// The 5 m car of the storyboard tests: wheelbase 3 m, maxSteering 0.5 rad, 10 m/s^2 both ways.
FollowLimits car_limits() {
  Entity car;
  car.performance = Performance{70, 10, 10};
  car.front_axle = Axle{0.5, 0.8, 1.68, 3, 0.4};
  car.rear_axle = Axle{0, 0.8, 1.68, 0, 0.4};
  return follow_limits(car);
}

// A path through `corners` due at constant `speed` from t = 0.
PathMotion timed_path(const std::vector<std::pair<double, double>>& corners, double speed) {
  std::vector<PathPoint> points;
  double along = 0;
  for (std::size_t i = 0; i < corners.size(); ++i) {
    if (i > 0) along += std::hypot(corners[i].first - corners[i - 1].first, corners[i].second - corners[i - 1].second);
    points.push_back({corners[i].first, corners[i].second, 0.0, along / speed, std::nullopt});
  }
  return make_path(points, true);
}

// Distance of (x, y) from the path's polyline.
double off_path(const PathMotion& path, double x, double y) {
  const opendrive::Pose2 p = path.pose_at(nearest_distance(path, x, y, 0, path.length()));
  return std::hypot(p.x - x, p.y - y);
}

struct FollowRun {
  double max_off = 0;          // largest distance from the path
  double max_schedule_lag = 0;  // largest (due distance - reached distance)
  double max_acceleration = 0, max_deceleration = 0, max_curvature = 0, max_lateral_acceleration = 0;
  double end_time = -1;        // when the path was done
};

FollowRun follow(PathMotion& path, opendrive::Pose2 pose, double speed, const FollowLimits& limits, double until) {
  start_following(path, pose, speed, limits);
  FollowRun run;
  for (int k = 1; k * kDt <= until + 1e-9 && run.end_time < 0; ++k) {
    const double t = k * kDt;
    const double before_speed = speed;
    const double before_heading = pose.heading;
    follow_step(path, pose, speed, std::nullopt, t, kDt);
    if (path.distance < path.length() - kFollowEnd)  // (the last step may pass the end)
      run.max_off = std::max(run.max_off, off_path(path, pose.x, pose.y));
    if (path.timed) run.max_schedule_lag = std::max(run.max_schedule_lag, path.distance_at(t) - path.distance);
    run.max_acceleration = std::max(run.max_acceleration, (speed - before_speed) / kDt);
    run.max_deceleration = std::max(run.max_deceleration, (before_speed - speed) / kDt);
    const double turn = std::remainder(pose.heading - before_heading, 2 * M_PI);
    if (speed > 0) run.max_curvature = std::max(run.max_curvature, std::abs(turn) / (speed * kDt));
    run.max_lateral_acceleration = std::max(run.max_lateral_acceleration, speed * std::abs(turn) / kDt);
    if (path.done(t)) run.end_time = t;
  }
  return run;
}

TEST(TrajectoryFollow, LimitsComeFromPerformanceAndAxles) {
  const FollowLimits limits = car_limits();
  EXPECT_DOUBLE_EQ(limits.max_speed, 70);
  EXPECT_DOUBLE_EQ(limits.max_acceleration, 10);
  EXPECT_NEAR(limits.max_curvature, std::tan(0.5) / 3.0, 1e-12);
  EXPECT_DOUBLE_EQ(limits.max_lateral_acceleration, kFollowMaxLateralAcceleration);
  const FollowLimits none = follow_limits(Entity{});  // a pedestrian: no performance, no axles
  EXPECT_TRUE(std::isinf(none.max_acceleration));
  EXPECT_TRUE(std::isinf(none.max_curvature));
  EXPECT_TRUE(std::isinf(none.max_lateral_acceleration));  // none assumed without a steering limit
}

// esmini's law for a timed Polyline (trajectory_follow.hpp), checked against esmini 3.6's own
// positions: bicycle_fall_over.xosc (10 m/s, vertices 0/20/25/30/30 m at 0/2/2.5/3.5/4 s:
// 127.187 m at 2.75 s, 128.750 at 3.0, 130 from 3.5) and that file with vertices 0/10/30/35 m
// at 0/2/4/6 s from rest (102.5 m at 1 s, 133.75 at 4.5, 135 at 5.0: stopped early).
TEST(TrajectoryFollow, VertexScheduleReachesEachVertexOnTime) {
  const auto bicycle = vertex_schedule({{0, 0}, {2, 20}, {2.5, 25}, {3.5, 30}, {4, 30}}, 10.0);
  EXPECT_NEAR(scheduled_distance(bicycle, 1.0), 10.0, 1e-9);
  EXPECT_NEAR(scheduled_distance(bicycle, 2.75), 27.1875, 1e-9);
  EXPECT_NEAR(scheduled_distance(bicycle, 3.0), 28.75, 1e-9);
  EXPECT_NEAR(scheduled_distance(bicycle, 3.5), 30.0, 1e-9);
  EXPECT_NEAR(scheduled_distance(bicycle, 9.0), 30.0, 1e-9);
  const auto from_rest = vertex_schedule({{0, 0}, {2, 10}, {4, 30}, {6, 35}}, 0.0);
  EXPECT_NEAR(scheduled_distance(from_rest, -1.0), 0.0, 1e-9);
  EXPECT_NEAR(scheduled_distance(from_rest, 1.0), 2.5, 1e-9);   // 5 m/s^2 to 10 m/s at 2 s
  EXPECT_NEAR(scheduled_distance(from_rest, 2.0), 10.0, 1e-9);  // each vertex on time
  EXPECT_NEAR(scheduled_distance(from_rest, 4.0), 30.0, 1e-9);
  // 5 m in 2 s from 10 m/s would need a reverse: 10 m/s^2 down to a stop on the vertex at 5 s.
  EXPECT_NEAR(scheduled_distance(from_rest, 4.5), 33.75, 1e-9);
  EXPECT_NEAR(scheduled_distance(from_rest, 5.5), 35.0, 1e-9);
}

TEST(TrajectoryFollow, TimedPolylineFollowsTheVertexSchedule) {
  // bicycle_fall_over.xosc's Cyclist: limits 10 m/s^2 (the schedule brakes at exactly that).
  std::vector<PathPoint> points;
  for (const auto& [x, due] : std::vector<std::pair<double, double>>{{0, 0}, {20, 2}, {25, 2.5}, {30, 3.5}, {30, 4}})
    points.push_back({x, 0, 0.0, due, std::nullopt});
  PathMotion path = make_path(points, true);
  ASSERT_EQ(path.timetable.size(), 5U);  // the repeated last vertex is kept as a time
  opendrive::Pose2 pose{0, 0, 0};
  double speed = 10;
  start_following(path, pose, speed, car_limits(), true);
  double worst = 0, end_time = -1;
  for (int k = 1; k <= 100 && end_time < 0; ++k) {
    const double t = k * kDt;
    follow_step(path, pose, speed, std::nullopt, t, kDt);
    worst = std::max(worst, std::abs(pose.x - scheduled_distance(path.follower->schedule, t)));
    if (path.done(t)) end_time = t;
  }
  EXPECT_LT(worst, 1e-6);
  EXPECT_NEAR(end_time, 4.0, 1e-9);  // on the spot from 3.5 s, done at the last time
  EXPECT_NEAR(speed, 0.0, 1e-9);
}

// No steering limit (a pedestrian): on its path it keeps to it exactly, corners included, at
// the speed it is given (no lateral acceleration limit slows it).
TEST(TrajectoryFollow, WithoutSteeringLimitThePathIsKeptExactly) {
  std::vector<PathPoint> points{{0, 0, 0, std::nullopt, std::nullopt},
                                {5, 0, 0, std::nullopt, std::nullopt},
                                {5, 5, 0, std::nullopt, std::nullopt},
                                {0, 5, 0, std::nullopt, std::nullopt}};
  PathMotion path = make_path(points, false);
  const FollowRun run = follow(path, {0, 0, 0}, 1.5, follow_limits(Entity{}), 20);
  EXPECT_LT(run.max_off, 1e-9);
  EXPECT_NEAR(run.end_time, std::ceil((15.0 - kFollowEnd) / 1.5 / kDt) * kDt, 1e-9);  // never slowed
  // Beside the path it steers onto it first, then keeps to it.
  PathMotion beside = make_path(points, false);
  const FollowRun steered = follow(beside, {0, 0.5, 0}, 1.5, follow_limits(Entity{}), 20);
  EXPECT_GT(steered.max_off, 0.1);
  EXPECT_GT(steered.end_time, 0.0);
}

TEST(TrajectoryFollow, StraightTimedPathIsFollowedClosely) {
  PathMotion path = timed_path({{0, 0}, {200, 0}}, 10.0);
  const FollowRun run = follow(path, {0, 0, 0}, 10.0, car_limits(), 30);
  EXPECT_LT(run.max_off, 1e-9);
  EXPECT_LT(run.max_schedule_lag, 0.01);
  EXPECT_NEAR(run.end_time, 20.0, 0.05);  // 200 m at 10 m/s, less the last 0.1 m
}

TEST(TrajectoryFollow, StartingBesideThePathItSteersOntoIt) {
  PathMotion path = timed_path({{0, 0}, {200, 0}}, 10.0);
  opendrive::Pose2 pose{0, 1.0, 0};
  double speed = 10;
  start_following(path, pose, speed, car_limits());
  for (int k = 1; k <= 100; ++k) follow_step(path, pose, speed, std::nullopt, k * kDt, kDt);
  EXPECT_LT(std::abs(pose.y), 0.02);  // after 5 s (50 m): on the path
  EXPECT_LT(std::abs(std::remainder(pose.heading, 2 * M_PI)), 0.01);
}

TEST(TrajectoryFollow, RightAngleCornerIsRoundedAndLate) {
  // 50 m east, then 50 m north, due at 10 m/s.
  PathMotion path = timed_path({{0, 0}, {50, 0}, {50, 50}}, 10.0);
  const FollowLimits limits = car_limits();
  const FollowRun run = follow(path, {0, 0, 0}, 10.0, limits, 30);
  // The corner is cut: the car turns no tighter than its 5.5 m radius (maxSteering 0.5 rad,
  // wheelbase 3 m), after slowing to sqrt(4 m/s^2 * 3 m / (pi / 2)) = 2.8 m/s.
  EXPECT_GT(run.max_off, 0.5);
  EXPECT_LT(run.max_off, 4.0);
  EXPECT_GT(run.end_time, 10.0 - 0.01 / 10.0);  // done when it gets there, never early
  EXPECT_GT(run.max_schedule_lag, 0.0);
  EXPECT_LE(run.max_curvature, limits.max_curvature + 1e-9);
  EXPECT_LE(run.max_lateral_acceleration, kFollowMaxLateralAcceleration + 1e-9);
  EXPECT_LE(run.max_acceleration, 10.0 + 1e-9);
  EXPECT_LE(run.max_deceleration, 10.0 + 1e-9);
}

TEST(TrajectoryFollow, AccelerationLimitMakesItLate) {
  // From rest on a path due at 20 m/s: at most 2 m/s^2, so it trails the schedule (and
  // catches up only later, faster than the schedule, within maxSpeed).
  PathMotion path = timed_path({{0, 0}, {400, 0}}, 20.0);
  FollowLimits limits = car_limits();
  limits.max_acceleration = 2.0;
  const FollowRun run = follow(path, {0, 0, 0}, 0.0, limits, 60);
  EXPECT_LE(run.max_acceleration, 2.0 + 1e-9);
  EXPECT_GT(run.max_schedule_lag, 50.0);  // 10 s to reach 20 m/s: 100 m short then
  EXPECT_GT(run.end_time, 20.0);
  EXPECT_LT(run.max_off, 1e-9);
}

TEST(TrajectoryFollow, UntimedPathAtTheStoryboardsSpeed) {
  std::vector<PathPoint> points{{0, 0, 0, std::nullopt, std::nullopt}, {100, 0, 0, std::nullopt, std::nullopt}};
  PathMotion path = make_path(points, false);
  opendrive::Pose2 pose{0, 0, 0};
  double speed = 5;
  start_following(path, pose, speed, car_limits());
  for (int k = 1; k <= 20; ++k) follow_step(path, pose, speed, std::nullopt, k * kDt, kDt);
  EXPECT_NEAR(pose.x, 5.0, 1e-9);
  speed = 15;  // a step SpeedAction: reached under the 10 m/s^2 limit, in 1 s
  for (int k = 21; k <= 30; ++k) follow_step(path, pose, speed, std::nullopt, k * kDt, kDt);
  EXPECT_NEAR(speed, 10.0, 1e-9);
  for (int k = 31; k <= 40; ++k) follow_step(path, pose, speed, std::nullopt, k * kDt, kDt);
  EXPECT_NEAR(speed, 15.0, 1e-9);
  follow_step(path, pose, speed, 12.0, 41 * kDt, kDt);  // a running speed profile, 10 m/s^2 down
  EXPECT_NEAR(speed, 14.5, 1e-9);
}

// Placed facing away from its path (esmini's pedestrian.xosc: a relative Orientation h=0 on a
// left-hand sidewalk, the path going the other way): the goal lies straight behind, where
// 2 sin(alpha) / L is 0. It walked away from the path for ever; now it turns round and
// follows it to the end.
TEST(TrajectoryFollow, FacingAwayFromThePathItTurnsRound) {
  std::vector<PathPoint> points{{0, 0, 0, std::nullopt, std::nullopt}, {-10, 0, 0, std::nullopt, std::nullopt}};
  PathMotion path = make_path(points, false);
  const FollowLimits pedestrian = follow_limits(Entity{});
  const FollowRun run = follow(path, {0, 0, 0}, 1.5, pedestrian, 30);
  EXPECT_GT(run.end_time, 0.0) << "never reached the path's end";
  EXPECT_LT(run.end_time, 15.0);  // 10 m at 1.5 m/s, plus the turn
  EXPECT_LT(run.max_off, 0.1);    // no axles: it turns round on the spot
  // A car turns on a circle (a U-turn, its lookahead the diameter), then follows the path.
  const FollowRun car = follow(path, {0, 0, 0}, 5.0, car_limits(), 30);
  EXPECT_GT(car.end_time, 0.0) << "the car never reached the path's end";
  EXPECT_GT(car.max_off, 3.0);
  EXPECT_LT(car.max_off, 15.0);
}

}  // namespace
}  // namespace orch::openscenario

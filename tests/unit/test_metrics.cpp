// Every metric family on hand-built values; the expected numbers are worked out by hand in
// the comments (docs/evaluation.md has the formulas).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "metrics/actor_metrics.hpp"
#include "sim/box.hpp"
#include "metrics/following.hpp"
#include "metrics/kinematics.hpp"
#include "metrics/lane_keeping.hpp"
#include "metrics/pet.hpp"

namespace orch::metrics {
namespace {

Polyline straight_x(double from, double to) { return Polyline({Vec2(from, 0), Vec2(to, 0)}); }

TEST(FollowingMeasures, ClosingIn) {
  // gap 20 m, 20 m/s behind 10 m/s: rel 10, ttc 20/10 = 2, thw 20/20 = 1, drac 10^2/(2*20) = 2.5
  const Following f = following_measures("1", 20, 20, 10);
  EXPECT_DOUBLE_EQ(f.gap, 20);
  EXPECT_DOUBLE_EQ(f.rel_speed, 10);
  EXPECT_DOUBLE_EQ(*f.ttc, 2);
  EXPECT_DOUBLE_EQ(*f.thw, 1);
  EXPECT_DOUBLE_EQ(*f.drac, 2.5);
}

TEST(FollowingMeasures, OpeningHasNoTtcNorDrac) {
  const Following f = following_measures("1", 20, 10, 20);
  EXPECT_DOUBLE_EQ(f.rel_speed, -10);
  EXPECT_FALSE(f.ttc);
  EXPECT_FALSE(f.drac);
  EXPECT_DOUBLE_EQ(*f.thw, 2);  // 20 m / 10 m/s
}

TEST(FollowingMeasures, StandingHasNoHeadwayAndOverlapIsGapZero) {
  const Following f = following_measures("1", -0.5, 0, 0);
  EXPECT_DOUBLE_EQ(f.gap, 0);
  EXPECT_FALSE(f.thw);
  EXPECT_FALSE(f.ttc);
}

TEST(FindNeighbours, LeaderAndFollowerOnTheOwnPathOnly) {
  const Polyline route = straight_x(0, 1000);
  const Body self{"0", {100, 0}, 0, 20, 4, 2};
  const std::vector<Body> others{
      {"1", {130, 0.5}, 0, 15, 5, 2},     // ahead, overlapping sideways (0.5 < 2)
      {"bg.1", {120, 3.5}, 0, 5, 4, 2},   // the next lane: 3.5 >= 2, not on the path
      {"2", {160, 0}, 0, 0, 4, 2},        // ahead but farther
      {"3", {80, -0.3}, 0, 25, 4, 2},     // behind
      {"0", {100, 0}, 0, 20, 4, 2},       // itself
  };
  const Neighbours n = find_neighbours(route, self, others);
  ASSERT_TRUE(n.leader);
  EXPECT_EQ(n.leader->other, "1");
  // ds 30, gap 30 - (4 + 5)/2 = 25.5; rel 20 - 15 = 5; ttc 5.1; thw 25.5/20 = 1.275; drac 25/51
  EXPECT_NEAR(n.leader->gap, 25.5, 1e-9);
  EXPECT_NEAR(n.leader->rel_speed, 5, 1e-9);
  EXPECT_NEAR(*n.leader->ttc, 5.1, 1e-9);
  EXPECT_NEAR(*n.leader->thw, 1.275, 1e-9);
  EXPECT_NEAR(*n.leader->drac, 25.0 / 51.0, 1e-9);
  ASSERT_TRUE(n.follower);
  EXPECT_EQ(n.follower->other, "3");
  // gap 20 - 4 = 16; the follower closes at 25 - 20 = 5: ttc 3.2, its headway 16/25 = 0.64
  EXPECT_NEAR(n.follower->gap, 16, 1e-9);
  EXPECT_NEAR(*n.follower->ttc, 3.2, 1e-9);
  EXPECT_NEAR(*n.follower->thw, 0.64, 1e-9);
}

TEST(FindNeighbours, AgainstTheRouteAheadIsTowardsItsStart) {
  // Driving the route backwards (overtaking in the oncoming lane): ahead = smaller x.
  const Polyline route = straight_x(0, 1000);
  const Body self{"0", {500, 0}, std::numbers::pi, 10, 4, 2};
  const std::vector<Body> others{{"1", {450, 0}, std::numbers::pi, 5, 4, 2}, {"2", {540, 0}, 0, 10, 4, 2}};
  const Neighbours n = find_neighbours(route, self, others);
  ASSERT_TRUE(n.leader);
  EXPECT_EQ(n.leader->other, "1");
  EXPECT_NEAR(n.leader->gap, 46, 1e-9);
  EXPECT_NEAR(n.leader->rel_speed, 5, 1e-9);
  ASSERT_TRUE(n.follower);
  EXPECT_EQ(n.follower->other, "2");
  // "2" drives the other way, away from us: its speed along our direction is -10, it opens
  EXPECT_NEAR(n.follower->rel_speed, -20, 1e-9);
  EXPECT_FALSE(n.follower->ttc);
}

TEST(FindNeighbours, AcrossACornerAlongTheRoute) {
  // An L-shaped route: 100 m east, then 100 m north. Leader 20 m after the corner.
  const Polyline route({Vec2(0, 0), Vec2(100, 0), Vec2(100, 100)});
  const Body self{"0", {90, 0}, 0, 10, 4, 2};
  const std::vector<Body> others{{"1", {100, 20}, std::numbers::pi / 2, 10, 4, 2}};
  const Neighbours n = find_neighbours(route, self, others);
  ASSERT_TRUE(n.leader);
  EXPECT_NEAR(n.leader->gap, 30 - 4, 1e-9);  // 10 m to the corner + 20 m, minus two half-lengths
  EXPECT_NEAR(n.leader->rel_speed, 0, 1e-9);
}

TEST(Kinematics, AccelJerkYawRateLateralAccel) {
  const KinematicSample s0{0.0, 10, 0}, s1{0.1, 11, 0.01}, s2{0.2, 11.5, 0.01};
  const Kinematics k0 = kinematics_step(nullptr, nullptr, s0);
  EXPECT_FALSE(k0.accel);
  const Kinematics k1 = kinematics_step(&s0, &k0, s1);
  EXPECT_NEAR(*k1.accel, 10, 1e-9);      // (11 - 10) / 0.1
  EXPECT_NEAR(*k1.yaw_rate, 0.1, 1e-9);  // 0.01 rad / 0.1 s
  EXPECT_NEAR(*k1.lat_accel, 1.1, 1e-9); // 11 * 0.1
  EXPECT_FALSE(k1.jerk);
  const Kinematics k2 = kinematics_step(&s1, &k1, s2);
  EXPECT_NEAR(*k2.accel, 5, 1e-9);       // (11.5 - 11) / 0.1
  EXPECT_NEAR(*k2.jerk, -50, 1e-9);      // (5 - 10) / 0.1
  EXPECT_NEAR(*k2.yaw_rate, 0, 1e-12);
}

TEST(Kinematics, YawRateWrapsAroundPi) {
  const KinematicSample a{0, 5, std::numbers::pi - 0.01}, b{0.1, 5, -std::numbers::pi + 0.01};
  EXPECT_NEAR(*kinematics_step(&a, nullptr, b).yaw_rate, 0.2, 1e-9);  // +0.02 rad over 0.1 s
}

TEST(Kinematics, StandstillAccumulatesAndResets) {
  const KinematicSample s0{0.9, 0.5, 0}, s1{1.0, 0.05, 0}, s2{1.1, 0.0, 0}, s3{1.2, 0.3, 0};
  const Kinematics k0 = kinematics_step(nullptr, nullptr, s0);
  EXPECT_DOUBLE_EQ(k0.standstill, 0);
  const Kinematics k1 = kinematics_step(&s0, &k0, s1);
  EXPECT_NEAR(k1.standstill, 0.1, 1e-9);
  const Kinematics k2 = kinematics_step(&s1, &k1, s2);
  EXPECT_NEAR(k2.standstill, 0.2, 1e-9);
  EXPECT_DOUBLE_EQ(kinematics_step(&s2, &k2, s3).standstill, 0);
}

TEST(LaneKeeping, BodyBeyondTheMarking) {
  // lateral 1.0, straight: 1 + 2/2 - 3.5/2 = 0.25 m beyond
  EXPECT_NEAR(lane_departure(1.0, 0, 4, 2, 3.5), 0.25, 1e-12);
  EXPECT_NEAR(lane_departure(-1.0, 0, 4, 2, 3.5), 0.25, 1e-12);
  EXPECT_DOUBLE_EQ(lane_departure(0, 0, 4, 2, 3.5), 0);
  // crosswise: the half-length 2 counts: 0 + 2 - 1.75 = 0.25
  EXPECT_NEAR(lane_departure(0, std::numbers::pi / 2, 4, 2, 3.5), 0.25, 1e-12);
  // turned 0.1 rad at 0.5 m: 0.5 + cos(0.1) + 2 sin(0.1) - 1.75 = -0.0553: inside
  EXPECT_DOUBLE_EQ(lane_departure(0.5, 0.1, 4, 2, 3.5), 0);
  // turned 0.1 rad at 0.6 m: 0.6 + 0.995004 + 0.199667 - 1.75 = 0.044671
  EXPECT_NEAR(lane_departure(0.6, 0.1, 4, 2, 3.5), 0.6 + std::cos(0.1) + 2 * std::sin(0.1) - 1.75, 1e-12);
}

TEST(BoxDistance, AxisAlignedDiagonalRotatedTouching) {
  const sim::Box a{{0, 0}, 0, 4, 2};
  EXPECT_NEAR(sim::box_distance(a, {{10, 0}, 0, 4, 2}), 6, 1e-9);                // 10 - 2 - 2
  EXPECT_NEAR(sim::box_distance(a, {{10, 5}, 0, 4, 2}), std::sqrt(45.0), 1e-9);  // corners (2,1)-(8,4)
  EXPECT_NEAR(sim::box_distance(a, {{5, 0}, std::numbers::pi / 2, 4, 2}), 2, 1e-9);  // x from 4: 4 - 2
  EXPECT_DOUBLE_EQ(sim::box_distance(a, {{3.9, 0}, 0, 4, 2}), 0);
}

std::vector<TrajectorySample> drive(Vec2 from, Vec2 velocity, double t0, double t1, double heading) {
  std::vector<TrajectorySample> out;
  for (int i = 0; t0 + i * 0.1 <= t1 + 1e-9; ++i) {
    const double t = t0 + i * 0.1;
    append_sample(out, {t, sim::Box{from + velocity * (t - t0), heading, 4, 2}});
  }
  return out;
}

TEST(PostEncroachmentTime, CrossingPathsOneAfterTheOther) {
  // a eastwards through (0,0) at 10 m/s: covers it while |x| <= 2, x = -50.05 + 10 t:
  // t in [4.805, 5.205], last sample 5.2. b northwards from t = 8: y = -50.05 + 10 (t - 8),
  // covers it for t in [12.805, 13.205], first sample 12.9. PET = 12.9 - 5.2 = 7.7.
  const auto a = drive({-50.05, 0}, {10, 0}, 0, 10, 0);
  const auto b = drive({0, -50.05}, {0, 10}, 8, 18, std::numbers::pi / 2);
  const auto pet = post_encroachment_time(a, b);
  ASSERT_TRUE(pet);
  EXPECT_NEAR(pet->pet, 7.7, 1e-9);
  EXPECT_NEAR(pet->time, 12.9, 1e-9);
  EXPECT_NEAR(pet->point.norm(), 0, 1e-9);
  const auto reverse = post_encroachment_time(b, a);
  ASSERT_TRUE(reverse);
  EXPECT_NEAR(reverse->pet, 7.7, 1e-9);
}

TEST(PostEncroachmentTime, SimultaneousIsZeroAndFollowingHasNone) {
  const auto a = drive({-50.05, 0}, {10, 0}, 0, 10, 0);
  const auto b = drive({0, -50.05}, {0, 10}, 0, 10, std::numbers::pi / 2);
  EXPECT_DOUBLE_EQ(post_encroachment_time(a, b)->pet, 0);
  const auto follower = drive({-80.05, 0}, {10, 0}, 0, 10, 0);
  EXPECT_FALSE(post_encroachment_time(a, follower));
}

TEST(PostEncroachmentTime, AStopIsKeptAsItsFirstAndLastSample) {
  std::vector<TrajectorySample> t;
  for (int i = 0; i < 100; ++i) append_sample(t, {i * 0.1, sim::Box{{5, 5}, 0, 4, 2}});
  ASSERT_EQ(t.size(), 2u);
  EXPECT_DOUBLE_EQ(t.front().time, 0);
  EXPECT_NEAR(t.back().time, 9.9, 1e-9);
}

// Hand-built snapshots, one per 0.1 s step: the ego eastwards through (0,0) at 10 m/s
// (covers it for t in [4.805, 5.205], last sample 5.2), a background vehicle northwards
// through it 3 s later (y = -50.05 + 10 (t - 3): covers it for t in [7.805, 8.205], first
// sample 7.9): PET = 7.9 - 5.2 = 2.7, against the background vehicle.
TEST(TrajectoryBook, PetAgainstABackgroundVehicle) {
  TrajectoryBook book;
  for (int i = 0; i <= 150; ++i) {
    const double t = i * 0.1;
    std::vector<TrajectoryBook::Seen> seen{{"0", {{-50.05 + 10 * t, 0}, 0, 4, 2}}};
    if (t >= 3 - 1e-9) seen.push_back({"bg.7", {{0, -50.05 + 10 * (t - 3)}, std::numbers::pi / 2, 4, 2}});
    // A scripted car behind the ego on its path: following, no conflict point.
    seen.push_back({"1", {{-80.05 + 10 * t, 0}, 0, 4, 2}});
    book.record(t, seen);
  }
  const auto pet = book.min_pet("0");
  ASSERT_TRUE(pet);
  EXPECT_EQ(pet->partner, "bg.7");
  EXPECT_NEAR(pet->pet.pet, 2.7, 1e-9);
  EXPECT_NEAR(pet->pet.time, 7.9, 1e-9);
  EXPECT_EQ(book.bodies(), 3u);
  EXPECT_FALSE(book.min_pet("nobody"));
}

// A background vehicle seen driving north towards the ego's road until t = 4.5 (y = -5.05),
// then out of sight, and seen again from t = 9 on the ego's path at (0, 0.5), driving east
// behind the ego. What it did in between nobody knows: joined, its two pieces would cross
// the ego's path at (0, 0), which it covers from t = 9 (a PET of 9 - 5.2 = 3.8); kept
// apart, its path never crosses the ego's.
TEST(TrajectoryBook, NoPathAcrossTheTimeABodyWasOutOfSight) {
  TrajectoryBook book;
  for (int i = 0; i <= 150; ++i) {
    const double t = i * 0.1;
    std::vector<TrajectoryBook::Seen> seen{{"0", {{-50.05 + 10 * t, 0}, 0, 4, 2}}};
    if (t <= 4.5 + 1e-9) seen.push_back({"bg.9", {{0, -50.05 + 10 * t}, std::numbers::pi / 2, 4, 2}});
    if (t >= 9 - 1e-9) seen.push_back({"bg.9", {{10 * (t - 9), 0.5}, 0, 4, 2}});
    book.record(t, seen);
  }
  EXPECT_FALSE(book.min_pet("0"));
  EXPECT_FALSE(book.min_pet("bg.9"));
}

TEST(ActorSummary, ExtremesWithTimeAndPartner) {
  ActorSummary s;
  ActorMetrics m;
  m.time = 1;
  m.speed = 20;
  m.leader = following_measures("1", 20, 20, 10);  // ttc 2
  m.kinematics.accel = -3;
  m.lane_departure = 0.1;
  s.add(m, 0.05);
  m.time = 2;
  m.leader = following_measures("bg.7", 10, 20, 10);  // ttc 1
  m.kinematics.accel = -1;
  m.kinematics.standstill = 0.5;
  m.lane_departure = 0;
  s.add(m, 0.05);
  const auto& min_ttc = s.extreme("min_ttc");
  ASSERT_TRUE(min_ttc);
  EXPECT_DOUBLE_EQ(min_ttc->value, 1);
  EXPECT_DOUBLE_EQ(min_ttc->time, 2);
  EXPECT_EQ(min_ttc->partner, "bg.7");
  const auto& max_decel = s.extreme("max_decel");
  ASSERT_TRUE(max_decel);
  EXPECT_DOUBLE_EQ(max_decel->value, 3);
  EXPECT_DOUBLE_EQ(max_decel->time, 1);
  EXPECT_DOUBLE_EQ(s.seconds("lane_departure_time"), 0.05);
  EXPECT_DOUBLE_EQ(s.seconds("standstill_time"), 0.05);
  EXPECT_FALSE(s.extreme("min_follower_ttc")) << "no follower in any step";
  EXPECT_THROW((void)s.extreme("min_ttcc"), std::invalid_argument);
}

// follower_drac (docs/evaluation.md): the deceleration the follower needs not to hit the actor,
// rel_speed^2 / (2 gap) while it closes in; its summary max_follower_drac is the largest value.
TEST(FollowerDrac, TheFollowersNeededDecelerationAndItsWorstOverTheRun) {
  const Polyline route = straight_x(0, 1000);
  ActorSummary s;
  ActorMetrics m;
  // Step 1: the actor (4 m long, 10 m/s) at x 100, a background vehicle (4 m, 16 m/s) at x 80:
  // gap 20 - (4 + 4)/2 = 16, closing at 16 - 10 = 6: 6^2 / (2 * 16) = 1.125 m/s^2.
  m.time = 1;
  Neighbours n = find_neighbours(route, {"0", {100, 0}, 0, 10, 4, 2}, {{"bg.3", {80, 0}, 0, 16, 4, 2}});
  m.follower = n.follower;
  EXPECT_DOUBLE_EQ(*metric_value(m, "follower_drac"), 1.125);
  EXPECT_EQ(metric_partner(m, "follower_drac"), "bg.3");
  s.add(m, 0.1);
  // Step 2: another follower, actor "2" (5 m, 20 m/s) at x 92.5: gap 7.5 - 4.5 = 3, closing at
  // 10: 100 / 6 = 16.667 m/s^2, the worst.
  m.time = 2;
  n = find_neighbours(route, {"0", {100, 0}, 0, 10, 4, 2}, {{"2", {92.5, 0}, 0, 20, 5, 2}});
  m.follower = n.follower;
  EXPECT_NEAR(*metric_value(m, "follower_drac"), 100.0 / 6.0, 1e-9);
  s.add(m, 0.1);
  // Step 3: the follower falls back (8 m/s behind 10 m/s): no DRAC.
  m.time = 3;
  n = find_neighbours(route, {"0", {100, 0}, 0, 10, 4, 2}, {{"bg.3", {80, 0}, 0, 8, 4, 2}});
  m.follower = n.follower;
  EXPECT_FALSE(metric_value(m, "follower_drac"));
  s.add(m, 0.1);
  const auto& worst = s.extreme("max_follower_drac");
  ASSERT_TRUE(worst);
  EXPECT_NEAR(worst->value, 100.0 / 6.0, 1e-9);
  EXPECT_DOUBLE_EQ(worst->time, 2);
  EXPECT_EQ(worst->partner, "2");
  // The leader's DRAC is another metric: none here, no leader.
  EXPECT_FALSE(s.extreme("max_drac"));
}

TEST(MetricNames, EveryNameHasAValueOrNone) {
  ActorMetrics m;
  m.speed = 3;
  m.leader = following_measures("1", 20, 20, 10);
  m.kinematics.accel = -2;
  EXPECT_DOUBLE_EQ(*metric_value(m, "decel"), 2);
  EXPECT_DOUBLE_EQ(*metric_value(m, "ttc"), 2);
  EXPECT_EQ(metric_partner(m, "ttc"), "1");
  EXPECT_FALSE(metric_value(m, "follower_ttc"));
  EXPECT_DOUBLE_EQ(*metric_value(m, "speed"), 3);
  for (auto name : metric_names()) (void)metric_value(m, name);  // no name throws
}

}  // namespace
}  // namespace orch::metrics

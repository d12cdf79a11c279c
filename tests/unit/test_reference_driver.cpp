// The R157 reference driver on hand-built views: the numbers are computed by hand here.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "reference_driver/r157_driver.hpp"
#include "reference_driver/r157_parameters.hpp"
#include "reference_driver_views.hpp"

using namespace orch::reference_driver;
using orch::reference_driver::test::car;
using orch::reference_driver::test::straight_road;

namespace {

constexpr double kKmh60 = 60.0 / 3.6;

}  // namespace

TEST(R157Parameters, TimeGapTableOfParagraph5233) {
  const R157Parameters p;
  EXPECT_DOUBLE_EQ(p.time_gap(60 / 3.6), 1.6);
  EXPECT_DOUBLE_EQ(p.time_gap(7.2 / 3.6), 1.0);
  EXPECT_NEAR(p.time_gap(45 / 3.6), 1.45, 1e-12);  // halfway between 40 (1.4) and 50 (1.5)
  EXPECT_DOUBLE_EQ(p.time_gap(130 / 3.6), 2.0);
  // 60 km/h: 16.667 m/s * 1.6 s = 26.67 m; 45 km/h: 12.5 m/s * 1.45 s = 18.125 m.
  EXPECT_NEAR(p.min_following_distance(kKmh60), 26.6667, 1e-3);
  EXPECT_NEAR(p.min_following_distance(12.5), 18.125, 1e-9);
  // 5 km/h: 1.39 m/s * 1.0 s = 1.39 m, but never below 2 m.
  EXPECT_DOUBLE_EQ(p.min_following_distance(5 / 3.6), 2.0);
}

TEST(R157Parameters, OverridesCheckNamesAndValues) {
  R157Parameters p;
  apply_overrides(p, {{"brake_reaction_time", 1.0}, {"max_deceleration", 6.0}});
  EXPECT_DOUBLE_EQ(p.brake_reaction_time, 1.0);
  EXPECT_DOUBLE_EQ(p.max_deceleration, 6.0);
  try {
    apply_overrides(p, {{"brake_reaction_tme", 1.0}});
    FAIL() << "an unknown key must be an error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("did you mean \"brake_reaction_time\""), std::string::npos) << e.what();
  }
  EXPECT_THROW(apply_overrides(p, {{"brake_jerk", -1.0}}), std::invalid_argument);
}

// Following a leader at 60 km/h from 60 m, the driver closes up to the minimum following
// distance of the time-gap table (26.67 m) and stays there.
TEST(R157Driver, KeepsTheMinimumFollowingDistance) {
  R157Driver driver;
  const double dt = 0.05;
  double ego_s = 0, ego_v = kKmh60, lead_s = 60 + 4.5;  // gap 60 m (centres 64.5 m apart)
  for (int i = 0; i < 2400; ++i) {  // 120 s
    DriverView v = straight_road(i * dt, dt, ego_s, ego_v, 80 / 3.6);
    v.objects.push_back(car("lead", lead_s, 0.0, kKmh60));
    const Decision d = driver.step(v);
    EXPECT_EQ(d.phase, Phase::Drive) << "normal following is no risk, t=" << v.time;
    ego_s += (ego_v + d.speed) / 2 * dt;
    ego_v = d.speed;
    lead_s += kKmh60 * dt;
  }
  EXPECT_NEAR(lead_s - 4.5 - ego_s, 26.667, 0.3);
  EXPECT_NEAR(ego_v, kKmh60, 0.05);
}

// A car in the left lane drifts towards the ego's lane at 1 m/s from t = 1 s: it is 0.375 m
// out of its lane centre at t = 1.375 s, first seen so in the snapshot of t = 1.40 s (the
// risk perception point). The driver decides at 1.40 + 0.4 = 1.80 s and the brake acts at
// 1.40 + 0.4 + 0.75 = 2.55 s; the first braking step loses j dt^2 / 2 = 12.65 * 0.05^2 / 2.
TEST(R157Driver, CutInReactionStartsAfterPerceptionAndReactionTime) {
  R157Driver driver;
  const double dt = 0.05;
  double ego_s = 0, ego_v = kKmh60;
  double other_s = 20, other_d = 3.5;
  const double other_v = 30 / 3.6;  // slower: critical once it is in the ego's lane
  std::optional<double> braking_from, react_from;
  double speed_at_brake = 0, speed_after_first_brake_step = 0;
  for (int i = 0; i <= 80; ++i) {
    const double t = i * dt;
    other_d = t <= 1.0 ? 3.5 : std::max(0.0, 3.5 - 1.0 * (t - 1.0));
    DriverView v = straight_road(t, dt, ego_s, ego_v, kKmh60);
    v.objects.push_back(car("cutter", other_s, other_d, other_v));
    const Decision d = driver.step(v);
    if (t < 1.40 - 1e-9) {
      EXPECT_EQ(d.phase, Phase::Drive) << t;
    }
    if (std::abs(t - 1.40) < 1e-9) {
      EXPECT_EQ(d.phase, Phase::Perceive);
      EXPECT_NEAR(*driver.risk_perceived_at(), 1.40, 1e-9);
      EXPECT_EQ(driver.risk(), "cut-in");
    }
    if (d.phase == Phase::React && !react_from) react_from = t;
    if (d.phase == Phase::Brake && !braking_from) {
      braking_from = t;
      speed_at_brake = ego_v;
      speed_after_first_brake_step = d.speed;
    }
    if (!braking_from) {
      EXPECT_NEAR(d.speed, kKmh60, 1e-9) << "no braking before the brake acts, t=" << t;
    }
    ego_s += (ego_v + d.speed) / 2 * dt;
    ego_v = d.speed;
    other_s += other_v * dt;
  }
  ASSERT_TRUE(react_from && braking_from);
  EXPECT_NEAR(*react_from, 1.40 + 0.4, 1e-9);
  EXPECT_NEAR(*braking_from, 1.40 + 0.4 + 0.75, 1e-9);
  EXPECT_NEAR(speed_at_brake - speed_after_first_brake_step, 12.65 * dt * dt / 2, 1e-9);
}

// An obstacle appears 45 m ahead of the ego at 60 km/h (comfortable braking, 3 m/s^2, would
// need 16.67^2 / (2 * 43) = 3.23 m/s^2): the risk is perceived at once. The ego travels
// 1.15 s at 60 km/h (19.17 m), then brakes with 12.65 m/s^3 up to 0.774 G = 7.593 m/s^2,
// reached after t_r = 7.593 / 12.65 = 0.600 s: v0 t_r - j t_r^3 / 6 = 9.548 m on the ramp,
// leaving v1 = v0 - j t_r^2 / 2 = 14.388 m/s, then v1^2 / (2 a) = 13.632 m: 42.35 m in all.
TEST(R157Driver, StoppingDistanceFrom60KmhAtTheModelsProfile) {
  R157Driver driver;
  const double dt = 0.001;
  const double a_max = 0.774 * 9.81;
  const double j = 12.65;
  const double t_r = a_max / j;
  const double v1 = kKmh60 - j * t_r * t_r / 2;
  const double expected = kKmh60 * (0.4 + 0.75) + (kKmh60 * t_r - j * t_r * t_r * t_r / 6) + v1 * v1 / (2 * a_max);
  EXPECT_NEAR(expected, 42.35, 0.01);

  double ego_s = 0, ego_v = kKmh60;
  const double obstacle_s = 4.5 / 2 + 45 + 1.0 / 2;  // its rear 45 m ahead of the ego's front
  int steps = 0;
  while (ego_v > 0 && steps < 20000) {
    DriverView v = straight_road(steps * dt, dt, ego_s, ego_v, kKmh60);
    PerceivedObject box = car("box", obstacle_s, 0.0, 0.0);
    box.kind = ObjectKind::Obstacle;
    box.length = 1.0;
    v.objects.push_back(box);
    const Decision d = driver.step(v);
    if (steps == 0) {
      EXPECT_EQ(driver.risk(), "obstacle in the path");
    }
    ego_s += (ego_v + d.speed) / 2 * dt;
    ego_v = d.speed;
    ++steps;
  }
  EXPECT_EQ(ego_v, 0.0);
  EXPECT_NEAR(ego_s, expected, 0.05);
}

// A leader braking at 6 m/s^2 (harder than 5) is a risk; at 4 m/s^2 it is not.
TEST(R157Driver, LeaderBrakingHarderThanFiveIsARisk) {
  for (const double decel : {4.0, 6.0}) {
    R157Driver driver;
    DriverView v = straight_road(0, 0.05, 0, kKmh60, kKmh60);
    PerceivedObject lead = car("lead", 4.5 + 26.7, 0.0, kKmh60);
    lead.accel_s = -decel;
    v.objects.push_back(lead);
    const Decision d = driver.step(v);
    EXPECT_EQ(d.phase, decel > 5 ? Phase::Perceive : Phase::Drive) << decel;
  }
}

// A pedestrian 1.5 m beside the ego's path walking towards it at 1.5 m/s, 45 m ahead (closer
// than a comfortable stop, 16.67^2 / (2 * 3) + 2 = 48.3 m), enters the path before the ego
// passes: a risk; walking away, none. The driver stops before it (it needs 42.35 m from
// 60 km/h, see above).
TEST(R157Driver, PedestrianEnteringThePathStopsTheEgo) {
  for (const double walk : {-1.5, 1.5}) {
    R157Driver driver;
    const double dt = 0.05;
    double ego_s = 0, ego_v = kKmh60, ped_d = 0.9 + 0.25 + 1.5;
    bool risk = false;
    for (int i = 0; i < 400; ++i) {
      DriverView v = straight_road(i * dt, dt, ego_s, ego_v, kKmh60);
      PerceivedObject ped = car("walker", 2.25 + 45 + 0.25, ped_d, 0.0);
      ped.kind = ObjectKind::Pedestrian;
      ped.length = 0.5;
      ped.width = 0.5;
      ped.speed_d = walk;
      if (walk < 0 && ped_d < -0.3) ped.speed_d = 0;  // stops in the middle of the lane
      v.objects.push_back(ped);
      const Decision d = driver.step(v);
      risk = risk || d.phase != Phase::Drive;
      ego_s += (ego_v + d.speed) / 2 * dt;
      ego_v = d.speed;
      ped_d += ped.speed_d * dt;
    }
    if (walk < 0) {
      EXPECT_TRUE(risk);
      EXPECT_LT(ego_v, 0.5);
      // Waits behind it, creeping up to the standstill gap (2 m) at most, never touching it.
      EXPECT_LT(ego_s + 2.25, 2.25 + 45) << "stopped before the pedestrian";
      EXPECT_GT(2.25 + 45 - (ego_s + 2.25), 1.5);
    } else {
      EXPECT_FALSE(risk);
    }
  }
}

// The end of the ego's route (ScenarioExecutor end_position): the driver stops with its centre
// there, as SUMO's stop does for the SUMO-driven ego (reach conditions allow 1 m), with at most
// the comfortable deceleration.
TEST(R157Driver, StopsWithItsCentreAtTheEndOfItsPath) {
  R157Driver driver;
  const double dt = 0.05;
  double ego_s = 0, ego_v = kKmh60, max_decel = 0;
  for (int i = 0; i < 1200; ++i) {
    DriverView v = straight_road(i * dt, dt, ego_s, ego_v, kKmh60);
    v.path_end = 200.0;
    const Decision d = driver.step(v);
    EXPECT_EQ(d.phase, Phase::Drive);
    max_decel = std::max(max_decel, -d.accel);
    ego_s += (ego_v + d.speed) / 2 * dt;
    ego_v = d.speed;
  }
  EXPECT_NEAR(ego_s, 200.0, 1.0);
  EXPECT_LT(ego_v, 0.05);
  EXPECT_LE(max_decel, 3.0 + 1e-9);
}

// A pedestrian standing in the path 140 m ahead is no emergency: normal driving stops behind
// it comfortably (at most 3 m/s^2), with the standstill gap left.
TEST(R157Driver, FarPedestrianInThePathIsAComfortableStop) {
  R157Driver driver;
  const double dt = 0.05;
  double ego_s = 0, ego_v = kKmh60, max_decel = 0;
  for (int i = 0; i < 1200; ++i) {
    DriverView v = straight_road(i * dt, dt, ego_s, ego_v, kKmh60);
    PerceivedObject ped = car("walker", 2.25 + 140 + 0.25, 0.0, 0.0);
    ped.kind = ObjectKind::Pedestrian;
    ped.length = 0.5;
    ped.width = 0.5;
    v.objects.push_back(ped);
    const Decision d = driver.step(v);
    EXPECT_EQ(d.phase, Phase::Drive) << v.time;
    max_decel = std::max(max_decel, -d.accel);
    ego_s += (ego_v + d.speed) / 2 * dt;
    ego_v = d.speed;
  }
  EXPECT_LE(max_decel, 3.0 + 1e-9);
  EXPECT_LT(ego_v, 0.5);
  EXPECT_LT(ego_s + 2.25, 2.25 + 140);
  EXPECT_GT(2.25 + 140 - (ego_s + 2.25), 1.5);
}

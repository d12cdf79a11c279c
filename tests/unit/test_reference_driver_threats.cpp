// The R157 reference driver's answer to threats, on hand-built views and snapshots (issue 26):
// cut-outs perceived at the wandering threshold, braking that continues from the current
// deceleration, one perception per threat, background leaders that brake, and the second
// braking stage after a full wrap. Every figure is worked out by hand in the comments.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "reference_driver/r157_driver.hpp"
#include "reference_driver/reference_ego.hpp"
#include "reference_driver_views.hpp"

using namespace orch;
using namespace orch::reference_driver;
using orch::reference_driver::test::car;

namespace {

constexpr double kKmh60 = 60.0 / 3.6;
constexpr double kDt = 0.05;

DriverView road(double time, double ego_s, double ego_speed, double set_speed) {
  return test::straight_road(time, kDt, ego_s, ego_speed, set_speed);
}

int count_events(const std::vector<std::string>& events, const std::string& part) {
  return static_cast<int>(
      std::count_if(events.begin(), events.end(), [&](const std::string& e) { return e.find(part) != std::string::npos; }));
}

}  // namespace

// The leader (60 km/h, 30 m ahead, at the ego's lane centre) moves left at 1 m/s from t = 1 s,
// revealing a car standing 120 m ahead. It is 0.375 m out of its lane centre at t = 1.375 s,
// first seen so in the snapshot of 1.40 s: the cut-out's risk perception point, within one
// step (R157 Annex 4 App. 3 Table 1: "deviation of the centre of a vehicle over 0.375 m from
// the centre of the driving lane"), not when its body has left the ego's path (|d| = 1.8 m,
// t = 2.8 s).
TEST(R157Threats, CutOutIsPerceivedAtTheWanderingThreshold) {
  R157Driver driver;
  double ego_s = 0, ego_v = kKmh60, lead_s = 2.25 + 30 + 2.25;
  std::optional<double> perceived;
  for (int i = 0; i <= 80 && !perceived; ++i) {
    const double t = i * kDt;
    DriverView v = road(t, ego_s, ego_v, kKmh60);
    PerceivedObject lead = car("leader", lead_s, t <= 1.0 ? 0.0 : 1.0 * (t - 1.0), kKmh60);
    lead.speed_d = t <= 1.0 ? 0.0 : 1.0;
    v.objects.push_back(lead);
    v.objects.push_back(car("standing", 120.0, 0.0, 0.0));
    const Decision d = driver.step(v);
    if (d.phase != Phase::Drive) perceived = driver.risk_perceived_at();
    ego_s += (ego_v + d.speed) / 2 * kDt;
    ego_v = d.speed;
    lead_s += kKmh60 * kDt;
  }
  ASSERT_TRUE(perceived) << "the cut-out was never perceived";
  EXPECT_EQ(driver.risk(), "cut-out");
  EXPECT_NEAR(*perceived, 1.375, kDt) << "risk at the 0.375 m crossing (1.375 s) +- one step";
}

// The ego brakes comfortably (3 m/s^2, its path ends 45 m ahead) when the leader 15 m ahead
// starts braking at 6 m/s^2 (t = 0.5 s, harder than 5: a risk). Perception and brake
// reaction keep the 3 m/s^2; then the brake builds up from 3 m/s^2, not from 0 (the ramp of
// 12.65 m/s^3 reaches 7.59 m/s^2 after (7.59 - 3) / 12.65 = 0.36 s instead of 0.6 s).
TEST(R157Threats, BrakingContinuesFromTheCurrentDeceleration) {
  R157Driver driver;
  double ego_s = 0, ego_v = kKmh60, lead_s = 2.25 + 15 + 2.25, lead_v = kKmh60;
  double max_decel = 0;
  bool brake_seen = false;
  for (int i = 0; i < 200 && ego_v > 0; ++i) {
    const double t = i * kDt;
    DriverView v = road(t, ego_s, ego_v, kKmh60);
    v.path_end = 45.0;
    const double lead_a = t >= 0.5 && lead_v > 0 ? -6.0 : 0.0;
    PerceivedObject lead = car("leader", lead_s, 0.0, lead_v);
    lead.accel_s = lead_a;
    v.objects.push_back(lead);
    const Decision d = driver.step(v);
    if (i > 0 && d.speed > 0) {
      EXPECT_GE(-d.accel, 3.0 - 1e-6) << "the deceleration dropped at t=" << t << " (" << to_string(d.phase) << ")";
    }
    if (d.phase == Phase::Brake) brake_seen = true;
    max_decel = std::max(max_decel, -d.accel);
    ego_s += (ego_v + d.speed) / 2 * kDt;
    ego_v = d.speed;
    const double next_v = std::max(0.0, lead_v + lead_a * kDt);
    lead_s += (lead_v + next_v) / 2 * kDt;
    lead_v = next_v;
  }
  EXPECT_TRUE(brake_seen);
  EXPECT_EQ(driver.risk(), "decelerating lead vehicle");
  EXPECT_NEAR(max_decel, 0.774 * 9.81, 1e-6);
}

// A car in the left lane, 30 m ahead at 12 m/s (the ego at 60 km/h), moves into the ego's
// lane at 1 m/s: the cut-in is perceived at 0.40 s (0.375 m out at 0.375 s) and judged at
// 1.55 s: a TTC of 22.8 m / 4.67 m/s = 4.9 s, not critical. From 1.75 s its body is in the
// ego's path (|d| < 1.8 m) with 21.8 m left, which comfortable braking no longer covers
// ((16.67^2 - 12^2) / (2 * 19.8) = 3.4 m/s^2 > 3): the same car, already perceived. The
// driver brakes then, not after a second perception and reaction (1.15 s later).
TEST(R157Threats, ACutInThatBecomesAnObstacleIsPerceivedOnce) {
  R157Driver driver;
  const double cutter_v = 12.0;
  double ego_s = 0, ego_v = kKmh60, cutter_s = 2.25 + 30 + 2.25;
  std::vector<std::string> events;
  std::optional<double> braking_from;
  for (int i = 0; i <= 100; ++i) {
    const double t = i * kDt;
    DriverView v = road(t, ego_s, ego_v, kKmh60);
    PerceivedObject cutter = car("cutter", cutter_s, std::max(0.0, 3.5 - 1.0 * t), cutter_v);
    cutter.speed_d = cutter.d > 0 ? -1.0 : 0.0;
    v.objects.push_back(cutter);
    const Decision d = driver.step(v);
    events.insert(events.end(), d.events.begin(), d.events.end());
    if (d.phase == Phase::Brake && !braking_from) braking_from = t;
    ego_s += (ego_v + d.speed) / 2 * kDt;
    ego_v = d.speed;
    cutter_s += cutter_v * kDt;
  }
  EXPECT_EQ(count_events(events, "risk perceived"), 1) << "one threat, one perception";
  EXPECT_EQ(count_events(events, "cut-in (cutter, gap"), 1);
  ASSERT_TRUE(braking_from);
  EXPECT_LT(*braking_from, 0.40 + 0.4 + 0.75 + 0.5) << "braking began " << *braking_from << " s";
  EXPECT_GE(*braking_from, 0.40 + 0.4 + 0.75) << "never before the first perception's reaction";
}

// Annex 4 App. 3 Table 1: "after full wrap of ego vehicle and cut-in vehicle" the deceleration
// goes on to 0.85 G. A car cutting in 12 m ahead at 40 km/h (the ego at 60 km/h; 3 m/s
// sideways: perceived at 0.15 s) is in the middle of the ego's lane when the brake acts
// (1.30 s): the ego brakes beyond 0.774 G, up to 0.85 G.
TEST(R157Threats, AFullyWrappedCutInRaisesBrakingToTheSecondStage) {
  R157Driver driver;
  const double cutter_v = 40 / 3.6;
  double ego_s = 0, ego_v = kKmh60, cutter_s = 2.25 + 12 + 2.25;
  double max_decel = 0;
  for (int i = 0; i <= 80 && ego_v > cutter_v; ++i) {
    const double t = i * kDt;
    DriverView v = road(t, ego_s, ego_v, kKmh60);
    PerceivedObject cutter = car("cutter", cutter_s, std::max(0.0, 3.5 - 3.0 * t), cutter_v);
    cutter.speed_d = cutter.d > 0 ? -3.0 : 0.0;
    v.objects.push_back(cutter);
    const Decision d = driver.step(v);
    max_decel = std::max(max_decel, -d.accel);
    ego_s += (ego_v + d.speed) / 2 * kDt;
    ego_v = d.speed;
    cutter_s += cutter_v * kDt;
  }
  EXPECT_GT(max_decel, 0.774 * 9.81 + 0.1);
  EXPECT_NEAR(max_decel, 0.85 * 9.81, 1e-6);
}

// A background vehicle (SUMO's, no scenario actor) drives ahead of the ego in its lane and
// brakes at 6 m/s^2 from t = 1 s. The snapshot carries no acceleration for background
// vehicles; the driver sees it from their speeds in consecutive snapshots and perceives the
// decelerating lead vehicle at t = 1.05 s (the first snapshot whose speed is 0.3 m/s lower).
TEST(R157Threats, ABackgroundLeaderBrakingHardIsARisk) {
  DrivingPath path;
  path.line = Polyline({{0, 0}, {2000, 0}});
  path.lane_width = 3.5;
  sim::TrackedActor me_tracked;
  me_tracked.sumo_id = "ego";
  me_tracked.length = 4.5;
  me_tracked.width = 1.8;
  const std::vector<sim::TrackedActor> tracked{me_tracked};
  ReferenceEgo ego(R157Parameters{}, path, "ego", {}, kDt, kKmh60);
  double ego_x = 10, ego_v = kKmh60, bg_x = 10 + 2.25 + 30 + 2.25, bg_v = kKmh60;
  std::vector<std::string> events;
  std::optional<double> perceived;
  for (int i = 0; i <= 60 && !perceived; ++i) {
    const double t = i * kDt;
    sim::WorldSnapshot snap;
    snap.time = t;
    sim::ActorState me;
    me.present = true;
    me.position = {ego_x, 0};
    me.speed = ego_v;
    snap.actors.push_back(me);
    snap.nearby.push_back({"flow.7", {bg_x, 0}, 0.0, bg_v, 4.5, 1.8});
    std::vector<std::string> step_events;
    const auto commands = ego.drive(snap, tracked, step_events);
    for (const auto& e : step_events)
      if (e.find("risk perceived") != std::string::npos) perceived = t;
    ASSERT_EQ(commands.size(), 1u);
    const double next = std::get<sim::DriveSpeed>(commands[0]).speed;
    ego_x += (ego_v + next) / 2 * kDt;
    ego_v = next;
    const double next_bg = t >= 1.0 - 1e-9 ? bg_v - 6.0 * kDt : bg_v;
    bg_x += (bg_v + next_bg) / 2 * kDt;
    bg_v = next_bg;
  }
  ASSERT_TRUE(perceived) << "the braking background leader was never a risk";
  EXPECT_NEAR(*perceived, 1.05, 1e-9);
  EXPECT_EQ(ego.driver().risk(), "decelerating lead vehicle");
}

// A car cutting in at the ego's speed (30 m ahead, 1 m/s sideways) is in the ego's path while
// still 1.7 m out of the lane centre, with a car standing 140 m ahead: that is the cut-in
// going on, not a cut-out revealing the standing car.
TEST(R157Threats, ACutInIsNoCutOut) {
  R157Driver driver;
  double ego_s = 0, ego_v = kKmh60, cutter_s = 2.25 + 30 + 2.25;
  std::vector<std::string> events;
  for (int i = 0; i <= 100; ++i) {
    const double t = i * kDt;
    DriverView v = road(t, ego_s, ego_v, kKmh60);
    PerceivedObject cutter = car("cutter", cutter_s, std::max(0.0, 3.5 - 1.0 * t), kKmh60);
    cutter.speed_d = cutter.d > 0 ? -1.0 : 0.0;
    v.objects.push_back(cutter);
    v.objects.push_back(car("standing", 2.25 + 140 + 2.25, 0.0, 0.0));
    const Decision d = driver.step(v);
    events.insert(events.end(), d.events.begin(), d.events.end());
    ego_s += (ego_v + d.speed) / 2 * kDt;
    ego_v = d.speed;
    cutter_s += kKmh60 * kDt;
  }
  EXPECT_EQ(count_events(events, "cut-in (cutter, gap"), 1);
  EXPECT_EQ(count_events(events, "cut-out"), 0) << (events.empty() ? "" : events.back());
}

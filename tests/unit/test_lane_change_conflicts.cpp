// Background vehicles in the way of a scripted lane change (scenario_executor_engine/lane_change_conflicts.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "scenario_executor_engine/lane_change_conflicts.hpp"

using namespace orch;
using namespace orch::engine;

namespace {

// A straight target lane along +x at y = 0, 1 km long.
WaypointRoute straight_route() {
  WaypointRoute r;
  r.id = "Target";
  std::vector<Vec2> pts;
  for (int x = 0; x <= 1000; x += 10) pts.emplace_back(x, 0.0);
  r.line = Polyline(pts);
  return r;
}

// The actor, 4 m long at x = 500, half way over from the lane to the right (y = -1.75).
WorldSnapshot snapshot_at(double t, double actor_speed, std::vector<NearbyVehicle> nearby) {
  WorldSnapshot s;
  s.time = t;
  ActorState a;
  a.id = 1;
  a.present = true;
  a.position = {500, -1.75};
  a.speed = actor_speed;
  s.actors = {a};
  s.nearby = std::move(nearby);
  return s;
}

NearbyVehicle car(const std::string& id, double x, double y, double speed, double heading = 0) {
  return NearbyVehicle{id, {x, y}, heading, speed, 4.0, 1.8};
}

}  // namespace

TEST(LaneChangeConflicts, AVehicleCloseBehindInTheTargetLaneIsAConflictOnce) {
  const WaypointRoute target = straight_route();
  LaneChangeConflicts w;
  w.watch(1, 4.0, target, +1, 3.5, 3.0);
  // 1 m bumper to bumper behind, 20 m/s: time gap 0.05 s.
  const auto first = w.step(snapshot_at(0.05, 20, {car("bg.close", 495, 0.3, 20)}));
  ASSERT_EQ(first.size(), 1u);
  EXPECT_EQ(first[0].vehicle, "bg.close");
  EXPECT_EQ(first[0].actor, 1);
  EXPECT_EQ(first[0].target_route, "Target");
  EXPECT_FALSE(first[0].vehicle_ahead);
  EXPECT_NEAR(first[0].gap, 1.0, 1e-9);
  EXPECT_NEAR(first[0].time_gap, 0.05, 1e-9);
  // Still there on the next step: not reported again.
  EXPECT_TRUE(w.step(snapshot_at(0.10, 20, {car("bg.close", 496, 0.3, 20)})).empty());
  EXPECT_EQ(w.all().size(), 1u);
}

TEST(LaneChangeConflicts, FarOtherLaneOncomingAndAfterTheEndAreNot) {
  const WaypointRoute target = straight_route();
  LaneChangeConflicts w;
  w.watch(1, 4.0, target, +1, 3.5, 3.0);
  const auto none = w.step(snapshot_at(1.0, 20, {
      car("bg.far", 450, 0, 20),                          // 46 m behind at 20 m/s: 2.3 s
      car("bg.left", 500, 3.5, 20),                       // side by side, one lane further left
      car("bg.oncoming", 503, 0, 20, std::numbers::pi),   // the other direction
  }));
  EXPECT_TRUE(none.empty());
  // A vehicle 10 m ahead is fine at 20 m/s (0.5 s) only if the actor is slow: here it is not.
  const auto ahead = w.step(snapshot_at(1.05, 20, {car("bg.ahead", 514, 0, 25)}));
  ASSERT_EQ(ahead.size(), 1u);
  EXPECT_TRUE(ahead[0].vehicle_ahead);
  EXPECT_NEAR(ahead[0].time_gap, 10.0 / 20.0, 1e-9);
  // Side by side at a standstill: gap 0, the time gap is infinite but the gap decides.
  const auto beside = w.step(snapshot_at(1.10, 0, {car("bg.beside", 501, -0.5, 0)}));
  ASSERT_EQ(beside.size(), 1u);
  EXPECT_DOUBLE_EQ(beside[0].gap, 0.0);
  EXPECT_TRUE(std::isinf(beside[0].time_gap));
  // After the lane change ended (t > 3 s) nothing is watched any more.
  EXPECT_TRUE(w.step(snapshot_at(3.2, 20, {car("bg.late", 495, 0, 20)})).empty());
}

TEST(LaneChangeConflicts, AgainstTheRouteAsDrawnAheadAndBehindSwap) {
  const WaypointRoute target = straight_route();
  LaneChangeConflicts w;
  // The actor drives towards -x in the target lane (a lane of the opposite side).
  w.watch(1, 4.0, target, -1, 3.5, 3.0);
  const auto found = w.step(snapshot_at(0.5, 10, {car("bg.west", 492, 0, 10, std::numbers::pi)}));
  ASSERT_EQ(found.size(), 1u);
  EXPECT_TRUE(found[0].vehicle_ahead);  // lower x is ahead when driving towards -x
  EXPECT_NEAR(found[0].gap, 4.0, 1e-9);
  EXPECT_NEAR(found[0].time_gap, 0.4, 1e-9);
}

TEST(LaneChangeConflicts, ANewLaneChangeReplacesTheWatchAndReportsAgain) {
  const WaypointRoute target = straight_route();
  LaneChangeConflicts w;
  w.watch(1, 4.0, target, +1, 3.5, 3.0);
  EXPECT_EQ(w.step(snapshot_at(0.5, 20, {car("bg.close", 495, 0, 20)})).size(), 1u);
  w.watch(1, 4.0, target, +1, 3.5, 6.0);
  EXPECT_EQ(w.step(snapshot_at(4.0, 20, {car("bg.close", 495, 0, 20)})).size(), 1u);
  EXPECT_EQ(w.all().size(), 2u);
}

// Vehicles enter real SUMO at the speed the scenario gives them (docs/openscenario.md "The
// ego"): SUMO refuses a departure above the lane's limit ("Departure speed ... is too high
// for the departure edge") and a negative or non-finite departSpeed ("Invalid departSpeed
// definition"); the adapter hands a driven vehicle over at its own speed and never sends such
// a value.
#include <gtest/gtest.h>
#include <libsumo/libsumo.h>

#include <cmath>
#include <limits>
#include <string>

#include "sim/world.hpp"
#include "sumo/sumo_simulator.hpp"
#include "unit/synthetic_roads.hpp"

using namespace orch;

namespace {

const std::string kNorth = "Waypoint03+Waypoint02+Waypoint01#";

sim::SpawnVehicle vehicle(const std::string& id, sim::ActorId actor, int lane, double speed, bool scripted) {
  sim::SpawnVehicle c;
  c.actor = {actor, id, ActorKind::Vehicle, 4.5, 2.0};
  c.model = {"test.car", ActorKind::Vehicle, 4.5, 2.0, 1.5, "passenger", "passenger", false};
  c.scripted = scripted;
  for (int i = 0; i < 8; ++i) c.route.push_back(kNorth + std::to_string(i));
  c.edge = kNorth + "1";
  c.lane = lane;
  c.lane_pos = 50 + 30 * actor;
  c.speed = speed;
  return c;
}

class SumoDeparture : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::string maps = std::string(ORCH_SOURCE_DIR) + "/sumo_nets/highway/";
    SimulatorConfig config;
    config.net_file = maps + "highway.net.xml";
    config.log_file = (dir.path() / "sumo.log").string();
    sim->start(config);
    limit = libsumo::Lane::getMaxSpeed(kNorth + "1_0");
    ASSERT_GT(limit, 10.0);
  }
  void TearDown() override { sim->close(); }

  test::TempDir dir{"sumo_departure"};
  std::unique_ptr<Simulator> sim = make_libsumo_simulator();
  double limit = 0;
};

// A driven vehicle 30 % over the limit departs at its speed and keeps it (its desired speed);
// a second one whose desired speed is below its departure speed departs at its speed, then
// slows to the desired one.
TEST_F(SumoDeparture, ADrivenVehicleDepartsAtItsOwnSpeedAboveTheLaneLimit) {
  auto fast = vehicle("fast", 0, 0, limit * 1.3, false);
  fast.max_speed = limit * 1.3;
  auto slowing = vehicle("slowing", 1, 1, limit * 1.3, false);
  slowing.max_speed = limit * 0.5;
  ASSERT_NO_THROW(sim->apply({fast, slowing}));
  const std::vector<sim::TrackedActor> tracked{fast.actor, slowing.actor};
  sim->advance();
  auto snap = sim->read(tracked);
  ASSERT_TRUE(snap.actors.at(0).present);
  ASSERT_TRUE(snap.actors.at(1).present);
  EXPECT_NEAR(snap.actors.at(0).speed, limit * 1.3, 0.01);
  EXPECT_NEAR(snap.actors.at(1).speed, limit * 1.3, 0.01);
  for (int step = 0; step < 400; ++step) sim->advance();  // 20 s
  snap = sim->read(tracked);
  EXPECT_NEAR(snap.actors.at(0).speed, limit * 1.3, 0.05);  // not capped at the limit
  EXPECT_NEAR(snap.actors.at(1).speed, limit * 0.5, 0.05);  // SUMO drives it at its desired speed
}

// Within the limit nothing changes: the speed factor stays 1.
TEST_F(SumoDeparture, WithinTheLimitTheSpeedFactorStaysOne) {
  auto calm = vehicle("calm", 0, 0, limit * 0.8, false);
  calm.max_speed = limit * 2;
  sim->apply({calm});
  sim->advance();
  EXPECT_DOUBLE_EQ(libsumo::Vehicle::getSpeedFactor("calm"), 1.0);
  for (int step = 0; step < 300; ++step) sim->advance();
  EXPECT_NEAR(sim->read({calm.actor}).actors.at(0).speed, limit, 0.05);  // the lane's limit caps it, as before
}

// Negative (reversing) and non-finite speeds never reach SUMO as a departSpeed.
TEST_F(SumoDeparture, NegativeOrNonFiniteSpeedsDepartStanding) {
  const auto nan = std::numeric_limits<double>::quiet_NaN();
  const auto inf = std::numeric_limits<double>::infinity();
  const std::vector<sim::Command> spawns{vehicle("reversing", 0, 0, -3, true), vehicle("nan", 1, 1, nan, true),
                                            vehicle("driven_nan", 2, 0, nan, false),
                                            vehicle("driven_inf", 3, 1, -inf, false)};
  ASSERT_NO_THROW(sim->apply(spawns));
  ASSERT_NO_THROW(sim->advance());
  std::vector<sim::TrackedActor> tracked;
  for (const auto& c : spawns) tracked.push_back(std::get<sim::SpawnVehicle>(c).actor);
  const auto snap = sim->read(tracked);
  for (const auto& a : snap.actors) {
    EXPECT_TRUE(a.present) << a.id;
    EXPECT_TRUE(std::isfinite(a.speed)) << a.id;
    EXPECT_GE(a.speed, 0.0) << a.id;
  }
}

// A scripted vehicle placed beyond a dead end, or far from every road, leaves SUMO's network
// there: SUMO's free match finds no lane for the point, and SUMO 1.15 then reads a lane position
// it never set and asserts on it (adapters/sumo/sumo_simulator.cpp, move_to_xy). Such a run
// aborted or not depending on what was on the stack; the adapter makes it defined.
sim::SetPose standing_pose(const std::string& id, const std::string& edge, const Vec2& centre, const Vec2& along) {
  sim::SetPose pose;
  pose.sumo_id = id;
  pose.length = 4.5;
  pose.heading = std::atan2(along.y(), along.x());
  pose.speed = 0;
  pose.edge = edge;
  pose.lane = 0;
  pose.position = centre;
  return pose;
}

void expect_off_network_at(const std::string& id, const Vec2& front) {
  EXPECT_EQ(libsumo::Vehicle::getLaneID(id), "");
  const auto at = libsumo::Vehicle::getPosition(id);
  EXPECT_NEAR(at.x, front.x(), 0.01);
  EXPECT_NEAR(at.y, front.y(), 0.01);
}

// Lane 0 of the route's last edge: it ends at `end` (a dead end), heading `along`.
const std::string kLast = kNorth + "7";
const Vec2 kEnd(185.9958, 1015.4363);
const Vec2 kAlong = (kEnd - Vec2(135.3365, 772.9482)).normalized();

// A scripted vehicle on the last edge, inserted by its first pose, `before` m before the end.
sim::SetPose insert_before_the_end(Simulator& sim, const std::string& id, double before, double speed) {
  sim::SpawnVehicle car = vehicle(id, 0, 0, 10, true);
  car.route = {kLast};
  car.edge = kLast;
  car.lane_pos = 240 - before;
  sim::SetPose pose = standing_pose(id, kLast, kEnd - before * kAlong, kAlong);
  pose.speed = speed;
  sim.apply({car, pose});
  sim.advance();
  return pose;
}

TEST_F(SumoDeparture, AVehiclePlacedBeyondADeadEndOrFarFromEveryRoadLeavesTheNetworkThere) {
  const std::string& last = kLast;
  const Vec2& end = kEnd;
  const Vec2& along = kAlong;
  sim::SetPose pose;
  ASSERT_NO_THROW(pose = insert_before_the_end(*sim, "deadend", 40, 0));
  ASSERT_EQ(libsumo::Vehicle::getLaneID("deadend"), last + "_0");
  for (const double beyond : {2.0, 2000.0}) {  // 2 m beyond the end; no road within 100 m
    pose.position = end + (beyond - 2.25) * along;
    ASSERT_NO_THROW(sim->apply({pose}));
    ASSERT_NO_THROW(sim->advance());
    expect_off_network_at("deadend", end + beyond * along);
  }
}

// A placed vehicle driving at a constant 10 m/s off the end of a dead end: SUMO stops its own
// copy at the lane's end (an emergency stop) before the next pose gives it its speed back, and
// SUMO's acceleration of it reads +200 m/s^2 that step. The snapshot's acceleration of a placed
// vehicle is that of the speeds it was given: 0 throughout.
TEST_F(SumoDeparture, APlacedVehicleDrivingOffADeadEndKeepsTheAccelerationOfItsSpeeds) {
  const Vec2& end = kEnd;
  const Vec2& along = kAlong;
  sim::SetPose pose;
  ASSERT_NO_THROW(pose = insert_before_the_end(*sim, "offend", 25, 10));
  const sim::TrackedActor actor = vehicle("offend", 0, 0, 10, true).actor;
  int off_network = 0;
  for (int step = 1; step <= 60; ++step) {  // 30 m: from 25 m before the end to 5 m beyond it
    pose.position = end + (-25.0 + 0.5 * step) * along;
    ASSERT_NO_THROW(sim->apply({pose}));
    ASSERT_NO_THROW(sim->advance());
    const auto snap = sim->read({actor});
    ASSERT_TRUE(snap.actors.at(0).present) << step;
    EXPECT_NEAR(snap.actors.at(0).speed, 10.0, 1e-9) << step;
    EXPECT_NEAR(snap.actors.at(0).accel, 0.0, 1e-9) << "step " << step;
    if (libsumo::Vehicle::getLaneID("offend").empty()) ++off_network;
  }
  EXPECT_GT(off_network, 0);  // it did drive off the end
}

}  // namespace

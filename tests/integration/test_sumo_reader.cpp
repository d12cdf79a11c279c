// The adapter reads the world through subscriptions (sumo_reader.hpp) instead of polling
// every vehicle. Checked here against libsumo's own, exhaustive answers, in the same
// process and simulation: the background count equals Vehicle::getIDCount, the nearby
// vehicles are exactly those within range of the actor.
#include <gtest/gtest.h>
#include <libsumo/libsumo.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>
#include <string>
#include <vector>

#include "sim/world.hpp"
#include "sumo/sumo_process.hpp"
#include "sumo/sumo_simulator.hpp"
#include "unit/synthetic_roads.hpp"

using namespace orch;

namespace {

const std::string kNorth = "Waypoint03+Waypoint02+Waypoint01#";

sim::SpawnVehicle ego_command() {
  sim::SpawnVehicle c;
  c.actor = {0, "ego", ActorKind::Vehicle, 4.5, 2.0};
  c.model = {"test.car", ActorKind::Vehicle, 4.5, 2.0, 1.5, "passenger", "passenger", false};
  c.scripted = false;
  for (int i = 0; i < 8; ++i) c.route.push_back(kNorth + std::to_string(i));
  c.edge = kNorth + "1";
  c.lane = 1;
  c.lane_pos = 50;
  c.speed = 20;
  c.max_speed = 25;
  return c;
}

// The shipped highway net, with its dense traffic or none.
SimulatorConfig highway_config(const std::string& log_file, bool dense_traffic) {
  const std::string maps = std::string(ORCH_SOURCE_DIR) + "/sumo_nets/highway/";
  SimulatorConfig config;
  config.net_file = maps + "highway.net.xml";
  if (dense_traffic) config.route_files = {maps + "traffic/dense.rou.xml"};
  config.log_file = log_file;
  return config;
}

}  // namespace

TEST(SumoReader, CountsAndNearbyVehiclesMatchLibsumosExhaustiveAnswers) {
  test::TempDir dir("sumo_reader");
  auto sim = make_libsumo_simulator();
  sim->start(highway_config((dir.path() / "sumo.log").string(), true));
  const auto spawn = ego_command();
  sim->apply({spawn});
  const std::vector<sim::TrackedActor> tracked{spawn.actor};
  int checked_nearby = 0;
  for (int step = 1; step <= 300; ++step) {
    sim->advance();
    const sim::WorldSnapshot snap = sim->read(tracked);
    if (step % 25 != 0) continue;
    SCOPED_TRACE(step);
    ASSERT_TRUE(snap.actors.at(0).present);
    EXPECT_EQ(snap.other_vehicles, libsumo::Vehicle::getIDCount() - 1);
    // Nearby: every other vehicle whose front is within 75 m of the ego's front.
    const auto ego = libsumo::Vehicle::getPosition("ego");
    std::set<std::string> expected;
    for (const auto& id : libsumo::Vehicle::getIDList()) {
      if (id == "ego") continue;
      const auto p = libsumo::Vehicle::getPosition(id);
      if (std::hypot(p.x - ego.x, p.y - ego.y) <= 75.0) expected.insert(id);
    }
    std::set<std::string> got;
    for (const auto& v : snap.nearby) {
      got.insert(v.sumo_id);
      EXPECT_NEAR(v.length, libsumo::Vehicle::getLength(v.sumo_id), 1e-9);
      EXPECT_NEAR(v.speed, libsumo::Vehicle::getSpeed(v.sumo_id), 1e-9);
    }
    EXPECT_EQ(got, expected);
    checked_nearby += static_cast<int>(expected.size());
  }
  EXPECT_GT(checked_nearby, 20);  // the comparison saw real neighbours
  sim->close();
}

// On libsumo the actors' context subscriptions wait until SUMO holds a vehicle that is not
// an actor (sumo_reader.hpp, contexts_needed): none while the ego is alone, and a vehicle
// inserted later is nearby from the step it enters, exactly as libsumo's exhaustive answer.
TEST(SumoReader, ContextsWaitForAVehicleThatIsNotAnActor) {
  test::TempDir dir("sumo_reader_contexts");
  auto sim = make_libsumo_simulator();
  sim->start(highway_config((dir.path() / "sumo.log").string(), false));
  const auto spawn = ego_command();
  sim->apply({spawn});
  const std::vector<sim::TrackedActor> tracked{spawn.actor};
  for (int step = 1; step <= 20; ++step) {
    sim->advance();
    const sim::WorldSnapshot snap = sim->read(tracked);
    ASSERT_TRUE(snap.actors.at(0).present);
    EXPECT_TRUE(snap.nearby.empty());
    EXPECT_TRUE(libsumo::Vehicle::getContextSubscriptionResults("ego").empty()) << "step " << step;
  }
  // A car 30 m ahead of the ego on the lane next to it.
  libsumo::Route::add("other.route", spawn.route);
  const double ego_front = libsumo::Vehicle::getLanePosition("ego");
  libsumo::Vehicle::add("other", "other.route", "DEFAULT_VEHTYPE", "now", "0", std::to_string(ego_front + 30), "20");
  int seen = 0;
  for (int step = 1; step <= 40; ++step) {
    sim->advance();
    const sim::WorldSnapshot snap = sim->read(tracked);
    SCOPED_TRACE(step);
    const auto ids = libsumo::Vehicle::getIDList();
    const bool in_sumo = std::find(ids.begin(), ids.end(), "other") != ids.end();
    bool expected = false;
    if (in_sumo) {
      const auto a = libsumo::Vehicle::getPosition("ego");
      const auto b = libsumo::Vehicle::getPosition("other");
      expected = std::hypot(a.x - b.x, a.y - b.y) <= 75.0;
    }
    ASSERT_EQ(snap.nearby.size(), expected ? 1U : 0U);
    if (expected) {
      EXPECT_EQ(snap.nearby.front().sumo_id, "other");
      EXPECT_NEAR(snap.nearby.front().speed, libsumo::Vehicle::getSpeed("other"), 1e-9);
      ++seen;
    }
  }
  EXPECT_GT(seen, 30);  // it entered in the first steps and stayed near
  sim->close();
}

// On libsumo a scenario vehicle is read by its getters after the step, over TraCI through a
// subscription (sumo_reader.hpp, read_vehicle): the same snapshots step by step, also when
// the vehicle reaches its route's end and leaves SUMO (absent from then on on both).
std::vector<sim::ActorState> drive_to_the_route_end(const std::string& backend, const std::string& dir) {
  auto sim = make_sumo_simulator(backend);
  sim->start(highway_config(dir + "/sumo_" + backend + ".log", false));
  auto spawn = ego_command();
  spawn.route = {kNorth + "6", kNorth + "7"};
  spawn.edge = kNorth + "6";
  const std::vector<sim::TrackedActor> tracked{spawn.actor};
  sim->apply({spawn});
  std::vector<sim::ActorState> states;
  for (int step = 1; step <= 600; ++step) {  // 30 s: ~450 m at 20-25 m/s, then gone
    sim->advance();
    states.push_back(sim->read(tracked).actors.at(0));
  }
  sim->close();
  return states;
}

TEST(SumoReader, BothBackendsReadAVehicleAlikeUntilAndAfterItLeaves) {
  test::TempDir dir("sumo_reader_leaving");
  const auto direct = drive_to_the_route_end("libsumo", dir.path().string());
  const auto subscribed = drive_to_the_route_end("traci", dir.path().string());
  ASSERT_EQ(direct.size(), subscribed.size());
  int present = 0;
  for (std::size_t i = 0; i < direct.size(); ++i) {
    SCOPED_TRACE(i + 1);
    const auto& a = direct[i];
    const auto& b = subscribed[i];
    ASSERT_EQ(a.present, b.present);
    if (!a.present) continue;
    ++present;
    EXPECT_NEAR(a.position.x(), b.position.x(), 1e-9);
    EXPECT_NEAR(a.position.y(), b.position.y(), 1e-9);
    EXPECT_NEAR(a.heading, b.heading, 1e-12);
    EXPECT_NEAR(a.speed, b.speed, 1e-9);
    EXPECT_NEAR(a.accel, b.accel, 1e-9);
    EXPECT_EQ(a.edge, b.edge);
    EXPECT_EQ(a.lane, b.lane);
    EXPECT_NEAR(a.lane_pos, b.lane_pos, 1e-9);
    ASSERT_EQ(a.lat_offset.has_value(), b.lat_offset.has_value());
    if (a.lat_offset) {
      EXPECT_NEAR(*a.lat_offset, *b.lat_offset, 1e-9);
    }
    EXPECT_EQ(a.signals, b.signals);
  }
  // It drove, then left: present first, absent at the end.
  EXPECT_GT(present, 100);
  EXPECT_TRUE(direct.front().present);
  EXPECT_FALSE(direct.back().present);
}

// SUMO's collisions reach the snapshot on both backends alike: a scripted car put onto the
// SUMO-driven ego (stage remoteControl), who collided with whom and of which type. libtraci
// answers getCollisions() with nothing, so the traci backend rebuilds them from the colliding
// vehicles' ids (sumo_reader.hpp, read_collisions); before that it saw none at all.
std::vector<sim::SimCollision> drive_into_the_ego(const std::string& backend, const std::string& dir) {
  auto sim = make_sumo_simulator(backend);
  sim->start(highway_config(dir + "/sumo_" + backend + ".log", false));
  const auto ego = ego_command();
  auto car = ego_command();
  car.actor = {1, "car", ActorKind::Vehicle, 4.5, 2.0};
  car.scripted = true;
  car.lane_pos = 10;
  const std::vector<sim::TrackedActor> tracked{ego.actor, car.actor};
  sim->apply({ego, car});
  std::vector<sim::SimCollision> seen;
  for (int step = 1; step <= 40; ++step) {
    sim->advance();
    const auto snap = sim->read(tracked);
    seen.insert(seen.end(), snap.collisions.begin(), snap.collisions.end());
    const auto& e = snap.actors.at(0);
    if (step < 5 || !e.present) continue;
    sim::SetPose pose;  // the car's centre 2 m behind the ego's, on its lane: they overlap
    pose.sumo_id = "car";
    pose.length = 4.5;
    pose.position = e.position - 2.0 * Vec2(std::cos(e.heading), std::sin(e.heading));
    pose.heading = e.heading;
    pose.speed = e.speed;
    pose.edge = e.edge;
    pose.lane = e.lane;
    pose.centred = true;
    sim->apply({pose});
  }
  sim->close();
  return seen;
}

TEST(SumoReader, BothBackendsReportSumosCollisionsAlike) {
  test::TempDir dir("sumo_reader_collisions");
  const auto direct = drive_into_the_ego("libsumo", dir.path().string());
  const auto over_traci = drive_into_the_ego("traci", dir.path().string());
  ASSERT_FALSE(direct.empty());
  ASSERT_EQ(direct.size(), over_traci.size());
  for (std::size_t i = 0; i < direct.size(); ++i) {
    SCOPED_TRACE(i);
    EXPECT_EQ(direct[i].collider, over_traci[i].collider);
    EXPECT_EQ(direct[i].victim, over_traci[i].victim);
    EXPECT_EQ(direct[i].type, over_traci[i].type);
    EXPECT_EQ(direct[i].lane, over_traci[i].lane);
  }
  EXPECT_TRUE(direct.front().collider == "car" || direct.front().victim == "car");
}

TEST(SumoErrors, SumosErrorLinesWithTheirContinuationsBecomeOneLine) {
  const std::string log =
      "Loading net-file from 'x.net.xml' ... done (3ms).\n"
      "Warning: something harmless\n"
      "Error: The edge 'nowhere' within the route for flow 'bg0' is not known.\n"
      " The route can not be build.\n"
      "Quitting (on error).\n";
  EXPECT_EQ(sumo_errors_in(log), "The edge 'nowhere' within the route for flow 'bg0' is not known. The route can not be build.");
  EXPECT_EQ(sumo_errors_in("Warning: only a warning\n"), "");
}

TEST(SumoProcess, FreePortsLieBelowTheEphemeralRange) {
  // A client polling such a port can never be handed it as its own (self-connection).
  std::ifstream range("/proc/sys/net/ipv4/ip_local_port_range");
  int ephemeral_low = 32768;
  range >> ephemeral_low;
  for (int i = 0; i < 20; ++i) {
    const int port = free_loopback_port();
    EXPECT_LT(port, ephemeral_low);
    EXPECT_GE(port, 1024);
    EXPECT_FALSE(port_is_listening(port));
  }
}

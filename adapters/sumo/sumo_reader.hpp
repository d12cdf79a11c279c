#pragma once
// What the orchestrator reads from SUMO each step, through subscriptions only, so that its
// cost does not grow with the background traffic (docs/performance.md):
//   - the simulation: time, the vehicles and persons that departed, how many arrived and
//     whether any collided (the running count is kept from departures and arrivals:
//     Vehicle::getIDCount builds the list of every vehicle id, O(n) each step); on libsumo
//     by their getters right after the step;
//   - each scenario actor, once SUMO has inserted it: its pose and lane (on libsumo a
//     vehicle's by its getters right after the step, read_vehicle; a person's and every
//     actor's over TraCI by a subscription);
//   - around each actor, a context subscription: the vehicles within kNearbyRange of it
//     (SUMO finds them through its lane tree, looking only at lanes near the actor; the
//     subscription is shared with an ego plug-in's, sumo_contexts.hpp). On libsumo it is
//     made only once SUMO holds a vehicle that is not a scenario actor (contexts_needed):
//     until then every context holds actors only, which the reader drops, and SUMO would
//     search its lanes around every actor after every step for nothing.
// On libsumo subscription results are computed in-process after each step; on libtraci
// they arrive with the answer to the step command, so reading costs no extra round trip.
//
// Included by sumo_simulator.cpp only (compiled once per SUMO client library).
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>
#include <numbers>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "sim/world.hpp"
#include "sumo_api.hpp"
#include "sumo_contexts.hpp"

namespace orch::sumo_reading {
// Internal linkage: this header is compiled once per client library, and the libsumo and
// libtraci versions of these functions must not be merged by the linker.
namespace {

namespace sumo = orch_sumo;
namespace tc = libsumo;
namespace contexts = ORCH_SUMO_CONCAT(contexts_, ORCH_SUMO_NS);

// m between an actor's and a background vehicle's reference points (front bumpers) within
// which the vehicle is "nearby": engine collision tests and --trace-background see it.
constexpr double kNearbyRange = 75.0;

// SUMO angles: degrees clockwise from north. Orchestrator headings: radians
// counter-clockwise from +x.
double from_sumo_angle(double angle_deg) { return wrap_angle((90.0 - angle_deg) * std::numbers::pi / 180.0); }

double number(const sumo::TraCIResults& r, int var) {
  const auto it = r.find(var);
  if (it == r.end()) {
    std::string have;
    for (const auto& [k, v] : r) have += " " + std::to_string(k);
    throw sumo::TraCIException("subscription result without variable " + std::to_string(var) + " (has:" + have + ")");
  }
  if (const auto* d = dynamic_cast<const sumo::TraCIDouble*>(it->second.get())) return d->value;
  if (const auto* i = dynamic_cast<const sumo::TraCIInt*>(it->second.get())) return i->value;
  throw sumo::TraCIException("subscription variable " + std::to_string(var) + " is not a number");
}
int integer(const sumo::TraCIResults& r, int var) { return static_cast<int>(std::lround(number(r, var))); }
std::string text(const sumo::TraCIResults& r, int var) {
  const auto it = r.find(var);
  if (it == r.end()) return "";
  if (const auto* s = dynamic_cast<const sumo::TraCIString*>(it->second.get())) return s->value;
  return it->second->getString();
}
[[maybe_unused]] std::vector<std::string> strings(const sumo::TraCIResults& r, int var) {  // libtraci
  const auto it = r.find(var);
  if (it == r.end()) return {};
  if (const auto* l = dynamic_cast<const sumo::TraCIStringList*>(it->second.get())) return l->value;
  return {};
}
Vec2 position(const sumo::TraCIResults& r) {
  const auto it = r.find(tc::VAR_POSITION);
  const auto* p = it == r.end() ? nullptr : dynamic_cast<const sumo::TraCIPosition*>(it->second.get());
  if (!p) throw sumo::TraCIException("subscription result without a position");
  return {p->x, p->y};
}
// SUMO's vehicle position is the middle of the front bumper; the orchestrator's is the centre.
Vec2 centre_of(const Vec2& front, double heading, double length) {
  return front - (length / 2) * Vec2(std::cos(heading), std::sin(heading));
}

class WorldReader {
 public:
  // Once, after SUMO started and before the first step.
  void start() {
    contexts::shared_contexts().reset();
    gone_.clear();
#ifdef LIBTRACI
    sumo::Simulation::subscribe(std::vector<int>{tc::VAR_TIME, tc::VAR_DEPARTED_VEHICLES_IDS,
                                                 tc::VAR_ARRIVED_VEHICLES_NUMBER, tc::VAR_COLLIDING_VEHICLES_NUMBER});
#endif
    // On libsumo the simulation's values are read by their getters right after the step
    // (after_step), the calls SUMO's subscription would make there, without wrapping each
    // value in a result object every step.
    edges_.clear();
    for (const auto& e : sumo::Edge::getIDList())
      if (e.empty() || e.front() != ':') edges_.push_back(e);
    next_wait_count_ = 0;
    long_waiting_ = 0;
    // Measurement only (scripts/bench/split.py): no context subscriptions, so no nearby
    // vehicles: the run is no longer the scenario's (collisions with background traffic go
    // unseen), but the benchmark can tell what the contexts cost.
    contexts_off_ = std::getenv("ORCH_BENCH_NO_CONTEXTS") != nullptr;
    contexts_needed_ = false;
  }

  [[nodiscard]] double time() const { return time_; }
  [[nodiscard]] long long running_vehicles() const { return running_; }

  // After every step (whether or not the step is read): departures and arrivals are only
  // reported for the step that just ran.
  void after_step() {
#ifdef LIBTRACI
    const sumo::TraCIResults simulation = sumo::Simulation::getSubscriptionResults();
    time_ = number(simulation, tc::VAR_TIME);
    const auto departed = strings(simulation, tc::VAR_DEPARTED_VEHICLES_IDS);
    running_ += static_cast<long long>(departed.size()) - integer(simulation, tc::VAR_ARRIVED_VEHICLES_NUMBER);
    colliding_ = integer(simulation, tc::VAR_COLLIDING_VEHICLES_NUMBER);
#else
    time_ = sumo::Simulation::getTime();
    const auto departed = sumo::Simulation::getDepartedIDList();
    // The arrivals by id: scenario vehicles are read directly, not through a subscription
    // that SUMO would empty when they leave (read_vehicle).
    const auto arrived = sumo::Simulation::getArrivedIDList();
    running_ += static_cast<long long>(departed.size()) - static_cast<long long>(arrived.size());
    colliding_ = sumo::Simulation::getCollidingVehiclesNumber();
#endif
    for (const auto& id : departed) {
      if (actor_kind_.count(id)) follow(id, false);
      else if (traffic_.count(id)) follow_traffic(id);
    }
#ifndef LIBTRACI
    // A followed vehicle that left SUMO reads as absent, as its emptied subscription did.
    for (const auto& id : arrived)
      if (const auto it = followed_.find(id); it != followed_.end() && !it->second) gone_.insert(id);
#endif
    // libsumo (1.15) leaves VAR_DEPARTED_PERSONS_IDS out of its simulation subscription
    // results, so scenario pedestrians are looked for by id: they depart in the step after
    // they were added, and there are only a few of them.
    for (auto it = pending_persons_.begin(); it != pending_persons_.end();) {
      if (person_departed(*it)) {
        follow(*it, true);
        it = pending_persons_.erase(it);
      } else {
        ++it;
      }
    }
  }

  // A scenario actor SUMO is about to insert (spawned): followed once it departs.
  void expect(const sim::TrackedActor& actor) {
    actor_kind_[actor.sumo_id] = actor.kind;
    if (actor.kind == ActorKind::Pedestrian) pending_persons_.push_back(actor.sumo_id);
  }

  // A traffic vehicle SUMO is about to insert (SpawnVehicle::traffic): read into
  // WorldSnapshot::traffic once it departs, until it leaves.
  void expect_traffic(const std::string& id, double length, double width) { traffic_[id] = {length, width, false}; }

  // A scenario actor about to be removed from SUMO: no longer followed, subscriptions ended.
  void forget(const std::string& id) {
    if (const auto t = traffic_.find(id); t != traffic_.end()) {
      if (t->second.followed) sumo::Vehicle::unsubscribe(id);
      traffic_.erase(t);
      return;
    }
    const auto it = followed_.find(id);
    if (it != followed_.end()) {
      if (it->second) sumo::Person::unsubscribe(id);
      else if (kVehicleSubscriptions) sumo::Vehicle::unsubscribe(id);
      contexts::shared_contexts().forget(id);
      followed_.erase(it);
    }
    actor_kind_.erase(id);
    std::erase(pending_persons_, id);
  }

  sim::WorldSnapshot read(const std::vector<sim::TrackedActor>& actors) {
    sim::WorldSnapshot snap;
    snap.time = time_;
    int vehicles_present = 0;
    for (const auto& a : actors) {
      snap.actors.push_back(read_actor(a));
      if (a.kind != ActorKind::Pedestrian && snap.actors.back().present) ++vehicles_present;
    }
    snap.other_vehicles = static_cast<int>(running_) - vehicles_present;
    if (time_ >= next_wait_count_ - 1e-9) {  // once a simulated second
      long_waiting_ = count_long_waiting();
      next_wait_count_ = std::floor(time_ + 1e-9) + 1.0;
    }
    snap.long_waiting = long_waiting_;
    read_nearby(actors, snap);
    read_traffic(snap);
    if (colliding_ > 0) read_collisions(snap);
    return snap;
  }

  // SUMO's collisions of the last step. libtraci (SUMO 1.15) answers getCollisions() with an
  // empty list (the client does not implement it; Python's traci does), so over TraCI they
  // are rebuilt from the colliding vehicles' ids, which SUMO lists as victim then collider
  // for each collision (checked against libsumo's getCollisions() on the same run); the type
  // is then "junction" where the two are on different lanes, one of them a junction's
  // internal lane (SUMO's check of foe lanes), and "collision" elsewhere (SUMO's rarer
  // "frontal" and "swap" only come through libsumo).
  void read_collisions(sim::WorldSnapshot& snap) {
#ifdef LIBTRACI
    const auto ids = sumo::Simulation::getCollidingVehiclesIDList();
    for (std::size_t i = 0; i + 1 < ids.size(); i += 2) {
      const std::string& victim = ids[i];
      const std::string& collider = ids[i + 1];
      const std::string lane = sumo::Vehicle::getLaneID(collider);
      const std::string victim_lane = sumo::Vehicle::getLaneID(victim);
      const auto internal = [](const std::string& l) { return !l.empty() && l.front() == ':'; };
      const bool junction = lane != victim_lane && (internal(lane) || internal(victim_lane));
      snap.collisions.push_back({collider, victim, junction ? "junction" : "collision", lane,
                                 sumo::Vehicle::getLanePosition(collider)});
    }
#else
    for (const auto& c : sumo::Simulation::getCollisions())
      snap.collisions.push_back({c.collider, c.victim, c.type, c.lane, c.pos});
#endif
  }

 private:
  // Vehicles standing for longer than kLongWait: only the edges with halting vehicles are
  // looked into, so the cost follows the queues, not the traffic.
  int count_long_waiting() {
    int n = 0;
    for (const auto& e : edges_) {
      if (sumo::Edge::getLastStepHaltingNumber(e) == 0) continue;
      for (const auto& v : sumo::Edge::getLastStepVehicleIDs(e))
        if (sumo::Vehicle::getWaitingTime(v) > sim::kLongWait) ++n;
    }
    return n;
  }

  // Subscribes to an actor that SUMO has just inserted; its results are there at once.
  void follow(const std::string& id, bool person) {
    static const std::vector<int> vehicle_vars = {tc::VAR_POSITION,     tc::VAR_ANGLE,        tc::VAR_SPEED,
                                                  tc::VAR_ACCELERATION, tc::VAR_ROAD_ID,      tc::VAR_LANE_INDEX,
                                                  tc::VAR_LANEPOSITION, tc::VAR_LANEPOSITION_LAT, tc::VAR_SIGNALS};
    static const std::vector<int> person_vars = {tc::VAR_POSITION, tc::VAR_ANGLE,   tc::VAR_SPEED,
                                                 tc::VAR_ROAD_ID,  tc::VAR_LANE_ID, tc::VAR_LANEPOSITION};
    // A vehicle the scenario moved off every lane before it departed (moveToXY, keepRoute 2:
    // a scenario without a road, run/roadless_net.hpp) has no lane, and SUMO's getRoadID
    // dereferences it (libsumo 1.15 crashes): its road and lane are not asked.
    if (!person && sumo::Vehicle::getLaneIndex(id) < 0) off_road_.insert(id);
    else off_road_.erase(id);
    static const std::vector<int> off_road_vars = {tc::VAR_POSITION, tc::VAR_ANGLE, tc::VAR_SPEED,
                                                   tc::VAR_ACCELERATION, tc::VAR_SIGNALS};
    if (person)
      sumo::Person::subscribe(id, person_vars);
    else if (kVehicleSubscriptions)
      sumo::Vehicle::subscribe(id, off_road_.count(id) ? off_road_vars : vehicle_vars);
    else
      gone_.erase(id);
    // On libsumo the context is subscribed by read_nearby, once it can hold anything.
    if (!contexts_off_ && kVehicleSubscriptions)
      contexts::shared_contexts().subscribe(id, person, tc::CMD_GET_VEHICLE_VARIABLE, kNearbyRange, kNeighbourVars);
    followed_[id] = person;
  }

  // A person added with DEPARTFLAG_NOW is in the id list once it departed; asking for one id
  // costs the same whatever the traffic.
  static bool person_departed(const std::string& id) {
    try {
      (void)sumo::Person::getRoadID(id);
      return true;
    } catch (const sumo::TraCIException&) {
      return false;  // not (yet) in the simulation
    }
  }

  sim::ActorState read_actor(const sim::TrackedActor& a) {
    sim::ActorState s;
    s.id = a.id;
    const auto it = followed_.find(a.sumo_id);
    if (it == followed_.end()) return s;  // not inserted yet
    const bool person = it->second;
    if (!person && !kVehicleSubscriptions) return read_vehicle(a, s);
    const sumo::TraCIResults r =
        person ? sumo::Person::getSubscriptionResults(a.sumo_id) : sumo::Vehicle::getSubscriptionResults(a.sumo_id);
    if (r.empty()) return s;  // gone: SUMO drops the subscription of a vehicle that left
    s.heading = from_sumo_angle(number(r, tc::VAR_ANGLE));
    s.speed = number(r, tc::VAR_SPEED);
    s.edge = text(r, tc::VAR_ROAD_ID);
    if (person) {
      s.position = position(r);
      const std::string lane = text(r, tc::VAR_LANE_ID);
      const auto underscore = lane.rfind('_');
      s.lane = underscore == std::string::npos ? -1 : std::stoi(lane.substr(underscore + 1));
      s.lane_pos = number(r, tc::VAR_LANEPOSITION);
    } else {
      s.position = centre_of(position(r), s.heading, a.length);
      s.accel = number(r, tc::VAR_ACCELERATION);
      s.signals = integer(r, tc::VAR_SIGNALS);
      if (!off_road_.count(a.sumo_id)) {
        s.lane = integer(r, tc::VAR_LANE_INDEX);
        if (s.lane == tc::INVALID_INT_VALUE) {
          // Placed off every lane later (moveToXY, keepRoute 2: an OpenSCENARIO entity past its
          // road's end): SUMO keeps the last edge's id but has no lane, lane position or offset.
          s.edge.clear();
          s.lane = -1;
        } else {
          s.lane_pos = number(r, tc::VAR_LANEPOSITION) - a.length / 2;
          s.lat_offset = number(r, tc::VAR_LANEPOSITION_LAT);
        }
      }
    }
    s.present = true;
    return s;
  }

  // On libsumo a scenario vehicle is read by its getters, the same calls SUMO's subscription
  // would make right after the step (nothing changes the vehicle between the step and this
  // read), without building a result object and a map entry per value (about 10,000
  // instructions per vehicle and step: docs/performance.md). Over TraCI each getter would be
  // a round trip, so libtraci keeps the subscription.
  sim::ActorState read_vehicle(const sim::TrackedActor& a, sim::ActorState s) {
    const std::string& id = a.sumo_id;
    if (gone_.count(id)) return s;
    try {
      s.heading = from_sumo_angle(sumo::Vehicle::getAngle(id));
      s.speed = sumo::Vehicle::getSpeed(id);
      const bool off_road = off_road_.count(id) > 0;
      if (!off_road) s.edge = sumo::Vehicle::getRoadID(id);
      const sumo::TraCIPosition front = sumo::Vehicle::getPosition(id);
      s.position = centre_of(Vec2(front.x, front.y), s.heading, a.length);
      s.accel = sumo::Vehicle::getAcceleration(id);
      s.signals = sumo::Vehicle::getSignals(id);
      if (!off_road) {
        s.lane = sumo::Vehicle::getLaneIndex(id);
        if (s.lane == tc::INVALID_INT_VALUE) {  // placed off every lane later (see read_actor)
          s.edge.clear();
          s.lane = -1;
        } else {
          s.lane_pos = sumo::Vehicle::getLanePosition(id) - a.length / 2;
          s.lat_offset = sumo::Vehicle::getLateralLanePosition(id);
        }
      }
    } catch (const sumo::TraCIException&) {
      sim::ActorState absent;  // not in SUMO (any more)
      absent.id = a.id;
      return absent;
    }
    s.present = true;
    return s;
  }

  // A traffic vehicle that departed: its pose each step (a few variables; as many vehicles
  // as the scenario's traffic actions keep, tens, not the whole background).
  void follow_traffic(const std::string& id) {
    sumo::Vehicle::subscribe(id, {tc::VAR_POSITION, tc::VAR_ANGLE, tc::VAR_SPEED});
    traffic_[id].followed = true;
  }

  void read_traffic(sim::WorldSnapshot& snap) {
    for (auto it = traffic_.begin(); it != traffic_.end();) {
      if (!it->second.followed) {
        ++it;
        continue;
      }
      const sumo::TraCIResults r = sumo::Vehicle::getSubscriptionResults(it->first);
      if (r.empty()) {  // it left SUMO (its route ended)
        it = traffic_.erase(it);
        continue;
      }
      sim::NearbyVehicle v;
      v.sumo_id = it->first;
      v.heading = from_sumo_angle(number(r, tc::VAR_ANGLE));
      v.length = it->second.length;
      v.width = it->second.width;
      v.position = centre_of(position(r), v.heading, v.length);
      v.speed = number(r, tc::VAR_SPEED);
      snap.traffic.push_back(std::move(v));
      ++it;
    }
  }

  // Background vehicles around any actor, once each, in id order (the same bytes on every
  // backend).
  void read_nearby(const std::vector<sim::TrackedActor>& actors, sim::WorldSnapshot& snap) {
    if (contexts_off_) return;
    if (!contexts_needed(snap)) {
      ++reads_;
      return;
    }
    std::map<std::string, sim::NearbyVehicle> found;
    for (const auto& a : actors) {
      const auto it = followed_.find(a.sumo_id);
      if (it == followed_.end()) continue;
      const sumo::SubscriptionResults around = nearby(a.sumo_id, it->second);
      for (const auto& [id, r] : around) {
        if (actor_kind_.count(id) || found.count(id) || r.empty()) continue;
        sim::NearbyVehicle v;
        v.sumo_id = id;
        v.heading = from_sumo_angle(number(r, tc::VAR_ANGLE));
        const Size& size = size_of(id);
        v.length = size.length;
        v.width = size.width;
        v.position = centre_of(position(r), v.heading, v.length);
        v.speed = number(r, tc::VAR_SPEED);
        found.emplace(id, std::move(v));
      }
    }
    snap.nearby.reserve(found.size());
    for (auto& [id, v] : found) snap.nearby.push_back(std::move(v));
    if (++reads_ % kSizeSweepEvery == 0) forget_sizes_unseen_since(reads_ - kSizeSweepEvery);
  }

  // Whether the actors' contexts can hold a vehicle the reader keeps: one that is not a
  // scenario actor. Their subscriptions are made when it first can (read_nearby's `within`
  // subscribes, and SUMO answers a new subscription at once, from the state the step left, as
  // it would have answered a standing one after the step) and stay from then on. SUMO's
  // contexts find vehicles on lanes, all of which Vehicle::getIDList lists; it is asked only
  // while the running count says the actors are alone (a handful of ids, not the traffic).
  // Over TraCI the contexts are subscribed as actors depart (follow): the list would be a
  // round trip, and the subscription's results come with the step's answer anyway.
  bool contexts_needed(const sim::WorldSnapshot& snap) {
    if (kVehicleSubscriptions || contexts_needed_) return true;
    if (snap.other_vehicles > 0) return contexts_needed_ = true;
    for (const auto& id : sumo::Vehicle::getIDList())
      if (!actor_kind_.count(id)) return contexts_needed_ = true;
    return false;
  }

  // A background vehicle's length and width do not change while it drives: asked once when
  // it first comes near an actor, not every step in every context result (SUMO builds a
  // result object per variable, vehicle and step; two of five variables were these).
  struct Size {
    double length = 0, width = 0;
    long long seen = 0;  // the read that last needed it
  };
  const Size& size_of(const std::string& id) {
    auto it = sizes_.find(id);
    if (it == sizes_.end())
      it = sizes_.emplace(id, Size{sumo::Vehicle::getLength(id), sumo::Vehicle::getWidth(id), 0}).first;
    it->second.seen = reads_;
    return it->second;
  }
  // Vehicles that left every actor's surroundings long ago (most have left SUMO): the cache
  // stays as large as the traffic near the actors, not the run's whole traffic.
  void forget_sizes_unseen_since(long long read) {
    std::erase_if(sizes_, [read](const auto& entry) { return entry.second.seen < read; });
  }

  // The vehicles within kNearbyRange of an actor (a context subscription shared with the ego
  // plug-in's, sumo_contexts.hpp).
  static sumo::SubscriptionResults nearby(const std::string& id, bool person) {
    return contexts::shared_contexts().within(id, person, tc::CMD_GET_VEHICLE_VARIABLE, kNearbyRange, kNeighbourVars);
  }
  inline static const std::vector<int> kNeighbourVars = {tc::VAR_POSITION, tc::VAR_ANGLE, tc::VAR_SPEED};
#ifdef LIBTRACI
  static constexpr bool kVehicleSubscriptions = true;
#else
  static constexpr bool kVehicleSubscriptions = false;  // read_vehicle
#endif
  static constexpr long long kSizeSweepEvery = 2000;  // reads

  struct Traffic {
    double length = 0, width = 0;
    bool followed = false;  // departed and subscribed
  };
  std::map<std::string, Traffic> traffic_;                 // traffic vehicles by SUMO id (id order)
  std::unordered_map<std::string, ActorKind> actor_kind_;  // scenario actors by SUMO id
  std::unordered_map<std::string, bool> followed_;         // subscribed actors: true = person
  std::unordered_set<std::string> off_road_;               // actors moved off every lane (no road asked)
  std::unordered_set<std::string> gone_;                   // followed vehicles that arrived (libsumo)
  std::vector<std::string> pending_persons_;               // scenario pedestrians not yet departed
  long long running_ = 0;                                  // SUMO vehicles on the road
  std::vector<std::string> edges_;                         // normal edges of the net
  double next_wait_count_ = 0;                             // s: when long waits are counted next
  int long_waiting_ = 0;
  int colliding_ = 0;                                      // vehicles in a collision in the last step
  double time_ = 0;
  bool contexts_off_ = false;  // ORCH_BENCH_NO_CONTEXTS (measurement only)
  bool contexts_needed_ = false;  // libsumo: a vehicle other than the actors was in SUMO
  std::unordered_map<std::string, Size> sizes_;  // background vehicles near an actor
  long long reads_ = 0;
};

}  // namespace
}  // namespace orch::sumo_reading

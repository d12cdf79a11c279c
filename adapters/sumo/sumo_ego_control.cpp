// SUMO side of the ego plug-in, compiled once per SUMO client library: ORCH_SUMO_NS is
// libsumo or libtraci (see adapters/CMakeLists.txt). SUMO's exceptions stop here and become
// WorldError (an error status for the plug-in, the run goes on).
//
// Reads are cached until the world advances: a plug-in asking for the same value twice costs
// one SUMO call per value and step (a socket round trip each on libtraci). A plug-in's context
// subscription is answered from SUMO's own (sumo_contexts.hpp), values included.
#include "sumo_ego_control.hpp"

#include <libsumo/TraCIConstants.h>

#include <algorithm>
#include <unordered_map>
#include ORCH_SUMO_HEADER

#include "run/ego_link.hpp"

#include "sumo_api.hpp"
#include "sumo_contexts.hpp"
#include "traci_server/traci_variables.hpp"

// Classes from ORCH_SUMO_NS, shared types and exceptions from libsumo (sumo_api.hpp).
namespace sumo = orch_sumo;

namespace orch {
namespace {

namespace tc = libsumo;
namespace contexts = ORCH_SUMO_CONCAT(contexts_, ORCH_SUMO_NS);
using traci::Domain;
using traci::Value;

Value pos2(const sumo::TraCIPosition& p) { return traci::Pos2{p.x, p.y}; }
Value pos3(const sumo::TraCIPosition& p) { return traci::Pos3{p.x, p.y, p.z}; }

class SumoEgoControl final : public traci::EgoWorld {
 public:
  void new_step() override { cache_.clear(); }

  void take_over_ego() override {
    guard([] { sumo::Vehicle::setLaneChangeMode(kEgoSumoId, kPluginEgoLaneChangeMode); });
  }

  // The one list of what the server serves (traci_server/traci_variables.hpp); read_vehicle,
  // read_person and read_simulation below answer each of its variables.
  [[nodiscard]] bool supports(Domain domain, int variable) const override {
    return traci::world_reads(domain, variable);
  }

  bool exists(Domain domain, const std::string& id) override {
    if (domain == Domain::Simulation) return true;
    // One cheap getter per object and step, not the whole id list (thousands of vehicles
    // with background traffic): SUMO throws for an unknown id.
    try {
      read(domain, tc::VAR_TYPE, id, std::nullopt);
      return true;
    } catch (const traci::WorldError&) {
      return false;
    }
  }

  Value read(Domain domain, int variable, const std::string& id, const std::optional<Value>& parameter) override {
    if (!supports(domain, variable))
      throw traci::NotImplemented(std::string(domain == Domain::Vehicle  ? "vehicle"
                                              : domain == Domain::Person ? "person"
                                                                         : "simulation") +
                                  " variable " + std::to_string(variable) +
                                  " is not implemented by the orchestrator's ego TraCI server");
    std::string key = cache_key(domain, variable, id, parameter);
    if (const auto it = cache_.find(key); it != cache_.end()) return it->second;
    Value v;
    guard([&] {
      switch (domain) {
        case Domain::Simulation: v = read_simulation(variable); break;
        case Domain::Vehicle: v = read_vehicle(variable, id, parameter); break;
        case Domain::Person: v = read_person(variable, id); break;
      }
    });
    cache_.emplace(std::move(key), v);
    return v;
  }

  // From the context subscription SUMO keeps for the centre (shared with the world reader):
  // SUMO's lane tree finds the objects, and their subscribed values go into the cache, so
  // the session's reads of them cost nothing more.
  std::vector<std::string> objects_in_range(Domain centre_domain, const std::string& centre, Domain context,
                                            double range, const std::vector<int>& variables) override {
    std::vector<int> subscribed;
    for (const int v : variables)
      if (supports(context, v) && v != tc::VAR_LEADER && v != tc::VAR_PARAMETER && v != tc::TRACI_ID_LIST &&
          v != tc::ID_COUNT)
        subscribed.push_back(v);
    sumo::SubscriptionResults found;
    guard([&] {
      found = contexts::shared_contexts().within(
          centre, centre_domain == Domain::Person,
          context == Domain::Person ? tc::CMD_GET_PERSON_VARIABLE : tc::CMD_GET_VEHICLE_VARIABLE, range, subscribed);
    });
    std::vector<std::string> ids;
    ids.reserve(found.size());
    for (const auto& [id, values] : found) {
      ids.push_back(id);
      for (const auto& [variable, value] : values)
        if (auto v = to_value(variable, *value)) cache_.emplace(cache_key(context, variable, id, std::nullopt), *v);
    }
    return ids;
  }

  void command(const std::string& vehicle, const traci::EgoCommand& command) override {
    guard([&] {
      std::visit(
          [&](const auto& c) {
            using T = std::decay_t<decltype(c)>;
            if constexpr (std::is_same_v<T, traci::SetSpeed>) {
              sumo::Vehicle::setSpeed(vehicle, c.speed);
            } else if constexpr (std::is_same_v<T, traci::SlowDown>) {
              sumo::Vehicle::slowDown(vehicle, c.speed, c.duration);
            } else if constexpr (std::is_same_v<T, traci::ChangeLane>) {
              change_lane(vehicle, c.lane);
            } else if constexpr (std::is_same_v<T, traci::MoveToXY>) {
              sumo::Vehicle::moveToXY(vehicle, c.edge, c.lane, c.x, c.y, c.angle, c.keep_route, c.match_threshold);
            } else if constexpr (std::is_same_v<T, traci::SetSignals>) {
              sumo::Vehicle::setSignals(vehicle, c.signals);
            } else if constexpr (std::is_same_v<T, traci::SetSpeedMode>) {
              sumo::Vehicle::setSpeedMode(vehicle, c.mode);
            } else {
              sumo::Vehicle::setLaneChangeMode(vehicle, c.mode);
            }
          },
          command);
    });
    // Some values change at once (signals, modes): read them again.
    cache_.clear();
  }

 private:
  template <typename F>
  static void guard(F&& f) {
    try {
      f();
    } catch (const sumo::TraCIException& e) {
      throw traci::WorldError(e.what());
    }
  }

  // changeLane as a lateral move to the target lane's centre. SUMO 1.15 with the sublane
  // model (which the orchestrator runs) leaves changeLane requests of vehicles inserted at run
  // time pending forever (observed: lane change state "TraCI, urgent, left", no movement);
  // changeSublane moves them. The ego then stays there: SUMO makes no lane change of its own.
  static void change_lane(const std::string& vehicle, int target) {
    const std::string edge = sumo::Vehicle::getRoadID(vehicle);
    const int current = sumo::Vehicle::getLaneIndex(vehicle);
    const int lanes = sumo::Edge::getLaneNumber(edge);
    if (target < 0 || target >= lanes)
      throw traci::WorldError("No lane with index " + std::to_string(target) + " on edge '" + edge + "'");
    const auto width = [&](int lane) { return sumo::Lane::getWidth(edge + "_" + std::to_string(lane)); };
    double distance = -sumo::Vehicle::getLateralLanePosition(vehicle);
    for (int lane = current; lane < target; ++lane) distance += (width(lane) + width(lane + 1)) / 2;
    for (int lane = current; lane > target; --lane) distance -= (width(lane) + width(lane - 1)) / 2;
    sumo::Vehicle::changeSublane(vehicle, distance);
  }

  static std::string cache_key(Domain domain, int variable, const std::string& id,
                               const std::optional<Value>& parameter) {
    std::string key;
    key += static_cast<char>(domain);
    key += static_cast<char>(variable);
    key += id;
    if (parameter) key += '\0' + parameter_text(*parameter);
    return key;
  }

  // A subscribed value as its getter returns it (nullopt: a type the cache does not keep).
  static std::optional<Value> to_value(int variable, const sumo::TraCIResult& r) {
    if (const auto* p = dynamic_cast<const sumo::TraCIPosition*>(&r))
      return variable == tc::VAR_POSITION3D ? pos3(*p) : pos2(*p);
    if (const auto* d = dynamic_cast<const sumo::TraCIDouble*>(&r)) return Value(d->value);
    if (const auto* i = dynamic_cast<const sumo::TraCIInt*>(&r)) return Value(static_cast<std::int32_t>(i->value));
    if (const auto* t = dynamic_cast<const sumo::TraCIString*>(&r)) return Value(t->value);
    return std::nullopt;
  }

  static std::string parameter_text(const Value& v) {
    if (const auto* s = std::get_if<std::string>(&v)) return *s;
    if (const auto* d = std::get_if<double>(&v)) return std::to_string(*d);
    if (const auto* i = std::get_if<std::int32_t>(&v)) return std::to_string(*i);
    return "?";
  }

  static double number(const std::optional<Value>& v) {
    if (!v) return 0.0;
    if (const auto* d = std::get_if<double>(&*v)) return *d;
    if (const auto* i = std::get_if<std::int32_t>(&*v)) return *i;
    throw traci::WorldError("the distance must be a number");
  }

  // A variable of the served list (traci_variables.cpp) that no case below answers: a
  // mistake in this file, reported to the plug-in instead of a wrong value.
  static traci::NotImplemented unanswered(const char* domain, int variable) {
    return traci::NotImplemented(std::string(domain) + " variable " + std::to_string(variable) +
                                 " is listed as served but not read by the SUMO side");
  }

  static Value read_simulation(int variable) {
    switch (variable) {
      case tc::VAR_TIME: return sumo::Simulation::getTime();
      case tc::VAR_TIME_STEP: return static_cast<std::int32_t>(sumo::Simulation::getCurrentTime());
      case tc::VAR_DELTA_T: return sumo::Simulation::getDeltaT();
      case tc::VAR_DEPARTED_VEHICLES_IDS: return sumo::Simulation::getDepartedIDList();
      case tc::VAR_DEPARTED_VEHICLES_NUMBER: return static_cast<std::int32_t>(sumo::Simulation::getDepartedNumber());
      case tc::VAR_ARRIVED_VEHICLES_IDS: return sumo::Simulation::getArrivedIDList();
      case tc::VAR_ARRIVED_VEHICLES_NUMBER: return static_cast<std::int32_t>(sumo::Simulation::getArrivedNumber());
      case tc::VAR_MIN_EXPECTED_VEHICLES: return static_cast<std::int32_t>(sumo::Simulation::getMinExpectedNumber());
      default: throw unanswered("simulation", variable);
    }
  }

  static Value read_vehicle(int variable, const std::string& id, const std::optional<Value>& parameter) {
    using V = sumo::Vehicle;
    switch (variable) {
      case tc::TRACI_ID_LIST: return V::getIDList();
      case tc::ID_COUNT: return static_cast<std::int32_t>(V::getIDCount());
      case tc::VAR_POSITION: return pos2(V::getPosition(id));
      case tc::VAR_POSITION3D: return pos3(V::getPosition3D(id));
      case tc::VAR_SPEED: return V::getSpeed(id);
      case tc::VAR_ACCELERATION: return V::getAcceleration(id);
      case tc::VAR_ANGLE: return V::getAngle(id);
      case tc::VAR_ROAD_ID: return V::getRoadID(id);
      case tc::VAR_LANE_ID: return V::getLaneID(id);
      case tc::VAR_LANE_INDEX: return static_cast<std::int32_t>(V::getLaneIndex(id));
      case tc::VAR_LANEPOSITION: return V::getLanePosition(id);
      case tc::VAR_LANEPOSITION_LAT: return V::getLateralLanePosition(id);
      case tc::VAR_LENGTH: return V::getLength(id);
      case tc::VAR_WIDTH: return V::getWidth(id);
      case tc::VAR_TYPE: return V::getTypeID(id);
      case tc::VAR_SIGNALS: return static_cast<std::int32_t>(V::getSignals(id));
      case tc::VAR_LEADER: {
        const auto [leader, gap] = V::getLeader(id, number(parameter));
        return traci::Leader{leader, gap};
      }
      case tc::VAR_PARAMETER: {
        const auto* key = parameter ? std::get_if<std::string>(&*parameter) : nullptr;
        if (!key) throw traci::WorldError("getParameter needs the key as a string");
        return V::getParameter(id, *key);
      }
      case tc::VAR_SPEEDSETMODE: return static_cast<std::int32_t>(V::getSpeedMode(id));
      case tc::VAR_LANECHANGE_MODE: return static_cast<std::int32_t>(V::getLaneChangeMode(id));
      default: throw unanswered("vehicle", variable);
    }
  }

  static Value read_person(int variable, const std::string& id) {
    using P = sumo::Person;
    switch (variable) {
      case tc::TRACI_ID_LIST: return P::getIDList();
      case tc::ID_COUNT: return static_cast<std::int32_t>(P::getIDCount());
      case tc::VAR_POSITION: return pos2(P::getPosition(id));
      case tc::VAR_POSITION3D: return pos3(P::getPosition3D(id));
      case tc::VAR_SPEED: return P::getSpeed(id);
      case tc::VAR_ANGLE: return P::getAngle(id);
      case tc::VAR_ROAD_ID: return P::getRoadID(id);
      case tc::VAR_LANE_ID: return P::getLaneID(id);
      case tc::VAR_LANEPOSITION: return P::getLanePosition(id);
      case tc::VAR_LENGTH: return P::getLength(id);
      case tc::VAR_WIDTH: return P::getWidth(id);
      case tc::VAR_TYPE: return P::getTypeID(id);
      default: throw unanswered("person", variable);
    }
  }

  std::unordered_map<std::string, Value> cache_;
};

}  // namespace

std::unique_ptr<traci::EgoWorld> ORCH_SUMO_CONCAT(make_ego_control_, ORCH_SUMO_NS)() {
  return std::make_unique<SumoEgoControl>();
}

}  // namespace orch

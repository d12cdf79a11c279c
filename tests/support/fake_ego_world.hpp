#pragma once
// A world for the TraCI session without SUMO: a table of vehicles and persons, a clock, and
// a record of the ego commands it received. Used by the unit tests and the fuzz target.
#include <libsumo/TraCIConstants.h>

#include <cmath>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "traci_server/ego_world.hpp"

namespace orch::test {

struct FakeObject {
  double x = 0, y = 0;
  double speed = 0;
  std::string road = "E0";
  int lane = 0;
  double lane_pos = 0;
  double length = 5;
  std::map<std::string, std::string> parameters;
};

class FakeEgoWorld : public traci::EgoWorld {
 public:
  double time = 0.05;
  double dt = 0.05;
  std::map<std::string, FakeObject> vehicles;
  std::map<std::string, FakeObject> persons;
  std::vector<std::pair<std::string, traci::EgoCommand>> commands;
  int new_steps = 0;
  bool taken_over = false;

  void new_step() override { ++new_steps; }
  void take_over_ego() override { taken_over = true; }

  [[nodiscard]] bool supports(traci::Domain d, int v) const override {
    namespace tc = libsumo;
    if (d == traci::Domain::Simulation)
      return v == tc::VAR_TIME || v == tc::VAR_DELTA_T || v == tc::VAR_MIN_EXPECTED_VEHICLES ||
             v == tc::VAR_DEPARTED_VEHICLES_IDS;
    return v == tc::TRACI_ID_LIST || v == tc::ID_COUNT || v == tc::VAR_POSITION || v == tc::VAR_SPEED ||
           v == tc::VAR_ROAD_ID || v == tc::VAR_LANE_INDEX || v == tc::VAR_LANEPOSITION || v == tc::VAR_LENGTH ||
           v == tc::VAR_LEADER || v == tc::VAR_PARAMETER;
  }

  bool exists(traci::Domain d, const std::string& id) override { return table(d).count(id) > 0; }

  traci::Value read(traci::Domain d, int v, const std::string& id, const std::optional<traci::Value>& p) override {
    namespace tc = libsumo;
    if (!supports(d, v)) throw traci::NotImplemented("variable " + std::to_string(v) + " not implemented");
    if (d == traci::Domain::Simulation) {
      if (v == tc::VAR_TIME) return time;
      if (v == tc::VAR_DELTA_T) return dt;
      if (v == tc::VAR_MIN_EXPECTED_VEHICLES) return static_cast<std::int32_t>(vehicles.size());
      return std::vector<std::string>{};
    }
    auto& objects = table(d);
    if (v == tc::TRACI_ID_LIST) {
      std::vector<std::string> ids;
      for (const auto& [name, o] : objects) ids.push_back(name);
      return ids;
    }
    if (v == tc::ID_COUNT) return static_cast<std::int32_t>(objects.size());
    const auto it = objects.find(id);
    if (it == objects.end()) throw traci::WorldError((d == traci::Domain::Vehicle ? "Vehicle '" : "Person '") + id + "' is not known");
    const FakeObject& o = it->second;
    switch (v) {
      case tc::VAR_POSITION: return traci::Pos2{o.x, o.y};
      case tc::VAR_SPEED: return o.speed;
      case tc::VAR_ROAD_ID: return o.road;
      case tc::VAR_LANE_INDEX: return static_cast<std::int32_t>(o.lane);
      case tc::VAR_LANEPOSITION: return o.lane_pos;
      case tc::VAR_LENGTH: return o.length;
      case tc::VAR_LEADER: return traci::Leader{"", -1};
      default: {
        const auto* key = p ? std::get_if<std::string>(&*p) : nullptr;
        if (!key) throw traci::WorldError("getParameter needs a key");
        const auto kv = o.parameters.find(*key);
        return kv == o.parameters.end() ? std::string{} : kv->second;
      }
    }
  }

  // By brute force over the table (SUMO searches its lane tree instead).
  std::vector<std::string> objects_in_range(traci::Domain centre_domain, const std::string& centre,
                                            traci::Domain context, double range, const std::vector<int>&) override {
    auto& centres = table(centre_domain);
    const auto c = centres.find(centre);
    if (c == centres.end()) throw traci::WorldError("'" + centre + "' is not known");
    std::vector<std::string> near;  // std::map: in id order
    for (const auto& [name, o] : table(context))
      if (std::hypot(o.x - c->second.x, o.y - c->second.y) <= range) near.push_back(name);
    return near;
  }

  void command(const std::string& vehicle, const traci::EgoCommand& c) override {
    if (!vehicles.count(vehicle)) throw traci::WorldError("Vehicle '" + vehicle + "' is not known");
    if (const auto* lane = std::get_if<traci::ChangeLane>(&c); lane && (lane->lane < 0 || lane->lane > 2))
      throw traci::WorldError("No lane with index " + std::to_string(lane->lane));
    commands.emplace_back(vehicle, c);
  }

 private:
  std::map<std::string, FakeObject>& table(traci::Domain d) { return d == traci::Domain::Person ? persons : vehicles; }
};

}  // namespace orch::test

// SUMO adapter, compiled once per client library: ORCH_SUMO_NS is libsumo or libtraci and
// ORCH_SUMO_HEADER its header (see adapters/CMakeLists.txt). SUMO's exceptions and sentinel
// values stop here.
#include "sumo_simulator.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>
#include <unordered_map>
#include ORCH_SUMO_HEADER

#include "core/errors.hpp"

namespace sumo = ORCH_SUMO_NS;

namespace orch {
namespace {

using engine::ActorState;
using engine::TrackedActor;

constexpr double kForever = 1e7;  // s; "until the end of the run" for waits and stops

// SUMO angles: degrees clockwise from north. Orchestrator headings: radians
// counter-clockwise from +x.
double to_sumo_angle(double heading) {
  double deg = 90.0 - heading * 180.0 / std::numbers::pi;
  deg = std::fmod(deg, 360.0);
  return deg < 0 ? deg + 360.0 : deg;
}
double from_sumo_angle(double angle_deg) { return wrap_angle((90.0 - angle_deg) * std::numbers::pi / 180.0); }

sumo::TraCIColor parse_color(const std::string& rrggbb) {
  if (rrggbb.size() != 6) return sumo::TraCIColor(255, 255, 0, 255);
  const auto byte = [&](std::size_t i) { return std::stoi(rrggbb.substr(i, 2), nullptr, 16); };
  try {
    return sumo::TraCIColor(byte(0), byte(2), byte(4), 255);
  } catch (const std::exception&) {
    return sumo::TraCIColor(255, 255, 0, 255);
  }
}

class SumoSimulator final : public Simulator {
 public:
  ~SumoSimulator() override { close(); }

  void start(const SimulatorConfig& config) override {
    std::vector<std::string> cmd{"sumo"};
    const auto args = sumo_arguments(config);
    cmd.insert(cmd.end(), args.begin(), args.end());
    guard("starting SUMO", [&] { sumo::Simulation::start(cmd); });
    started_ = true;
  }

  void apply(const std::vector<engine::Command>& commands) override {
    for (const auto& c : commands) std::visit([this](const auto& cmd) { execute(cmd); }, c);
  }

  void advance() override {
    guard("simulation step", [] { sumo::Simulation::step(); });
  }

  engine::WorldSnapshot read(const std::vector<TrackedActor>& actors) override {
    engine::WorldSnapshot snap;
    guard("reading the simulation", [&] {
      snap.time = sumo::Simulation::getTime();
      int vehicles_tracked = 0;
      for (const auto& a : actors) {
        snap.actors.push_back(a.kind == ActorKind::Pedestrian ? read_person(a) : read_vehicle(a));
        if (a.kind != ActorKind::Pedestrian && snap.actors.back().present) ++vehicles_tracked;
      }
      snap.other_vehicles = sumo::Vehicle::getIDCount() - vehicles_tracked;
      for (const auto& c : sumo::Simulation::getCollisions())
        snap.collisions.push_back({c.collider, c.victim, c.type, c.lane, c.pos});
    });
    return snap;
  }

  double time() override {
    double t = 0;
    guard("reading the time", [&] { t = sumo::Simulation::getTime(); });
    return t;
  }

  [[nodiscard]] std::string backend() const override { return ORCH_SUMO_BACKEND; }

  std::string version() override {
    std::string v;
    guard("reading SUMO's version", [&] { v = sumo::Simulation::getVersion().second; });
    return v;
  }

  void close() override {
    if (!started_) return;
    started_ = false;
    try {
      sumo::Simulation::close();
    } catch (const std::exception&) {
      // Closing after SUMO already failed: nothing left to release.
    }
  }

 private:
  template <typename F>
  static void guard(const char* what, F&& f) {
    try {
      f();
    } catch (const sumo::TraCIException& e) {
      throw SimulationError(fmt::format("SUMO error while {}: {}", what, e.what()));
    } catch (const SimulationError&) {
      throw;
    } catch (const std::exception& e) {
      throw SimulationError(fmt::format("SUMO failed while {}: {}", what, e.what()));
    }
  }

  ActorState read_vehicle(const TrackedActor& a) {
    ActorState s;
    s.id = a.id;
    try {
      const auto front = sumo::Vehicle::getPosition(a.sumo_id);
      s.heading = from_sumo_angle(sumo::Vehicle::getAngle(a.sumo_id));
      // SUMO's vehicle position is the middle of the front bumper; actors are judged by
      // their centre.
      s.position = Vec2(front.x, front.y) - (a.length / 2) * Vec2(std::cos(s.heading), std::sin(s.heading));
      s.speed = sumo::Vehicle::getSpeed(a.sumo_id);
      s.accel = sumo::Vehicle::getAcceleration(a.sumo_id);
      s.edge = sumo::Vehicle::getRoadID(a.sumo_id);
      s.lane = sumo::Vehicle::getLaneIndex(a.sumo_id);
      s.lane_pos = sumo::Vehicle::getLanePosition(a.sumo_id) - a.length / 2;
      s.lat_offset = sumo::Vehicle::getLateralLanePosition(a.sumo_id);
      s.signals = sumo::Vehicle::getSignals(a.sumo_id);
      s.present = true;
    } catch (const sumo::TraCIException&) {
      s.present = false;  // not inserted yet, or gone
    }
    return s;
  }

  ActorState read_person(const TrackedActor& a) {
    ActorState s;
    s.id = a.id;
    try {
      const auto p = sumo::Person::getPosition(a.sumo_id);
      s.position = Vec2(p.x, p.y);
      s.heading = from_sumo_angle(sumo::Person::getAngle(a.sumo_id));
      s.speed = sumo::Person::getSpeed(a.sumo_id);
      s.edge = sumo::Person::getRoadID(a.sumo_id);
      const std::string lane = sumo::Person::getLaneID(a.sumo_id);
      const auto underscore = lane.rfind('_');
      s.lane = underscore == std::string::npos ? -1 : std::stoi(lane.substr(underscore + 1));
      s.lane_pos = sumo::Person::getLanePosition(a.sumo_id);
      s.present = true;
    } catch (const sumo::TraCIException&) {
      s.present = false;
    }
    return s;
  }

  std::string make_type(const std::string& base, const std::string& sumo_id, const ModelInfo& m,
                        const std::string& color) {
    const std::string type = "orch." + sumo_id;
    sumo::VehicleType::copy(base, type);
    sumo::VehicleType::setLength(type, m.length);
    sumo::VehicleType::setWidth(type, m.width);
    sumo::VehicleType::setHeight(type, m.height);
    if (!color.empty()) sumo::VehicleType::setColor(type, parse_color(color));
    return type;
  }

  void execute(const engine::SpawnVehicle& c) {
    guard("inserting a vehicle", [&] {
      const std::string type = make_type("DEFAULT_VEHTYPE", c.actor.sumo_id, c.model, c.color);
      sumo::VehicleType::setVehicleClass(type, c.model.vclass);
      sumo::VehicleType::setShapeClass(type, c.model.gui_shape);
      // Deterministic driver: no dawdling, no speed deviation.
      sumo::VehicleType::setImperfection(type, 0.0);
      sumo::VehicleType::setSpeedFactor(type, 1.0);
      sumo::VehicleType::setSpeedDeviation(type, 0.0);
      const std::string route = "orch.route." + c.actor.sumo_id;
      sumo::Route::add(route, c.route);
      const std::string lane_id = c.edge + "_" + std::to_string(c.lane);
      const double lane_length = sumo::Lane::getLength(lane_id);
      const double front = std::clamp(c.lane_pos + c.actor.length / 2, 0.0, lane_length);
      sumo::Vehicle::add(c.actor.sumo_id, route, type, "now", std::to_string(c.lane), fmt::format("{:.3f}", front),
                         fmt::format("{:.3f}", c.speed));
      if (c.scripted) {
        // Placed by the orchestrator every step: SUMO must neither slow nor steer it.
        sumo::Vehicle::setSpeedMode(c.actor.sumo_id, 0);
        sumo::Vehicle::setLaneChangeMode(c.actor.sumo_id, 0);
      } else {
        // The built-in ego keeps the lane of its route and drives at the route's speed.
        sumo::Vehicle::setLaneChangeMode(c.actor.sumo_id, 0);
        if (c.max_speed > 0) sumo::Vehicle::setMaxSpeed(c.actor.sumo_id, c.max_speed);
        if (c.keep_lateral) sumo::VehicleType::setLateralAlignment(type, "arbitrary");
      }
    });
  }

  void execute(const engine::SpawnPerson& c) {
    guard("inserting a pedestrian", [&] {
      const std::string type = make_type("DEFAULT_PEDTYPE", c.actor.sumo_id, c.model, c.color);
      sumo::Person::add(c.actor.sumo_id, c.edge, c.lane_pos, sumo::DEPARTFLAG_NOW, type);
      // Stands until placed elsewhere; poses come from the orchestrator every step.
      sumo::Person::appendWaitingStage(c.actor.sumo_id, kForever, "scenario actor");
    });
  }

  void execute(const engine::SetPose& c) {
    guard("placing an actor", [&] {
      const double angle = to_sumo_angle(c.heading);
      if (c.kind == ActorKind::Pedestrian) {
        sumo::Person::moveToXY(c.sumo_id, c.edge, c.position.x(), c.position.y(), angle, 2);
        return;
      }
      const Vec2 front = c.position + (c.length / 2) * Vec2(std::cos(c.heading), std::sin(c.heading));
      sumo::Vehicle::moveToXY(c.sumo_id, c.edge, c.lane, front.x(), front.y(), angle, 2);
      if (!c.scripted) return;
      // Without an explicit speed SUMO derives one from the lane positions, which jump when
      // the vehicle crosses into another lane of a curved edge: followers would see a
      // phantom brake. The scenario's speed is exact.
      sumo::Vehicle::setSpeed(c.sumo_id, c.speed);
      if (c.signals != 0 || signals_sent_[c.sumo_id] != 0) {
        sumo::Vehicle::setSignals(c.sumo_id, c.signals);
        signals_sent_[c.sumo_id] = c.signals;
      }
    });
  }

  void execute(const engine::SetSignals& c) {
    guard("setting signals", [&] { sumo::Vehicle::setSignals(c.sumo_id, c.signals); });
  }

  void execute(const engine::SetMaxSpeed& c) {
    guard("setting a speed", [&] { sumo::Vehicle::setMaxSpeed(c.sumo_id, c.speed); });
  }

  void execute(const engine::SetStop& c) {
    guard("setting the ego's stop", [&] {
      const double lane_length = sumo::Lane::getLength(c.edge + "_" + std::to_string(c.lane));
      const double front = std::clamp(c.lane_pos + c.length / 2, 0.0, lane_length);
      sumo::Vehicle::setStop(c.sumo_id, c.edge, front, c.lane, kForever);
    });
  }

  void execute(const engine::SetParameter& c) {
    guard("setting a parameter", [&] { sumo::Vehicle::setParameter(c.sumo_id, c.key, c.value); });
  }

  bool started_ = false;
  std::unordered_map<std::string, int> signals_sent_;
};

}  // namespace

std::unique_ptr<Simulator> ORCH_SUMO_FACTORY() { return std::make_unique<SumoSimulator>(); }

}  // namespace orch

#pragma once
// A fake simulator for unit tests of the engine's pure logic: it places scripted actors
// exactly where SetPose says and moves the ego at a speed the test chooses along its route.
// Real SUMO behaviour is covered by the integration and end-to-end tests.
#include <map>
#include <string>
#include <vector>

#include "scenario_executor_engine/engine.hpp"

namespace orch::test {

class FakeWorld {
 public:
  FakeWorld(engine::Engine& engine, const WaypointRoute& ego_route, double step)
      : engine_(engine), ego_route_(ego_route), step_(step) {
    tracked_ = engine.tracked();
  }

  // Starts the engine and places everything for the first step.
  void start(double ego_s) {
    ego_s_ = ego_s;
    apply(engine_.start().commands);
  }

  // One step: time advances, the ego moves, the engine reacts. Returns the engine's events.
  std::vector<engine::Event> step() {
    time_ += step_;
    ego_s_ += ego_speed * step_;
    // Poses commanded during the last step are where the actors are now (as in SUMO).
    for (const auto& [id, p] : pending_) shown_[id] = p;
    sim::WorldSnapshot snap;
    snap.time = time_;
    for (const auto& t : tracked_) {
      sim::ActorState a;
      a.id = t.id;
      if (t.sumo_id == "ego") {
        a.present = !ego_gone;
        a.position = ego_route_.line.point_at(ego_s_);
        a.heading = ego_route_.line.heading_at(ego_s_);
        a.speed = ego_speed;
      } else if (auto it = shown_.find(t.sumo_id); it != shown_.end()) {
        a.present = !gone.count(t.id);
        a.position = it->second.position;
        a.heading = it->second.heading;
        a.speed = it->second.speed;
      }
      snap.actors.push_back(a);
    }
    snap.nearby = nearby;
    last_ = snap;
    auto out = engine_.step(snap);
    apply(out.commands);
    return out.events;
  }

  // Steps until time reaches t (inclusive).
  void run_until(double t) {
    while (time_ < t - 1e-9) step();
  }

  [[nodiscard]] double time() const { return time_; }
  // Where an actor is at time(): the pose commanded on the step before.
  [[nodiscard]] const sim::SetPose& pose(const std::string& sumo_id) const { return shown_.at(sumo_id); }
  [[nodiscard]] const sim::WorldSnapshot& last() const { return last_; }
  [[nodiscard]] int signals(const std::string& sumo_id) const { return shown_.at(sumo_id).signals; }
  [[nodiscard]] const std::vector<sim::Command>& history() const { return history_; }

  double ego_speed = 0;                      // m/s, set by the test
  bool ego_gone = false;
  std::set<int> gone;                        // actors the "simulator" removed
  std::vector<sim::NearbyVehicle> nearby;  // background traffic the test injects

 private:
  void apply(const std::vector<sim::Command>& commands) {
    for (const auto& c : commands) {
      history_.push_back(c);
      if (const auto* p = std::get_if<sim::SetPose>(&c)) pending_[p->sumo_id] = *p;
    }
  }

  engine::Engine& engine_;
  const WaypointRoute& ego_route_;
  double step_;
  double time_ = 0;
  double ego_s_ = 0;
  std::vector<sim::TrackedActor> tracked_;
  std::map<std::string, sim::SetPose> pending_;  // commanded, shown after the next step
  std::map<std::string, sim::SetPose> shown_;
  std::vector<sim::Command> history_;
  sim::WorldSnapshot last_;
};

}  // namespace orch::test

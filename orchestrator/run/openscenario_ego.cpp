#include "run/openscenario_ego.hpp"

#include "run/ego_link.hpp"

namespace orch {

double storyboard_desired_speed(const openscenario::EntityState& state, double last) {
  if (state.speed_profile) return state.speed_profile->to;
  return last >= 0 ? last : state.speed;
}

std::string OpenScenarioEgo::sumo_id() const { return external_ ? kEgoSumoId : name_; }

OpenScenarioEgo::Driver OpenScenarioEgo::driver(const openscenario::EntityState& state) const {
  if (external_ && state.controller_active) return Driver::Plugin;
  if (state.lateral_profile) return Driver::Storyboard;
  return Driver::Sumo;
}

const char* OpenScenarioEgo::label(Driver d) {
  switch (d) {
    case Driver::Plugin: return "plugin";
    case Driver::Storyboard: return "script";
    case Driver::Sumo: break;
  }
  return "sumo";
}

double OpenScenarioEgo::spawn_speed(const openscenario::EntityState& state) {
  desired_speed_ = storyboard_desired_speed(state, -1);
  return desired_speed_;
}

std::vector<sim::Command> OpenScenarioEgo::commands(const openscenario::EntityState& state, sim::SetPose pose) {
  std::vector<sim::Command> out;
  const Driver d = driver(state);
  const bool hand_over = d == Driver::Plugin;
  if (external_ && hand_over != handed_over_) {
    out.push_back(sim::SetParameter{sumo_id(), "orch.hand_over", hand_over ? "1" : "0"});
    handed_over_ = hand_over;
  }
  if (d == Driver::Plugin) return out;  // the system under test alone
  const double desired = storyboard_desired_speed(state, desired_speed_);
  if (desired != desired_speed_) out.push_back(sim::SetMaxSpeed{sumo_id(), desired});
  desired_speed_ = desired;
  if (d == Driver::Storyboard) {
    pose.sumo_id = sumo_id();
    pose.scripted = false;  // placed; SUMO keeps its own speed handling
    out.push_back(std::move(pose));
  }
  return out;
}

}  // namespace orch

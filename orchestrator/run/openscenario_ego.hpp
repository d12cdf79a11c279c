#pragma once
// The ego entity of an OpenSCENARIO run in SUMO (docs/openscenario.md, "The ego"). Pure:
// decides each step who moves the ego and which commands SUMO gets for it.
//  - SUMO drives it (car-following) with the storyboard's speed target as desired speed;
//  - during a LaneChangeAction or LaneOffsetAction on it, the storyboard moves it: SUMO's
//    vehicle is placed on the storyboard's pose each step (speed left to SUMO, which takes
//    it from the move), and SUMO drives again from the step the action ends;
//  - with an external ego (--ego-port) its SUMO id is `ego` (the only vehicle a plug-in may
//    command); once an ActivateControllerAction activates its controller, the plug-in
//    drives: the orchestrator sends it nothing but the vehicle parameter `orch.hand_over`
//    ("1" on activation, "0" when deactivated), as ScenarioExecutor's hand_over does.
#include <string>
#include <vector>

#include "sim/world.hpp"
#include "openscenario/entity_motion.hpp"

namespace orch {

// The desired speed SUMO gets for an entity it drives: the storyboard's speed target (the
// last SpeedAction's), else `last` (the one sent before), else (`last` < 0) its speed now.
double storyboard_desired_speed(const openscenario::EntityState& state, double last);

class OpenScenarioEgo {
 public:
  enum class Driver { Sumo, Storyboard, Plugin };

  OpenScenarioEgo(std::string name, bool external) : name_(std::move(name)), external_(external) {}

  [[nodiscard]] const std::string& name() const { return name_; }
  [[nodiscard]] bool external() const { return external_; }
  // "ego" with an external ego (ego_link.hpp's kEgoSumoId), else the entity's name.
  [[nodiscard]] std::string sumo_id() const;
  // Who moves the ego in the step to come, given its storyboard state.
  [[nodiscard]] Driver driver(const openscenario::EntityState& state) const;
  // The trace's `driver` column: sumo, script (the storyboard) or plugin.
  [[nodiscard]] static const char* label(Driver d);

  // The desired speed SUMO gets at the spawn: the storyboard's target, else its speed.
  double spawn_speed(const openscenario::EntityState& state);
  // Commands for the spawned ego this step; `pose` puts its centre where the storyboard has
  // it (used while the storyboard moves it).
  std::vector<sim::Command> commands(const openscenario::EntityState& state, sim::SetPose pose);

 private:
  std::string name_;
  bool external_ = false;
  double desired_speed_ = -1;  // last sent
  bool handed_over_ = false;   // orch.hand_over last sent as "1"
};

}  // namespace orch

#pragma once
// SynchronizeAction in the storyboard: its targets resolved when it starts, and each step the
// distances and speeds synchronize_step needs, measured on the entities (synchronize.hpp).
#include <string>

#include "openscenario/action_start.hpp"
#include "openscenario/synchronize.hpp"

namespace orch::openscenario {

// Resolves both target positions now (relative ones against the entities now). Throws
// MapError when the master has no position.
SynchronizeRun start_synchronize(const SynchronizeAction& a, ActionContext& ctx);

// One step: sets the entity's speed for the next step; true when the action is done.
bool step_synchronize(const SynchronizeAction& a, SynchronizeRun& run, const std::string& entity, ActionContext& ctx);

// Distance from the entity to `target` along what it drives: its trajectory, else its road
// and the lanes ahead of it (route plan or straight on); the straight line when the target
// is on none of them (as esmini, when its road network has no path).
double distance_ahead(const EntityState& state, const SynchronizeTarget& target, const opendrive::RoadNetwork& roads);

}  // namespace orch::openscenario

#pragma once
// LongitudinalDistanceAction (distance_keeping.cpp): the entity placed at the distance at
// once, or driven towards it within its DynamicConstraints.
#include <string>

#include "openscenario/action_start.hpp"

namespace orch::openscenario {

// Whether the action has DynamicConstraints (then the entity drives to the distance).
bool has_limits(const LongitudinalDistanceAction& a);
// Throws MapError unless the entity and the one it keeps the distance to are placed.
void check_distance_entities(const LongitudinalDistanceAction& a, const EntityState& state, ActionContext& ctx,
                             const std::string& entity);
// Without DynamicConstraints: placed at the distance at once, at the referenced speed.
void longitudinal_distance(const LongitudinalDistanceAction& a, EntityState& state, ActionContext& ctx,
                           const std::string& entity);
// With them: the speed for the coming step towards the distance; true once there (within
// 0.1 m, whatever the speed). `acceleration`: the one of the step before, its jerk limits' start
// (updated).
bool approach_distance(const LongitudinalDistanceAction& a, EntityState& state, ActionContext& ctx,
                       const std::string& entity, double& acceleration);

}  // namespace orch::openscenario

#pragma once
// LateralDistanceAction (lateral_distance.cpp): the entity keeps a lateral distance to
// another, moved sideways by the storyboard's own motion model (never by SUMO: an entity
// that follows the storyboard is placed by the orchestrator every step).
//
// The lateral coordinate is the road's t (coordinateSystem road or lane; the other entity
// measured on the same road by its t, on another road by its offset along the road's
// normal at the entity's s), or the offset along the normal of the entity's own heading
// (coordinateSystem entity). The target is the other's coordinate plus the distance (with
// freespace plus the half widths of both bounding boxes) to the side the displacement asks
// for, "left" and "right" as seen in the other entity's direction of travel; "any" keeps the
// side the entity is on. Without a distance the one at the start is kept. Without
// DynamicConstraints the entity is put there at once; with them it moves there with a
// lateral speed up to maxSpeed: with maxAcceleration by esmini's damped spring (within
// +-maxAcceleration, slowing within maxDeceleration), without it straight at up to maxSpeed,
// slowed by at most maxDeceleration (braking in time to stop on the target).
#include <optional>
#include <string>

#include "openscenario/action_start.hpp"

namespace orch::openscenario {

// The lateral speed (m/s, positive to the lateral coordinate's +) for one step of `dt` from
// `speed` towards a target `error` metres away, within the limits (absent: unlimited). Pure.
double lateral_speed_step(double error, double speed, double dt, std::optional<double> max_speed,
                          std::optional<double> max_acceleration, std::optional<double> max_deceleration);

// One step of the action for `entity`, after the step's move along the lane. When it
// `starts`, an entity with DynamicConstraints only measures and moves from the second step
// after its start on, as esmini moves it (like a lane offset, LateralProfile::lane_offset;
// the standard gives the constraints, not how a player steps them); one without is put on
// the target at once. A step that moves it sideways at v_lat takes back what the lane's
// move gave beyond sqrt(v^2 - v_lat^2) along s (the speed is along its path, as a lane
// change's). True once the entity is on its target (within 1 cm, at rest sideways). Throws
// MapError unless both are placed on a road.
bool keep_lateral_distance(const LateralDistanceAction& a, EntityState& state, ActionContext& ctx,
                           const std::string& entity, LateralDistanceRun& run, bool starts = false);

}  // namespace orch::openscenario

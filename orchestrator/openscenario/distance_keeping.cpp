// LongitudinalDistanceAction: keeping a distance or time gap to another entity along its
// road, placed at once (no DynamicConstraints) or driven there within the constraints.
#include "openscenario/distance_keeping.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "core/errors.hpp"

namespace orch::openscenario {
namespace {

// Where the entity keeps the distance: the s on the referenced entity's road, and the
// direction of travel there; `error`: the metres the entity is short of it (> 0: behind it).
struct DistanceTarget {
  const EntityState* ref = nullptr;
  double s = 0;
  int direction = 1;
  double error = 0;
};

DistanceTarget distance_target(const LongitudinalDistanceAction& a, const EntityState& state, ActionContext& ctx,
                               const std::string& entity) {
  const EntityState& ref = ctx.entities.at(a.entity);
  if (!ref.placed) throw MapError(fmt::format("entity \"{}\" has no position yet", a.entity));
  if (!state.placed) throw MapError(fmt::format("entity \"{}\" has no position yet", entity));
  const opendrive::Road& road = ctx.roads.road(ref.road_id);
  const int direction = travel_direction(ref, road);
  // How far the referenced entity is ahead: along its road when both are on it, else (one
  // past a junction or a road's end) along the entity's heading, as the distance in the
  // entity's frame (the standard's default coordinateSystem, and esmini's measure).
  const bool same_road = state.road_id == ref.road_id;
  const double along =
      same_road ? (ref.s - state.s) * direction
                : (ref.pose.x - state.pose.x) * std::cos(state.pose.heading) +
                      (ref.pose.y - state.pose.y) * std::sin(state.pose.heading);
  double gap = a.distance ? *a.distance : *a.time_gap * ref.speed;
  const bool ahead = a.displacement == "leadingReferencedEntity" || (a.displacement == "any" && along <= 0);
  if (a.freespace) {
    const BoundingBox& own = ctx.scenario.entity(entity)->box;
    const BoundingBox& other = ctx.scenario.entity(a.entity)->box;
    gap += ahead ? (other.center_x + other.length / 2) - (own.center_x - own.length / 2)
                 : (own.center_x + own.length / 2) - (other.center_x - other.length / 2);
  }
  return {&ref, ref.s + direction * (ahead ? gap : -gap), direction, along + (ahead ? gap : -gap)};
}

}  // namespace

void check_distance_entities(const LongitudinalDistanceAction& a, const EntityState& state, ActionContext& ctx,
                             const std::string& entity) {
  (void)distance_target(a, state, ctx, entity);
}

bool has_limits(const LongitudinalDistanceAction& a) {
  return a.max_acceleration || a.max_deceleration || a.max_speed;
}

// Without DynamicConstraints: placed at the distance at once, at the referenced speed.
void longitudinal_distance(const LongitudinalDistanceAction& a, EntityState& state, ActionContext& ctx,
                           const std::string& entity) {
  const DistanceTarget target = distance_target(a, state, ctx, entity);
  state.road_id = target.ref->road_id;
  state.s = target.s;
  state.direction = target.direction;
  state.speed = target.ref->speed;
  update_pose(state, ctx.roads);
}

// With DynamicConstraints: the entity stays in its lane and sets its speed for the next
// step towards the distance. The standard gives the constraints only as limits and leaves the
// law to the controller; it is esmini's damped spring (as esmini, which the standard allows):
// a = k e - 2 sqrt(k) (v - v_ref), critically damped, e the metres short of the target, v_ref
// the referenced speed, the stiffness k = 0.4 1/m times maxDeceleration while behind the
// target (e > 0: it will brake on arriving), times maxAcceleration while beyond it (either
// stands in for the other when absent; with neither, the speed jumps to [0, maxSpeed]'s end
// towards the target). The jerk limits are read as esmini applies them (the standard gives
// no more than their names: "maxAccelerationRate: Maximum acceleration rate the distance
// controller is allowed to use for keeping the distance", the same for deceleration): while
// the law asks for an acceleration (a >= 0), maxAccelerationRate bounds how fast the
// acceleration rises towards it; while it asks for a deceleration (a < 0),
// maxDecelerationRate bounds how fast it falls; easing off (an acceleration falling towards
// a smaller one, a deceleration rising towards a smaller one) is not bounded.
// Always within the acceleration limits and [0, maxSpeed], each capped by the vehicle's
// Performance. True once within kDistanceReached m of the target: the standard ends a
// non-continuous one when the distance is reached (its speed need not be the referenced one
// yet), as esmini (distance_test.xosc: ended 0.094 m from the distance, 0.147 m/s faster than
// the referenced car; measured on four more distances and limits, always as the distance
// falls below 0.1 m).
constexpr double kDistanceReached = 0.1;
constexpr double kSpringPerAcceleration = 0.4;  // esmini's spring constant, 1/m
bool approach_distance(const LongitudinalDistanceAction& a, EntityState& state, ActionContext& ctx,
                       const std::string& entity, double& acceleration) {
  const DistanceTarget target = distance_target(a, state, ctx, entity);
  const double unlimited = std::numeric_limits<double>::infinity();
  double accelerate = a.max_acceleration.value_or(unlimited);
  double decelerate = a.max_deceleration.value_or(unlimited);
  double max_speed = a.max_speed.value_or(unlimited);
  // The vehicle's Performance caps them too: the standard gives it as the vehicle's maximum,
  // a physical limit (as a SpeedAction's transition; esmini does the same).
  if (const Entity* e = ctx.scenario.entity(entity); e != nullptr && e->performance) {
    if (e->performance->max_acceleration > 0) accelerate = std::min(accelerate, e->performance->max_acceleration);
    if (e->performance->max_deceleration > 0) decelerate = std::min(decelerate, e->performance->max_deceleration);
    if (e->performance->max_speed > 0) max_speed = std::min(max_speed, e->performance->max_speed);
  }
  const double error = target.error;
  const double v_ref = target.ref->speed;
  double tension = error > 0 ? decelerate : accelerate;
  if (std::isinf(tension)) tension = error > 0 ? accelerate : decelerate;
  if (!(ctx.dt > 0)) {
    acceleration = 0;  // no step to limit the change over: the speed stays
    state.acceleration = 0;
  } else {
    const double before = state.speed;
    double change = 0;
    if (std::isinf(tension)) {
      const double wanted = error > 0 ? max_speed : error < 0 ? 0.0 : v_ref;  // no limit to ease in by
      change = (std::clamp(wanted, 0.0, max_speed) - before) / ctx.dt;
    } else {
      const double k = kSpringPerAcceleration * tension;
      change = k * error - 2 * std::sqrt(k) * (before - v_ref);
    }
    change = std::clamp(change, -decelerate, accelerate);
    // The jerk limits, on a build-up only (from the step before's acceleration).
    if (change < 0 && change < acceleration)
      change = std::max(change, acceleration - a.max_deceleration_rate.value_or(unlimited) * ctx.dt);
    else if (change >= 0 && change > acceleration)
      change = std::min(change, acceleration + a.max_acceleration_rate.value_or(unlimited) * ctx.dt);
    // Within [0, maxSpeed] (an entity already beyond either slows or speeds up into it).
    state.speed = std::clamp(before + change * ctx.dt, std::min(0.0, before), std::max(max_speed, before));
    acceleration = change;  // the law's, the next step's jerk limits start from it (as esmini's)
    state.acceleration = (state.speed - before) / ctx.dt;
  }
  return std::abs(error) < kDistanceReached;
}

}  // namespace orch::openscenario

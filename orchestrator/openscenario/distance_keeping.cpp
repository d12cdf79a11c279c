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
// direction of travel there.
struct DistanceTarget {
  const EntityState* ref = nullptr;
  double s = 0;
  int direction = 1;
};

DistanceTarget distance_target(const LongitudinalDistanceAction& a, const EntityState& state, ActionContext& ctx,
                               const std::string& entity) {
  const EntityState& ref = ctx.entities.at(a.entity);
  if (!ref.placed) throw MapError(fmt::format("entity \"{}\" has no position yet", a.entity));
  if (!state.placed) throw MapError(fmt::format("entity \"{}\" has no position yet", entity));
  const opendrive::Road& road = ctx.roads.road(ref.road_id);
  const int direction = travel_direction(ref, road);
  double gap = a.distance ? *a.distance : *a.time_gap * ref.speed;
  const bool ahead = a.displacement == "leadingReferencedEntity" ||
                     (a.displacement == "any" && (state.s - ref.s) * direction >= 0);
  if (a.freespace) {
    const BoundingBox& own = ctx.scenario.entity(entity)->box;
    const BoundingBox& other = ctx.scenario.entity(a.entity)->box;
    gap += ahead ? (other.center_x + other.length / 2) - (own.center_x - own.length / 2)
                 : (own.center_x + own.length / 2) - (other.center_x - other.length / 2);
  }
  return {&ref, ref.s + direction * (ahead ? gap : -gap), direction};
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
// step towards the distance. Without jerk limits: the speed from which braking (or speeding
// up) at the limit ends at the referenced speed on the target, v = v_ref + sign(e)
// sqrt(2 a |e|) (e: metres short of the target), within [0, maxSpeed], reached with an
// acceleration within maxAcceleration / maxDeceleration. That law asks for a full swing of
// the acceleration at the target, which a jerk limit cannot give (it overshoots and swings
// round the target), so with maxAccelerationRate / maxDecelerationRate the acceleration is
// a critically damped spring's, a = w^2 e - 2 w (v - v_ref), with w = J / (the larger
// acceleration limit), J the smaller rate: the loop is no faster than the acceleration can
// swing across its range; it changes by at most maxAccelerationRate (growing) /
// maxDecelerationRate (falling) per second (the same reading of the rates as a
// SpeedProfileAction's), within the acceleration limits and [0, maxSpeed]. Absent limits:
// none. True once within kDistanceReached m and m/s of the target and the referenced speed.
constexpr double kDistanceReached = 0.1;
bool approach_distance(const LongitudinalDistanceAction& a, EntityState& state, ActionContext& ctx,
                       const std::string& entity, double& acceleration) {
  const DistanceTarget target = distance_target(a, state, ctx, entity);
  const double unlimited = std::numeric_limits<double>::infinity();
  const double accelerate = a.max_acceleration.value_or(unlimited);
  const double decelerate = a.max_deceleration.value_or(unlimited);
  const double max_speed = a.max_speed.value_or(unlimited);
  const double error = state.road_id == target.ref->road_id ? (target.s - state.s) * target.direction : 0.0;
  const double v_ref = target.ref->speed;
  double wanted = v_ref + std::copysign(std::sqrt(2 * (error > 0 ? decelerate : accelerate) * std::abs(error)), error);
  wanted = std::clamp(wanted, 0.0, max_speed);
  const bool jerk_limited = a.max_acceleration_rate || a.max_deceleration_rate;
  if (!(ctx.dt > 0)) {
    acceleration = 0;  // no step to limit the change over: the speed stays
  } else {
    const double before = state.speed;
    double change = (wanted - before) / ctx.dt;
    if (jerk_limited) {
      const double rate = std::min(a.max_acceleration_rate.value_or(unlimited), a.max_deceleration_rate.value_or(unlimited));
      double range = std::max(std::isinf(accelerate) ? 0.0 : accelerate, std::isinf(decelerate) ? 0.0 : decelerate);
      if (!(range > 0)) range = rate;  // no acceleration limit: a 1 s loop
      const double w = rate / range;
      change = w * w * error - 2 * w * (before - v_ref);
    }
    change = std::clamp(change, -decelerate, accelerate);
    change = std::clamp(change, acceleration - a.max_deceleration_rate.value_or(unlimited) * ctx.dt,
                        acceleration + a.max_acceleration_rate.value_or(unlimited) * ctx.dt);
    change = std::clamp(change, -decelerate, accelerate);
    // Within [0, maxSpeed] (an entity already beyond either slows or speeds up into it).
    state.speed = std::clamp(before + change * ctx.dt, std::min(0.0, before), std::max(max_speed, before));
    acceleration = (state.speed - before) / ctx.dt;
  }
  state.acceleration = acceleration;
  return std::abs(error) <= kDistanceReached && std::abs(state.speed - v_ref) <= kDistanceReached;
}

}  // namespace orch::openscenario

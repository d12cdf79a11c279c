#include "openscenario/lateral_distance.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "core/errors.hpp"

namespace orch::openscenario {

namespace {

constexpr double kOnTarget = 0.01;  // m
constexpr double kSpringPerAcceleration = 0.4;  // esmini's spring constant, 1/m per m/s^2

double half_width(const Scenario& scenario, const std::string& name) {
  const Entity* e = scenario.entity(name);
  return e ? e->box.width / 2 : 0.0;
}

}  // namespace

double lateral_speed_step(double error, double speed, double dt, std::optional<double> max_speed,
                          std::optional<double> max_acceleration, std::optional<double> max_deceleration) {
  if (dt <= 0) return 0;
  if (max_acceleration && *max_acceleration > 0) {
    // With maxAcceleration: esmini's damped spring (the standard gives the constraints only as
    // limits, not the law), the one its LongitudinalDistanceAction uses: a = k e - 2 sqrt(k) v,
    // critically damped, k = 0.4 1/m times maxAcceleration, within +-maxAcceleration
    // (measured against esmini: its lateral positions to 0.5 mm, maxSpeed 3 or 10 and
    // maxAcceleration 2 or 5). esmini ignores maxDeceleration; here slowing down stays within
    // it too, as the standard has it a limit.
    const double k = kSpringPerAcceleration * *max_acceleration;
    double acceleration = std::clamp(k * error - 2 * std::sqrt(k) * speed, -*max_acceleration, *max_acceleration);
    if (max_deceleration && acceleration * speed < 0)
      acceleration = std::clamp(acceleration, -*max_deceleration, *max_deceleration);
    double next = speed + acceleration * dt;
    if (max_speed) next = std::clamp(next, -*max_speed, *max_speed);
    return next;
  }
  // Without it: the speed that reaches the target in this step, within maxSpeed and, to stop
  // on the target, within what maxDeceleration can still brake to rest over the distance left.
  double wanted = error / dt;
  if (max_speed) wanted = std::clamp(wanted, -*max_speed, *max_speed);
  if (max_deceleration) {
    const double stoppable = std::sqrt(2 * *max_deceleration * std::abs(error));
    wanted = std::clamp(wanted, -stoppable, stoppable);
  }
  const double change = wanted - speed;
  // Away from rest (same sign, larger) is free; towards rest within maxDeceleration.
  const bool speeding_up = std::abs(wanted) > std::abs(speed) && wanted * speed >= 0;
  if (speeding_up || !max_deceleration) return wanted;
  return speed + std::clamp(change, -*max_deceleration * dt, *max_deceleration * dt);
}

bool keep_lateral_distance(const LateralDistanceAction& a, EntityState& state, ActionContext& ctx,
                           const std::string& entity, LateralDistanceRun& run, bool starts) {
  const auto other_it = ctx.entities.find(a.entity);
  if (!state.placed || state.road_id.empty() || other_it == ctx.entities.end() || !other_it->second.placed)
    throw MapError(fmt::format("LateralDistanceAction of \"{}\": both it and \"{}\" need a place on a road", entity,
                               a.entity));
  const EntityState& other = other_it->second;
  const opendrive::Road& road = ctx.roads.road(state.road_id);
  const double s = std::clamp(state.s, 0.0, road.length);
  // The lateral axis: the road's normal at the entity (t), or the entity's own left.
  const bool road_frame = a.coordinate_system != "entity";
  const double axis_heading = road_frame ? road.plan_view.pose(s).heading : state.pose.heading;
  const double nx = -std::sin(axis_heading), ny = std::cos(axis_heading);
  const double self = road_frame ? state.t : 0.0;
  const double others = road_frame && other.road_id == state.road_id
                            ? other.t
                            : self + (other.pose.x - state.pose.x) * nx + (other.pose.y - state.pose.y) * ny;
  // "Left" of the other in its direction of travel: +t along s, -t against it.
  const int other_direction = other.road_id == state.road_id ? travel_direction(other, road) : travel_direction(state, road);
  const double left = road_frame ? other_direction : 1.0;
  const double freespace = a.freespace ? half_width(ctx.scenario, entity) + half_width(ctx.scenario, a.entity) : 0.0;
  std::optional<double>& kept = run.kept;
  if (!kept) kept = a.distance ? *a.distance : std::max(std::abs(self - others) - freespace, 0.0);
  double side = a.displacement == "leftToReferencedEntity"    ? left
                : a.displacement == "rightToReferencedEntity" ? -left
                : (self - others) * left >= 0                 ? left
                                                              : -left;
  const double target = others + side * (*kept + freespace);
  const double error = target - self;
  const bool at_once = ctx.dt <= 0 || (!a.max_speed && !a.max_acceleration && !a.max_deceleration);
  if (starts && !at_once) return false;
  if (!at_once && !run.waited) {  // the step after its start: still where it was
    run.waited = true;
    return false;
  }
  const double rate = at_once ? 0.0
                              : lateral_speed_step(error, run.speed, ctx.dt, a.max_speed, a.max_acceleration,
                                                   a.max_deceleration);
  const double move = at_once ? error : rate * ctx.dt;
  run.speed = rate;
  // Along the axis; in the road frame that is the entity's t.
  state.lateral_profile.reset();
  state.path.reset();
  if (road_frame) {
    // The step's move along the lane went at the full speed: back by what the sideways
    // motion takes (ds = sqrt(v^2 - v_lat^2) dt, over the path's stretch at t on a curve).
    if (!at_once && rate != 0) {
      const double along = std::sqrt(std::max(state.speed * state.speed - rate * rate, 0.0));
      const double s_now = std::clamp(state.s, 0.0, road.length);
      const double stretch = 1.0 - road.plan_view.curvature(s_now) * state.t;
      state.s = std::clamp(state.s - travel_direction(state, road) * (std::abs(state.speed) - along) * ctx.dt /
                                         (stretch > 0.1 ? stretch : 0.1),
                           0.0, road.length);
    }
    state.offset += move;
    state.lateral_rate = at_once ? 0.0 : rate;
    update_pose(state, ctx.roads);
  } else {
    state.pose.x += move * nx;
    state.pose.y += move * ny;
    state.lateral_rate = 0;
    relocate(state, ctx.roads);
    update_pose(state, ctx.roads);
  }
  // Beyond its lane: on the lane it is now in (the offset measured from that lane).
  if (const auto lane = road.lane_at(std::clamp(state.s, 0.0, road.length), state.t); lane && *lane != 0 && *lane != state.lane) {
    state.offset = state.t - road.lane_center_t(*lane, std::clamp(state.s, 0.0, road.length));
    state.lane = *lane;
  }
  const bool reached = std::abs(error - move) < kOnTarget && (at_once || std::abs(run.speed) < 0.05);
  if (reached) state.lateral_rate = run.speed = 0;
  return reached;
}

}  // namespace orch::openscenario

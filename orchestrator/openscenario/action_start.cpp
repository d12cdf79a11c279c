#include "openscenario/action_start.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "core/errors.hpp"
#include "core/exhaustive.hpp"
#include "openscenario/distance_keeping.hpp"
#include "openscenario/expression.hpp"
#include "openscenario/lane_offset.hpp"
#include "openscenario/lateral_distance.hpp"
#include "openscenario/random_route.hpp"
#include "openscenario/route_plan.hpp"
#include "openscenario/synchronize_motion.hpp"
#include "openscenario/text_number.hpp"
#include "openscenario/trajectory_follow.hpp"
#include "openscenario/transition_shape.hpp"

namespace orch::openscenario {
namespace {

EntityState& state_of(ActionContext& ctx, const std::string& entity) {
  EntityState& s = ctx.entities.at(entity);
  return s;
}

const EntityState& placed(ActionContext& ctx, const std::string& entity) {
  const EntityState& s = ctx.entities.at(entity);
  if (!s.placed) throw MapError(fmt::format("entity \"{}\" has no position yet", entity));
  return s;
}

EntityPoseLookup poses(ActionContext& ctx) {
  return [&ctx](const std::string& name) -> std::optional<opendrive::Pose2> {
    const auto it = ctx.entities.find(name);
    if (it == ctx.entities.end() || !it->second.placed) return std::nullopt;
    return it->second.pose;
  };
}

// A LanePosition without an Orientation: the entity faces its lane's driving direction, the
// way the runtime then moves it (update_pose), as esmini places it (an Orientation left out is
// a relative one of h=0, and a LanePosition's relative heading is the lane's driving
// direction: map/position_resolver.cpp). The road positions and the relative lane position
// face the road's s then, as in esmini (measured: a RelativeLanePosition, RoadPosition or
// RelativeRoadPosition without Orientation on a left lane of right-hand traffic faces along s).
bool faces_driving_direction(const position::Position& p) {
  const auto* lane = std::get_if<position::LanePosition>(&p);
  return lane && !lane->orientation.has_value();
}

// The height above the road a position gives: dz above its reference entity (RelativeObject /
// RelativeWorld: "relative position in the z axis"); a WorldPosition's z (the world frame's
// "z coordinate value") less the road surface under the point; else on the road (a
// WorldPosition without z too: the standard gives no height, esmini aligns such a point to
// the road).
double height_of(const position::Position& p, const ResolvedPosition& r, ActionContext& ctx) {
  return std::visit(
      [&](const auto& kind) {
        using T = std::decay_t<decltype(kind)>;
        if constexpr (std::is_same_v<T, position::RelativeObjectPosition> ||
                      std::is_same_v<T, position::RelativeWorldPosition>) {
          return ctx.entities.at(kind.entity).height + kind.dz;
        } else if constexpr (std::is_same_v<T, position::WorldPosition>) {
          return kind.z ? *kind.z - surface_height(ctx.roads, r.pose) : 0.0;
        } else {
          return 0.0;
        }
      },
      p);
}

void teleport(const TeleportAction& a, EntityState& state, ActionContext& ctx) {
  const ResolvedPosition r = ctx.resolver.resolve(a.position, poses(ctx));
  // A scenario without a road, or a place off every lane of the roads (a camera or an object
  // beside the road, esmini's parking_demo.xosc): placed by its pose alone, and moving as on no
  // road (straight on along its heading) until an action puts it on a lane.
  if (!r.road || !r.lane) {
    state.placed = true;
    state.road_id.clear();
    state.s = state.t = state.offset = 0;
    state.lane = 0;
    state.pose = r.pose;
    state.height = height_of(a.position, r, ctx);
    state.lateral_profile.reset();
    state.lateral_rate = 0;
    return;
  }
  const opendrive::Road& road = ctx.roads.road(r.road->road_id);
  state.placed = true;
  state.road_id = road.id;
  state.s = r.road->s;
  state.lane = *r.lane;
  state.offset = r.road->t - road.lane_center_t(state.lane, state.s);
  state.height = height_of(a.position, r, ctx);
  const bool along_lane = faces_driving_direction(a.position);
  // A LanePosition faces its own lane's direction, also with an offset that puts the point in
  // the lane beside it (esmini's speed-profile.xosc: lane -1, offset 3.07 into lane 1).
  const auto* lane_position = std::get_if<position::LanePosition>(&a.position);
  const int named_lane = lane_position && lane_position->road_id == road.id ? lane_position->lane_id : state.lane;
  state.direction = along_lane ? travel_direction(road, named_lane) : direction_of_heading(road, state.s, r.pose.heading);
  state.lateral_profile.reset();
  state.lateral_rate = 0;
  update_pose(state, ctx.roads);
  if (!along_lane) state.pose.heading = r.pose.heading;  // the position's own orientation
}

double target_speed(const SpeedAction& a, ActionContext& ctx) {
  if (const auto* abs = std::get_if<AbsoluteTargetSpeed>(&a.target)) return abs->value;
  const auto& rel = std::get<RelativeTargetSpeed>(a.target);
  const double reference = placed(ctx, rel.entity).speed;
  return rel.factor ? reference * rel.value : reference + rel.value;
}

// A speed change no faster than the vehicle's Performance allows (maxAcceleration speeding
// up, maxDeceleration slowing down): the standard gives them as the vehicle's maximum, a
// physical limit. At a rate, the rate is capped (acc-test.xosc asks a car of maxAcceleration
// 5 m/s^2 for 10 m/s^2); in a time, the transition keeps its shape and takes as long as its
// steepest point needs (lane_change_simple.xosc: 0 to 25 m/s "cubic in 4 s" peaks at
// 9.4 m/s^2, so the car of 5 m/s^2 takes 7.5 s); over a distance, the time the distance
// gives at the mean of the two speeds is stretched the same way (a car of 4 m/s^2 asked for
// 15 to 25 m/s "cubic over 60 m", 3 s, takes 3.75 s). esmini does all three the same way.
TransitionDynamics within_performance(TransitionDynamics dynamics, const Entity* entity, double from, double to) {
  const double change = to - from;
  if (entity == nullptr || !entity->performance || dynamics.shape == DynamicsShape::Step) return dynamics;
  const double limit = change >= 0 ? entity->performance->max_acceleration : entity->performance->max_deceleration;
  if (limit <= 0) return dynamics;
  if (dynamics.dimension == DynamicsDimension::Rate) dynamics.value = std::min(dynamics.value, limit);
  if (dynamics.dimension == DynamicsDimension::Distance && dynamics.value > 0) {
    const double needed = std::abs(change) * peak_slope(dynamics.shape) / limit;
    if (transition_duration(dynamics, change, from, to) < needed)
      dynamics = TransitionDynamics{dynamics.shape, DynamicsDimension::Time, needed};
  }
  // A time of 0 asks for a jump (override_bb.xosc sets its start speed so): not stretched.
  if (dynamics.dimension == DynamicsDimension::Time && dynamics.value > 0)
    dynamics.value = std::max(dynamics.value, std::abs(change) * peak_slope(dynamics.shape) / limit);
  return dynamics;
}

// Lane `value` lanes to the left of `from`'s lane, in the direction `from` drives.
int lane_to_the_left(const opendrive::Road& road, const EntityState& from, int value) {
  return shifted_lane(from.lane, travel_direction(from, road) * value);
}

// A resolved position as a route waypoint on a lane of the roads.
EntityState::Waypoint waypoint_at(const Position& position, ActionContext& ctx, const std::string& what) {
  const ResolvedPosition r = ctx.resolver.resolve(position, poses(ctx));
  if (!r.road || !r.lane || *r.lane == 0)
    throw MapError(fmt::format("{} (x {:.3f}, y {:.3f}) is on no lane of the road network", what, r.pose.x, r.pose.y));
  return {r.road->road_id, r.road->s, *r.lane};
}

// The route's waypoints as planning targets, each named with its element for messages.
std::vector<RouteTarget> route_targets(const AssignRouteAction& a, const EntityState& state, const std::string& entity) {
  std::vector<RouteTarget> targets;
  for (std::size_t i = 0; i < state.route.size(); ++i) {
    const Place place = i < a.waypoint_places.size() ? a.waypoint_places[i] : Place{};
    targets.push_back({state.route[i], route_strategy(i < a.strategies.size() ? a.strategies[i] : "shortest"),
                       fmt::format("waypoint {} of route \"{}\" of \"{}\" ({}, line {})", i + 1, a.name, entity,
                                   place.path, place.line)});
  }
  return targets;
}

PathMotion trajectory_path(const FollowTrajectoryAction& a, ActionContext& ctx, const std::string& entity) {
  // Vertex times to simulation times: t = (start of the action when relative) + time * scale + offset.
  const auto due = [&](std::optional<double> time) -> std::optional<double> {
    if (!a.timing || !time) return std::nullopt;
    return (a.timing->absolute ? 0.0 : ctx.t) + *time * a.timing->scale + a.timing->offset;
  };
  std::vector<opendrive::Pose2> resolved;
  for (const Position& p : shape_positions(a.trajectory)) resolved.push_back(ctx.resolver.resolve(p, poses(ctx)).pose);
  std::vector<PathPoint> points;
  try {
    points = shape_points(a.trajectory, resolved, state_of(ctx, entity).pose);
  } catch (const MapError& e) {
    throw MapError(fmt::format("trajectory \"{}\" of \"{}\": {}", a.trajectory.name, entity, e.what()));
  }
  for (PathPoint& p : points) p.due = due(p.due);
  try {
    PathMotion path = make_path(std::move(points), a.timing.has_value());
    path.distance = std::min(a.initial_distance_offset, path.length());
    return path;
  } catch (const MapError& e) {
    throw MapError(fmt::format("trajectory \"{}\" of \"{}\": {}", a.trajectory.name, entity, e.what()));
  }
}

double parameter_number(const Parameter& p) {
  const auto value = parse_whole<double>(p.value);
  if (!value) throw MapError(fmt::format("parameter {} holds \"{}\", not a number", p.name, p.value));
  return *value;
}

// ParameterModifyAction / VariableModifyAction: add or multiply; whole-number types stay whole.
void modify_value(Parameter& p, bool multiply, double by) {
  const double now = parameter_number(p);
  const double value = multiply ? now * by : now + by;
  p.value = p.type == "double" ? format_number(value) : format_number(std::round(value));
}

}  // namespace

std::vector<std::string> start_action(const PrivateAction& action, const std::string& entity,
                                      const std::string& action_name, ActionContext& ctx,
                                      std::vector<RunningAction>& running) {
  EntityState no_entity;  // global actions have no actor
  EntityState& state = entity.empty() ? no_entity : state_of(ctx, entity);
  std::vector<std::string> replaced;
  const auto take_over = [&](MotionDomain domain, bool takes_time, bool continuous) {
    for (auto it = running.begin(); it != running.end();) {
      if (it->entity == entity && it->domain == domain) {
        if (!it->action.empty()) replaced.push_back(it->action);
        it = running.erase(it);
      } else {
        ++it;
      }
    }
    if (takes_time || continuous) {
      RunningAction r;
      r.action = action_name;
      r.entity = entity;
      r.domain = domain;
      r.continuous = continuous;
      r.spec = &action;
      running.push_back(std::move(r));
    }
  };
  std::visit(
      [&](const auto& a) {
        using T = std::decay_t<decltype(a)>;
        if constexpr (std::is_same_v<T, TeleportAction>) {
          teleport(a, state, ctx);
        } else if constexpr (std::is_same_v<T, SpeedAction>) {
          const double to = target_speed(a, ctx);
          const double duration =
              transition_duration(within_performance(a.dynamics, ctx.scenario.entity(entity), state.speed, to),
                                  to - state.speed, state.speed, to);
          const bool continuous = std::holds_alternative<RelativeTargetSpeed>(a.target) &&
                                  std::get<RelativeTargetSpeed>(a.target).continuous;
          state.speed_profile.reset();
          if (duration > 0) state.speed_profile = SpeedProfile{ctx.t, duration, state.speed, to, a.dynamics.shape};
          else state.speed = to;
          take_over(MotionDomain::Longitudinal, duration > 0, continuous);
        } else if constexpr (std::is_same_v<T, SpeedProfileAction>) {
          const double reference = a.relative_to ? placed(ctx, *a.relative_to).speed : 0.0;
          SpeedProfileRun run = start_speed_profile(a, ctx.t, state.speed, reference);
          state.speed_profile.reset();
          take_over(MotionDomain::Longitudinal, true, false);
          running.back().speed_profile = std::move(run);
          if (step_speed_profile(a, *running.back().speed_profile, state, ctx.t, ctx.dt)) {
            running.pop_back();  // every entry a step: done at once
          }
        } else if constexpr (std::is_same_v<T, LaneChangeAction>) {
          const EntityState& from = a.relative_to ? placed(ctx, *a.relative_to) : state;
          if (!state.placed) throw MapError(fmt::format("entity \"{}\" has no position yet", entity));
          const opendrive::Road& road = ctx.roads.road(state.road_id);
          const int target = a.relative_to ? lane_to_the_left(road, from, a.lane) : a.lane;
          state.path.reset();
          const double start_offset = state.t - road.lane_center_t(target, state.s);
          const double end_offset = a.target_lane_offset.value_or(0.0);
          const double duration = transition_duration(a.dynamics, end_offset - start_offset, state.speed, state.speed);
          state.lane = target;
          state.offset = start_offset;
          state.lateral_profile = LateralProfile{ctx.t, duration, start_offset, end_offset, a.dynamics.shape};
          if (a.dynamics.dimension == DynamicsDimension::Distance && duration > 0) {
            state.lateral_profile->distance = a.dynamics.value;  // run by the distance travelled
            state.lateral_profile->odometer_start = state.odometer;
          }
          take_over(MotionDomain::Lateral, duration > 0, false);
          if (duration <= 0) {
            state.offset = end_offset;
            state.lateral_profile.reset();
          }
          update_pose(state, ctx.roads);
        } else if constexpr (std::is_same_v<T, LaneOffsetAction>) {
          if (!state.placed) throw MapError(fmt::format("entity \"{}\" has no position yet", entity));
          const double to =
              a.relative_to ? relative_lane_offset(state, placed(ctx, *a.relative_to), a.value, ctx.roads) : a.value;
          state.path.reset();
          const double duration =
              a.max_lateral_acc ? duration_for_lateral_acceleration(a.shape, to - state.offset, *a.max_lateral_acc) : 0.0;
          state.lateral_profile = LateralProfile{ctx.t, duration, state.offset, to, a.shape, true};
          take_over(MotionDomain::Lateral, duration > 0, a.continuous);
          if (duration <= 0) {
            state.offset = to;
            state.lateral_profile.reset();
            update_pose(state, ctx.roads);
          }
        } else if constexpr (std::is_same_v<T, LongitudinalDistanceAction>) {
          state.speed_profile.reset();
          if (has_limits(a)) {
            check_distance_entities(a, state, ctx, entity);  // both placed: checked now
            take_over(MotionDomain::Longitudinal, true, a.continuous);
            // Its speed for the coming step is set now, as every other action started now acts
            // from the coming step on (a SpeedAction's profile starts now); it is kept from the
            // end of each step on (update_running_actions). Before the first step (no step
            // size yet: Init, or an event at 0 s) the first step's start sets it.
            if (!running.empty() && running.back().entity == entity && running.back().spec == &action) {
              running.back().distance_acceleration = state.acceleration;
              if (ctx.dt > 0)
                (void)approach_distance(a, state, ctx, entity, running.back().distance_acceleration);
              else
                running.back().distance_unstepped = true;  // step_unstepped_distances, at the first step
            }
          } else {
            longitudinal_distance(a, state, ctx, entity);
            take_over(MotionDomain::Longitudinal, false, a.continuous);
          }
        } else if constexpr (std::is_same_v<T, ActivateControllerAction>) {
          // The entity's controller drives from now on (on SUMO: SUMO's driver, see openscenario_world);
          // 1.3: objectControllerRef chooses which of its ObjectControllers (checked at load).
          if (const Entity* e = ctx.scenario.entity(entity); e != nullptr && !a.object_controller.empty())
            for (const auto& [name, controller] : e->object_controllers)
              if (name == a.object_controller) state.controller = controller.name;
          state.controller_active = a.longitudinal.value_or(true) || a.lateral.value_or(true);
        } else if constexpr (std::is_same_v<T, AssignControllerAction>) {
          state.controller = a.controller.name;
          state.controller_active = a.longitudinal.value_or(false) || a.lateral.value_or(false);
        } else if constexpr (std::is_same_v<T, VisibilityAction>) {
          state.visibility = a;
        } else if constexpr (std::is_same_v<T, FollowTrajectoryAction>) {
          // An entity not placed yet (Init may place an entity by its trajectory alone) starts
          // on the trajectory, at initialDistanceOffset: "position" puts it there anyway, and
          // "follow" has no other place to steer from.
          state.path = trajectory_path(a, ctx, entity);
          state.lateral_profile.reset();
          if (!state.placed) state.pose = state.path->pose_at(state.path->distance);
          if (a.follow_mode)  // stays where it is; its controller steers onto the path
            start_following(*state.path, state.pose, state.speed, follow_limits(*ctx.scenario.entity(entity)),
                            std::holds_alternative<PolylineShape>(a.trajectory.shape));
          else
            state.pose = state.path->pose_at(state.path->distance);
          state.placed = true;
          relocate(state, ctx.roads);
          if (const std::optional<double> z = state.path->z_at(state.path->distance); z && !a.follow_mode)
            state.height = *z - surface_height(ctx.roads, state.pose);
          // Timed: the trajectory sets the speed too; untimed: the speed actions keep it.
          if (a.timing) {
            state.speed_profile.reset();
            take_over(MotionDomain::Longitudinal, false, false);
          }
          take_over(MotionDomain::Lateral, true, false);
        } else if constexpr (std::is_same_v<T, AssignRouteAction>) {
          state.route.clear();
          for (std::size_t i = 0; i < a.waypoints.size(); ++i)
            state.route.push_back(waypoint_at(a.waypoints[i], ctx,
                                              fmt::format("waypoint {} of route \"{}\" of \"{}\"", i + 1, a.name, entity)));
          state.route_passed = 0;
          if (state.placed) count_passed_waypoints(state, ctx.roads);
          plan_entity_route(state, ctx.roads, route_targets(a, state, entity), a.closed);
        } else if constexpr (std::is_same_v<T, AcquirePositionAction>) {
          state.route = {waypoint_at(a.position, ctx, fmt::format("the position \"{}\" is to acquire", entity))};
          state.route_passed = 0;
          plan_entity_route(state, ctx.roads,
                            {{state.route[0], opendrive::RouteStrategy::Shortest,
                              fmt::format("the position \"{}\" is to acquire", entity)}},
                            false);
          take_over(MotionDomain::Route, true, false);
        } else if constexpr (std::is_same_v<T, AddEntityAction>) {
          EntityState& added = state_of(ctx, a.entity);
          added = EntityState{};
          added.controller = ctx.scenario.entity(a.entity)->controller ? ctx.scenario.entity(a.entity)->controller->name : "";
          teleport(TeleportAction{a.position}, added, ctx);
        } else if constexpr (std::is_same_v<T, DeleteEntityAction>) {
          state_of(ctx, a.entity).placed = false;
          std::erase_if(running, [&](const RunningAction& r) {
            if (r.entity != a.entity) return false;
            if (!r.action.empty()) replaced.push_back(r.action);
            return true;
          });
        } else if constexpr (std::is_same_v<T, ParameterSetAction>) {
          ctx.parameters.at(a.parameter).value = a.value;
        } else if constexpr (std::is_same_v<T, ParameterModifyAction>) {
          modify_value(ctx.parameters.at(a.parameter), a.multiply, a.value);
        } else if constexpr (std::is_same_v<T, VariableSetAction>) {
          ctx.variables.at(a.variable).value = a.value;
        } else if constexpr (std::is_same_v<T, VariableModifyAction>) {
          modify_value(ctx.variables.at(a.variable), a.multiply, a.value);
        } else if constexpr (std::is_same_v<T, ConnectTrailerAction>) {
          connect_trailer(ctx.scenario, ctx.entities, ctx.trailers, entity, a.entity, ctx.roads);
        } else if constexpr (std::is_same_v<T, DisconnectTrailerAction>) {
          disconnect_trailer(ctx.entities, ctx.trailers, entity);
        } else if constexpr (std::is_same_v<T, SynchronizeAction>) {
          if (!state.placed) throw MapError(fmt::format("entity \"{}\" has no position yet", entity));
          SynchronizeRun run = start_synchronize(a, ctx);
          state.speed_profile.reset();
          take_over(MotionDomain::Longitudinal, true, false);
          running.back().synchronize = std::move(run);
        } else if constexpr (std::is_same_v<T, LateralDistanceAction>) {
          // Kept by the storyboard's motion (lateral_distance.hpp), also for an entity SUMO does not drive.
          LateralDistanceRun run;
          const bool reached = keep_lateral_distance(a, state, ctx, entity, run, true);
          take_over(MotionDomain::Lateral, !reached, a.continuous);
          if (!running.empty() && running.back().entity == entity && running.back().spec == &action)
            running.back().lateral_distance = run;
        } else if constexpr (std::is_same_v<T, TrafficSignalStateAction>) {
          ctx.signals->set_state(a.signal, a.state);
        } else if constexpr (std::is_same_v<T, TrafficSignalControllerAction>) {
          ctx.signals->set_phase(a.controller, a.phase, ctx.t);
        } else if constexpr (std::is_same_v<T, TrafficSwarmAction>) {
          ctx.traffic->start(Traffic{0, a.name, a, std::nullopt, 0, std::nullopt, {}}, ctx.t);
        } else if constexpr (std::is_same_v<T, TrafficSourceAction> || std::is_same_v<T, TrafficSinkAction>) {
          ctx.traffic->start(Traffic{0, a.name, a, ctx.resolver.resolve(a.position, poses(ctx)), 0, std::nullopt, {}},
                             ctx.t);
        } else if constexpr (std::is_same_v<T, TrafficAreaAction>) {
          // A polygon's corners are where they are when the action starts (a relative one follows no entity after).
          Traffic area{0, a.name, a, std::nullopt, 0, std::nullopt, {}};
          for (const Position& corner : a.polygon) {
            const ResolvedPosition r = ctx.resolver.resolve(corner, poses(ctx));
            area.polygon.push_back({r.pose.x, r.pose.y});
          }
          ctx.traffic->start(std::move(area), ctx.t);
        } else if constexpr (std::is_same_v<T, RandomRouteAction>) {
          plan_random_route(state, ctx.roads, entity, ctx.seed);
        } else if constexpr (std::is_same_v<T, TrafficStopAction>) {
          ctx.traffic->stop(a.name, ctx.t);  // none running yet (its action not started): nothing to stop
        } else if constexpr (std::is_same_v<T, SetMonitorAction>) {
          if (ctx.monitors) ctx.monitors->at(a.monitor) = a.value;  // declared: checked at load
        } else if constexpr (std::is_same_v<T, EnvironmentAction>) {
          // Only the time of day matters here (TimeOfDayCondition); SUMO renders no weather.
          if (a.time_of_day && ctx.time_of_day) *ctx.time_of_day = TimeOfDayClock{*a.time_of_day, ctx.t};
        } else if constexpr (std::is_same_v<T, AppearanceAction>) {
          // No effect on motion: SUMO has no lights, animations or weather here, the entities
          // no vehicle dynamics for controller overrides, custom commands no meaning (model.hpp).
        } else {
          static_assert(kUnhandled<T>, "an OpenSCENARIO action the reader makes needs its behaviour here");
        }
      },
      action);
  return replaced;
}

}  // namespace orch::openscenario

#include "openscenario/action_start.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "core/errors.hpp"
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

void teleport(const TeleportAction& a, EntityState& state, ActionContext& ctx, const std::string& entity) {
  const ResolvedPosition r = ctx.resolver.resolve(a.position, poses(ctx));
  if (!r.road || !r.lane)
    throw MapError(fmt::format("the position of \"{}\" (x {:.3f}, y {:.3f}) is on no lane of the road network", entity,
                               r.pose.x, r.pose.y));
  const opendrive::Road& road = ctx.roads.road(r.road->road_id);
  state.placed = true;
  state.road_id = road.id;
  state.s = r.road->s;
  state.lane = *r.lane;
  state.offset = r.road->t - road.lane_center_t(state.lane, state.s);
  state.lateral_profile.reset();
  state.lateral_rate = 0;
  update_pose(state, ctx.roads);
  state.pose.heading = r.pose.heading;  // the position's own orientation
}

double target_speed(const SpeedAction& a, ActionContext& ctx) {
  if (const auto* abs = std::get_if<AbsoluteTargetSpeed>(&a.target)) return abs->value;
  const auto& rel = std::get<RelativeTargetSpeed>(a.target);
  const double reference = placed(ctx, rel.entity).speed;
  return rel.factor ? reference * rel.value : reference + rel.value;
}

// Lane `value` lanes to the left (in the driving direction) of `lane`.
int lane_to_the_left(const opendrive::Road& road, int lane, int value) {
  return shifted_lane(lane, travel_direction(road, lane) * value);
}

void longitudinal_distance(const LongitudinalDistanceAction& a, EntityState& state, ActionContext& ctx,
                           const std::string& entity) {
  if (a.max_acceleration || a.max_deceleration || a.max_speed)
    throw MapError(fmt::format("LongitudinalDistanceAction of \"{}\" with DynamicConstraints is not run yet", entity));
  const EntityState& ref = placed(ctx, a.entity);
  if (!state.placed) throw MapError(fmt::format("entity \"{}\" has no position yet", entity));
  const opendrive::Road& road = ctx.roads.road(ref.road_id);
  const int direction = travel_direction(road, ref.lane);
  double gap = a.distance ? *a.distance : *a.time_gap * ref.speed;
  const bool ahead = a.displacement == "leadingReferencedEntity" ||
                     (a.displacement == "any" && (state.s - ref.s) * direction >= 0);
  if (a.freespace) {
    const BoundingBox& own = ctx.scenario.entity(entity)->box;
    const BoundingBox& other = ctx.scenario.entity(a.entity)->box;
    gap += ahead ? (other.center_x + other.length / 2) - (own.center_x - own.length / 2)
                 : (own.center_x + own.length / 2) - (other.center_x - other.length / 2);
  }
  state.road_id = ref.road_id;
  state.s = ref.s + direction * (ahead ? gap : -gap);
  state.speed = ref.speed;
  update_pose(state, ctx.roads);
}

}  // namespace

std::vector<std::string> start_action(const PrivateAction& action, const std::string& entity,
                                      const std::string& action_name, ActionContext& ctx,
                                      std::vector<RunningAction>& running) {
  EntityState& state = state_of(ctx, entity);
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
    if (takes_time || continuous) running.push_back({action_name, entity, domain, continuous, &action});
  };
  std::visit(
      [&](const auto& a) {
        using T = std::decay_t<decltype(a)>;
        if constexpr (std::is_same_v<T, TeleportAction>) {
          teleport(a, state, ctx, entity);
        } else if constexpr (std::is_same_v<T, SpeedAction>) {
          const double to = target_speed(a, ctx);
          const double duration = transition_duration(a.dynamics, to - state.speed, state.speed, to);
          const bool continuous = std::holds_alternative<RelativeTargetSpeed>(a.target) &&
                                  std::get<RelativeTargetSpeed>(a.target).continuous;
          state.speed_profile.reset();
          if (duration > 0) state.speed_profile = SpeedProfile{ctx.t, duration, state.speed, to, a.dynamics.shape};
          else state.speed = to;
          take_over(MotionDomain::Longitudinal, duration > 0, continuous);
        } else if constexpr (std::is_same_v<T, LaneChangeAction>) {
          const EntityState& from = a.relative_to ? placed(ctx, *a.relative_to) : state;
          if (!state.placed) throw MapError(fmt::format("entity \"{}\" has no position yet", entity));
          const opendrive::Road& road = ctx.roads.road(state.road_id);
          const int target = a.relative_to ? lane_to_the_left(road, from.lane, a.lane) : a.lane;
          const double start_offset = state.t - road.lane_center_t(target, state.s);
          const double end_offset = a.target_lane_offset.value_or(0.0);
          const double duration = transition_duration(a.dynamics, end_offset - start_offset, state.speed, state.speed);
          state.lane = target;
          state.offset = start_offset;
          state.lateral_profile = LateralProfile{ctx.t, duration, start_offset, end_offset, a.dynamics.shape};
          take_over(MotionDomain::Lateral, duration > 0, false);
          if (duration <= 0) {
            state.offset = end_offset;
            state.lateral_profile.reset();
          }
          update_pose(state, ctx.roads);
        } else if constexpr (std::is_same_v<T, LaneOffsetAction>) {
          if (!state.placed) throw MapError(fmt::format("entity \"{}\" has no position yet", entity));
          const double to = a.relative_to ? placed(ctx, *a.relative_to).offset + a.value : a.value;
          const double duration =
              a.max_lateral_acc ? duration_for_lateral_acceleration(a.shape, to - state.offset, *a.max_lateral_acc) : 0.0;
          state.lateral_profile = LateralProfile{ctx.t, duration, state.offset, to, a.shape};
          take_over(MotionDomain::Lateral, duration > 0, a.continuous);
          if (duration <= 0) {
            state.offset = to;
            state.lateral_profile.reset();
            update_pose(state, ctx.roads);
          }
        } else if constexpr (std::is_same_v<T, LongitudinalDistanceAction>) {
          longitudinal_distance(a, state, ctx, entity);
          state.speed_profile.reset();
          take_over(MotionDomain::Longitudinal, false, a.continuous);
        } else {  // ActivateControllerAction: the system under test drives from now on
          state.controller_active = a.longitudinal.value_or(true) || a.lateral.value_or(true);
        }
      },
      action);
  return replaced;
}

std::vector<std::string> update_running_actions(ActionContext& ctx, std::vector<RunningAction>& running) {
  std::vector<std::string> ended;
  for (auto it = running.begin(); it != running.end();) {
    EntityState& state = ctx.entities.at(it->entity);
    bool done = false;
    if (it->domain == MotionDomain::Longitudinal) {
      if (const auto* distance = std::get_if<LongitudinalDistanceAction>(it->spec)) {
        longitudinal_distance(*distance, state, ctx, it->entity);  // continuous: keep the distance
      } else if (state.speed_profile && state.speed_profile->done(ctx.t)) {
        state.speed = state.speed_profile->to;
        state.speed_profile.reset();
        done = !it->continuous;
      } else if (!state.speed_profile && it->continuous) {
        state.speed = target_speed(std::get<SpeedAction>(*it->spec), ctx);  // follows the reference
      }
    } else if (state.lateral_profile && state.lateral_profile->done(ctx.t)) {
      state.offset = state.lateral_profile->to;
      state.lateral_profile.reset();
      state.lateral_rate = 0;
      update_pose(state, ctx.roads);
      done = !it->continuous;
    }
    if (!done) {
      ++it;
      continue;
    }
    const std::string name = it->action;
    it = running.erase(it);
    if (std::none_of(running.begin(), running.end(), [&](const RunningAction& r) { return r.action == name; }))
      ended.push_back(name);
  }
  return ended;
}

}  // namespace orch::openscenario

// What start positions, conditions and actions refer to (actors, routes and indices), what
// the actor they move can do (a pedestrian has no lanes or lights), and value ranges.
#include <fmt/format.h>

#include "core/suggest.hpp"
#include "scenario_executor/elements.hpp"
#include "scenario_executor/validator_internal.hpp"

namespace orch::scenario_checks {

using namespace orch::scenario;

void check_actor_ref(CheckContext& ctx, ActorId id, const SourceLocation& where, const char* key) {
  if (!ctx.s.find_actor(id))
    ctx.diags.error(where, fmt::format("{} {} is not defined under \"actors\" (defined: {})", key, id,
                                       defined_actor_ids(ctx.s)));
}

const WaypointRoute* check_route(CheckContext& ctx, const std::string& wp_id, const SourceLocation& where) {
  if (wp_id.empty()) return nullptr;  // reported by the loader
  // No routes: the map's waypoints are unknown (`validate` with a map it cannot find);
  // a real waypoint file always has routes (load_waypoint_file refuses one without).
  if (ctx.waypoints.routes.empty()) return nullptr;
  const WaypointRoute* route = ctx.waypoints.find(wp_id);
  if (!route) {
    const auto ids = ctx.waypoints.route_ids();
    ctx.diags.error(where, fmt::format("wp_id \"{}\" is not a route of the map's waypoint file {}{}; its routes: {}",
                                       wp_id, ctx.waypoints.path, did_you_mean(wp_id, ids), quoted_list(ids)));
  }
  return route;
}

void check_waypoint(CheckContext& ctx, const WaypointRef& ref, WaypointUse use) {
  const WaypointRoute* route = check_route(ctx, ref.wp_id, ref.where);
  if (!route) return;
  if (ref.wp_idx < 0) {
    ctx.diags.error(ref.where, fmt::format("wp_idx {} is negative: indices count from 0 along route \"{}\"",
                                           ref.wp_idx, ref.wp_id));
    return;
  }
  const double last = route->last_index();
  if (ref.wp_idx <= last) return;
  const std::string past = fmt::format("wp_idx {} is past the end of route \"{}\" (last index {})", ref.wp_idx,
                                       ref.wp_id, last);
  if (use == WaypointUse::Placement)
    ctx.diags.error(ref.where, past + ": an actor cannot be placed there");
  else if (ctx.options.strict)
    ctx.diags.error(ref.where, past + " (strict: a target must lie on the route)");
  else
    ctx.diags.warning(ref.where, past + "; it will mean the route's last point");
}

void check_not_negative(CheckContext& ctx, double value, const SourceLocation& where, const char* key,
                        const char* unit) {
  if (value < 0) ctx.diags.error(where, fmt::format("\"{}\" is {} {}; it must be >= 0", key, value, unit));
}

// Actions that make no sense for what the actor is: an obstacle does not move, a
// pedestrian has no lane, lights or siren.
void check_can(CheckContext& ctx, ActorId actor, const SourceLocation& where, const char* action, bool pedestrian_ok,
               const char* hint) {
  const ModelInfo* model = ctx.model_of(actor);
  if (!model || model->kind == ActorKind::Vehicle) return;
  if (model->kind == ActorKind::Pedestrian && pedestrian_ok) return;
  const bool obstacle = model->kind == ActorKind::Obstacle;
  ctx.diags.error(where, fmt::format("{} on actor {}, which is {} (model \"{}\"): {}{}", action, actor,
                                     obstacle ? "an obstacle" : "a pedestrian", ctx.s.find_actor(actor)->model_id,
                                     obstacle ? "an obstacle does not move or signal"
                                              : "a pedestrian has no lane, lights or siren",
                                     hint));
}

void check_speed(CheckContext& ctx, const SpeedAction& a, const SourceLocation& where, const char* what) {
  if (a.target) {
    check_actor_ref(ctx, *a.target, where, "target_actor_id");
    if (*a.target == a.actor)
      ctx.diags.error(where, fmt::format("{} of actor {} is relative to the actor itself", what, a.actor));
  }
  if (a.type == SpeedType::Absolute && a.value < 0)
    ctx.diags.error(where, fmt::format("an absolute speed must be >= 0, found {} km/h", a.value * 3.6));
  if (a.accel.type == AccelType::Specify && a.accel.value <= 0)
    ctx.diags.error(where, fmt::format("accel \"value\" is {} m/s^2; with type \"specify\" it must be > 0 (it is the "
                                       "rate of speeding up and of slowing down)",
                                       a.accel.value));
  check_can(ctx, a.actor, where, what, true);
}

void check_signals(CheckContext& ctx, ActorId actor, const SourceLocation& where, const char* action,
                   bool uses_special) {
  check_can(ctx, actor, where, action, false);
  const ModelInfo* model = ctx.model_of(actor);
  if (uses_special && model && model->kind == ActorKind::Vehicle && !model->emergency)
    ctx.diags.warning(where, fmt::format("{} on actor {}: model \"{}\" is not an emergency vehicle and has no "
                                         "special lights or siren",
                                         action, actor, ctx.s.find_actor(actor)->model_id));
}

namespace {

// The actor an element names in `actor` (every kind that has one), then the element's own
// checks from its table row (scenario/elements.hpp).
template <typename Kind>
void check_element(CheckContext& ctx, const std::vector<scenario_elements::Element<Kind>>& table, const Kind& kind,
                   const SourceLocation& where) {
  std::visit(
      [&](const auto& k) {
        if constexpr (requires { k.actor; })
          if constexpr (std::is_same_v<std::decay_t<decltype(k.actor)>, ActorId>)
            check_actor_ref(ctx, k.actor, where, "actor_id");
      },
      kind);
  if (const auto* element = scenario_elements::element_of(table, kind)) element->check(ctx, kind, where);
}

void check_group(CheckContext& ctx, const ConditionGroup& g) {
  for (const auto& item : g.items) {
    if (const auto* c = std::get_if<Condition>(&item.node))
      check_element(ctx, scenario_elements::condition_elements(), c->kind, c->where);
    else
      check_group(ctx, std::get<ConditionGroup>(item.node));
  }
}

}  // namespace

void check_opening(CheckContext& ctx) {
  const auto& opening = ctx.s.opening;
  if (opening.ego.start.waypoint) check_waypoint(ctx, *opening.ego.start.waypoint, WaypointUse::Placement);
  if (opening.ego.end) check_waypoint(ctx, *opening.ego.end, WaypointUse::Target);
  for (const auto& entry : opening.others) {
    const StartPosition& start = entry.start;
    if (start.type == StartPositionType::Waypoint && start.waypoint)
      check_waypoint(ctx, *start.waypoint, WaypointUse::Placement);
    if (start.type == StartPositionType::Distance && start.target)
      check_actor_ref(ctx, *start.target, start.where, "target_actor_id");
    if (start.type == StartPositionType::Distance && start.waypoint)
      check_route(ctx, start.waypoint->wp_id, start.waypoint->where);
    if (entry.start_speed) check_speed(ctx, *entry.start_speed, entry.where, "start_speed");
  }
}

void check_scene_contents(CheckContext& ctx) {
  for (const auto& scene : ctx.s.scenes) {
    check_not_negative(ctx, scene.duration, scene.where, "duration", "s");
    check_group(ctx, scene.conditions);
    for (const auto& action : scene.actions)
      check_element(ctx, scenario_elements::action_elements(), action.kind, action.where);
  }
  if (const auto& stop = ctx.s.stop_conditions) {
    check_group(ctx, *stop);
    if (stop->items.empty())
      ctx.diags.warning(stop->where, "\"stop_conditions\" holds no condition, so it always holds: the run stops at "
                                     "its first step");
  }
}

}  // namespace orch::scenario_checks

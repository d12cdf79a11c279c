// Scene actions, one row each: the key in the file, the reader, the checker (elements.hpp).
// The behaviour of each is Engine::act (engine/engine_actions.cpp).
#include <fmt/format.h>

#include "scenario_executor/elements.hpp"

namespace orch::scenario_elements {

using namespace orch::scenario;
using scenario_checks::CheckContext;
using scenario_checks::WaypointUse;
using scenario_loading::LoadContext;
namespace checks = scenario_checks;

namespace {

// ---------------------------------------------------------------- speed
std::optional<SpeedAction> read_speed(LoadContext& ctx, ObjectReader& r) {
  return scenario_loading::read_speed_body(ctx, r, true);
}
void check_speed(CheckContext& ctx, const SpeedAction& a, const SourceLocation& where) {
  checks::check_speed(ctx, a, where, "speed action");
}

// ---------------------------------------------------------------- traveled_distance
std::optional<TraveledDistanceAction> read_traveled_distance(LoadContext& ctx, ObjectReader& r) {
  const auto actor = r.integer("actor_id", Need::Required);
  const auto target = r.integer("target_actor_id", Need::Optional);
  const auto value = r.number("value", Need::Required, Quantity::Length);
  const auto measure = scenario_loading::read_measure_type(r);
  if (!actor || !value || !measure) return std::nullopt;
  // Absent target_actor_id: the distance is kept to the ego, as in the reference.
  return TraveledDistanceAction{*actor, target.value_or(ctx.ego_id), *value, *measure};
}
void check_traveled_distance(CheckContext& ctx, const TraveledDistanceAction& a, const SourceLocation& where) {
  checks::check_actor_ref(ctx, a.target, where, "target_actor_id");
  if (a.actor == a.target)
    ctx.diags.error(where, fmt::format("traveled_distance keeps actor {} at a distance from itself (without "
                                       "\"target_actor_id\" the target is the ego)",
                                       a.actor));
  checks::check_can(ctx, a.actor, where, "traveled_distance", true);
}

// ---------------------------------------------------------------- lane_change
std::optional<LaneChangeAction> read_lane_change(LoadContext&, ObjectReader& r) {
  const auto actor = r.integer("actor_id", Need::Required);
  r.choice("type", {"lane"}, Need::Optional);  // "lane" is the only kind, and the default
  const auto wp_id = scenario_loading::read_id_string(r, "wp_id", Need::Required);
  const auto time = r.number("time", Need::Required, Quantity::Time);
  if (!actor || !wp_id || !time) return std::nullopt;
  return LaneChangeAction{*actor, *wp_id, *time};
}
void check_lane_change(CheckContext& ctx, const LaneChangeAction& a, const SourceLocation& where) {
  checks::check_route(ctx, a.wp_id, where);
  // time 0 is allowed and means an instant move onto the target lane.
  checks::check_not_negative(ctx, a.time, where, "time", "s");
  checks::check_can(ctx, a.actor, where, "lane_change", false, "; move it with route_move");
}

// ---------------------------------------------------------------- lane_offset
std::optional<LaneOffsetAction> read_lane_offset(LoadContext&, ObjectReader& r) {
  const auto actor = r.integer("actor_id", Need::Required);
  const auto value = r.number("value", Need::Required, Quantity::Length);
  const auto time = r.number("time", Need::Required, Quantity::Time);
  if (!actor || !value || !time) return std::nullopt;
  return LaneOffsetAction{*actor, *value, *time};
}
void check_lane_offset(CheckContext& ctx, const LaneOffsetAction& a, const SourceLocation& where) {
  checks::check_not_negative(ctx, a.time, where, "time", "s");
  checks::check_can(ctx, a.actor, where, "lane_offset", false, "; move it with route_move");
}

// ---------------------------------------------------------------- route_move
std::optional<RouteLeg> read_route_leg(LoadContext& ctx, const nlohmann::json& value, const std::string& pointer,
                                       RouteMoveType type) {
  ObjectReader r(ctx.doc, value, pointer, ctx.diags, "route point");
  RouteLeg leg;
  leg.where = r.where();
  const auto time = r.number("time", Need::Required, Quantity::Time);
  bool complete = time.has_value();
  if (type == RouteMoveType::Waypoint) {
    leg.waypoint = scenario_loading::read_waypoint_ref(r);
    leg.wp_offset = r.number("wp_offset", Need::Optional, Quantity::Length);
    complete = complete && leg.waypoint;
  } else {
    leg.wp_offset = r.number("wp_offset", Need::Required, Quantity::Length);
    complete = complete && leg.wp_offset;
    for (const char* key : {"wp_id", "wp_idx"})
      scenario_loading::reject_key(r, key,
                                   fmt::format("\"{}\" belongs to route_move of type \"waypoint\"; type \"wp_offset\" "
                                               "moves sideways on the current route by \"wp_offset\" m only",
                                               key));
  }
  r.finish();
  if (!complete || !r.is_object()) return std::nullopt;
  leg.time = *time;
  return leg;
}
std::optional<RouteMoveAction> read_route_move(LoadContext& ctx, ObjectReader& r) {
  const auto actor = r.integer("actor_id", Need::Required);
  const auto type = r.choice("type", {"waypoint", "wp_offset"}, Need::Required);
  const auto* route = r.array("route", Need::Required);
  if (!actor || !type || !route) return std::nullopt;
  RouteMoveAction move;
  move.actor = *actor;
  move.type = *type == "waypoint" ? RouteMoveType::Waypoint : RouteMoveType::WpOffset;
  if (route->empty()) {
    r.error("route", "\"route\" is empty: give at least one point to move to");
    return std::nullopt;
  }
  bool all_read = true;
  for (std::size_t i = 0; i < route->size(); ++i) {
    auto leg = read_route_leg(ctx, (*route)[i], json_pointer_child(r.child("route"), i), move.type);
    if (leg) move.legs.push_back(std::move(*leg));
    else all_read = false;
  }
  if (!all_read) return std::nullopt;
  return move;
}
void check_route_move(CheckContext& ctx, const RouteMoveAction& a, const SourceLocation& where) {
  checks::check_can(ctx, a.actor, where, "route_move", true);
  for (const auto& leg : a.legs) {
    checks::check_not_negative(ctx, leg.time, leg.where, "time", "s");
    if (leg.waypoint) checks::check_waypoint(ctx, *leg.waypoint, WaypointUse::Placement);
  }
}

// ---------------------------------------------------------------- light_state
std::optional<LightStateAction> read_light_state(LoadContext&, ObjectReader& r) {
  LightStateAction a;
  const auto actor = r.integer("actor_id", Need::Required);
  a.blinker_left = r.boolean("blinker_left", Need::Optional);
  a.blinker_right = r.boolean("blinker_right", Need::Optional);
  a.special1 = r.boolean("special1", Need::Optional);
  if (!actor) return std::nullopt;
  a.actor = *actor;
  if (!r.has("blinker_left") && !r.has("blinker_right") && !r.has("special1"))
    r.warning("", "this light_state changes nothing: give \"blinker_left\", \"blinker_right\" or \"special1\"");
  return a;
}
void check_light_state(CheckContext& ctx, const LightStateAction& a, const SourceLocation& where) {
  checks::check_signals(ctx, a.actor, where, "light_state", a.special1.value_or(false));
}

// ---------------------------------------------------------------- sound_state
std::optional<SoundStateAction> read_sound_state(LoadContext&, ObjectReader& r) {
  const auto actor = r.integer("actor_id", Need::Required);
  const auto sound = r.boolean("sound", Need::Required);
  if (!actor || !sound) return std::nullopt;
  return SoundStateAction{*actor, sound};
}
void check_sound_state(CheckContext& ctx, const SoundStateAction& a, const SourceLocation& where) {
  checks::check_signals(ctx, a.actor, where, "sound_state", a.sound.value_or(false));
}

// ---------------------------------------------------------------- hand_over
std::optional<HandOverAction> read_hand_over(LoadContext&, ObjectReader& r) {
  HandOverAction a;
  a.actor = r.integer("actor_id", Need::Optional);
  const auto hand_over = r.boolean("hand_over", Need::Required);
  a.throttle = r.number("throttle", Need::Optional);
  a.brake = r.number("brake", Need::Optional);
  a.steer = r.number("steer", Need::Optional);
  if (!hand_over) return std::nullopt;
  a.hand_over = *hand_over;
  return a;
}
void check_hand_over(CheckContext& ctx, const HandOverAction& a, const SourceLocation& where) {
  if (a.actor && *a.actor != ctx.s.ego.id)
    ctx.diags.error(where, fmt::format("hand_over applies to the ego (actor {}), not to actor {}", ctx.s.ego.id,
                                       *a.actor));
  auto in_range = [&](const std::optional<double>& v, const char* key, double lo, double hi) {
    if (v && (*v < lo || *v > hi))
      ctx.diags.error(where, fmt::format("\"{}\" is {}; it must lie in [{}, {}]", key, *v, lo, hi));
  };
  in_range(a.throttle, "throttle", 0, 1);
  in_range(a.brake, "brake", 0, 1);
  in_range(a.steer, "steer", -1, 1);
}

}  // namespace

const std::vector<ActionElement>& action_elements() {
  // The order is the order "did you mean" and messages list them in.
  static const std::vector<ActionElement> table = {
      row<ActionKind, read_speed, check_speed>("speed"),
      row<ActionKind, read_traveled_distance, check_traveled_distance>("traveled_distance"),
      row<ActionKind, read_lane_change, check_lane_change>("lane_change"),
      row<ActionKind, read_lane_offset, check_lane_offset>("lane_offset"),
      row<ActionKind, read_route_move, check_route_move>("route_move"),
      row<ActionKind, read_light_state, check_light_state>("light_state"),
      row<ActionKind, read_sound_state, check_sound_state>("sound_state"),
      row<ActionKind, read_hand_over, check_hand_over>("hand_over"),
  };
  return table;
}

}  // namespace orch::scenario_elements

// Actions of scenes: each entry of "actions" holds exactly one action key (plus an optional
// "description"); `{}` is accepted as an action that does nothing.
#include <fmt/format.h>

#include "scenario/loader_internal.hpp"

namespace orch::scenario_loading {

using namespace orch::scenario;

namespace {

std::optional<Accel> read_accel(LoadContext& ctx, ObjectReader& parent) {
  const auto* value = parent.object("accel", Need::Optional);
  // Absent accel: the speed is set at once ("gods_hand"), as in the reference implementation.
  if (!parent.has("accel")) return Accel{AccelType::GodsHand, 0};
  if (!value) return std::nullopt;
  ObjectReader r(ctx.doc, *value, parent.child("accel"), ctx.diags, "accel");
  // The document spells it "gods_hand", the reference implementation "god_hands".
  const auto type = r.choice("type", {"specify", "gods_hand", "god_hands"}, Need::Required);
  const bool specify = type && *type == "specify";
  const auto magnitude = r.number("value", specify ? Need::Required : Need::Optional);
  r.finish();
  if (!type || (specify && !magnitude)) return std::nullopt;
  return Accel{specify ? AccelType::Specify : AccelType::GodsHand, magnitude.value_or(0.0)};
}

std::optional<ActionKind> read_traveled_distance(LoadContext& ctx, ObjectReader& r) {
  const auto actor = r.integer("actor_id", Need::Required);
  const auto target = r.integer("target_actor_id", Need::Optional);
  const auto value = r.number("value", Need::Required);
  const auto measure = read_measure_type(r);
  if (!actor || !value || !measure) return std::nullopt;
  // Absent target_actor_id: the distance is kept to the ego, as in the reference.
  return TraveledDistanceAction{*actor, target.value_or(ctx.ego_id), *value, *measure};
}

std::optional<ActionKind> read_lane_change(LoadContext&, ObjectReader& r) {
  const auto actor = r.integer("actor_id", Need::Required);
  r.choice("type", {"lane"}, Need::Optional);  // "lane" is the only kind, and the default
  const auto wp_id = read_id_string(r, "wp_id", Need::Required);
  const auto time = r.number("time", Need::Required);
  if (!actor || !wp_id || !time) return std::nullopt;
  return LaneChangeAction{*actor, *wp_id, *time};
}

std::optional<ActionKind> read_lane_offset(LoadContext&, ObjectReader& r) {
  const auto actor = r.integer("actor_id", Need::Required);
  const auto value = r.number("value", Need::Required);
  const auto time = r.number("time", Need::Required);
  if (!actor || !value || !time) return std::nullopt;
  return LaneOffsetAction{*actor, *value, *time};
}

std::optional<RouteLeg> read_route_leg(LoadContext& ctx, const nlohmann::json& value, const std::string& pointer,
                                       RouteMoveType type) {
  ObjectReader r(ctx.doc, value, pointer, ctx.diags, "route point");
  RouteLeg leg;
  leg.where = r.where();
  const auto time = r.number("time", Need::Required);
  bool complete = time.has_value();
  if (type == RouteMoveType::Waypoint) {
    leg.waypoint = read_waypoint_ref(r);
    leg.wp_offset = r.number("wp_offset", Need::Optional);
    complete = complete && leg.waypoint;
  } else {
    leg.wp_offset = r.number("wp_offset", Need::Required);
    complete = complete && leg.wp_offset;
    for (const char* key : {"wp_id", "wp_idx"})
      reject_key(r, key,
                 fmt::format("\"{}\" belongs to route_move of type \"waypoint\"; type \"wp_offset\" moves "
                             "sideways on the current route by \"wp_offset\" m only",
                             key));
  }
  r.finish();
  if (!complete || !r.is_object()) return std::nullopt;
  leg.time = *time;
  return leg;
}

std::optional<ActionKind> read_route_move(LoadContext& ctx, ObjectReader& r) {
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

std::optional<ActionKind> read_light_state(LoadContext&, ObjectReader& r) {
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

std::optional<ActionKind> read_sound_state(LoadContext&, ObjectReader& r) {
  const auto actor = r.integer("actor_id", Need::Required);
  const auto sound = r.boolean("sound", Need::Required);
  if (!actor || !sound) return std::nullopt;
  return SoundStateAction{*actor, sound};
}

std::optional<ActionKind> read_hand_over(LoadContext&, ObjectReader& r) {
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

std::optional<ActionKind> read_kind(LoadContext& ctx, const std::string& kind, ObjectReader& r) {
  if (kind == "speed") {
    if (auto speed = read_speed_body(ctx, r, true)) return *speed;
    return std::nullopt;
  }
  if (kind == "traveled_distance") return read_traveled_distance(ctx, r);
  if (kind == "lane_change") return read_lane_change(ctx, r);
  if (kind == "lane_offset") return read_lane_offset(ctx, r);
  if (kind == "route_move") return read_route_move(ctx, r);
  if (kind == "light_state") return read_light_state(ctx, r);
  if (kind == "sound_state") return read_sound_state(ctx, r);
  return read_hand_over(ctx, r);
}

std::optional<Action> read_action(LoadContext& ctx, const nlohmann::json& item, const std::string& pointer) {
  if (!item.is_object()) {
    ctx.diags.error(ctx.doc.where(pointer),
                    fmt::format("expected an action such as {{\"speed\": {{...}}}}, found {}", json_type_name(item)));
    return std::nullopt;
  }
  const int errors_before = ctx.diags.error_count();
  ObjectReader r(ctx.doc, item, pointer, ctx.diags, "action");
  const auto outer_description = r.string("description", Need::Optional);
  r.allow(kActionKinds);
  std::vector<std::string> kinds;
  for (const auto& kind : kActionKinds)
    if (item.contains(kind)) kinds.push_back(kind);
  if (kinds.size() > 1)
    r.error(kinds[1], fmt::format("one entry of \"actions\" holds exactly one action, found \"{}\" and \"{}\"; "
                                  "give each its own entry",
                                  kinds[0], kinds[1]));
  if (kinds.empty()) {
    r.finish();  // unknown keys, with "did you mean"
    if (ctx.diags.error_count() != errors_before) return std::nullopt;
    // `{}` (real files have it): does nothing, but it is probably an unfinished edit.
    r.warning("", "empty action: it does nothing");
    return Action{EmptyAction{}, outer_description.value_or(""), r.where()};
  }
  r.finish();

  const std::string& kind = kinds.front();
  ObjectReader body(ctx.doc, item[kind], r.child(kind), ctx.diags, kind + " action");
  const auto inner_description = body.string("description", Need::Optional);
  auto parsed = body.is_object() ? read_kind(ctx, kind, body) : std::nullopt;
  body.finish();
  // An action with an error of its own stays out of the model (see loader_internal.hpp).
  if (!parsed || ctx.diags.error_count() != errors_before) return std::nullopt;
  return Action{std::move(*parsed), inner_description.value_or(outer_description.value_or("")), body.where()};
}

}  // namespace

std::optional<SpeedAction> read_speed_body(LoadContext& ctx, ObjectReader& r, bool needs_actor) {
  SpeedAction a;
  const auto actor = needs_actor ? r.integer("actor_id", Need::Required) : std::optional<int>(0);
  const auto type = read_speed_type(r);
  const auto target = r.integer("target_actor_id", Need::Optional);
  const auto value = r.number("value", Need::Required);
  const auto accel = read_accel(ctx, r);
  if (!actor || !type || !value || !accel) return std::nullopt;
  a.actor = *actor;
  a.type = *type;
  a.value = kmh_to_ms(*value);
  a.accel = *accel;
  if (a.type == SpeedType::Relative) {
    a.target = target.value_or(ctx.ego_id);  // absent: relative to the ego, as in the reference
  } else if (target) {
    r.warning("target_actor_id", "\"target_actor_id\" has no effect on an absolute speed");
  }
  return a;
}

std::vector<Action> read_actions(LoadContext& ctx, const nlohmann::json& array, const std::string& pointer) {
  std::vector<Action> actions;
  for (std::size_t i = 0; i < array.size(); ++i)
    if (auto action = read_action(ctx, array[i], json_pointer_child(pointer, i))) actions.push_back(std::move(*action));
  return actions;
}

}  // namespace orch::scenario_loading

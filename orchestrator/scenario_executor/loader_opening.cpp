// The opening scene: where the ego and every other actor start, their first speeds, and the
// scenes that may follow.
#include <fmt/format.h>

#include "scenario_executor/loader_internal.hpp"

namespace orch::scenario_loading {

using namespace orch::scenario;

namespace {

// "orientation": {"heading": rad}, relative to the route direction, + = to the left.
std::optional<double> read_orientation(LoadContext& ctx, ObjectReader& parent) {
  const auto* value = parent.object("orientation", Need::Optional);
  if (!value) return std::nullopt;
  ObjectReader r(ctx.doc, *value, parent.child("orientation"), ctx.diags, "orientation");
  const auto heading = r.number("heading", Need::Required);
  r.finish();
  return heading;
}

void read_waypoint_placement(LoadContext& ctx, ObjectReader& r, StartPosition& start) {
  start.waypoint = read_waypoint_ref(r);
  start.wp_offset = r.number("wp_offset", Need::Optional, Quantity::Length).value_or(0.0);
  start.heading = read_orientation(ctx, r);
}

StartPosition read_ego_start(LoadContext& ctx, const nlohmann::json& value, const std::string& pointer) {
  ObjectReader r(ctx.doc, value, pointer, ctx.diags, "ego's start position");
  StartPosition start;
  start.where = r.where();
  if (const auto type = r.string("type", Need::Optional); type && *type != "waypoint") {
    r.error("type", fmt::format("the ego's start position is a waypoint: \"type\" may only be \"waypoint\" "
                                "(or left out), found \"{}\"",
                                *type));
  }
  read_waypoint_placement(ctx, r, start);
  for (const char* key : {"target_actor_id", "distance", "measure_type"})
    reject_key(r, key,
               fmt::format("\"{}\" belongs to start positions of type \"distance\", which only others may use; "
                           "the ego starts at \"wp_id\"/\"wp_idx\"",
                           key));
  r.finish();
  return start;
}

std::optional<WaypointRef> read_ego_end(LoadContext& ctx, const nlohmann::json& value, const std::string& pointer) {
  ObjectReader r(ctx.doc, value, pointer, ctx.diags, "ego's end position");
  auto end = read_waypoint_ref(r);
  r.finish();
  return end;
}

EgoOpening read_ego_opening(LoadContext& ctx, const nlohmann::json& value, const std::string& pointer) {
  ObjectReader r(ctx.doc, value, pointer, ctx.diags, "ego's opening");
  EgoOpening ego;
  ego.start.where = r.where();
  if (const auto* start = r.object("start_position", Need::Required))
    ego.start = read_ego_start(ctx, *start, r.child("start_position"));
  if (const auto* end = r.object("end_position", Need::Optional))
    ego.end = read_ego_end(ctx, *end, r.child("end_position"));
  r.finish();
  return ego;
}

StartPosition read_other_start(LoadContext& ctx, const nlohmann::json& value, const std::string& pointer) {
  ObjectReader r(ctx.doc, value, pointer, ctx.diags, "start position");
  StartPosition start;
  start.where = r.where();
  // Absent type: a waypoint, as in the format document's own example.
  const auto type = r.choice("type", {"waypoint", "distance"}, Need::Optional);
  if (r.has("type") && !type) {
    r.allow({"wp_id", "wp_idx", "wp_offset", "orientation", "target_actor_id", "distance", "measure_type"});
    r.finish();
    return start;
  }
  if (type && *type == "distance") {
    start.type = StartPositionType::Distance;
    // Absent target_actor_id: placed relative to the ego, like relative speeds and distances.
    start.target = r.integer("target_actor_id", Need::Optional).value_or(ctx.ego_id);
    start.distance = r.number("distance", Need::Required, Quantity::Length).value_or(0.0);
    start.measure = read_measure_type(r).value_or(MeasureType::Center);
    start.wp_offset = r.number("wp_offset", Need::Optional, Quantity::Length).value_or(0.0);
    start.heading = read_orientation(ctx, r);
    // The route the actor drives (the reference implementation reads it for every start
    // position); absent: the target's route.
    if (const auto wp_id = r.string("wp_id", Need::Optional))
      start.waypoint = WaypointRef{*wp_id, 0.0, r.where("wp_id")};
    reject_key(r, "wp_idx",
               "\"wp_idx\" belongs to start positions of type \"waypoint\"; type \"distance\" places the actor "
               "\"distance\" m along the road from \"target_actor_id\" (on the route \"wp_id\" when given)");
  } else {
    start.type = StartPositionType::Waypoint;
    read_waypoint_placement(ctx, r, start);
    for (const char* key : {"target_actor_id", "distance", "measure_type"})
      reject_key(r, key,
                 fmt::format("\"{}\" belongs to start positions of type \"distance\"; this one is of type "
                             "\"waypoint\"{}",
                             key, r.has("type") ? "" : " (the default when \"type\" is left out)"));
  }
  r.finish();
  return start;
}

std::optional<SpeedAction> read_start_speed(LoadContext& ctx, const nlohmann::json& value,
                                            const std::string& pointer, ActorId actor) {
  ObjectReader r(ctx.doc, value, pointer, ctx.diags, "start speed");
  auto speed = r.is_object() ? read_speed_body(ctx, r, false) : std::nullopt;
  r.finish();  // reports the format document's own typo "vlaue" with "did you mean \"value\""
  if (speed) speed->actor = actor;
  return speed;
}

std::optional<OtherOpening> read_other_opening(LoadContext& ctx, const nlohmann::json& value,
                                               const std::string& pointer, std::vector<SceneId>& misplaced_next) {
  ObjectReader r(ctx.doc, value, pointer, ctx.diags, "opening entry of \"others\"");
  OtherOpening other;
  other.where = r.where();
  const auto actor = r.integer("actor_id", Need::Required);
  other.description = r.string("description", Need::Optional).value_or("");
  if (const auto* start = r.object("start_position", Need::Required))
    other.start = read_other_start(ctx, *start, r.child("start_position"));
  if (const auto* speed = r.object("start_speed", Need::Optional))
    other.start_speed = read_start_speed(ctx, *speed, r.child("start_speed"), actor.value_or(0));
  // The format document's example puts next_scenes here; real files (and the reference
  // implementation) read it directly under opening_scene.
  reject_key(r, "next_scenes",
             "\"next_scenes\" belongs directly under \"opening_scene\" (beside \"ego\" and \"others\"), not inside "
             "an entry of \"others\"");
  if (r.has("next_scenes") && value["next_scenes"].is_array())
    misplaced_next = read_int_list(ctx, value["next_scenes"], r.child("next_scenes"), "next_scenes");
  r.finish();
  if (!actor) return std::nullopt;  // nothing to attach the rest to
  other.actor = *actor;
  return other;
}

}  // namespace

OpeningScene read_opening_scene(LoadContext& ctx, const nlohmann::json& value, const std::string& pointer) {
  ObjectReader r(ctx.doc, value, pointer, ctx.diags, "opening scene");
  OpeningScene opening;
  opening.where = r.where();
  opening.ego.start.where = r.where();
  if (const auto* ego = r.object("ego", Need::Required)) opening.ego = read_ego_opening(ctx, *ego, r.child("ego"));
  std::vector<SceneId> misplaced_next;
  const auto* others = r.array("others", Need::Optional);
  ctx.need(others || !r.has("others"));
  if (others) {
    for (std::size_t i = 0; i < others->size(); ++i) {
      auto other = read_other_opening(ctx, (*others)[i], json_pointer_child(r.child("others"), i), misplaced_next);
      if (ctx.need(other.has_value())) opening.others.push_back(std::move(*other));
    }
  }
  const auto* next = r.array("next_scenes", Need::Optional);
  ctx.need(next || !r.has("next_scenes"));
  if (next)
    opening.next_scenes = read_int_list(ctx, *next, r.child("next_scenes"), "next_scenes");
  else if (!misplaced_next.empty())
    opening.next_scenes = misplaced_next;  // already reported; spares a follow-on "unreachable" error
  r.finish();
  return opening;
}

}  // namespace orch::scenario_loading

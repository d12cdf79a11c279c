// The top of a ScenarioExecutor file: title, map_id, actors, scenes, stop conditions.
// Opening scene, conditions and actions have their own files (loader_*.cpp).
#include "scenario_executor/loader.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>

#include "core/errors.hpp"
#include "scenario_executor/loader_internal.hpp"

namespace orch {

namespace scenario_loading {

using namespace orch::scenario;

namespace {

bool is_hex_colour(const std::string& text) {
  return text.size() == 6 &&
         std::all_of(text.begin(), text.end(), [](char c) { return std::isxdigit(static_cast<unsigned char>(c)); });
}

std::optional<ActorSpec> read_actor(LoadContext& ctx, const nlohmann::json& value, const std::string& pointer,
                                    bool is_ego) {
  ObjectReader r(ctx.doc, value, pointer, ctx.diags, is_ego ? "ego actor" : "actor");
  ActorSpec actor;
  actor.is_ego = is_ego;
  actor.where = r.where();
  const auto id = r.integer("actor_id", Need::Required);
  actor.model_id = read_id_string(r, "model_id", Need::Required).value_or("");
  actor.description = r.string("description", Need::Optional).value_or("");
  if (const auto colour = r.string("color", Need::Optional)) {
    if (is_hex_colour(*colour)) actor.color = *colour;
    else r.error("color", fmt::format("\"color\" must be six hex digits \"rrggbb\" (e.g. \"ff0000\"), found \"{}\"",
                                      *colour));
  }
  r.finish();
  if (!id) return std::nullopt;
  actor.id = *id;
  return actor;
}

void read_actors(LoadContext& ctx, const nlohmann::json& value, const std::string& pointer, Scenario& s) {
  ObjectReader r(ctx.doc, value, pointer, ctx.diags, "actors");
  s.ego.is_ego = true;
  s.ego.where = r.where();
  if (const auto* ego = r.object("ego", Need::Required)) {
    if (auto actor = read_actor(ctx, *ego, r.child("ego"), true); ctx.need(actor.has_value())) s.ego = std::move(*actor);
  } else {
    ctx.need(false);
  }
  const auto* others = r.array("others", Need::Optional);
  ctx.need(others || !r.has("others"));
  if (others) {
    for (std::size_t i = 0; i < others->size(); ++i)
      if (auto actor = read_actor(ctx, (*others)[i], json_pointer_child(r.child("others"), i), false);
          ctx.need(actor.has_value()))
        s.others.push_back(std::move(*actor));
  }
  r.finish();
  ctx.ego_id = s.ego.id;
}

std::optional<Scene> read_scene(LoadContext& ctx, const nlohmann::json& value, const std::string& pointer,
                                bool ending) {
  ObjectReader r(ctx.doc, value, pointer, ctx.diags, ending ? "ending scene" : "scene");
  Scene scene;
  scene.ending = ending;
  scene.where = r.where();
  const auto id = r.integer("scene_id", Need::Required);
  scene.description = r.string("description", Need::Optional).value_or("");
  scene.conditions.where = r.where();
  r.allow({"conditions"});
  if (r.has("conditions")) {
    scene.conditions = read_condition_group(ctx, value["conditions"], r.child("conditions"));
  }
  if (!ending) {
    scene.duration = r.number("duration", Need::Optional, Quantity::Time).value_or(0.0);
    if (const auto* actions = r.array("actions", Need::Optional))
      scene.actions = read_actions(ctx, *actions, r.child("actions"));
    const auto* next = r.array("next_scenes", Need::Optional);
    ctx.need(next || !r.has("next_scenes"));
    if (next) scene.next_scenes = read_int_list(ctx, *next, r.child("next_scenes"), "next_scenes");
  } else {
    // Reported here with what to do instead; an empty "actions" list is accepted.
    r.already_reported({"actions", "next_scenes", "duration"});
    const bool has_actions = r.has("actions") && !(value["actions"].is_array() && value["actions"].empty());
    if (has_actions)
      r.error("actions", "an ending scene has no actions: the scenario ends as soon as it is entered; move them to "
                         "a scene before it");
    if (r.has("next_scenes"))
      r.error("next_scenes", "an ending scene has no \"next_scenes\": the scenario ends as soon as it is entered");
    if (r.has("duration"))
      r.warning("duration", "\"duration\" has no effect on an ending scene: the scenario ends as soon as it is "
                            "entered");
  }
  r.finish();
  if (!id) return std::nullopt;
  scene.id = *id;
  return scene;
}

void read_scenes(LoadContext& ctx, ObjectReader& r, const std::string& key, bool ending, Scenario& s) {
  const auto* scenes = r.array(key, Need::Optional);
  if (!ctx.need(scenes || !r.has(key)) || !scenes) return;
  for (std::size_t i = 0; i < scenes->size(); ++i)
    if (auto scene = read_scene(ctx, (*scenes)[i], json_pointer_child(r.child(key), i), ending);
        ctx.need(scene.has_value()))
      s.scenes.push_back(std::move(*scene));
}

void read_scenario_block(LoadContext& ctx, const nlohmann::json& value, const std::string& pointer, Scenario& s) {
  ObjectReader r(ctx.doc, value, pointer, ctx.diags, "scenario block");
  s.opening.where = r.where();
  if (const auto* opening = r.object("opening_scene", Need::Required); ctx.need(opening != nullptr))
    s.opening = read_opening_scene(ctx, *opening, r.child("opening_scene"));
  read_scenes(ctx, r, "scenes", false, s);
  read_scenes(ctx, r, "ending_scenes", true, s);
  // The document spells the top-level block "stop_condition" in one place; it belongs at the top.
  reject_key(r, "stop_conditions", "\"stop_conditions\" belongs at the top level of the file, beside \"scenario\"");
  r.finish();
}

}  // namespace

ReadScenario read_scenario(const JsonDocument& doc, Diagnostics& diags) {
  LoadContext ctx{doc, diags};
  Scenario s;
  s.file = doc.path();
  s.opening.where = s.ego.where = doc.where("");
  ObjectReader r(doc, doc.root(), "", diags, "scenario file");
  ctx.need(r.is_object());
  s.title = r.string("title", Need::Optional).value_or("");
  s.description = r.string("description", Need::Optional).value_or("");
  s.map_id = read_id_string(r, "map_id", Need::Required).value_or("");
  s.traffic = r.string("traffic", Need::Optional).value_or("");
  // Actors first: relative speeds and distances without a target refer to the ego's id.
  if (const auto* actors = r.object("actors", Need::Required); ctx.need(actors != nullptr))
    read_actors(ctx, *actors, r.child("actors"), s);
  if (const auto* block = r.object("scenario", Need::Required); ctx.need(block != nullptr))
    read_scenario_block(ctx, *block, r.child("scenario"), s);
  r.allow({"stop_conditions"});  // read below; any JSON type gets read_condition_group's message
  if (r.has("stop_conditions")) {
    s.stop_conditions = read_condition_group(ctx, doc.root()["stop_conditions"], r.child("stop_conditions"));
  }
  if (r.has("stop_condition"))  // the format document's table spells it so
    reject_key(r, "stop_condition", "the key is \"stop_conditions\" (plural), as in the reference implementation");
  r.finish();
  return {std::move(s), ctx.skeleton_complete};
}

}  // namespace scenario_loading

LoadedScenario load_scenario(const std::string& path) {
  try {
    return load_scenario(JsonDocument::load(path));
  } catch (const ScenarioError& e) {  // unreadable file, invalid JSON, duplicate key
    return {std::nullopt, e.diagnostics()};
  }
}

LoadedScenario load_scenario(const JsonDocument& doc) {
  LoadedScenario loaded;
  auto read = scenario_loading::read_scenario(doc, loaded.diagnostics);
  // Nothing may run a half-read file: the model is only handed out when it read cleanly.
  if (!loaded.diagnostics.has_errors()) loaded.scenario = std::move(read.scenario);
  return loaded;
}

}  // namespace orch

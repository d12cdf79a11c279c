#pragma once
// Pieces check_scenario's source files share (validator*.cpp).
//
// Messages point at the element a model value came from (an action, a condition, a start
// position): the model keeps one SourceLocation per element, so a problem with its
// "wp_idx" is reported at the object that holds it, and the message names the key.
#include <optional>
#include <string>

#include "core/diagnostics.hpp"
#include "map/waypoint_file.hpp"
#include "scenario_executor/catalog.hpp"
#include "scenario_executor/model.hpp"
#include "scenario_executor/validator.hpp"

namespace orch::scenario_checks {

struct CheckContext {
  const scenario::Scenario& s;
  const WaypointFile& waypoints;
  const Catalog& catalog;
  const ValidationOptions& options;
  Diagnostics& diags;

  // The catalog entry of an actor's model; nullptr for unknown actors and models (both
  // reported on their own), so kind checks are skipped rather than repeated.
  [[nodiscard]] const ModelInfo* model_of(sim::ActorId id) const {
    const auto* actor = s.find_actor(id);
    return actor ? catalog.find(actor->model_id) : nullptr;
  }
};

// validator.cpp: actor ids, models, one opening entry per actor.
void check_actors(CheckContext& ctx);

// validator_references.cpp: actor ids, waypoints, actor kinds and value ranges used by
// start positions, conditions and actions.
void check_opening(CheckContext& ctx);
void check_scene_contents(CheckContext& ctx);

// validator_graph.cpp: scene ids and next_scenes, reachability, start positions relative
// to actors that form a cycle.
void check_scene_graph(CheckContext& ctx);
void check_start_cycles(CheckContext& ctx);

// Text "0, 1 and 2" of the actor ids defined, for "no such actor" messages.
std::string defined_actor_ids(const scenario::Scenario& s);

// validator_references.cpp: checks the element checkers share (scenario/elements.hpp).
void check_actor_ref(CheckContext& ctx, sim::ActorId id, const SourceLocation& where, const char* key);
// The route `wp_id` names, or null (reported unless "" or the map's waypoints are unknown).
const WaypointRoute* check_route(CheckContext& ctx, const std::string& wp_id, const SourceLocation& where);
// Placements put an actor at the point: it must exist. Targets are places to reach: the
// real ALKS templates, copied to a shorter map, aim past the end of the route, which the
// reference reads as the route's last point, so that is a warning unless strict.
enum class WaypointUse { Placement, Target };
void check_waypoint(CheckContext& ctx, const scenario::WaypointRef& ref, WaypointUse use);
void check_not_negative(CheckContext& ctx, double value, const SourceLocation& where, const char* key,
                        const char* unit);
// Actions that make no sense for what the actor is: an obstacle does not move, a
// pedestrian has no lane, lights or siren.
void check_can(CheckContext& ctx, sim::ActorId actor, const SourceLocation& where, const char* action,
               bool pedestrian_ok, const char* hint = "");
// A speed action or an opening's start_speed.
void check_speed(CheckContext& ctx, const scenario::SpeedAction& a, const SourceLocation& where, const char* what);
// light_state, sound_state: vehicles only; special lights and sirens on emergency vehicles.
void check_signals(CheckContext& ctx, sim::ActorId actor, const SourceLocation& where, const char* action,
                   bool uses_special);

}  // namespace orch::scenario_checks

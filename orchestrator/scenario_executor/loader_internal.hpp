#pragma once
// Pieces the scenario loader's source files share (loader*.cpp); not for other modules,
// except read_scenario, which `validate` uses to check references even in a file with
// errors (see its comment).
//
// Convention: every reader reports its problems into ctx.diags and returns what it could
// read. An element with an error of its own (a condition, an action) is left out of the
// model, so that check_scenario, run over a best-effort model, does not repeat the problem
// as a follow-on message. Elements others refer to by id (actors, scenes, opening entries)
// are kept whenever their id could be read.
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/diagnostics.hpp"
#include "json/json_document.hpp"
#include "json/object_reader.hpp"
#include "scenario_executor/model.hpp"

namespace orch::scenario_loading {

struct LoadContext {
  const JsonDocument& doc;
  Diagnostics& diags;
  // The ego's actor id: the target of relative speeds and distances that name none.
  sim::ActorId ego_id = 0;
  // False once something others refer to by id could not be read (an actor, a scene, the
  // opening scene, a next_scenes entry): checking references would then only repeat it.
  bool skeleton_complete = true;

  // Records whether a part the skeleton needs was read; returns `read`.
  bool need(bool read) {
    if (!read) skeleton_complete = false;
    return read;
  }
};

// Every key one condition / action may hold (the names of scenario/elements.hpp's tables),
// for "did you mean" on a misspelt kind.
const std::vector<std::string>& condition_kinds();
const std::vector<std::string>& action_kinds();

// ---------------------------------------------------------------- loader_common.cpp
inline double kmh_to_ms(double kmh) { return kmh / 3.6; }

std::optional<scenario::Comparison> read_comparison(ObjectReader& r, Need need);
std::optional<scenario::MeasureType> read_measure_type(ObjectReader& r);  // absent = center
std::optional<scenario::SpeedType> read_speed_type(ObjectReader& r);       // required
// wp_id (non-empty string) and wp_idx (number, may be fractional) of the object `r` reads.
// The reference's `where` is that object: both keys are reported against it.
std::optional<scenario::WaypointRef> read_waypoint_ref(ObjectReader& r);
// A non-empty string; "" in a file is an error (check_scenario treats "" as already reported).
std::optional<std::string> read_id_string(ObjectReader& r, const std::string& key, Need need);
// An array of whole numbers (next_scenes); bad elements are reported and skipped.
std::vector<int> read_int_list(LoadContext& ctx, const nlohmann::json& array, const std::string& pointer,
                               const std::string& what);
// A key present where it does not belong, with a message saying where it goes.
void reject_key(ObjectReader& r, const std::string& key, const std::string& why);

// ---------------------------------------------------------------- loader_conditions.cpp
// A conditions object: {"and": [...]} and/or {"or": [...]}, items may be groups again.
// Absent or {} = always true (an empty And group).
scenario::ConditionGroup read_condition_group(LoadContext& ctx, const nlohmann::json& value,
                                              const std::string& pointer);

// ---------------------------------------------------------------- loader_actions.cpp
std::vector<scenario::Action> read_actions(LoadContext& ctx, const nlohmann::json& array,
                                           const std::string& pointer);
// The body of a speed action or of an opening start_speed (same keys, same meaning).
std::optional<scenario::SpeedAction> read_speed_body(LoadContext& ctx, ObjectReader& r, bool needs_actor);

// ---------------------------------------------------------------- loader_opening.cpp
scenario::OpeningScene read_opening_scene(LoadContext& ctx, const nlohmann::json& value,
                                          const std::string& pointer);

// ---------------------------------------------------------------- loader.cpp
// The whole file as far as it can be read, with every problem in `diags`. Unlike
// load_scenario (which gives no scenario when the file has errors, so that nothing runs
// a half-read file), this always returns a model: `validate` checks its references too
// whenever every actor, scene and next_scenes entry could be read, so that one pass
// reports structural and reference problems together without follow-on noise.
struct ReadScenario {
  scenario::Scenario scenario;
  bool skeleton_complete = true;  // see LoadContext
};
ReadScenario read_scenario(const JsonDocument& doc, Diagnostics& diags);

}  // namespace orch::scenario_loading

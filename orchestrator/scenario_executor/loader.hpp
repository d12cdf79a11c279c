#pragma once
// Reads a ScenarioExecutor JSON file into scenario::Scenario. Checks the file on its own:
// JSON syntax, types, required and unknown keys (with "did you mean"), enum values, and the
// documented spellings (both gods_hand and god_hands). References to actors, scenes, the
// map and its waypoints are checked by check_scenario (validator.hpp).
#include <optional>
#include <string>

#include "core/diagnostics.hpp"
#include "json/json_document.hpp"
#include "scenario_executor/model.hpp"

namespace orch {

struct LoadedScenario {
  std::optional<scenario::Scenario> scenario;  // empty when errors prevented building it
  Diagnostics diagnostics;
};

LoadedScenario load_scenario(const std::string& path);
LoadedScenario load_scenario(const JsonDocument& doc);

}  // namespace orch

#pragma once
// Binds a parameter set's values into a template scenario.
//
// A template is any scenario document whose values may be written as "${group.name}":
//  - a string that is exactly one placeholder becomes the parameter's value with its JSON
//    type (a number stays a number: "${ego.speed}" -> 62.5);
//  - placeholders inside a longer string are replaced by the value's text
//    ("lead at ${lead.gap} m" -> "lead at 40 m"); "$${" writes a literal "${".
// The binder works on a JSON value tree, not on a particular scenario format: today's only
// format is the ScenarioExecutor JSON, and a YAML (or other) wrapper only has to turn its
// file into the same tree first. Object keys are never substituted.
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "batch/logical_scenario.hpp"
#include "core/diagnostics.hpp"
#include "json/json_document.hpp"

namespace orch::batch {

struct Placeholder {
  std::string key;      // "group.name"
  std::string pointer;  // JSON pointer of the string holding it
  bool whole = false;   // the string is exactly this placeholder
};

// Every placeholder in the template; malformed ones ("${x}", an unclosed "${") are errors.
std::vector<Placeholder> find_placeholders(const JsonDocument& tmpl, Diagnostics& diags);

// Checks a template against a logical scenario: a placeholder naming no parameter is an
// error at the template's line (with "did you mean"), a parameter no placeholder uses is an
// error at the parameter's line in the logical file.
Diagnostics check_template(const LogicalScenario& logical, const JsonDocument& tmpl);
// The same for a template made of several files (an evaluation YAML and the scenario
// template it names): a parameter must be used in one of them.
Diagnostics check_template(const LogicalScenario& logical, const std::vector<const JsonDocument*>& docs);

// The template with every placeholder replaced. `values` maps "group.name" to the value.
// Throws ScenarioError when the template does not fit the values (unknown or malformed
// placeholders); call check_template first for the complete list of problems.
nlohmann::ordered_json bind_template(const JsonDocument& tmpl, const std::map<std::string, nlohmann::json>& values);

// {"group": {"name": v}} -> {"group.name": v}
std::map<std::string, nlohmann::json> flatten_values(const nlohmann::json& grouped);

}  // namespace orch::batch

#pragma once
// A logical scenario's template is a ScenarioExecutor JSON file or an evaluation YAML
// (docs/evaluation.md "Batches"): placeholders are bound in the same value tree either way,
// so criteria thresholds can be parameters too. What differs is how the file is read, the
// name of the bound file in the run folder, and that a bound evaluation file names its
// scenario by absolute path (the run folder is elsewhere).
//
// The scenario an evaluation template names may be a template itself (it holds
// placeholders): it is then bound with the same values into the run folder's
// scenario.json, which the bound evaluation file names. Its placeholders count as the
// template's: a parameter may be used in either file.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "batch/logical_scenario.hpp"
#include "core/diagnostics.hpp"
#include "json/json_document.hpp"

namespace orch::batch {

// The bound scenario beside a bound evaluation file, when its scenario is a template.
inline constexpr const char* kBoundScenarioFile = "scenario.json";

JsonDocument load_template(const std::filesystem::path& file);
bool is_evaluation_template(const std::filesystem::path& file);
// "evaluation.yaml" or "scenario.json": what `orchestrator run` gets in the run folder.
std::string bound_file_name(const std::filesystem::path& template_file);
// The scenario template an evaluation template names (Conditions/Scenario holds no
// placeholder and names a JSON file with placeholders); none otherwise.
std::optional<std::filesystem::path> scenario_template_of(const JsonDocument& tmpl);
// Every placeholder problem of the template and of the scenario template it names.
Diagnostics check_templates(const LogicalScenario& logical, const JsonDocument& tmpl);
// A bound evaluation file: its Conditions/Scenario made absolute against the template's
// folder, or kBoundScenarioFile (beside it in the run folder) when that scenario is a template.
void anchor_scenario_path(nlohmann::ordered_json& bound, const std::filesystem::path& template_file);

// One file of a run's folder, bound from the templates.
struct BoundFile {
  std::string name;  // in the run folder
  std::string text;
};
// The map of a run's bound files (the first is what `run` gets), and that they load: throws
// ScenarioError naming `label`.
std::string map_of_bound(const std::vector<BoundFile>& files, const std::string& label,
                         const std::filesystem::path& template_file);

}  // namespace orch::batch

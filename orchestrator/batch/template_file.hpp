#pragma once
// A logical scenario's template is a ScenarioExecutor JSON file or an evaluation YAML
// (docs/evaluation.md "Batches"): placeholders are bound in the same value tree either way,
// so criteria thresholds can be parameters too. What differs is how the file is read, the
// name of the bound file in the run folder, and that a bound evaluation file names its
// scenario by absolute path (the run folder is elsewhere).
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "json/json_document.hpp"

namespace orch::batch {

JsonDocument load_template(const std::filesystem::path& file);
bool is_evaluation_template(const std::filesystem::path& file);
// "evaluation.yaml" or "scenario.json": what `orchestrator run` gets in the run folder.
std::string bound_file_name(const std::filesystem::path& template_file);
// A bound evaluation file: its Conditions/Scenario made absolute against the template's folder.
void anchor_scenario_path(nlohmann::ordered_json& bound, const std::filesystem::path& template_file);
// The map and the loadable scenario of a bound file's text: throws ScenarioError naming `label`.
std::string map_of_bound(const std::string& text, const std::string& label, const std::filesystem::path& template_file);

}  // namespace orch::batch

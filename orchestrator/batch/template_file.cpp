#include "batch/template_file.hpp"

#include "core/errors.hpp"
#include "evaluation/evaluation_file.hpp"
#include "evaluation/yaml_tree.hpp"
#include "scenario/loader.hpp"

namespace orch::batch {

bool is_evaluation_template(const std::filesystem::path& file) { return is_evaluation_file(file); }

JsonDocument load_template(const std::filesystem::path& file) {
  return is_evaluation_template(file) ? load_yaml_document(file.string()) : JsonDocument::load(file.string());
}

std::string bound_file_name(const std::filesystem::path& template_file) {
  return is_evaluation_template(template_file) ? "evaluation.yaml" : "scenario.json";
}

void anchor_scenario_path(nlohmann::ordered_json& bound, const std::filesystem::path& template_file) {
  if (!is_evaluation_template(template_file)) return;
  const auto conditions = bound.find("Evaluation");
  if (conditions == bound.end() || !conditions->is_object() || !conditions->contains("Conditions")) return;
  auto& c = (*conditions)["Conditions"];
  if (!c.is_object() || !c.contains("Scenario") || !c["Scenario"].is_string()) return;
  const std::filesystem::path scenario(c["Scenario"].get<std::string>());
  if (scenario.is_relative())
    c["Scenario"] = std::filesystem::absolute(template_file.parent_path() / scenario).lexically_normal().string();
}

std::string map_of_bound(const std::string& text, const std::string& label, const std::filesystem::path& template_file) {
  std::string scenario_text = text;
  std::string scenario_label = label;
  if (is_evaluation_template(template_file)) {
    // JSON text is YAML: the bound evaluation file is read as `run` will read it.
    const LoadedEvaluation e = read_evaluation(parse_yaml_document(text, label));
    if (!e.file) throw ScenarioError(e.diagnostics);
    const LoadedScenario loaded = load_scenario(e.file->scenario_file);
    if (!loaded.scenario) throw ScenarioError(loaded.diagnostics);
    return loaded.scenario->map_id;
  }
  const LoadedScenario loaded = load_scenario(JsonDocument::parse(scenario_text, scenario_label));
  if (!loaded.scenario) throw ScenarioError(loaded.diagnostics);
  return loaded.scenario->map_id;
}

}  // namespace orch::batch

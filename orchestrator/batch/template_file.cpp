#include "batch/template_file.hpp"

#include "batch/template_binder.hpp"
#include "core/errors.hpp"
#include "core/scenario_format.hpp"
#include "evaluation/evaluation_file.hpp"
#include "evaluation/yaml_tree.hpp"
#include "json/json_text.hpp"
#include "scenario_executor/loader.hpp"

namespace orch::batch {

namespace {

// The value of /Evaluation/Conditions/Scenario in a tree, or null.
template <typename Json>
Json* scenario_value(Json& tree) {
  if (!tree.is_object()) return nullptr;
  const auto evaluation = tree.find("Evaluation");
  if (evaluation == tree.end() || !evaluation->is_object()) return nullptr;
  const auto conditions = evaluation->find("Conditions");
  if (conditions == evaluation->end() || !conditions->is_object()) return nullptr;
  const auto scenario = conditions->find("Scenario");
  if (scenario == conditions->end() || !scenario->is_string()) return nullptr;
  return &*scenario;
}

// A JSON (ScenarioExecutor) file with at least one placeholder: a scenario template. Any
// other file (OpenSCENARIO XML, not JSON at all) is not one.
bool is_scenario_template(const std::filesystem::path& file) {
  if (!std::filesystem::is_regular_file(file) || is_evaluation_file(file)) return false;
  try {
    Diagnostics ignored;  // a broken file is reported when it is loaded as a scenario
    return !find_placeholders(JsonDocument::load(file.string()), ignored).empty();
  } catch (const std::exception&) {
    return false;
  }
}

std::filesystem::path resolve(const std::filesystem::path& scenario, const std::filesystem::path& template_file) {
  return scenario.is_relative() ? std::filesystem::absolute(template_file.parent_path() / scenario).lexically_normal()
                                : scenario;
}

}  // namespace

bool is_evaluation_template(const std::filesystem::path& file) { return is_evaluation_file(file); }

JsonDocument load_template(const std::filesystem::path& file) {
  return is_evaluation_template(file) ? load_yaml_document(file.string()) : JsonDocument::load(file.string());
}

std::string bound_file_name(const std::filesystem::path& template_file) {
  return is_evaluation_template(template_file) ? "evaluation.yaml" : kBoundScenarioFile;
}

std::optional<std::filesystem::path> scenario_template_of(const JsonDocument& tmpl) {
  if (!is_evaluation_template(tmpl.path())) return std::nullopt;
  const nlohmann::json* value = scenario_value(tmpl.root());
  if (!value || value->get<std::string>().find("${") != std::string::npos) return std::nullopt;
  const auto file = resolve(value->get<std::string>(), tmpl.path());
  if (!is_scenario_template(file)) return std::nullopt;
  return file;
}

Diagnostics check_templates(const LogicalScenario& logical, const JsonDocument& tmpl) {
  const auto scenario = scenario_template_of(tmpl);
  if (!scenario) return check_template(logical, tmpl);
  const JsonDocument scenario_tmpl = JsonDocument::load(scenario->string());
  return check_template(logical, std::vector<const JsonDocument*>{&tmpl, &scenario_tmpl});
}

void anchor_scenario_path(nlohmann::ordered_json& bound, const std::filesystem::path& template_file) {
  if (!is_evaluation_template(template_file)) return;
  nlohmann::ordered_json* value = scenario_value(bound);
  if (!value) return;
  const auto file = resolve(value->get<std::string>(), template_file);
  *value = is_scenario_template(file) ? std::string(kBoundScenarioFile) : file.string();
}

std::string map_of_bound(const std::vector<BoundFile>& files, const std::string& label,
                         const std::filesystem::path& template_file) {
  if (!is_evaluation_template(template_file)) {
    const LoadedScenario loaded = load_scenario(JsonDocument::parse(files.front().text, label));
    if (!loaded.scenario) throw ScenarioError(loaded.diagnostics);
    return loaded.scenario->map_id;
  }
  // JSON text is YAML: the bound evaluation file is read as `run` will read it, except that
  // a bound scenario beside it is not on disk yet: its template stands in for the check.
  nlohmann::ordered_json tree = nlohmann::ordered_json::parse(files.front().text);
  const bool beside = files.size() > 1;
  if (nlohmann::ordered_json* value = scenario_value(tree); value && beside) {
    const JsonDocument tmpl = load_template(template_file);
    if (const auto scenario = scenario_template_of(tmpl)) *value = scenario->string();
  }
  const LoadedEvaluation e = read_evaluation(parse_yaml_document(json_text(tree, 2), label));
  if (!e.file) throw ScenarioError(e.diagnostics);
  // An OpenSCENARIO scenario (never a template: its own parameters vary by *_variation.xosc)
  // is read and checked, with its road, by the run; the set records no map for it.
  if (!beside && detect_scenario_format(e.file->scenario_file) == ScenarioFormat::OpenScenario) return "";
  const LoadedScenario loaded = beside ? load_scenario(JsonDocument::parse(files[1].text, label + " (" + files[1].name + ")"))
                                       : load_scenario(e.file->scenario_file);
  if (!loaded.scenario) throw ScenarioError(loaded.diagnostics);
  return loaded.scenario->map_id;
}

}  // namespace orch::batch

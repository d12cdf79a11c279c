#include "batch/search_objective.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>

#include "core/errors.hpp"
#include "core/suggest.hpp"
#include "metrics/metric_table.hpp"

namespace orch::batch {

namespace {

constexpr const char* kCriterionPrefix = "criterion:";

bool starts_with(const std::string& s, const std::string& prefix) { return s.rfind(prefix, 0) == 0; }

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

// The ego's label among result.json's metrics: the actor marked ego, as the metrics name it.
std::string ego_label(const nlohmann::json& result) {
  const nlohmann::json& metrics = result.at("metrics");
  for (const auto& [label, _] : metrics.items())
    if (lower(label) == "ego") return label;
  if (result.contains("actors") && result["actors"].is_array())
    for (const auto& a : result["actors"]) {
      if (!a.value("ego", false)) continue;
      for (const char* field : {"description", "sumo_id"})
        if (a.contains(field) && a[field].is_string() && metrics.contains(a[field].get<std::string>()))
          return a[field].get<std::string>();
      if (a.contains("actor_id") && metrics.contains(a["actor_id"].dump())) return a["actor_id"].dump();
    }
  return metrics.empty() ? "" : metrics.begin().key();
}

std::vector<std::string> criterion_names(const nlohmann::json& result) {
  std::vector<std::string> out;
  if (result.contains("criteria") && result["criteria"].is_array())
    for (const auto& c : result["criteria"]) out.push_back(c.value("name", ""));
  return out;
}

const nlohmann::json* find_criterion(const nlohmann::json& result, const std::string& name) {
  if (result.contains("criteria") && result["criteria"].is_array())
    for (const auto& c : result["criteria"])
      if (c.value("name", "") == name) return &c;
  return nullptr;
}

std::optional<double> summary_number(const nlohmann::json& v) {
  if (v.is_number()) return v.get<double>();
  if (v.is_object() && v.contains("value") && v["value"].is_number()) return v["value"].get<double>();
  return std::nullopt;
}

}  // namespace

std::vector<std::string> objective_metric_names() {
  std::vector<std::string> out;
  for (const std::size_t i : metrics::summary_rows()) out.emplace_back(metrics::metric_table()[i].summary_key);
  return out;
}

void check_objective(const std::string& objective) {
  if (objective == "sim_time" || starts_with(objective, kCriterionPrefix)) return;
  const auto dot = objective.rfind('.');
  const std::string metric = dot == std::string::npos ? objective : objective.substr(dot + 1);
  std::vector<std::string> names = objective_metric_names();
  if (std::find(names.begin(), names.end(), metric) != names.end()) return;
  names.emplace_back("sim_time");
  throw OrchError(fmt::format("--objective \"{}\": no metric \"{}\"{}; expected sim_time, criterion:NAME, METRIC or "
                              "ACTOR.METRIC with METRIC one of {}",
                              objective, metric, did_you_mean(metric, names), fmt::join(objective_metric_names(), ", ")));
}

std::optional<double> objective_value(const nlohmann::json& result, const std::string& objective) {
  if (objective == "sim_time") return summary_number(result.value("sim_time", nlohmann::json()));
  if (starts_with(objective, kCriterionPrefix)) {
    const std::string name = objective.substr(std::string(kCriterionPrefix).size());
    const nlohmann::json* c = find_criterion(result, name);
    if (!c)
      throw OrchError(fmt::format("--objective {}: the runs have no criterion \"{}\"{} (their criteria: {})", objective,
                                  name, did_you_mean(name, criterion_names(result)),
                                  fmt::join(criterion_names(result), ", ")));
    return summary_number(c->value("actual", nlohmann::json()));
  }
  if (!result.contains("metrics") || !result["metrics"].is_object()) return std::nullopt;
  const nlohmann::json& metrics = result["metrics"];
  const auto dot = objective.rfind('.');
  const std::string actor = dot == std::string::npos ? ego_label(result) : objective.substr(0, dot);
  const std::string metric = dot == std::string::npos ? objective : objective.substr(dot + 1);
  if (!metrics.contains(actor)) {
    std::vector<std::string> actors;
    for (const auto& [label, _] : metrics.items()) actors.push_back(label);
    throw OrchError(fmt::format("--objective {}: the runs have no actor \"{}\"{} (their actors: {})", objective, actor,
                                did_you_mean(actor, actors), fmt::join(actors, ", ")));
  }
  return summary_number(metrics[actor].value(metric, nlohmann::json()));
}

bool criterion_passed(const nlohmann::json& result, const std::string& criterion) {
  if (criterion == "verdict") return result.value("verdict", "") == "success";
  if (criterion == "collision") return !result.contains("collision") || result["collision"].is_null();
  if (const nlohmann::json* c = find_criterion(result, criterion)) return c->value("success", false);
  std::vector<std::string> names{"verdict", "collision"};
  for (auto& n : criterion_names(result)) names.push_back(n);
  throw OrchError(fmt::format("--boundary {}: the runs have no criterion \"{}\"{}; expected one of {}", criterion,
                              criterion, did_you_mean(criterion, names), fmt::join(names, ", ")));
}

}  // namespace orch::batch

#include "batch/batch_metrics_csv.hpp"

#include <fmt/format.h>

#include <map>
#include <set>

#include "batch/template_binder.hpp"

namespace orch::batch {

namespace {

std::string csv_cell(const nlohmann::json& v) {
  std::string text;
  if (v.is_null()) return "";
  if (v.is_string()) text = v.get<std::string>();
  else if (v.is_boolean()) text = v.get<bool>() ? "true" : "false";
  else if (v.is_number_float()) text = fmt::format("{:.6g}", v.get<double>());
  else text = v.dump();
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

// The row's values by column name, besides the fixed columns.
std::map<std::string, nlohmann::json> values_of(const ExecutionSummary& s) {
  std::map<std::string, nlohmann::json> row;
  if (!s.preventable.empty()) row["preventable"] = s.preventable;  // --reference-run
  if (s.sampled_values.is_object())
    for (const auto& [key, value] : flatten_values(s.sampled_values)) row[key] = value;
  if (s.criteria.is_array())
    for (const auto& c : s.criteria) {
      const std::string name = c.value("name", "");
      row["criterion." + name + ".actual"] = c.contains("actual") ? c["actual"] : nlohmann::json();
      row["criterion." + name + ".success"] = c.value("success", false);
    }
  if (s.metrics.is_object())
    for (const auto& [actor, summary] : s.metrics.items())
      for (const auto& [key, value] : summary.items())
        row["metrics." + actor + "." + key] = value.is_object() ? value.value("value", nlohmann::json()) : value;
  return row;
}

}  // namespace

std::string batch_metrics_csv(const BatchReport& report) {
  std::vector<std::map<std::string, nlohmann::json>> rows;
  std::set<std::string> columns;
  for (const auto& e : report.planned) {
    const auto it = report.done.find(e.id);
    rows.push_back(it == report.done.end() ? std::map<std::string, nlohmann::json>{} : values_of(it->second));
    for (const auto& [key, value] : rows.back()) columns.insert(key);
  }
  std::string out = "run_id,logical_uuid,parameter_uuid,seed,verdict";
  for (const auto& c : columns) out += "," + csv_cell(c);
  out += "\n";
  for (std::size_t i = 0; i < report.planned.size(); ++i) {
    const auto& e = report.planned[i];
    const auto it = report.done.find(e.id);
    const bool done = it != report.done.end();
    out += fmt::format("{},{},{},{},{}", e.id, e.logical_uuid, e.parameter_uuid,
                       done && it->second.seed ? std::to_string(*it->second.seed) : "",
                       done ? it->second.verdict : "missing");
    for (const auto& c : columns) {
      const auto v = rows[i].find(c);
      out += "," + (v == rows[i].end() ? std::string() : csv_cell(v->second));
    }
    out += "\n";
  }
  return out;
}

}  // namespace orch::batch

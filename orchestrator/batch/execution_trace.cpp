#include "batch/execution_trace.hpp"

#include <fmt/format.h>

#include "batch/template_file.hpp"
#include "core/errors.hpp"
#include "json/json_document.hpp"
#include "json/json_text.hpp"
#include "json/object_file.hpp"

namespace orch::batch {

namespace {

using nlohmann::ordered_json;

ordered_json path_or_null(const std::filesystem::path& p) {
  return p.empty() ? ordered_json(nullptr) : ordered_json(p.string());
}

template <typename T>
ordered_json opt(const std::optional<T>& v) {
  return v ? ordered_json(*v) : ordered_json(nullptr);
}

ordered_json attempt_json(const Attempt& a) {
  return {{"attempt", a.number},     {"started_at", a.started_at}, {"verdict", a.verdict},
          {"reason", a.reason},      {"exit_code", opt(a.exit_code)}, {"signal", opt(a.signal)},
          {"timed_out", a.timed_out}, {"wall_time_s", a.wall_time_s}, {"sim_time", opt(a.sim_time)},
          {"run_wall_time_s", opt(a.run_wall_time_s)}};
}

}  // namespace

std::string shell_command(const std::vector<std::string>& argv) {
  std::string out;
  for (const auto& a : argv) {
    if (!out.empty()) out += ' ';
    const bool plain = !a.empty() && a.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                                         "0123456789-_./=:,+") == std::string::npos;
    if (plain) {
      out += a;
      continue;
    }
    out += '\'';
    for (char c : a) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    out += '\'';
  }
  return out;
}

std::filesystem::path execution_trace_path(const std::filesystem::path& batch_dir, const std::string& run_id) {
  return batch_dir / "executions" / ("execution_" + run_id + ".json");
}

std::string execution_trace_text(const PlannedRun& run, const PlannedLogical& logical, const ExecutionRecord& record) {
  const Attempt& last = record.attempts.back();
  const ordered_json out_block = output_block(run.logical_uuid, run.parameter_uuid);
  ordered_json j;
  j["execution_uuid"] = record.execution_uuid;
  j["logical_uuid"] = run.logical_uuid;
  j["abstract_uuid"] = logical.lineage.abstract_uuid.empty() ? ordered_json(nullptr) : ordered_json(logical.lineage.abstract_uuid);
  j["parameter_uuid"] = run.parameter_uuid;
  j["name"] = run.name;
  j["description"] = run.set.seed ? fmt::format("parameter set {} (seed {})", run.parameter_uuid, *run.set.seed)
                                  : fmt::format("parameter set {}", run.parameter_uuid);
  j["executed_at"] = record.executed_at;
  ordered_json trace;
  trace["abstract_scenario_file"] = path_or_null(logical.lineage.abstract_file);
  trace["natural_scenario_file"] = path_or_null(logical.lineage.natural_file);
  trace["original_prompt"] = logical.lineage.original_prompt.empty() ? ordered_json(nullptr)
                                                                     : ordered_json(logical.lineage.original_prompt);
  trace["logical_scenario_file"] = std::filesystem::absolute(logical.logical.file).lexically_normal().string();
  trace["parameter_file"] = std::filesystem::absolute(logical.parameter_file).lexically_normal().string();
  trace["parameter_uuid"] = run.parameter_uuid;
  trace["seed"] = opt(run.set.seed);
  trace["sampled_values"] = ordered_json(run.set.sampled_values);
  ordered_json impl;
  impl["template_file"] = std::filesystem::absolute(logical.logical.template_file).lexically_normal().string();
  impl["scenario_file"] = logical.variation ? impl["template_file"].get<std::string>()  // run as it is, with --param
                                            : out_block["run_dir"].get<std::string>() + "/" +
                                                  bound_file_name(logical.logical.template_file);
  impl["command"] = shell_command(record.command);
  impl["exit_code"] = opt(last.exit_code);
  impl["final_status"] = last.verdict;
  impl["reason"] = last.reason;
  impl["metrics"] = last.metrics;
  impl["criteria"] = last.criteria;
  if (!last.preventable.empty()) impl["preventable"] = last.preventable;
  if (!record.fork.is_null()) impl["fork"] = record.fork;
  impl["attempts"] = ordered_json::array();
  for (const auto& a : record.attempts) impl["attempts"].push_back(attempt_json(a));
  trace["implementation"] = impl;
  j["trace"] = trace;
  ordered_json outputs;
  outputs["run_dir"] = out_block["run_dir"];
  outputs["result_file"] = out_block["result_file"];
  outputs["trace_file"] = out_block["trace_file"];
  outputs["log_file"] = out_block["log_file"];
  outputs["sumo_log_file"] = out_block["run_dir"].get<std::string>() + "/sumo.log";
  outputs["child_log_file"] = out_block["run_dir"].get<std::string>() + "/child.log";
  j["outputs"] = outputs;
  return json_text(j, 2) + "\n";
}

ExecutionSummary read_execution_summary(const std::filesystem::path& file) {
  JsonObjectFile json(file.string(), "execution trace");
  const JsonDocument& doc = json.doc();
  Diagnostics& diags = json.diags();
  ExecutionSummary s;
  s.file = file;
  ObjectReader& top = json.top();
  s.logical_uuid = top.string("logical_uuid", Need::Required).value_or("");
  s.parameter_uuid = top.string("parameter_uuid", Need::Required).value_or("");
  s.name = top.string("name", Need::Optional).value_or("");
  top.allow({"execution_uuid", "abstract_uuid", "description", "executed_at"});
  s.run_id = run_id(s.logical_uuid, s.parameter_uuid);
  if (const auto* trace = top.object("trace", Need::Required)) {
    ObjectReader t(doc, *trace, "/trace", diags, "trace");
    if (t.has("seed") && trace->at("seed").is_number_integer()) s.seed = trace->at("seed").get<long long>();
    if (const auto* values = t.object("sampled_values", Need::Optional)) s.sampled_values = *values;
    t.allow({"seed", "abstract_scenario_file", "natural_scenario_file", "original_prompt", "logical_scenario_file",
             "parameter_file", "parameter_uuid"});
    if (const auto* impl = t.object("implementation", Need::Required)) {
      ObjectReader i(doc, *impl, "/trace/implementation", diags, "implementation");
      s.verdict = i.choice("final_status", {"success", "failure", "error"}, Need::Required).value_or("error");
      s.reason = i.string("reason", Need::Optional).value_or("");
      if (const auto* attempts = i.array("attempts", Need::Required)) {
        s.attempts = static_cast<int>(attempts->size());
        for (const auto& a : *attempts) {
          if (a.contains("wall_time_s") && a["wall_time_s"].is_number()) s.wall_time_s += a["wall_time_s"].get<double>();
          s.sim_time = (a.contains("sim_time") && a["sim_time"].is_number()) ? std::optional(a["sim_time"].get<double>())
                                                                          : std::nullopt;
        }
      }
      if (impl->contains("metrics")) s.metrics = impl->at("metrics");
      if (impl->contains("criteria")) s.criteria = impl->at("criteria");
      s.preventable = i.string("preventable", Need::Optional).value_or("");
      i.allow({"template_file", "scenario_file", "command", "exit_code", "metrics", "criteria", "fork"});
      i.finish();
    }
    t.finish();
  }
  if (const auto* outputs = top.object("outputs", Need::Required)) {
    if (outputs->contains("run_dir") && outputs->at("run_dir").is_string()) s.run_dir = outputs->at("run_dir").get<std::string>();
  }
  json.finish();
  return s;
}

}  // namespace orch::batch

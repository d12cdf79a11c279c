#include "batch/parameter_file.hpp"

#include <fmt/format.h>

#include "batch/identifiers.hpp"
#include "core/errors.hpp"
#include "json/json_text.hpp"
#include "json/object_reader.hpp"

namespace orch::batch {

namespace {

using nlohmann::json;
using nlohmann::ordered_json;

void read_sumo_config(ObjectReader& set, ParameterSet& out) {
  const json* cfg = set.object("sumo_config", Need::Required);
  if (!cfg) return;
  ObjectReader r(set.doc(), *cfg, set.child("sumo_config"), set.diags(), "sumo_config");
  out.sumo_config.map = r.string("map", Need::Optional).value_or("");
  out.sumo_config.step = r.number("step", Need::Required, Quantity::Time).value_or(0.05);
  if (out.sumo_config.step < 0.001 || out.sumo_config.step > 1.0)
    r.error("step", fmt::format("\"step\" must lie in [0.001, 1] s, found {}", out.sumo_config.step));
  // null means "not set" for the optional ones: the file says so explicitly.
  for (const char* key : {"max_time", "traffic", "backend"})
    if (r.has(key) && cfg->at(key).is_null()) r.allow({key});
  if (!(r.has("max_time") && cfg->at("max_time").is_null())) {
    out.sumo_config.max_time = r.number("max_time", Need::Optional, Quantity::Time);
    if (out.sumo_config.max_time && *out.sumo_config.max_time <= 0)
      r.error("max_time", fmt::format("\"max_time\" must be positive, found {}", *out.sumo_config.max_time));
  }
  if (!(r.has("traffic") && cfg->at("traffic").is_null())) out.sumo_config.traffic = r.string("traffic", Need::Optional);
  if (!(r.has("backend") && cfg->at("backend").is_null())) out.sumo_config.backend = r.string("backend", Need::Optional);
  r.finish();
}

std::optional<ParameterSet> read_set(const JsonDocument& doc, const std::string& uuid, const json& value,
                                     Diagnostics& diags) {
  const std::string pointer = json_pointer_child("/parameters", uuid);
  ObjectReader r(doc, value, pointer, diags, fmt::format("parameter set \"{}\"", uuid));
  if (!r.is_object()) return std::nullopt;
  const int errors_before = diags.error_count();
  ParameterSet set;
  set.uuid = uuid;
  set.where = doc.where(pointer);
  if (!is_file_safe_id(uuid))
    diags.error(set.where, fmt::format("parameter set id \"{}\" cannot name files: use letters, digits, '-' and '_'", uuid));
  set.created_at = r.string("created_at", Need::Optional).value_or("");
  if (r.has("seed")) {
    const json& s = value.at("seed");
    if (!s.is_number_integer() && !s.is_number_unsigned()) r.error("seed", "\"seed\" must be a whole number");
    else if (s.get<long long>() < 0 || s.get<long long>() > 2147483647) r.error("seed", "\"seed\" must lie in [0, 2147483647]");
    else set.seed = s.get<long long>();
    r.allow({"seed"});
  }
  if (const json* values = r.object("sampled_values", Need::Required)) set.sampled_values = *values;
  read_sumo_config(r, set);
  if (const json* out = r.object("output", Need::Optional)) set.output = *out;
  r.finish();
  if (diags.error_count() > errors_before) return std::nullopt;
  return set;
}

}  // namespace

const ParameterSet* ParameterFile::find(const std::string& uuid) const {
  for (const auto& s : sets)
    if (s.uuid == uuid) return &s;
  return nullptr;
}

bool is_parameter_file(const JsonDocument& doc) {
  return doc.root().is_object() && doc.root().contains("parameters") && doc.root().contains("logical_uuid");
}

ParameterFile read_parameter_file(const JsonDocument& doc) {
  Diagnostics diags;
  ParameterFile out;
  out.file = doc.path();
  ObjectReader top(doc, doc.root(), "", diags, "parameter file");
  if (top.is_object()) {
    out.logical_uuid = top.string("logical_uuid", Need::Required).value_or("");
    out.created_at = top.string("created_at", Need::Optional).value_or("");
    if (const json* sets = top.object("parameters", Need::Required)) {
      // nlohmann::json sorts keys; the file's own order of sets comes from an ordered parse.
      const ordered_json ordered = ordered_json::parse(doc.text());
      for (auto it = ordered.at("parameters").begin(); it != ordered.at("parameters").end(); ++it)
        if (auto set = read_set(doc, it.key(), sets->at(it.key()), diags)) out.sets.push_back(std::move(*set));
    }
    top.finish();
  }
  if (diags.has_errors()) throw ScenarioError(diags);
  return out;
}

ParameterFile load_parameter_file(const std::filesystem::path& file) {
  return read_parameter_file(JsonDocument::load(file.string()));
}

std::string run_id(const std::string& logical_uuid, const std::string& parameter_uuid) {
  return logical_uuid + "_" + parameter_uuid;
}

ordered_json output_block(const std::string& logical_uuid, const std::string& parameter_uuid) {
  const std::string id = run_id(logical_uuid, parameter_uuid);
  return {{"run_dir", "runs/" + id},
          {"result_file", "runs/" + id + "/result.json"},
          {"trace_file", "runs/" + id + "/trace.csv"},
          {"log_file", "runs/" + id + "/run.log"},
          // Written by `batch --video` for the runs it films (the failing ones), as the ATLAS
          // model's parameter sets name their video.
          {"mp4_file", "runs/" + id + "/video.mp4"},
          {"execution_file", "executions/execution_" + id + ".json"}};
}

std::string to_json_text(const ParameterFile& f) {
  ordered_json j;
  j["logical_uuid"] = f.logical_uuid;
  j["created_at"] = f.created_at;
  j["parameters"] = ordered_json::object();
  for (const auto& s : f.sets) {
    ordered_json set;
    set["created_at"] = s.created_at;
    if (s.seed) set["seed"] = *s.seed;
    set["sampled_values"] = ordered_json(s.sampled_values);
    ordered_json cfg;
    cfg["map"] = s.sumo_config.map;
    cfg["step"] = s.sumo_config.step;
    cfg["max_time"] = s.sumo_config.max_time ? ordered_json(*s.sumo_config.max_time) : ordered_json(nullptr);
    cfg["traffic"] = s.sumo_config.traffic ? ordered_json(*s.sumo_config.traffic) : ordered_json(nullptr);
    cfg["backend"] = s.sumo_config.backend ? ordered_json(*s.sumo_config.backend) : ordered_json(nullptr);
    set["sumo_config"] = cfg;
    // Where a batch puts this set's files is fixed by the ids; the block records it.
    set["output"] = output_block(f.logical_uuid, s.uuid);
    j["parameters"][s.uuid] = set;
  }
  return json_text(j, 2) + "\n";
}

}  // namespace orch::batch

#include "batch/manifest.hpp"

#include <fmt/format.h>

#include "core/errors.hpp"
#include "json/json_document.hpp"
#include "json/json_text.hpp"
#include "json/object_reader.hpp"

namespace orch::batch {

using nlohmann::json;
using nlohmann::ordered_json;

std::filesystem::path manifest_path(const std::filesystem::path& batch_dir) { return batch_dir / "batch.json"; }

std::string manifest_text(const BatchPlan& plan, const ordered_json& options) {
  ordered_json j;
  j["format"] = "orchestrator-batch/1";
  j["orchestrator_version"] = ORCH_VERSION;
  j["inputs"] = plan.inputs;
  j["shard"] = plan.shard ? ordered_json(plan.shard->text()) : ordered_json(nullptr);
  j["total_runs"] = plan.total_runs;
  j["options"] = options;
  j["input_sha256"] = ordered_json::object();
  for (const auto& [path, sha] : plan.input_hashes) j["input_sha256"][path] = sha;
  j["runs"] = ordered_json::array();
  for (const auto& r : plan.runs)
    j["runs"].push_back({{"id", r.id}, {"logical_uuid", r.logical_uuid}, {"parameter_uuid", r.parameter_uuid},
                         {"name", r.name}});
  return json_text(j, 2) + "\n";
}

Manifest read_manifest(const std::filesystem::path& batch_dir) {
  const auto path = manifest_path(batch_dir);
  if (!std::filesystem::exists(path))
    throw OrchError(fmt::format("{} is no batch folder: it has no batch.json", batch_dir.string()));
  const JsonDocument doc = JsonDocument::load(path.string());
  Diagnostics diags;
  Manifest m;
  m.batch_dir = batch_dir;
  ObjectReader top(doc, doc.root(), "", diags, "batch manifest");
  top.choice("format", {"orchestrator-batch/1"}, Need::Required);
  top.string("orchestrator_version", Need::Optional);
  if (const json* inputs = top.array("inputs", Need::Required))
    for (const auto& i : *inputs)
      if (i.is_string()) m.inputs.push_back(i.get<std::string>());
  if (top.has("shard") && !doc.root().at("shard").is_null()) {
    if (const auto shard = top.string("shard", Need::Required)) {
      try {
        m.shard = parse_shard(*shard);
      } catch (const OrchError& e) {
        top.error("shard", e.what());
      }
    }
  } else {
    top.allow({"shard"});
  }
  m.total_runs = static_cast<std::size_t>(top.integer("total_runs", Need::Required).value_or(0));
  if (const json* options = top.object("options", Need::Required)) m.options = *options;
  if (const json* hashes = top.object("input_sha256", Need::Required))
    for (auto it = hashes->begin(); it != hashes->end(); ++it)
      if (it->is_string()) m.input_sha256[it.key()] = it->get<std::string>();
  if (const json* runs = top.array("runs", Need::Required)) {
    for (std::size_t i = 0; i < runs->size(); ++i) {
      ObjectReader r(doc, (*runs)[i], json_pointer_child("/runs", i), diags, "planned run");
      PlannedEntry e;
      e.id = r.string("id", Need::Required).value_or("");
      e.logical_uuid = r.string("logical_uuid", Need::Required).value_or("");
      e.parameter_uuid = r.string("parameter_uuid", Need::Required).value_or("");
      e.name = r.string("name", Need::Optional).value_or("");
      e.batch_dir = batch_dir;
      r.finish();
      m.runs.push_back(std::move(e));
    }
  }
  top.finish();
  if (diags.has_errors()) throw ScenarioError(diags);
  return m;
}

}  // namespace orch::batch

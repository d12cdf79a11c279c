#include "batch/batch_plan.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <set>

#include "batch/sampling.hpp"
#include "batch/template_binder.hpp"
#include "batch/template_file.hpp"
#include "core/errors.hpp"
#include "core/files.hpp"
#include "json/object_file.hpp"

namespace orch::batch {

namespace {

namespace fs = std::filesystem;
using nlohmann::ordered_json;

// The seed's abstract scenario: only the links and the prompt matter here, the rest is
// accepted as the seed defines it (unknown keys are still reported).
void read_abstract(const fs::path& file, const std::string& expected_uuid, Lineage& out) {
  JsonObjectFile json(file.string(), "abstract scenario");
  ObjectReader& r = json.top();
  const auto uuid = r.string("uuid", Need::Required);
  if (uuid && *uuid != expected_uuid)
    r.error("uuid", fmt::format("\"uuid\" is \"{}\" but the logical scenario names \"{}\"", *uuid, expected_uuid));
  out.natural_uuid = r.string("natural_scenario_uuid", Need::Optional).value_or("");
  out.original_prompt = r.string("original_prompt", Need::Optional).value_or("");
  r.string("pegasus_analysis_uuid", Need::Optional);
  r.string("name", Need::Optional);
  r.string("description", Need::Optional);
  r.string("created_at", Need::Optional);
  r.allow({"pegasus_layers", "environment", "actors", "scenario_type", "criticality"});
  json.finish();
}

void read_natural(const fs::path& file, const std::string& expected_uuid, Lineage& out) {
  JsonObjectFile json(file.string(), "natural-language scenario");
  ObjectReader& r = json.top();
  const auto uuid = r.string("uuid", Need::Required);
  if (uuid && *uuid != expected_uuid)
    r.error("uuid", fmt::format("\"uuid\" is \"{}\" but the abstract scenario names \"{}\"", *uuid, expected_uuid));
  const auto prompt = r.string("prompt", Need::Optional);
  if (out.original_prompt.empty()) out.original_prompt = prompt.value_or("");
  r.string("created_at", Need::Optional);
  r.object("user_metadata", Need::Optional);
  json.finish();
}

Lineage find_lineage(const LogicalScenario& logical) {
  Lineage out;
  out.abstract_uuid = logical.parent_abstract_uuid;
  if (out.abstract_uuid.empty()) return out;
  const fs::path dir = logical.file.parent_path();
  const fs::path abstract = dir / ("abstract_" + out.abstract_uuid + ".json");
  if (!fs::exists(abstract)) return out;
  out.abstract_file = fs::absolute(abstract);
  read_abstract(abstract, out.abstract_uuid, out);
  if (out.natural_uuid.empty()) return out;
  const fs::path natural = dir / ("natural_" + out.natural_uuid + ".json");
  if (fs::exists(natural)) {
    out.natural_file = fs::absolute(natural);
    read_natural(natural, out.natural_uuid, out);
  }
  return out;
}

// Resolves one input to (logical file, parameter file).
std::pair<fs::path, fs::path> resolve_input(const fs::path& input) {
  const JsonDocument doc = JsonDocument::load(input.string());
  if (is_logical_scenario(doc)) {
    const LogicalScenario logical = read_logical_scenario(doc);
    const fs::path params = logical.parameter_file();
    if (!fs::exists(params))
      throw ScenarioError(SourceLocation{input.string(), "", 1},
                          fmt::format("logical scenario \"{}\" has no parameter sets yet ({} does not exist): "
                                      "create them with `orchestrator sample {} --count N`",
                                      logical.uuid, params.string(), input.string()));
    return {input, params};
  }
  if (is_parameter_file(doc)) {
    const ParameterFile params = read_parameter_file(doc);
    const fs::path logical = input.parent_path() / ("logical_" + params.logical_uuid + ".json");
    if (!fs::exists(logical))
      throw ScenarioError(SourceLocation{input.string(), "/logical_uuid", doc.line_of("/logical_uuid")},
                          fmt::format("its logical scenario {} does not exist beside it", logical.string()));
    return {logical, input};
  }
  throw ScenarioError(SourceLocation{input.string(), "", 1},
                      "neither a logical scenario (no \"parameter_space\") nor a parameter file "
                      "(no \"logical_uuid\" and \"parameters\")");
}

}  // namespace

Shard parse_shard(const std::string& text) {
  const auto slash = text.find('/');
  Shard s;
  try {
    if (slash == std::string::npos) throw std::invalid_argument("no slash");
    std::size_t used_k = 0, used_n = 0;
    s.index = std::stoi(text.substr(0, slash), &used_k);
    s.count = std::stoi(text.substr(slash + 1), &used_n);
    if (used_k != slash || used_n != text.size() - slash - 1) throw std::invalid_argument("trailing text");
  } catch (const std::exception&) {
    throw OrchError(fmt::format("--shard \"{}\": expected K/N, e.g. 1/4", text));
  }
  if (s.count < 1 || s.index < 1 || s.index > s.count)
    throw OrchError(fmt::format("--shard \"{}\": shards are numbered 1..N (N >= 1)", text));
  return s;
}

bool in_shard(const std::vector<std::string>& sorted_ids, const std::string& id, const Shard& shard) {
  const auto it = std::lower_bound(sorted_ids.begin(), sorted_ids.end(), id);
  if (it == sorted_ids.end() || *it != id) return false;
  const auto position = static_cast<int>(it - sorted_ids.begin());
  return position % shard.count + 1 == shard.index;
}

BatchPlan plan_batch(const std::vector<std::string>& inputs, const std::optional<Shard>& shard) {
  BatchPlan plan;
  plan.shard = shard;
  std::set<std::string> seen_files;
  std::set<std::string> hashed;
  const auto hash = [&](const fs::path& p) {
    if (hashed.insert(p.string()).second) plan.input_hashes.emplace_back(p.string(), sha256_of_file(p));
  };
  std::vector<PlannedRun> all;
  std::set<std::string> ids;
  for (const auto& input : inputs) {
    const fs::path abs = fs::absolute(input).lexically_normal();
    plan.inputs.push_back(abs.string());
    if (auto variation = resolve_variation_input(abs)) {
      if (!seen_files.insert(fs::weakly_canonical(variation->sets_file).string()).second) continue;
      PlannedLogical pl{variation->variation->logical, variation->sets_file, {}, nullptr, variation->variation};
      hash(pl.logical.file);
      hash(variation->sets_file);
      hash(pl.logical.template_file);
      for (const auto& set : variation->sets) {
        check_variation_set(*pl.variation, set);  // every set loads, or the batch does not start
        PlannedRun run{run_id(pl.logical.uuid, set.uuid), pl.logical.uuid, set.uuid, pl.logical.name,
                       plan.logicals.size(), set};
        if (ids.insert(run.id).second) all.push_back(std::move(run));
      }
      plan.logicals.push_back(std::move(pl));
      continue;
    }
    const auto [logical_file, parameter_file] = resolve_input(abs);
    const std::string key = fs::weakly_canonical(parameter_file).string();
    if (!seen_files.insert(key).second) continue;  // the same sets named twice run once

    PlannedLogical pl{load_logical_scenario(logical_file), parameter_file, {}, nullptr, nullptr};
    pl.lineage = find_lineage(pl.logical);
    const ParameterFile params = load_parameter_file(parameter_file);
    if (params.logical_uuid != pl.logical.uuid)
      throw ScenarioError(SourceLocation{parameter_file.string(), "/logical_uuid", 0},
                          fmt::format("the parameter file names logical scenario \"{}\", its logical file has \"{}\"",
                                      params.logical_uuid, pl.logical.uuid));
    pl.template_doc = std::make_shared<const JsonDocument>(load_template(pl.logical.template_file));
    if (Diagnostics d = check_templates(pl.logical, *pl.template_doc); d.has_errors()) throw ScenarioError(d);
    hash(logical_file);
    hash(parameter_file);
    hash(pl.logical.template_file);
    if (const auto scenario = scenario_template_of(*pl.template_doc)) hash(*scenario);
    for (const auto& set : params.sets) {
      bound_run_files(pl.logical, *pl.template_doc, set);  // every set binds, or the batch does not start
      PlannedRun run{run_id(pl.logical.uuid, set.uuid), pl.logical.uuid, set.uuid, pl.logical.name,
                     plan.logicals.size(), set};
      if (ids.insert(run.id).second) all.push_back(std::move(run));
    }
    plan.logicals.push_back(std::move(pl));
  }
  plan.total_runs = all.size();
  if (!shard) {
    plan.runs = std::move(all);
    return plan;
  }
  const std::vector<std::string> sorted(ids.begin(), ids.end());
  for (auto& run : all)
    if (in_shard(sorted, run.id, *shard)) plan.runs.push_back(std::move(run));
  return plan;
}

}  // namespace orch::batch

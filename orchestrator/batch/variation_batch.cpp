#include "batch/variation_batch.hpp"

#include <fmt/format.h>

#include <map>
#include <set>

#include "batch/identifiers.hpp"
#include "batch/template_binder.hpp"
#include "batch/variation_sampling.hpp"
#include "core/errors.hpp"
#include "core/suggest.hpp"
#include "core/scenario_format.hpp"
#include "openscenario/xosc_reader.hpp"

namespace orch::batch {

namespace {

namespace fs = std::filesystem;
constexpr const char* kParametersSuffix = "_parameters.json";

VariationValues values_of(const VariationLogical& v, long long seed) {
  const openscenario::Variation& var = v.variation;
  if (var.stochastic) return stochastic_values(var, static_cast<std::uint64_t>(seed));
  return product_values(var, static_cast<std::uint64_t>(seed - 1));
}

std::map<std::string, std::string> overrides_of(const VariationLogical& v, const ParameterSet& set) {
  std::map<std::string, std::string> out;
  for (const auto& [key, value] : flatten_values(set.sampled_values)) {
    const std::string name = key.substr(std::string(kVariationGroup).size() + 1);
    out[name] = value.is_string() ? value.get<std::string>() : value.dump();
  }
  (void)v;
  return out;
}

}  // namespace

fs::path VariationLogical::parameter_file() const {
  return logical.file.parent_path() / (logical.file.stem().string() + kParametersSuffix);
}

bool is_variation_input(const fs::path& file) {
  return detect_scenario_format(file.string()) == ScenarioFormat::OpenScenario &&
         openscenario::is_variation_file(file.string());
}

std::shared_ptr<const VariationLogical> load_variation_logical(const fs::path& file) {
  auto out = std::make_shared<VariationLogical>();
  out->variation = openscenario::load_variation(file.string());
  LogicalScenario& l = out->logical;
  l.file = fs::absolute(file).lexically_normal();
  // Named by the file name (not its folder), so every machine of a sharded batch agrees.
  l.uuid = name_based_uuid("openscenario-variation/" + l.file.filename().string());
  l.name = l.file.stem().string();
  l.description = fmt::format("OpenSCENARIO parameter variation of {}", out->variation.scenario_file);
  l.template_file = out->variation.scenario_file;
  l.template_where = SourceLocation{l.file.string(), "/OpenSCENARIO/ParameterValueDistribution/ScenarioFile", 0};
  return out;
}

ParameterSet variation_set(const VariationLogical& v, long long seed) {
  ParameterSet set;
  set.uuid = name_based_uuid(fmt::format("{}/{}", v.logical.uuid, seed));
  set.created_at = utc_timestamp();
  set.seed = seed;
  nlohmann::json values = nlohmann::json::object();
  for (const auto& [name, text] : values_of(v, seed))
    values[kVariationGroup][name] = typed_value(*v.variation.declaration(name), text);
  set.sampled_values = values;
  set.sumo_config.map = fs::path(v.variation.road_file).stem().string();
  set.output = nlohmann::json(output_block(v.logical.uuid, set.uuid));
  set.where = SourceLocation{v.logical.file.string(), "", 0};
  return set;
}

std::vector<ParameterSet> all_variation_sets(const VariationLogical& v) {
  const std::uint64_t runs = v.variation.stochastic ? static_cast<std::uint64_t>(v.variation.number_of_test_runs)
                                                    : product_size(v.variation);
  if (runs > kMaxVariationRuns)
    throw OrchError(fmt::format("{}: {} runs are more than one batch takes ({}): draw a subset with "
                                "`orchestrator sample {} --count N` and run its parameter file",
                                v.logical.file.string(), runs, kMaxVariationRuns, v.logical.file.string()));
  std::vector<ParameterSet> sets;
  for (std::uint64_t seed = 1; seed <= runs; ++seed) sets.push_back(variation_set(v, static_cast<long long>(seed)));
  return sets;
}

void check_variation_set(const VariationLogical& v, const ParameterSet& set) {
  const auto names = v.variation.parameter_names();
  const std::set<std::string> expected(names.begin(), names.end());
  std::set<std::string> given;
  for (const auto& [key, value] : flatten_values(set.sampled_values)) given.insert(key);
  Diagnostics diags;
  for (const auto& name : names)
    if (!given.count(std::string(kVariationGroup) + "." + name))
      diags.error(set.where, fmt::format("parameter set \"{}\" has no value for \"{}.{}\" of variation {}", set.uuid,
                                         kVariationGroup, name, v.logical.file.string()));
  for (const auto& key : given) {
    const auto dot = key.find('.');
    if (key.substr(0, dot) != kVariationGroup || !expected.count(key.substr(dot + 1)))
      diags.error(set.where, fmt::format("parameter set \"{}\" has a value for \"{}\", which variation {} does not "
                                         "vary{}", set.uuid, key, v.logical.file.string(),
                                         did_you_mean(key.substr(dot + 1), names)));
  }
  if (diags.has_errors()) throw ScenarioError(diags);
  try {
    openscenario::load_scenario(v.variation.scenario_file, {overrides_of(v, set)});
  } catch (const ScenarioError& e) {
    Diagnostics d = e.diagnostics();
    d.error(set.where, fmt::format("the scenario does not load with the values of parameter set \"{}\" (seed {})",
                                   set.uuid, set.seed.value_or(0)));
    throw ScenarioError(d);
  }
}

std::vector<std::string> variation_run_arguments(const VariationLogical& v, const ParameterSet& set) {
  const auto overrides = overrides_of(v, set);
  std::vector<std::string> args;
  for (const auto& name : v.variation.parameter_names()) {
    args.emplace_back("--param");
    args.push_back(name + "=" + overrides.at(name));
  }
  return args;
}

SampleOutcome sample_variation_sets(const VariationLogical& v, const SampleRequest& request) {
  SampleOutcome outcome;
  const fs::path path = v.parameter_file();
  if (fs::exists(path)) {
    outcome.file = load_parameter_file(path);
    if (outcome.file.logical_uuid != v.logical.uuid)
      throw ScenarioError(SourceLocation{path.string(), "/logical_uuid", 0},
                          fmt::format("the parameter file belongs to logical scenario \"{}\", not to variation {} (\"{}\")",
                                      outcome.file.logical_uuid, v.logical.file.string(), v.logical.uuid));
  } else {
    outcome.file.file = path;
    outcome.file.logical_uuid = v.logical.uuid;
    outcome.file.created_at = utc_timestamp();
  }
  std::set<std::uint64_t> used;
  for (const auto& s : outcome.file.sets)
    if (s.seed) used.insert(static_cast<std::uint64_t>(*s.seed));
  std::vector<long long> seeds;
  if (v.variation.stochastic) {
    for (long long seed = request.first_seed; static_cast<int>(seeds.size()) < request.count; ++seed)
      if (!used.count(static_cast<std::uint64_t>(seed))) seeds.push_back(seed);
  } else {
    // Combination i is seed i + 1: a subset drawn with --seed, skipping those sampled before.
    std::set<std::uint64_t> taken;
    for (auto s : used) taken.insert(s - 1);
    for (auto i : seeded_subset(product_size(v.variation), static_cast<std::uint64_t>(request.count),
                                static_cast<std::uint64_t>(request.first_seed), taken))
      seeds.push_back(static_cast<long long>(i + 1));
  }
  for (long long seed : seeds) {
    ParameterSet set = variation_set(v, seed);
    set.sumo_config.step = request.step.value_or(0.05);
    set.sumo_config.max_time = request.max_time;
    set.sumo_config.traffic = request.traffic;
    set.sumo_config.backend = request.backend;
    check_variation_set(v, set);
    outcome.new_set_ids.push_back(set.uuid);
    outcome.file.sets.push_back(std::move(set));
  }
  return outcome;
}

Diagnostics check_variation_file(const fs::path& file) {
  Diagnostics diags;
  try {
    const auto v = load_variation_logical(file);
    const std::uint64_t runs = v->variation.stochastic ? static_cast<std::uint64_t>(v->variation.number_of_test_runs)
                                                       : product_size(v->variation);
    if (runs <= 1000)
      for (const auto& set : all_variation_sets(*v)) check_variation_set(*v, set);
  } catch (const ScenarioError& e) {
    diags.append(e.diagnostics());
  } catch (const OrchError& e) {
    diags.error(SourceLocation{file.string(), "", 0}, e.what());
  }
  return diags;
}

std::optional<VariationInput> resolve_variation_input(const fs::path& input) {
  if (is_variation_input(input)) {
    VariationInput in;
    in.variation = load_variation_logical(input);
    in.sets_file = input;
    in.sets = all_variation_sets(*in.variation);
    return in;
  }
  const std::string name = input.filename().string();
  if (name.size() <= std::string(kParametersSuffix).size() || !name.ends_with(kParametersSuffix)) return std::nullopt;
  const fs::path variation = input.parent_path() / (name.substr(0, name.size() - std::string(kParametersSuffix).size()) + ".xosc");
  if (!fs::exists(variation) || !is_variation_input(variation)) return std::nullopt;
  VariationInput in;
  in.variation = load_variation_logical(variation);
  in.sets_file = input;
  ParameterFile file = load_parameter_file(input);
  if (file.logical_uuid != in.variation->logical.uuid)
    throw ScenarioError(SourceLocation{input.string(), "/logical_uuid", 0},
                        fmt::format("the parameter file names logical scenario \"{}\", its variation {} is \"{}\"",
                                    file.logical_uuid, variation.string(), in.variation->logical.uuid));
  in.sets = std::move(file.sets);
  return in;
}

}  // namespace orch::batch

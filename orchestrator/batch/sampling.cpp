#include "batch/sampling.hpp"

#include <fmt/format.h>

#include <set>

#include "batch/identifiers.hpp"
#include "batch/sampler.hpp"
#include "batch/template_binder.hpp"
#include "batch/template_file.hpp"
#include "core/errors.hpp"
#include "json/json_text.hpp"
#include "scenario_executor/loader.hpp"

namespace orch::batch {

namespace {

// A set written by hand (or for an older version of the logical scenario) must still name
// exactly the parameters of the space: a missing value would leave a placeholder unbound,
// an extra one suggests a set sampled from another logical scenario.
void check_set_fits(const LogicalScenario& logical, const ParameterSet& set,
                    const std::map<std::string, nlohmann::json>& values) {
  Diagnostics diags;
  for (const auto& spec : logical.parameters)
    if (!values.count(spec.key()))
      diags.error(set.where, fmt::format("parameter set \"{}\" has no value for \"{}\" of logical scenario {}", set.uuid,
                                         spec.key(), logical.file.string()));
  for (const auto& [key, value] : values)
    if (!logical.find(key))
      diags.error(set.where, fmt::format("parameter set \"{}\" has a value for \"{}\", which logical scenario {} does "
                                         "not define", set.uuid, key, logical.file.string()));
  if (diags.has_errors()) throw ScenarioError(diags);
}

}  // namespace

std::string bound_scenario_text(const LogicalScenario& logical, const ParameterSet& set) {
  return bound_scenario_text(logical, load_template(logical.template_file), set);
}

std::string bound_scenario_text(const LogicalScenario& logical, const JsonDocument& tmpl, const ParameterSet& set) {
  const auto values = flatten_values(set.sampled_values);
  check_set_fits(logical, set, values);
  nlohmann::ordered_json bound = bind_template(tmpl, values);
  anchor_scenario_path(bound, logical.template_file);
  return json_text(bound, 2) + "\n";
}

std::vector<BoundFile> bound_run_files(const LogicalScenario& logical, const JsonDocument& tmpl, const ParameterSet& set) {
  std::vector<BoundFile> files{{bound_file_name(logical.template_file), bound_scenario_text(logical, tmpl, set)}};
  if (const auto scenario = scenario_template_of(tmpl)) {
    const JsonDocument scenario_tmpl = JsonDocument::load(scenario->string());
    files.push_back({kBoundScenarioFile, json_text(bind_template(scenario_tmpl, flatten_values(set.sampled_values)), 2) + "\n"});
  }
  return files;
}

SampleOutcome sample_parameter_sets(const LogicalScenario& logical, const SampleRequest& request) {
  const JsonDocument tmpl = load_template(logical.template_file);
  if (Diagnostics problems = check_templates(logical, tmpl); problems.has_errors()) throw ScenarioError(problems);

  SampleOutcome outcome;
  const auto path = logical.parameter_file();
  if (std::filesystem::exists(path)) {
    outcome.file = load_parameter_file(path);
    if (outcome.file.logical_uuid != logical.uuid)
      throw ScenarioError(SourceLocation{path.string(), "/logical_uuid", 0},
                          fmt::format("the parameter file belongs to logical scenario \"{}\", not \"{}\"",
                                      outcome.file.logical_uuid, logical.uuid));
  } else {
    outcome.file.file = path;
    outcome.file.logical_uuid = logical.uuid;
    outcome.file.created_at = utc_timestamp();
  }
  std::set<long long> used;
  for (const auto& s : outcome.file.sets)
    if (s.seed) used.insert(*s.seed);

  const std::string now = utc_timestamp();
  long long seed = request.first_seed;
  for (int made = 0; made < request.count; ++seed) {
    if (seed > 2147483647) throw OrchError("seeds run past 2147483647; choose a smaller --seed");
    if (used.count(seed)) continue;
    ParameterSet set;
    set.uuid = name_based_uuid(fmt::format("{}/{}", logical.uuid, seed));
    set.created_at = now;
    set.seed = seed;
    set.sampled_values = nlohmann::json(sample_values(logical, static_cast<std::uint64_t>(seed)));
    set.sumo_config.step = request.step.value_or(logical.sumo_config.step.value_or(0.05));
    set.sumo_config.max_time = request.max_time ? request.max_time : logical.sumo_config.max_time;
    set.sumo_config.traffic = request.traffic ? request.traffic : logical.sumo_config.traffic;
    set.sumo_config.backend = request.backend ? request.backend : logical.sumo_config.backend;

    // Bind and load now, so a template that yields an invalid scenario for some values is
    // reported at sampling time with the set's values, not at 3 a.m. in the batch.
    const std::vector<BoundFile> files = bound_run_files(logical, tmpl, set);
    const std::string label = fmt::format("{} bound with seed {}", logical.template_file.string(), seed);
    set.sumo_config.map = map_of_bound(files, label, logical.template_file);

    set.output = nlohmann::json(output_block(logical.uuid, set.uuid));
    outcome.new_set_ids.push_back(set.uuid);
    outcome.file.sets.push_back(std::move(set));
    used.insert(seed);
    ++made;
  }
  return outcome;
}

}  // namespace orch::batch

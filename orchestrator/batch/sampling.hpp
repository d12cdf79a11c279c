#pragma once
// `orchestrator sample`: new parameter sets for a logical scenario, appended to its
// parameter file. New sets take the seeds S, S+1, ... skipping seeds the file already has,
// and a set's values depend on nothing but the parameter space and its own seed, so the
// same seed always gives the same values (and the same parameter set uuid).
#include <optional>
#include <string>
#include <vector>

#include "batch/logical_scenario.hpp"
#include "batch/parameter_file.hpp"
#include "batch/template_file.hpp"
#include "json/json_document.hpp"

namespace orch::batch {

struct SampleRequest {
  int count = 1;
  long long first_seed = 1;
  // Override the logical scenario's sumo_config suggestions.
  std::optional<double> step;
  std::optional<double> max_time;
  std::optional<std::string> traffic;
  std::optional<std::string> backend;
};

struct SampleOutcome {
  ParameterFile file;                    // everything, old sets first
  std::vector<std::string> new_set_ids;  // in the order created
};

// Reads the logical scenario's parameter file when it exists, adds `count` sets, and checks
// each one by binding it into the template and loading the result as a scenario. Throws
// ScenarioError (template or bound scenario problems) without writing anything.
SampleOutcome sample_parameter_sets(const LogicalScenario& logical, const SampleRequest& request);

// The template bound with one parameter set, as scenario file text. Throws ScenarioError
// when the set does not fit the logical scenario (a parameter missing or extra).
std::string bound_scenario_text(const LogicalScenario& logical, const ParameterSet& set);
// The same with the template already loaded (a batch binds every set into one template).
std::string bound_scenario_text(const LogicalScenario& logical, const JsonDocument& tmpl, const ParameterSet& set);
// Every file of the run folder bound with one set: first the one `run` gets (as
// bound_scenario_text), then an evaluation template's bound scenario when its scenario is a
// template too (template_file.hpp).
std::vector<BoundFile> bound_run_files(const LogicalScenario& logical, const JsonDocument& tmpl, const ParameterSet& set);

}  // namespace orch::batch

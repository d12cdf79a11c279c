#pragma once
// OpenSCENARIO parameter variations (`*_variation.xosc`) as logical scenarios of the batch
// machinery (docs/openscenario.md, "Parameter variations"):
//  - `batch X_variation.xosc` runs all of the variation's runs: the full factorial product of
//    a Deterministic one (combination i gets seed i + 1), or the `numberOfTestRuns` draws of a
//    Stochastic one (seeds 1..numberOfTestRuns);
//  - `sample X_variation.xosc --count N [--seed S]` writes N of them into
//    `X_variation_parameters.json` beside it (a parameter file in the usual shape): a seeded
//    subset of the product, or the draws with seeds S, S+1, ...; `batch` runs that file.
// Each set records its values as {"param": {"NAME": value}}; a run is
// `orchestrator run SCENARIO.xosc --param NAME=VALUE ...` on the referenced scenario.
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "batch/logical_scenario.hpp"
#include "batch/parameter_file.hpp"
#include "batch/sampling.hpp"
#include "openscenario/variation.hpp"

namespace orch::batch {

// The group name of a variation's values in `sampled_values`.
inline constexpr const char* kVariationGroup = "param";
// Beyond this many runs, `batch` of the variation itself is refused: sample a subset.
inline constexpr std::uint64_t kMaxVariationRuns = 100000;

struct VariationLogical {
  openscenario::Variation variation;
  // uuid: name-based on the variation's file name; name: the file's stem; template_file:
  // the referenced scenario.
  LogicalScenario logical;
  [[nodiscard]] std::filesystem::path parameter_file() const;  // X_variation_parameters.json
};

// True when `file` is an OpenSCENARIO file holding a ParameterValueDistribution.
bool is_variation_input(const std::filesystem::path& file);
// Throws ScenarioError (file, line, element path) for a bad variation or scenario.
std::shared_ptr<const VariationLogical> load_variation_logical(const std::filesystem::path& file);

// The parameter set of run `seed` (deterministic: combination seed - 1).
ParameterSet variation_set(const VariationLogical& v, long long seed);
// Every run of the variation itself. Throws OrchError beyond kMaxVariationRuns.
std::vector<ParameterSet> all_variation_sets(const VariationLogical& v);
// `sample` of a variation: adds `request.count` sets to its parameter file (read when it
// exists); every new set is checked by loading the scenario with its values.
SampleOutcome sample_variation_sets(const VariationLogical& v, const SampleRequest& request);

// Checks a set against the variation (exactly its parameters) and loads the scenario with
// its values (types, ConstraintGroups). Throws ScenarioError naming the set.
void check_variation_set(const VariationLogical& v, const ParameterSet& set);
// `--param NAME=VALUE` arguments of a set, in the variation's parameter order.
std::vector<std::string> variation_run_arguments(const VariationLogical& v, const ParameterSet& set);

// `validate` of a variation: the file, its scenario, and (up to 1000 runs) every run's
// values loaded into the scenario. Every problem as a diagnostic.
Diagnostics check_variation_file(const std::filesystem::path& file);

// An input of `batch`: the variation itself or its parameter file, with the sets to run.
struct VariationInput {
  std::shared_ptr<const VariationLogical> variation;
  std::filesystem::path sets_file;  // the parameter file, or the variation file itself
  std::vector<ParameterSet> sets;
};
// nullopt when `input` is neither a variation nor a parameter file `X_parameters.json`
// whose `X.xosc` beside it is a variation.
std::optional<VariationInput> resolve_variation_input(const std::filesystem::path& input);

}  // namespace orch::batch

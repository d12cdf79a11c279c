#include "batch/fork_event_check.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <set>

#include "batch/sampling.hpp"
#include "batch/template_file.hpp"
#include "batch/variation_batch.hpp"
#include "core/errors.hpp"
#include "openscenario/storyboard_names.hpp"
#include "openscenario/xosc_reader.hpp"
#include "scenario_executor/loader.hpp"

namespace orch::batch {

namespace {

struct Events {
  std::string file;
  bool openscenario = false;
  std::vector<std::string> names;  // empty: unknown (the scenario does not load)
};

Events events_of(const PlannedLogical& pl, const ParameterSet& set) {
  Events e;
  try {
    if (pl.variation) {
      e.file = pl.variation->variation.scenario_file;
      e.openscenario = true;
      std::vector<std::string> params;
      const auto args = variation_run_arguments(*pl.variation, set);  // --param NAME=VALUE ...
      for (std::size_t i = 1; i < args.size(); i += 2) params.push_back(args[i]);
      e.names = openscenario::storyboard_element_names(
          openscenario::load_scenario(e.file, {openscenario::parse_parameter_overrides(params)}).storyboard);
      return e;
    }
    e.file = pl.logical.template_file.string();
    for (const auto& f : bound_run_files(pl.logical, *pl.template_doc, set)) {
      if (f.name != kBoundScenarioFile) continue;
      const LoadedScenario loaded = load_scenario(JsonDocument::parse(f.text, e.file));
      if (!loaded.scenario) break;
      e.names.push_back(fmt::format("scene:{}", scenario::kOpeningSceneId));
      for (const auto& s : loaded.scenario->scenes) e.names.push_back(fmt::format("scene:{}", s.id));
    }
  } catch (const std::exception&) {
    e.names.clear();  // the runs report what is wrong with the scenario
  }
  return e;
}

}  // namespace

void check_fork_event(const BatchPlan& plan, const ForkCheckpoint& checkpoint) {
  if (checkpoint.time_s) return;
  std::set<std::size_t> checked;
  for (const auto& run : plan.runs) {
    if (!checked.insert(run.logical_index).second) continue;
    const Events e = events_of(plan.logicals[run.logical_index], run.set);
    if (e.names.empty() || std::find(e.names.begin(), e.names.end(), checkpoint.event) != e.names.end()) continue;
    throw OrchError(unknown_event_message(checkpoint, e.file, e.openscenario, e.names));
  }
}

}  // namespace orch::batch

#include "run/fork_checkpoint.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "core/errors.hpp"
#include "core/scenario_format.hpp"
#include "openscenario/storyboard_names.hpp"
#include "openscenario/xosc_reader.hpp"
#include "scenario_executor/loader.hpp"

namespace orch {

std::vector<std::string> checkpoint_events(const RunRequest& request) {
  try {
    if (detect_scenario_format(request.scenario_file) == ScenarioFormat::OpenScenario)
      return openscenario::storyboard_element_names(
          openscenario::load_scenario(request.scenario_file, {request.parameter_overrides}).storyboard);
    const LoadedScenario loaded = load_scenario(request.scenario_file);
    if (!loaded.scenario) return {};
    std::vector<std::string> names{fmt::format("scene:{}", scenario::kOpeningSceneId)};
    for (const auto& s : loaded.scenario->scenes) names.push_back(fmt::format("scene:{}", s.id));
    return names;
  } catch (const std::exception&) {
    return {};  // the run itself says what is wrong with its scenario
  }
}

void check_checkpoint_event(const ForkCheckpoint& checkpoint, const RunRequest& request) {
  if (checkpoint.time_s) return;
  const std::vector<std::string> names = checkpoint_events(request);
  if (names.empty() || std::find(names.begin(), names.end(), checkpoint.event) != names.end()) return;
  throw OrchError(unknown_event_message(checkpoint, request.scenario_file,
                                        detect_scenario_format(request.scenario_file) == ScenarioFormat::OpenScenario,
                                        names));
}

}  // namespace orch

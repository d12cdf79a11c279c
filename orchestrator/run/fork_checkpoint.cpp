#include "run/fork_checkpoint.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "core/errors.hpp"
#include "core/scenario_format.hpp"
#include "core/suggest.hpp"
#include "openscenario/xosc_reader.hpp"
#include "scenario_executor/loader.hpp"

namespace orch {

namespace {

void add(std::vector<std::string>& names, const std::string& name) {
  if (!name.empty() && std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
}

std::vector<std::string> storyboard_names(const openscenario::Storyboard& board) {
  std::vector<std::string> names;
  for (const auto& story : board.stories) {
    add(names, story.name);
    for (const auto& act : story.acts) {
      add(names, act.name);
      for (const auto& group : act.groups) {
        add(names, group.name);
        for (const auto& maneuver : group.maneuvers) {
          add(names, maneuver.name);
          for (const auto& event : maneuver.events) {
            add(names, event.name);
            for (const auto& action : event.actions) add(names, action.name);
          }
        }
      }
    }
  }
  return names;
}

}  // namespace

std::vector<std::string> checkpoint_events(const RunRequest& request) {
  try {
    if (detect_scenario_format(request.scenario_file) == ScenarioFormat::OpenScenario)
      return storyboard_names(
          openscenario::load_scenario(request.scenario_file, {request.parameter_overrides}).storyboard);
    const LoadedScenario loaded = load_scenario(request.scenario_file);
    if (!loaded.scenario) return {};
    std::vector<std::string> names{fmt::format("scene:{}", scenario::kOpeningSceneId)};
    for (const auto& s : loaded.scenario->scenes) add(names, fmt::format("scene:{}", s.id));
    return names;
  } catch (const std::exception&) {
    return {};  // the run itself says what is wrong with its scenario
  }
}

void check_checkpoint_event(const ForkCheckpoint& checkpoint, const RunRequest& request) {
  if (checkpoint.time_s) return;
  const std::vector<std::string> names = checkpoint_events(request);
  if (names.empty() || std::find(names.begin(), names.end(), checkpoint.event) != names.end()) return;
  const bool osc = detect_scenario_format(request.scenario_file) == ScenarioFormat::OpenScenario;
  const std::string what = osc                     ? "storyboard element named " + checkpoint.event
                           : checkpoint.is_scene() ? "scene " + checkpoint.event.substr(6)
                                                   : "event " + checkpoint.event + " (its events are its scenes, scene:N)";
  throw OrchError(fmt::format("--fork-at {}: {} has no {}; {}: {}{}", checkpoint.event, request.scenario_file, what,
                              osc ? "its storyboard elements (Story, Act, ManeuverGroup, Maneuver, Event, Action)"
                                  : "its scenes",
                              fmt::join(names, ", "),
                              osc ? did_you_mean(checkpoint.event, names) : std::string()));  // scene ids: the list says it
}

}  // namespace orch

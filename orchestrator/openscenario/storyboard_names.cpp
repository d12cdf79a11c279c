#include "openscenario/storyboard_names.hpp"

#include <algorithm>

namespace orch::openscenario {

namespace {

void add(std::vector<std::string>& names, const std::string& name) {
  if (!name.empty() && std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
}

}  // namespace

std::vector<std::string> storyboard_element_names(const Storyboard& board) {
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

}  // namespace orch::openscenario

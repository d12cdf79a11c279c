#pragma once
// The names of a storyboard's elements (Story, Act, ManeuverGroup, Maneuver, Event, Action),
// in file order, each once: what `--fork-at ELEMENT` may name (docs/forking.md).
#include <string>
#include <vector>

#include "openscenario/model.hpp"

namespace orch::openscenario {

std::vector<std::string> storyboard_element_names(const Storyboard& board);

}  // namespace orch::openscenario

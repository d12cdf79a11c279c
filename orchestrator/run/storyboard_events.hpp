#pragma once
// The storyboard's element transitions as result.json events (docs/openscenario.md
// "Report"): what the report's timeline draws for an OpenSCENARIO run. The text is the
// run.log line's ("act CutInAct startTransition"), so the report finds the line. Pure.
#include <string>
#include <vector>

#include "scenario_executor_engine/engine.hpp"
#include "openscenario/storyboard_runtime.hpp"

namespace orch {

// kind Action for an action's transition, Storyboard for every other element's.
engine::Event storyboard_event(const openscenario::TransitionLog& entry);
// The run.log text of a transition: "<type> <name> <transition>".
std::string storyboard_log_text(const openscenario::TransitionLog& entry);

}  // namespace orch

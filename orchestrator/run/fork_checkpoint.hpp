#pragma once
// `--fork-at EVENT` (core/fork_checkpoint.hpp) against a scenario: which events it has,
// and a clear error for one it does not have, before any run starts (docs/forking.md).
#include <string>
#include <vector>

#include "core/fork_checkpoint.hpp"
#include "run/runner.hpp"

namespace orch {

// The events a checkpoint can name in the scenario of `request`: "scene:N" for every scene
// of a ScenarioExecutor scenario (scene:0 is the opening), the names of the storyboard
// elements (Story, Act, ManeuverGroup, Maneuver, Event, Action) of an OpenSCENARIO one, in
// file order. Empty when the scenario does not load (the run reports that itself).
std::vector<std::string> checkpoint_events(const RunRequest& request);

// Throws OrchError when `checkpoint` is an event the scenario of `request` does not have:
// the event, the file, the events it has, and a "did you mean".
void check_checkpoint_event(const ForkCheckpoint& checkpoint, const RunRequest& request);

}  // namespace orch

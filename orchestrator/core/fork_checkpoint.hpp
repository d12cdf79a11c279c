#pragma once
// `--fork-at EVENT|SECONDS` (docs/forking.md): where the variants of a fork group are asked
// to continue each in a process of its own. A number is a SUMO time in seconds; anything
// else names an event of the scenario: `scene:N` (a ScenarioExecutor scene entered) or the
// name of an OpenSCENARIO storyboard element (Story, Act, ManeuverGroup, Maneuver, Event,
// Action) that starts. Here only the words; run/fork_checkpoint.hpp knows the scenarios.
#include <optional>
#include <string>
#include <vector>

namespace orch {

struct ForkCheckpoint {
  std::optional<double> time_s;  // a time ...
  std::string event;             // ... or an event: "scene:N" or a storyboard element's name

  [[nodiscard]] bool is_scene() const { return event.rfind("scene:", 0) == 0; }
  // As the user gives it (and batch.json records it): the time as a number, or the event.
  [[nodiscard]] std::string text() const;
};

// Throws OrchError for an empty text, a negative or non-finite time, or `scene:` without a
// scene id (a whole number >= 0).
ForkCheckpoint parse_fork_checkpoint(const std::string& text);

// The error for an event `file` does not have: what it has (`events`: scene:N, or storyboard
// element names when `openscenario`), with a "did you mean" for element names.
std::string unknown_event_message(const ForkCheckpoint& checkpoint, const std::string& file, bool openscenario,
                                  const std::vector<std::string>& events);

}  // namespace orch

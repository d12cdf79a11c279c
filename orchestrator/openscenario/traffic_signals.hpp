#pragma once
// The traffic signals as the storyboard runs them (pure): each signal's state, set by the
// phases of its controller (RoadNetwork/TrafficSignals/TrafficSignalController) and by
// TrafficSignalStateAction, and each controller's phase (TrafficSignalControllerAction
// jumps to one). TrafficSignalCondition / TrafficSignalControllerCondition read them.
//
// A controller's phases follow one another by their durations, cyclically, from its start:
// `delay` after the start of its `reference` controller (after t = 0 without one; the
// standard: "its first phase virtually starts delaytime seconds after the start of the
// reference's first phase"). A phase that starts sets the states of its signals; a
// TrafficSignalStateAction sets one signal until the next phase that names it starts.
// TrafficSignalControllerAction starts the named phase now; the cycle goes on from there.
// A phase's TrafficSignalGroupState sets every signal of the controller's signal group: the
// road network's OpenDRIVE <controller> whose id (else whose name) is the
// TrafficSignalController's name (the standard, 6.11.2: the controller "references the
// identifier of a signal group in the road network ... with the name attribute"); then the
// phase's own TrafficSignalStates, more specific, set theirs.
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "opendrive/road_network.hpp"
#include "openscenario/model.hpp"

namespace orch::openscenario {

// A state as compared: lower case, no blanks ("On; off;OFF" equals "on;off;off").
std::string normalized_signal_state(const std::string& state);

class TrafficSignals {
 public:
  // Throws MapError naming the TrafficSignalGroupState when the road network has no signal
  // group of its controller's name (or the group controls no signal).
  explicit TrafficSignals(const std::vector<TrafficSignalController>& controllers,
                          const std::vector<opendrive::SignalController>& groups = {});

  // The phases due at time t start (their signals take their states).
  void advance(double t);
  void set_state(const std::string& signal, const std::string& state);
  // Starts `phase` of `controller` at time t (both checked at load).
  void set_phase(const std::string& controller, const std::string& phase, double t);

  [[nodiscard]] std::optional<std::string> state(const std::string& signal) const;
  [[nodiscard]] std::string phase(const std::string& controller) const;  // "" before its first
  // Every signal that has a state, by id (as written in the file).
  [[nodiscard]] const std::map<std::string, std::string>& states() const { return states_; }

 private:
  struct Running {
    const TrafficSignalController* spec = nullptr;
    double start = 0;  // when its phase 0 (virtually) started
    int phase = -1;    // the current phase (-1 before the first starts)
    std::vector<std::string> group;  // the signals of its signal group (a phase's group state sets them)
  };
  [[nodiscard]] int phase_at(const Running& c, double t) const;
  void enter(Running& c, int phase);

  std::map<std::string, Running> controllers_;
  std::map<std::string, std::string> states_;
};

}  // namespace orch::openscenario

#pragma once
// The storyboard's traffic signals on SUMO's traffic lights (pure): each OpenDRIVE signal
// netconvert made part of a traffic light (opendrive/sumo_signals.hpp) gives its links the
// SUMO colour of its OpenSCENARIO state, sent when a light's colours change.
//
// A state's lamps, as esmini's examples and the standard's write them ("on;off;off"): three
// lamps are red;yellow;green (a vehicle signal, OpenDRIVE type 1000001), two red;green (a
// pedestrian or bicycle signal). Red is 'r', red and yellow 'u', yellow 'y', green 'G', all
// off 'O'; a lamp "flashing" is 'o' (yellow flashing: yield). A single word works too (red,
// yellow or amber, green, off). Other states leave SUMO's light as it is. A link several
// signals control takes the colour of the vehicle signals (three lamps) among them when any
// has a state, then the most restrictive (red before yellow before green).
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "opendrive/sumo_signals.hpp"
#include "sim/world.hpp"

namespace orch {

// The SUMO colour of an OpenSCENARIO signal state, with whether it is a vehicle signal
// (three lamps); nullopt when the state means no colour this mapping knows.
struct SumoSignalColour {
  char colour = 'O';
  bool vehicle = false;
};
std::optional<SumoSignalColour> sumo_signal_colour(const std::string& state);

class OpenScenarioSignals {
 public:
  explicit OpenScenarioSignals(opendrive::SumoSignalLinks links) : links_(std::move(links)) {}
  // Commands for the lights whose colours the states (signal id -> state) change.
  std::vector<sim::Command> update(const std::map<std::string, std::string>& states);
  // Signals with a state that control no SUMO link (reported once each by the caller).
  [[nodiscard]] std::vector<std::string> take_unlinked();

 private:
  opendrive::SumoSignalLinks links_;
  std::map<std::string, std::string> sent_;  // tls -> links last sent
  std::set<std::string> unlinked_seen_;
  std::vector<std::string> unlinked_new_;
};

}  // namespace orch

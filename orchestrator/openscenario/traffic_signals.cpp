#include "openscenario/traffic_signals.hpp"

#include <cctype>
#include <cmath>
#include <set>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "core/errors.hpp"

namespace orch::openscenario {

std::string normalized_signal_state(const std::string& state) {
  std::string out;
  for (const char c : state)
    if (std::isspace(static_cast<unsigned char>(c)) == 0) out.push_back(static_cast<char>(std::tolower(static_cast<unsigned char>(c))));
  return out;
}

namespace {

// The signal group a controller's name refers to: an OpenDRIVE controller's id, else its name.
const opendrive::SignalController* signal_group(const std::string& name,
                                                const std::vector<opendrive::SignalController>& groups) {
  for (const auto& g : groups)
    if (g.id == name) return &g;
  for (const auto& g : groups)
    if (!g.name.empty() && g.name == name) return &g;
  return nullptr;
}

}  // namespace

TrafficSignals::TrafficSignals(const std::vector<TrafficSignalController>& controllers,
                               const std::vector<opendrive::SignalController>& groups) {
  for (const TrafficSignalController& c : controllers) {
    controllers_[c.name].spec = &c;
    for (const TrafficSignalPhase& p : c.phases) {
      if (!p.group_state) continue;
      const opendrive::SignalController* group = signal_group(c.name, groups);
      if (group == nullptr || group->signals.empty()) {
        std::vector<std::string> ids;
        for (const auto& g : groups) ids.push_back(g.id);
        throw MapError(fmt::format(
            "the TrafficSignalGroupState of phase \"{}\" of TrafficSignalController \"{}\" ({}, line {}): {}; a "
            "group state sets the signals of the road network's signal group (OpenDRIVE <controller>) whose id is the "
            "controller's name{}",
            p.name, c.name, p.group_place.path, p.group_place.line,
            group == nullptr ? "the road network has no signal group of that id" : "that signal group controls no signal",
            group == nullptr ? (ids.empty() ? std::string(" (the road network defines none: give each signal's "
                                                          "TrafficSignalState)")
                                            : fmt::format(" (it has: {})", fmt::join(ids, ", ")))
                             : std::string()));
      }
      controllers_[c.name].group = group->signals;
      break;
    }
  }
  // Start times follow the references (checked acyclic at load; a broken chain starts at 0).
  for (auto& [name, c] : controllers_) {
    double start = 0;
    std::set<std::string> seen;
    for (const TrafficSignalController* at = c.spec; at != nullptr && seen.insert(at->name).second;) {
      start += at->delay;
      const auto ref = controllers_.find(at->reference);
      at = ref == controllers_.end() ? nullptr : ref->second.spec;
    }
    c.start = start;
  }
}

int TrafficSignals::phase_at(const Running& c, double t) const {
  const auto& phases = c.spec->phases;
  if (phases.empty()) return c.phase;
  double cycle = 0;
  for (const TrafficSignalPhase& p : phases) cycle += p.duration;
  if (cycle <= 0) return 0;
  // Times are whole steps: a phase due at t starts at t, not one step later.
  // Before its start the cycle runs backwards from it (its first phase "virtually" starts then).
  double in_cycle = std::fmod(t - c.start + 1e-9, cycle);
  if (in_cycle < 0) in_cycle += cycle;
  for (std::size_t i = 0; i < phases.size(); ++i) {
    if (in_cycle < phases[i].duration) return static_cast<int>(i);
    in_cycle -= phases[i].duration;
  }
  return static_cast<int>(phases.size()) - 1;
}

void TrafficSignals::enter(Running& c, int phase) {
  c.phase = phase;
  const TrafficSignalPhase& p = c.spec->phases[static_cast<std::size_t>(phase)];
  if (p.group_state)
    for (const std::string& signal : c.group) states_[signal] = *p.group_state;
  for (const TrafficSignalPhaseState& s : p.states)
    states_[s.signal] = s.state;
}

void TrafficSignals::advance(double t) {
  for (auto& [name, c] : controllers_) {
    const int now = phase_at(c, t);
    if (now >= 0 && now != c.phase) enter(c, now);
  }
}

void TrafficSignals::set_state(const std::string& signal, const std::string& state) { states_[signal] = state; }

void TrafficSignals::set_phase(const std::string& controller, const std::string& phase, double t) {
  const auto it = controllers_.find(controller);
  if (it == controllers_.end()) return;
  Running& c = it->second;
  double before = 0;  // the phase's offset in the cycle
  for (std::size_t i = 0; i < c.spec->phases.size(); ++i) {
    if (c.spec->phases[i].name == phase) {
      c.start = t - before;
      enter(c, static_cast<int>(i));
      return;
    }
    before += c.spec->phases[i].duration;
  }
}

std::optional<std::string> TrafficSignals::state(const std::string& signal) const {
  const auto it = states_.find(signal);
  if (it == states_.end()) return std::nullopt;
  return it->second;
}

std::string TrafficSignals::phase(const std::string& controller) const {
  const auto it = controllers_.find(controller);
  if (it == controllers_.end() || it->second.phase < 0) return "";
  return it->second.spec->phases[static_cast<std::size_t>(it->second.phase)].name;
}

}  // namespace orch::openscenario

// Traffic signals: the RoadNetwork's TrafficSignals (controllers and their phases), the
// InfrastructureAction's TrafficSignalAction (TrafficSignalStateAction,
// TrafficSignalControllerAction) and TrafficSignalCondition / TrafficSignalControllerCondition.
// Signal ids are the OpenDRIVE road's (the file may name a signal of the road only); a
// controller or a phase that the file does not declare is an error with "did you mean".
#include <algorithm>
#include <set>

#include <fmt/format.h>

#include "core/suggest.hpp"
#include "openscenario/reader_context.hpp"

namespace orch::openscenario::reading {
namespace {

const TrafficSignalController& declared_controller(Element& e, const char* attribute, const Context& context) {
  const std::string name = e.text(attribute);
  for (const TrafficSignalController& c : context.signal_controllers)
    if (c.name == name) return c;
  std::vector<std::string> names;
  for (const TrafficSignalController& c : context.signal_controllers) names.push_back(c.name);
  e.fail_attribute(attribute, fmt::format("no TrafficSignalController \"{}\" is declared (RoadNetwork/TrafficSignals){}",
                                          name, did_you_mean(name, names)));
}

std::string declared_phase(Element& e, const TrafficSignalController& controller) {
  const std::string phase = e.text("phase");
  std::vector<std::string> names;
  for (const TrafficSignalPhase& p : controller.phases) names.push_back(p.name);
  if (std::find(names.begin(), names.end(), phase) == names.end())
    e.fail_attribute("phase", fmt::format("TrafficSignalController \"{}\" has no phase \"{}\"{}", controller.name, phase,
                                          did_you_mean(phase, names)));
  // PhaseRef (1.0: the phase as a reference) adds nothing to the phase's name.
  e.ignore_children({"PhaseRef"});
  return phase;
}

TrafficSignalPhase read_phase(Element& e) {
  TrafficSignalPhase p;
  p.name = e.text("name");
  p.duration = e.number("duration");
  if (p.duration < 0) e.fail_attribute("duration", "a phase's duration cannot be negative");
  for (Element s : e.children("TrafficSignalState")) {
    p.states.push_back({s.text("trafficSignalId"), s.text("state")});
    s.finish();
  }
  // TrafficSignalGroupState (1.2): the state of every signal of the controller's signal group
  // (the road network's; resolved against the OpenDRIVE controllers when the run starts).
  if (auto group = e.optional_child("TrafficSignalGroupState")) {
    p.group_state = group->text("state");
    p.group_place = group->place();
    group->finish();
  }
  e.finish();
  return p;
}

}  // namespace

std::vector<TrafficSignalController> read_traffic_signals(Element& traffic_signals) {
  std::vector<TrafficSignalController> out;
  std::vector<Element> elements = traffic_signals.children("TrafficSignalController");
  for (Element& e : elements) {
    TrafficSignalController c;
    c.name = e.text("name");
    c.delay = e.optional_number("delay").value_or(0.0);
    if (c.delay < 0) e.fail_attribute("delay", "a controller's delay cannot be negative");
    c.reference = e.optional_text("reference").value_or("");
    for (Element phase : e.children("Phase")) {
      c.phases.push_back(read_phase(phase));
      for (std::size_t i = 0; i + 1 < c.phases.size(); ++i)
        if (c.phases[i].name == c.phases.back().name)
          phase.fail_attribute("name", fmt::format("a second phase named \"{}\"", c.phases.back().name));
    }
    for (const TrafficSignalController& other : out)
      if (other.name == c.name) e.fail_attribute("name", fmt::format("a second TrafficSignalController \"{}\"", c.name));
    out.push_back(std::move(c));
  }
  // References name declared controllers, without a cycle (each start would wait for itself).
  std::vector<std::string> names;
  for (const TrafficSignalController& c : out) names.push_back(c.name);
  for (std::size_t i = 0; i < out.size(); ++i) {
    std::set<std::string> seen{out[i].name};
    for (std::string ref = out[i].reference; !ref.empty();) {
      const auto it = std::find(names.begin(), names.end(), ref);
      if (it == names.end())
        elements[i].fail_attribute("reference", fmt::format("no TrafficSignalController \"{}\" is declared{}", ref,
                                                            did_you_mean(ref, names)));
      if (!seen.insert(ref).second)
        elements[i].fail_attribute("reference", "the controllers' references go round in a circle");
      ref = out[static_cast<std::size_t>(it - names.begin())].reference;
    }
    elements[i].finish();
  }
  traffic_signals.finish();
  return out;
}

PrivateAction read_traffic_signal_action(Element& e, const Context& context) {
  Element action = e.one_of({"TrafficSignalStateAction", "TrafficSignalControllerAction"});
  e.finish();
  PrivateAction out;
  if (action.name() == "TrafficSignalStateAction") {
    out = TrafficSignalStateAction{action.text("name"), action.text("state")};
  } else {
    const TrafficSignalController& c = declared_controller(action, "trafficSignalControllerRef", context);
    out = TrafficSignalControllerAction{c.name, declared_phase(action, c)};
  }
  action.finish();
  return out;
}

TrafficSignalCondition read_traffic_signal_condition(Element& e) { return {e.text("name"), e.text("state")}; }

TrafficSignalControllerCondition read_traffic_signal_controller_condition(Element& e, const Context& context) {
  const TrafficSignalController& c = declared_controller(e, "trafficSignalControllerRef", context);
  return {c.name, declared_phase(e, c)};
}

}  // namespace orch::openscenario::reading

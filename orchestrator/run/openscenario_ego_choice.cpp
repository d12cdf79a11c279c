#include "run/openscenario_ego_choice.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <functional>
#include <string_view>
#include <vector>

#include "core/errors.hpp"
#include "core/suggest.hpp"
#include "reference_driver/ego_model.hpp"

namespace orch {

namespace {

std::string lower(std::string_view text) {
  std::string out(text);
  std::transform(out.begin(), out.end(), out.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return out;
}

bool one_of(std::string_view text, std::initializer_list<std::string_view> names) {
  const std::string l = lower(text);
  return std::any_of(names.begin(), names.end(), [&](std::string_view n) { return l == lower(n); });
}

// Rank 2: the controller says it is the system under test (its name, or esmini's external one).
std::string controller_rule(const openscenario::Entity& e) {
  if (!e.controller) return "";
  const auto& c = *e.controller;
  if (c.name == "ALKSController" || c.name == kR157ControllerName ||
      one_of(c.name, {"SystemUnderTest", "SUT", "ExternalController"}))
    return fmt::format("its controller is named {}", c.name);
  if (const auto p = c.properties.find("esminiController");
      p != c.properties.end() && p->second == "ExternalController")
    return fmt::format("its controller {} has the Property esminiController=ExternalController", c.name);
  return "";
}

// Rank 3: CARLA ScenarioRunner's mark on the vehicle.
std::string property_rule(const openscenario::Entity& e) {
  if (const auto p = e.properties.find("type"); p != e.properties.end() && p->second == "ego_vehicle")
    return "it has the Property type=ego_vehicle";
  return "";
}

// Rank 4: the names files give the ego.
std::string name_rule(const openscenario::Entity& e) {
  return one_of(e.name, {"Ego", "ego_vehicle", "hero"}) ? fmt::format("its name is {}", e.name) : "";
}

// What the ego's controller is, in words (run.log says why the ego is or is not driven).
std::string controller_note(const openscenario::Entity& e) {
  if (!e.controller) return "no controller";
  const std::string sut = controller_rule(e);
  if (sut.empty()) return fmt::format("controller {} is not a system under test", e.controller->name);
  return sut.find("esminiController") != std::string::npos
             ? fmt::format("controller {} (esminiController=ExternalController) is a system under test", e.controller->name)
             : fmt::format("controller {} is a system under test", e.controller->name);
}

EgoChoice with_note(const openscenario::Scenario& scenario, EgoChoice choice, bool system_under_test) {
  choice.system_under_test = system_under_test;
  if (const auto* e = scenario.entity(choice.entity)) choice.controller_note = controller_note(*e);
  return choice;
}

}  // namespace

EgoDriving ego_driving(const EgoChoice& choice, const EgoRequests& requests) {
  if (choice.entity.empty()) return {false, choice.rule};
  if (requests.controllers_off) return {false, "--controllers off; " + choice.controller_note};
  if (requests.plugin) return {true, "--ego-port: an external plug-in"};
  if (!requests.ego_model.empty()) return {true, "--ego-model " + requests.ego_model};
  if (requests.reference_driver) return {true, "the reference run"};
  if (choice.rule.rfind("--ego ", 0) == 0) return {true, choice.rule};
  if (choice.system_under_test) return {true, choice.controller_note};
  return {false, choice.controller_note};
}

EgoChoice choose_ego(const openscenario::Scenario& scenario, const std::string& requested) {
  std::vector<std::string> names;
  for (const auto& e : scenario.entities) names.push_back(e.name);
  const SourceLocation where{scenario.file, "/OpenSCENARIO/Entities", 0};
  if (!requested.empty()) {
    if (scenario.entity(requested)) return with_note(scenario, {requested, "--ego " + requested, false, ""}, true);
    throw ScenarioError(where, fmt::format("--ego {}: no such entity{}; the entities are {}", requested,
                                           did_you_mean(requested, names), fmt::join(names, ", ")));
  }
  using Rule = std::function<std::string(const openscenario::Entity&)>;
  const std::array<Rule, 3> ranks{controller_rule, property_rule, name_rule};
  for (std::size_t rank = 0; rank < ranks.size(); ++rank) {
    std::vector<EgoChoice> found;
    for (const auto& e : scenario.entities)
      if (std::string why = ranks[rank](e); !why.empty()) found.push_back({e.name, std::move(why), false, ""});
    if (found.size() == 1) return with_note(scenario, found.front(), rank == 0);
    if (found.size() > 1) {
      std::string list;
      for (const auto& f : found) list += fmt::format("{}{} ({})", list.empty() ? "" : ", ", f.entity, f.rule);
      throw ScenarioError(where, fmt::format("{} entities could be the ego: {}; name one with --ego NAME",
                                             found.size(), list));
    }
  }
  return {"", "no entity has a system-under-test controller, a Property type=ego_vehicle or the name Ego/hero, "
              "and no --ego", false, ""};
}

}  // namespace orch

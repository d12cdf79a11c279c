#include "run/openscenario_ego_choice.hpp"

#include <fmt/format.h>

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

}  // namespace

EgoChoice choose_ego(const openscenario::Scenario& scenario, const std::string& requested) {
  std::vector<std::string> names;
  for (const auto& e : scenario.entities) names.push_back(e.name);
  const SourceLocation where{scenario.file, "/OpenSCENARIO/Entities", 0};
  if (!requested.empty()) {
    if (scenario.entity(requested)) return {requested, "--ego " + requested};
    throw ScenarioError(where, fmt::format("--ego {}: no such entity{}", requested, did_you_mean(requested, names)));
  }
  using Rule = std::function<std::string(const openscenario::Entity&)>;
  const std::array<Rule, 3> ranks{controller_rule, property_rule, name_rule};
  for (const Rule& rule : ranks) {
    std::vector<EgoChoice> found;
    for (const auto& e : scenario.entities)
      if (std::string why = rule(e); !why.empty()) found.push_back({e.name, std::move(why)});
    if (found.size() == 1) return found.front();
    if (found.size() > 1) {
      std::string list;
      for (const auto& f : found) list += fmt::format("{}{} ({})", list.empty() ? "" : ", ", f.entity, f.rule);
      throw ScenarioError(where, fmt::format("{} entities could be the ego: {}; name one with --ego NAME",
                                             found.size(), list));
    }
  }
  return {"", "no entity has a system-under-test controller, a Property type=ego_vehicle or the name Ego/hero, "
              "and no --ego"};
}

}  // namespace orch

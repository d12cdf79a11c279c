#pragma once
// Which entity of an OpenSCENARIO file is the ego (the system under test), by the rules
// mature players follow, in this order (docs/openscenario.md "The ego"):
//   1. --ego NAME;
//   2. a controller that names the system under test: ALKSController (the OSC-ALKS files),
//      R157ReferenceDriver (the reference driver), SystemUnderTest / SUT, ExternalController,
//      or a controller Property esminiController="ExternalController" (esmini's external ego);
//   3. a Property type="ego_vehicle" on the entity (CARLA ScenarioRunner's mark);
//   4. the entity's name: Ego, ego_vehicle or hero (any case; CARLA's role names).
// Two candidates at the first rank that has any are ambiguous: a ScenarioError asking for --ego.
// No candidate at any rank: no ego. Pure.
#include <string>

#include "openscenario/model.hpp"

namespace orch {

struct EgoChoice {
  std::string entity;  // "" : no ego
  std::string rule;    // why, for run.log: "--ego", "controller ALKSController", ...
};

EgoChoice choose_ego(const openscenario::Scenario& scenario, const std::string& requested);

}  // namespace orch

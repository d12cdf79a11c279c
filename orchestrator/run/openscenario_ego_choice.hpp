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
//
// Being the ego is not being driven (docs/openscenario.md "The ego"): an entity with no
// controller, or one that is not a system under test, does exactly what the storyboard says,
// as in every other player, even when the rules above make it the ego of the metrics and the
// report. SUMO, the reference driver or a plug-in drive the ego only when the file names a
// system-under-test controller (rank 2) or the user asks (--ego, --ego-model, --ego-port).
#include <string>

#include "openscenario/model.hpp"

namespace orch {

struct EgoChoice {
  std::string entity;  // "" : no ego
  std::string rule;    // why, for run.log: "--ego", "controller ALKSController", ...
  // Chosen by --ego or by a system-under-test controller (ranks 1 and 2): something other
  // than the storyboard drives it. The ranks below only name the ego of metrics and report.
  bool system_under_test = false;
  std::string controller_note;  // the ego's controller, said for run.log: "no controller", "controller X ..."
};

EgoChoice choose_ego(const openscenario::Scenario& scenario, const std::string& requested);

// What the user asked for on the command line (or in the evaluation file) that drives the ego.
struct EgoRequests {
  std::string ego_model;  // --ego-model / EgoModel given: its name ("sumo", "r157"); "" not given
  bool reference_driver = false;  // the run's model is the R157 reference driver (--ego-model r157, --reference-run)
  bool plugin = false;            // --ego-port
  bool controllers_off = false;   // --controllers off: nothing but the storyboard drives (wins)
};

// Whether the chosen ego is driven (by SUMO, the reference driver or a plug-in) or follows the
// storyboard, and why, in words for run.log and the report.
struct EgoDriving {
  bool driven = false;
  std::string why;  // "controller ALKSController is a system under test", "no controller", "--ego-model r157", ...
};
EgoDriving ego_driving(const EgoChoice& choice, const EgoRequests& requests);

}  // namespace orch

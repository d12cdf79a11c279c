#pragma once
// One scenario run from files to verdict. Every way a run can end goes through here and
// ends with result.json written: success, failure, or error with a reason. Typed errors
// are caught once, in run_scenario, and never reported as a test failure.
#include <atomic>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "evaluation/evaluation_request.hpp"
#include "reference_driver/ego_model.hpp"
#include "run/ego_link.hpp"
#include "run/run_result.hpp"
#include "run/simulator.hpp"

namespace orch {

// A run ends here when no --max-time is given and nothing else ended it (a StopTrigger that
// never fires, a scene never left): two hours of simulated time, beyond the "never" limits
// real files write themselves (the shared ScenarioExecutor files end at simulation_time >
// 3600, esmini's examples at 1200 s), but a batch never hangs on one run and a trace never
// grows without bound.
inline constexpr double kDefaultMaxTimeS = 7200.0;

struct RunRequest {
  std::string scenario_file;
  std::filesystem::path out_dir = "out";
  double step = 0.05;
  long long seed = 42;
  std::optional<double> max_time;  // none: kDefaultMaxTimeS
  bool strict = false;  // validation warnings stop the run
  bool echo = true;     // run log to the terminal too
  std::vector<std::filesystem::path> map_dirs;  // empty: MapRegistry::default_search_dirs()
  std::string catalog_file;                     // empty: the compiled-in catalog
  const std::atomic<bool>* interrupted = nullptr;  // set by a signal handler to end the run
  EgoLink* ego_link = nullptr;  // an external plug-in drives the ego (--ego-port); null: SUMO does
  // Background traffic (docs/background-traffic.md): none, light, medium, dense, vehicles
  // per hour and lane, or a SUMO route file; empty: the scenario's own "traffic", else none.
  std::string traffic;
  bool trace_background = false;  // background.csv: the background vehicles near the actors
  // An evaluation file's criteria (docs/evaluation.md): judged every step, folded into the
  // verdict, written to result.json's "criteria" and to result.jsonl.
  std::optional<EvaluationRequest> evaluation;
  // OpenSCENARIO runs: the ego entity (--ego NAME), driven; empty: by the rules of
  // run/openscenario_ego_choice.hpp.
  std::string ego_entity;
  // OpenSCENARIO runs: --param NAME=VALUE overrides of declared parameters.
  std::map<std::string, std::string> parameter_overrides;
  // --ssm: SUMO's device.ssm on the ego while SUMO drives it, output ssm.xml (run/ssm_device.hpp).
  bool ssm = false;
  // Which model drives the ego when no plug-in does (docs/reference-driver.md).
  EgoModelChoice ego_model;
  // --ego-model (or the evaluation file's EgoModel) was given: in OpenSCENARIO runs the user
  // asks for the ego to be driven, even without a system-under-test controller.
  bool ego_model_given = false;
  // Run the scenario again with the R157 reference driver as the ego (into reference/) and
  // judge whether a collision was preventable (docs/reference-driver.md).
  bool reference_run = false;
  // OpenSCENARIO runs, --controllers off: no controller runs (esmini's --disable_controllers).
  // Every entity, the ego too, follows the storyboard; controllers are still read and checked,
  // Activate/AssignControllerAction run (and are logged) but hand nobody to SUMO.
  bool controllers_off = false;
};

RunResult run_scenario(const RunRequest& request, Simulator& simulator);

}  // namespace orch

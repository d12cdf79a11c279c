#pragma once
// An OpenSCENARIO 1.x run on SUMO (docs/openscenario.md "Running"): the storyboard runtime
// steps over the simulator seam; its entities are placed in SUMO every step. run_scenario
// hands .xosc files here (the format is chosen by content, core/scenario_format.hpp).
#include "run/runner.hpp"

namespace orch {

RunResult run_openscenario(const RunRequest& request, Simulator& simulator);

}  // namespace orch

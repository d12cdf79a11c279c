#pragma once
// OpenSCENARIO 1.x files in the run loop (run_format.hpp; docs/openscenario.md "Running"):
// the storyboard runtime on the OpenDRIVE roads, its entities placed in SUMO every step.
// run_scenario picks it by the file's content (core/scenario_format.hpp).
#include <memory>

#include "run/run_format.hpp"
#include "run/runner.hpp"

namespace orch {

std::unique_ptr<RunFormat> openscenario_format(const RunRequest& request);

}  // namespace orch

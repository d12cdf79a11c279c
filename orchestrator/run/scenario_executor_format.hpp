#pragma once
// ScenarioExecutor JSON files in the run loop (run_format.hpp): the scene graph's engine
// (engine/engine.hpp) on a RoadEditor map.
#include <memory>

#include "run/run_format.hpp"
#include "run/runner.hpp"

namespace orch {

std::unique_ptr<RunFormat> scenario_executor_format(const RunRequest& request);

}  // namespace orch

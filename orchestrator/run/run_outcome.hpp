#pragma once
// What every run (ScenarioExecutor or OpenSCENARIO) does alike at its start and when it
// fails: the result's recorded settings, and typed errors turned into verdict "error".
#include "run/run_log.hpp"
#include "run/run_result.hpp"
#include "run/runner.hpp"

namespace orch {

// A result with the run's settings (step, seed, --max-time, backend) filled in.
RunResult new_run_result(const RunRequest& request, Simulator& simulator);

// Call inside `catch (...)`: the exception being handled becomes verdict "error" with its
// reason (a scenario's error diagnostics go to the log too; unknown exceptions are marked
// "internal error").
void record_run_error(RunResult& result, RunLog& log);

}  // namespace orch

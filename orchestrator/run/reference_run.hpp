#pragma once
// --reference-run: the scenario run a second time, same seed, with the UN R157 reference
// driver as the ego (into reference/ of the run folder), and the verdict that rests on it:
// was the run's collision preventable (the reference driver avoided it), unavoidable (it
// did not), or was there none (docs/reference-driver.md).
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "run/preventability.hpp"
#include "run/run_result.hpp"
#include "run/runner.hpp"

namespace orch {

// Runs req (on `sim`), then the reference run (on a simulator from `make_reference_sim`),
// and returns the first run's result with `reference_run` filled in (result.json rewritten).
RunResult run_with_reference(const RunRequest& req, Simulator& sim,
                             const std::function<std::unique_ptr<Simulator>()>& make_reference_sim);

}  // namespace orch

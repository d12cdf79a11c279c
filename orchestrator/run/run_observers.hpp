#pragma once
// The step loop's observers as both runners use them: added in order, begun, stepped with
// their time counted (result.json timing.observers_s), finished. add_measurement() adds
// what every run measures and judges, the same for both scenario languages: the metrics
// (metrics.csv), and with an evaluation file the criteria judge and result.jsonl.
#include <filesystem>
#include <memory>
#include <vector>

#include "core/diagnostics.hpp"
#include "map/lane_map.hpp"
#include "run/run_observer.hpp"
#include "run/runner.hpp"

namespace orch {

class RunObservers {
 public:
  void add(std::unique_ptr<RunObserver> observer);
  // metrics.csv over `lanes` (lane keeping), then, when `req` has an evaluation, the criteria
  // judge and result.jsonl.
  void add_measurement(const RunRequest& req, const LaneMap& lanes);
  void begin(const ObservedRun& run);
  void step(const StepView& view);
  // Every observer's finish, in order, and their times; an evaluation run whose observers
  // never existed (it failed before) still gets its result.jsonl.
  void finish(const RunRequest& req, RunResult& result) noexcept;
  // An evaluation run whose scenario was not valid: result.jsonl says ScenarioFormatError
  // (unless its observer is already writing it).
  void format_error(const RunRequest& req, const Diagnostics& diagnostics);

 private:
  std::vector<std::unique_ptr<RunObserver>> observers_;
  std::vector<double> seconds_;  // time in each observer's step
  bool jsonl_written_ = false;   // result.jsonl has its observer or its error line
};

}  // namespace orch

#pragma once
// Judges an evaluation's criteria during a run (a RunObserver after the metrics) and folds
// them into the verdict: success only when the scene graph reached an ending scene and every
// criterion holds; failure names every failing criterion with its expected and measured
// value; error stays error (the criteria are still listed).
#include <functional>
#include <vector>

#include "criteria/criterion.hpp"
#include "run/metrics_recorder.hpp"
#include "run/run_observer.hpp"

namespace orch::criteria {

// One step's frames, for result.jsonl.
struct FrameReport {
  double time = 0;
  std::vector<std::pair<const CriterionState*, Frame>> frames;
};

class CriteriaJudge : public RunObserver {
 public:
  [[nodiscard]] const char* name() const override { return "criteria"; }
  using FrameSink = std::function<void(const FrameReport&)>;
  CriteriaJudge(std::vector<CriterionSpec> specs, const metrics::MetricsRecorder& metrics, FrameSink sink = {});

  void begin(const ObservedRun& run) override;
  void step(const StepView& view) override;
  void finish(RunResult& result) noexcept override;

  [[nodiscard]] const std::vector<CriterionState>& states() const { return states_; }

 private:
  std::vector<CriterionSpec> specs_;
  const metrics::MetricsRecorder& metrics_;
  FrameSink sink_;
  std::vector<CriterionState> states_;
};

// The verdict with the criteria folded in (see above); `reason` gains the failing criteria.
void apply_criteria(RunResult& result);
// "name: expected ..., actual ... at t=... s" for a failing criterion.
std::string describe_failure(const CriterionResult& r);

}  // namespace orch::criteria

#pragma once
// result.jsonl (docs/evaluation.md "result.jsonl"), in driving_log_replayer's shape so its
// tooling carries over:
//   {"Condition": {...}}                         the Conditions as loaded
//   {"Result": {"Success", "Summary"}, "Stamp": {"System", "Simulation"},
//    "Frame": {"<criterion>": {"Result": {"Total", "Frame"}, "Info": {...}}}}   every N steps
//   {"Result": {"Success", "Summary"}, "Stamp": {...}, "Frame": {}}            the final result
// An evaluator reads the last line. "System" is the wall clock (Unix time, s): the only
// value that differs between two runs of the same inputs.
#include <filesystem>

#include <nlohmann/json.hpp>

#include "core/diagnostics.hpp"
#include "core/output_file.hpp"
#include "run/criteria_judge.hpp"
#include "run/run_observer.hpp"

namespace orch {

class ResultJsonl : public RunObserver {
 public:
  [[nodiscard]] const char* name() const override { return "result_jsonl"; }
  ResultJsonl(const std::filesystem::path& path, const nlohmann::json& conditions, int every);

  // The judge's sink: one frame line every `every` steps.
  void frame(const criteria::FrameReport& report);
  void step(const StepView& /*view*/) override {}
  // The last line: the run's final result.
  void finish(RunResult& result) noexcept override;

 private:
  OutputFile file_;
  int every_ = 1;
  long long steps_ = 0;
  double last_time_ = 0;
};

// A file that is not a valid evaluation file (or whose scenario is not valid) still gets a
// result.jsonl, whose last line says ScenarioFormatError with the first problem.
void write_format_error_jsonl(const std::filesystem::path& path, const Diagnostics& diagnostics);
// A run that ended before its first step (a missing map, SUMO failing to start): the
// Condition line and the final result only.
void write_unstarted_jsonl(const std::filesystem::path& path, const nlohmann::json& conditions, const RunResult& result);

}  // namespace orch

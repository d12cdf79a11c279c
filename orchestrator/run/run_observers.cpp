#include "run/run_observers.hpp"

#include <chrono>

#include "run/criteria_judge.hpp"
#include "run/metrics_recorder.hpp"
#include "run/result_jsonl.hpp"
#include "run/run_result.hpp"

namespace orch {

void RunObservers::add(std::unique_ptr<RunObserver> observer) {
  observers_.push_back(std::move(observer));
  seconds_.push_back(0.0);
}

void RunObservers::add_measurement(const RunRequest& req, const LaneMap& lanes) {
  auto metrics = std::make_unique<metrics::MetricsRecorder>(req.out_dir / "metrics.csv", lanes);
  const metrics::MetricsRecorder& measured = *metrics;
  add(std::move(metrics));
  if (!req.evaluation) return;
  const EvaluationRequest& ev = *req.evaluation;
  auto jsonl = std::make_unique<ResultJsonl>(req.out_dir / "result.jsonl", ev.conditions, ev.jsonl_every);
  ResultJsonl* sink = jsonl.get();
  add(std::make_unique<criteria::CriteriaJudge>(ev.criteria, measured,
                                                [sink](const criteria::FrameReport& r) { sink->frame(r); }));
  add(std::move(jsonl));
  jsonl_written_ = true;
}

void RunObservers::begin(const ObservedRun& run) {
  for (const auto& o : observers_) o->begin(run);
}

void RunObservers::step(const StepView& view) {
  using Clock = std::chrono::steady_clock;
  for (std::size_t i = 0; i < observers_.size(); ++i) {
    const auto before = Clock::now();
    observers_[i]->step(view);
    seconds_[i] += std::chrono::duration<double>(Clock::now() - before).count();
  }
}

void RunObservers::finish(const RunRequest& req, RunResult& result) noexcept {
  for (const auto& o : observers_) o->finish(result);
  for (std::size_t i = 0; i < observers_.size(); ++i)
    result.timing.observers_s.emplace_back(observers_[i]->name(), seconds_[i]);
  if (req.evaluation && !jsonl_written_) {
    try {
      write_unstarted_jsonl(req.out_dir / "result.jsonl", req.evaluation->conditions, result);
    } catch (...) {
      // result.json is written all the same
    }
  }
}

void RunObservers::format_error(const RunRequest& req, const Diagnostics& diagnostics) {
  if (!req.evaluation || jsonl_written_) return;
  write_format_error_jsonl(req.out_dir / "result.jsonl", diagnostics);
  jsonl_written_ = true;
}

}  // namespace orch

#include "run/criteria_judge.hpp"

#include <fmt/format.h>

#include "run/run_result.hpp"

namespace orch::criteria {

CriteriaJudge::CriteriaJudge(std::vector<CriterionSpec> specs, const metrics::MetricsRecorder& metrics, FrameSink sink)
    : specs_(std::move(specs)), metrics_(metrics), sink_(std::move(sink)) {}

void CriteriaJudge::begin(const ObservedRun& run) {
  const sim::ActorId ego = run.ego().value_or(0);
  states_.clear();
  for (const auto& s : specs_) states_.emplace_back(s, ego);
}

void CriteriaJudge::step(const StepView& view) {
  FrameReport report;
  report.time = view.run.judged().time;
  const RunFacts facts{report.time, view.run.scene(), view.run.ending_reached(), view.run.visits(),
                       view.run.contacts()};
  for (auto& state : states_) {
    const Frame f = state.step(facts, metrics_.current(state.actor()));
    if (sink_) report.frames.emplace_back(&state, f);
  }
  if (sink_) sink_(report);
}

void CriteriaJudge::finish(RunResult& result) noexcept {
  for (const auto& state : states_) result.criteria.push_back(state.result());
  apply_criteria(result);
}

std::string describe_failure(const CriterionResult& r) {
  std::string actual = r.actual ? fmt::format("{:.3f}", *r.actual) : std::string("not measured");
  if (r.at_time) actual += fmt::format(" at t={:.2f} s", *r.at_time);
  return fmt::format("{}: expected {}, actual {}", r.name, r.expected, actual);
}

void apply_criteria(RunResult& result) {
  if (result.verdict == Verdict::Error) return;
  std::string failing;
  for (const auto& c : result.criteria)
    if (!c.success) failing += (failing.empty() ? "" : "; ") + describe_failure(c);
  if (failing.empty()) return;
  result.reason = result.verdict == Verdict::Success
                      ? "criteria failed: " + failing + " (" + result.reason + ")"
                      : result.reason + "; criteria failed: " + failing;
  result.verdict = Verdict::Failure;
}

}  // namespace orch::criteria

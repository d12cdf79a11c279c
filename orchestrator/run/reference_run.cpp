#include "run/reference_run.hpp"

#include <fmt/format.h>

#include <cmath>
#include <map>

#include "core/errors.hpp"

namespace orch {

namespace {

std::optional<ActorRecord> ego_of(const RunResult& r) {
  for (const auto& a : r.actors)
    if (a.ego) return a;
  return std::nullopt;
}

std::optional<double> ego_min(const RunResult& r, std::string_view summary) {
  const auto ego = ego_of(r);
  if (!ego) return std::nullopt;
  for (const auto& m : r.metrics)
    if (m.actor == ego->id && m.extreme(summary)) return m.extreme(summary)->value;
  return std::nullopt;
}

// The criterion no_preventable_collision can only be judged now: it fails on a preventable
// collision only. R157's rule for unavoidable-collision scenarios: with that criterion, a
// collision the reference driver could not avoid either does not fail a run that reached
// its ending scene and kept every other criterion.
void judge_preventable_collisions(RunResult& result) {
  const std::string& outcome = result.reference_run->outcome;
  bool asked = false;
  bool others_hold = true;
  for (auto& c : result.criteria) {
    if (c.metric != "preventable_collision") {
      others_hold = others_hold && c.success;
      continue;
    }
    asked = true;
    c.actual = outcome == "preventable" ? 1.0 : 0.0;
    c.at_time = result.collision ? std::optional<double>(result.collision->time) : std::nullopt;
    c.success = outcome != "preventable";
  }
  if (!asked || result.verdict == Verdict::Error || !result.collision) return;
  if (outcome == "preventable") {
    result.verdict = Verdict::Failure;
    result.reason = fmt::format("preventable collision with {} at t={:.2f} s (the R157 reference driver avoided it); {}",
                                result.collision->with, result.collision->time, result.reason);
  } else if (result.verdict == Verdict::Failure && result.ending_scene && others_hold) {
    result.verdict = Verdict::Success;
    result.reason = fmt::format("ending scene {} reached; the collision with {} at t={:.2f} s was unavoidable (the R157 "
                                "reference driver collided too)",
                                *result.ending_scene, result.collision->with, result.collision->time);
  }
}

}  // namespace

RunResult run_with_reference(const RunRequest& req, Simulator& sim,
                             const std::function<std::unique_ptr<Simulator>()>& make_reference_sim) {
  RunResult result = run_scenario(req, sim);
  RunRequest ref = req;
  ref.out_dir = req.out_dir / "reference";
  ref.ego_link = nullptr;
  ref.reference_run = false;
  ref.echo = false;
  ref.ego_model.name = "r157";
  ref.ego_model_given = false;  // the reference run's own model: run.log says "the reference run"
  if (!req.ego_model.r157()) ref.ego_model.parameters.clear();
  const auto ref_sim = make_reference_sim();
  const RunResult reference = run_scenario(ref, *ref_sim);

  ReferenceRunRecord rec;
  rec.verdict = to_string(reference.verdict);
  rec.reference_collision = reference.collision;
  auto place = [](const RunResult& r) {
    return r.collision ? story_place(r.events, r.collision->time) : StoryPlace{};
  };
  rec.outcome = preventability(result.collision, rec.reference_collision, place(result), place(reference));
  auto measured = [](const RunResult& r, std::string_view summary, const std::optional<double>& watched) {
    const auto m = ego_min(r, summary);
    return m ? m : watched;
  };
  rec.min_ttc = measured(result, "min_ttc", result.ego_min_ttc);
  rec.reference_min_ttc = measured(reference, "min_ttc", reference.ego_min_ttc);
  rec.min_gap = measured(result, "min_gap", result.ego_min_gap);
  rec.reference_min_gap = measured(reference, "min_gap", reference.ego_min_gap);
  result.reference_run = rec;
  judge_preventable_collisions(result);
  write_result(req.out_dir, result);
  return result;
}

}  // namespace orch

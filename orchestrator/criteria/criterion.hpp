#pragma once
// Criteria (docs/evaluation.md "Criteria"): a limit on something measured for an actor over
// the run. Every criterion is judged step by step: each step in its window gives a frame
// (measured or not, within the limit or not); the mode folds the frames into the verdict:
//   all_of     every measured frame within the limit (none measured: holds)
//   any_of     at least one measured frame within it
//   pass_rate  at least `pass_rate` % of the measured frames within it
//   duration   the longest unbroken stretch outside the limit lasts at most `duration` s
// The types are a closed set, one row each in criterion_types() with one frame function:
// adding a type is one row and one function (criterion_types.cpp).
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "criteria/criterion_result.hpp"
#include "scenario_executor_engine/engine.hpp"
#include "metrics/actor_metrics.hpp"

namespace orch::criteria {

enum class Mode { AllOf, AnyOf, PassRate, Duration };
const char* to_string(Mode m);
std::optional<Mode> parse_mode(std::string_view text);

struct CriterionSpec {
  std::string name;
  std::string type = "metric";           // a row of criterion_types()
  std::optional<sim::ActorId> actor;  // none: the ego
  std::string metric;                    // type metric: one of metrics::metric_names()
  std::optional<double> min;             // the limit: min <= value <= max
  std::optional<double> max;
  Mode mode = Mode::AllOf;
  double pass_rate = 100;                // %, mode pass_rate
  double duration = 0;                   // s, mode duration
  std::optional<double> from_time, to_time;  // s: judged only within [from_time, to_time]
  std::optional<int> from_scene, to_scene;   // judged from entering from_scene until entering to_scene
  std::vector<std::string> with;         // no_collision: only contacts with these bodies (actor ids, SUMO ids)
  std::optional<int> scene;              // reach_scene: this scene (none: an ending scene)
};

// What the criteria see of the run in one step: plain values (the judge takes them from the
// engine), so that criteria are tested without one.
struct RunFacts {
  double time = 0;
  int scene = 0;                 // after this step's transition
  bool ending_reached = false;
  const std::vector<engine::SceneVisit>& visits;
  const std::vector<engine::Contact>& contacts;
};

// What a frame function sees of one step.
struct StepInput {
  const RunFacts& run;
  sim::ActorId actor = 0;                    // the criterion's actor (resolved)
  const metrics::ActorMetrics* metrics = nullptr;  // the actor's metrics this step (null: not measured)
};

struct Frame {
  bool measured = false;  // false: nothing to judge in this step (no leader, not present, ...)
  bool ok = true;
  std::optional<double> value;
  std::string partner;
};

struct CriterionType {
  std::string_view name;
  std::string_view metric;  // the metric it judges ("" for type metric: the spec names it)
  Mode mode;                // the default mode
  Frame (*frame)(const CriterionSpec&, const StepInput&);
  std::string (*expected)(const CriterionSpec&);
};

const std::vector<CriterionType>& criterion_types();
const CriterionType* find_criterion_type(std::string_view name);

// The running judgement of one criterion.
class CriterionState {
 public:
  CriterionState(CriterionSpec spec, sim::ActorId ego);

  // Judges this step (if it lies in the window); returns the frame (measured false outside).
  Frame step(const RunFacts& run, const metrics::ActorMetrics* metrics);
  // The verdict so far ("Total" of result.jsonl).
  [[nodiscard]] bool holds() const;
  [[nodiscard]] CriterionResult result() const;
  [[nodiscard]] const CriterionSpec& spec() const { return spec_; }
  [[nodiscard]] sim::ActorId actor() const { return actor_; }

 private:
  [[nodiscard]] bool in_window(const RunFacts& run);
  // How far a value lies outside the limit (<= 0 inside): orders values worst first.
  [[nodiscard]] double excess(double value) const;

  CriterionSpec spec_;
  const CriterionType* type_;
  sim::ActorId actor_;
  bool opened_ = false;
  bool closed_ = false;
  long long measured_ = 0;
  long long ok_ = 0;
  std::optional<double> last_time_;
  // all_of, pass_rate: the worst value and its time; any_of: the best.
  std::optional<double> decisive_value_;
  std::optional<double> decisive_time_;
  bool violated_ = false;
  bool satisfied_ = false;
  // duration: the current and the longest stretch outside the limit.
  std::optional<double> stretch_start_;
  double stretch_ = 0;
  double longest_ = 0;
  std::optional<double> longest_start_;
};

}  // namespace orch::criteria

#include "criteria/criterion.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/errors.hpp"

namespace orch::criteria {

const char* to_string(Mode m) {
  switch (m) {
    case Mode::AllOf: return "all_of";
    case Mode::AnyOf: return "any_of";
    case Mode::PassRate: return "pass_rate";
    case Mode::Duration: return "duration";
  }
  return "all_of";
}

std::optional<Mode> parse_mode(std::string_view text) {
  for (Mode m : {Mode::AllOf, Mode::AnyOf, Mode::PassRate, Mode::Duration})
    if (text == to_string(m)) return m;
  return std::nullopt;
}

CriterionState::CriterionState(CriterionSpec spec, sim::ActorId ego)
    : spec_(std::move(spec)), type_(find_criterion_type(spec_.type)), actor_(spec_.actor.value_or(ego)) {
  if (!type_) throw OrchError("unknown criterion type \"" + spec_.type + "\"");
  opened_ = !spec_.from_scene;
}

bool CriterionState::in_window(const RunFacts& run) {
  const double time = run.time;
  if (spec_.from_scene && run.scene == *spec_.from_scene) opened_ = true;
  if (opened_ && spec_.to_scene && run.scene == *spec_.to_scene) closed_ = true;
  if (!opened_ || closed_) return false;
  if (spec_.from_time && time < *spec_.from_time - 1e-9) return false;
  if (spec_.to_time && time > *spec_.to_time + 1e-9) return false;
  return true;
}

double CriterionState::excess(double value) const {
  double e = -std::numeric_limits<double>::infinity();
  if (spec_.min) e = std::max(e, *spec_.min - value);
  if (spec_.max) e = std::max(e, value - *spec_.max);
  if (!spec_.min && !spec_.max) e = 0;
  return e;
}

Frame CriterionState::step(const RunFacts& run, const metrics::ActorMetrics* metrics) {
  const double time = run.time;
  const double dt = time - last_time_.value_or(0.0);
  last_time_ = time;
  if (!in_window(run)) return {};
  const Frame f = type_->frame(spec_, StepInput{run, actor_, metrics});
  if (!f.measured) {
    stretch_start_.reset();  // an unmeasured step ends a stretch outside the limit
    return f;
  }
  ++measured_;
  if (f.ok) ++ok_;
  const double v = f.value.value_or(0.0);
  switch (spec_.mode) {
    case Mode::AllOf:
    case Mode::PassRate:
      // The worst value decides what is reported (the first of equals).
      violated_ = violated_ || !f.ok;
      if (!decisive_value_ || excess(v) > excess(*decisive_value_)) {
        decisive_value_ = v;
        decisive_time_ = time;
      }
      break;
    case Mode::AnyOf:
      // The best value (the first of equals).
      satisfied_ = satisfied_ || f.ok;
      if (!decisive_value_ || excess(v) < excess(*decisive_value_)) {
        decisive_value_ = v;
        decisive_time_ = time;
      }
      break;
    case Mode::Duration:
      if (f.ok) {
        stretch_start_.reset();
      } else {
        if (!stretch_start_) {
          stretch_start_ = time;
          stretch_ = 0;
        }
        stretch_ += dt;
        if (stretch_ > longest_) {
          longest_ = stretch_;
          longest_start_ = stretch_start_;
        }
      }
      break;
  }
  return f;
}

bool CriterionState::holds() const {
  switch (spec_.mode) {
    case Mode::AllOf: return !violated_;
    case Mode::AnyOf: return satisfied_;
    case Mode::PassRate: return measured_ > 0 && 100.0 * static_cast<double>(ok_) / static_cast<double>(measured_) >= spec_.pass_rate - 1e-9;
    case Mode::Duration: return longest_ <= spec_.duration + 1e-9;
  }
  return false;
}

CriterionResult CriterionState::result() const {
  CriterionResult r;
  r.name = spec_.name;
  r.actor = actor_;
  r.metric = type_->metric.empty() ? spec_.metric : std::string(type_->metric);
  r.expected = type_->expected(spec_);
  r.success = holds();
  switch (spec_.mode) {
    case Mode::AllOf:
    case Mode::AnyOf:
      r.actual = decisive_value_;
      r.at_time = decisive_time_;
      break;
    case Mode::PassRate:
      if (measured_ > 0) r.actual = 100.0 * static_cast<double>(ok_) / static_cast<double>(measured_);
      break;
    case Mode::Duration:
      r.actual = longest_;
      r.at_time = longest_start_;
      break;
  }
  return r;
}

}  // namespace orch::criteria

// The closed set of criterion types: one row and one frame function each.
#include <fmt/format.h>

#include <algorithm>

#include "criteria/criterion.hpp"

namespace orch::criteria {

namespace {

std::string number(double v) { return fmt::format("{:g}", v); }

std::string bounds_text(const CriterionSpec& s, std::string_view metric) {
  if (s.min && s.max) return fmt::format("{} <= {} <= {}", number(*s.min), metric, number(*s.max));
  if (s.min) return fmt::format("{} >= {}", metric, number(*s.min));
  if (s.max) return fmt::format("{} <= {}", metric, number(*s.max));
  return std::string(metric);
}

std::string mode_text(const CriterionSpec& s) {
  switch (s.mode) {
    case Mode::AllOf: return "at every step";
    case Mode::AnyOf: return "at some step";
    case Mode::PassRate: return fmt::format("in at least {} % of the steps", number(s.pass_rate));
    case Mode::Duration: return fmt::format("outside for at most {} s at a stretch", number(s.duration));
  }
  return "";
}

bool within(const CriterionSpec& s, double v) { return (!s.min || v >= *s.min) && (!s.max || v <= *s.max); }

// A metric of metrics.csv (or speed, standstill, ...), judged against min/max.
Frame metric_frame_named(const CriterionSpec& s, const StepInput& in, std::string_view metric) {
  Frame f;
  if (!in.metrics) return f;
  f.value = metrics::metric_value(*in.metrics, metric);
  if (!f.value) return f;
  f.measured = true;
  f.ok = within(s, *f.value);
  f.partner = metrics::metric_partner(*in.metrics, metric);
  return f;
}

Frame metric_frame(const CriterionSpec& s, const StepInput& in) { return metric_frame_named(s, in, s.metric); }
std::string metric_expected(const CriterionSpec& s) { return bounds_text(s, s.metric) + " " + mode_text(s); }

Frame speed_frame(const CriterionSpec& s, const StepInput& in) { return metric_frame_named(s, in, "speed"); }
std::string speed_expected(const CriterionSpec& s) { return bounds_text(s, "speed") + " m/s " + mode_text(s); }

Frame standstill_frame(const CriterionSpec& s, const StepInput& in) { return metric_frame_named(s, in, "standstill"); }
std::string standstill_expected(const CriterionSpec& s) {
  return fmt::format("standing still at most {} s at a time", number(s.max.value_or(0)));
}

Frame keep_lane_frame(const CriterionSpec& s, const StepInput& in) {
  return metric_frame_named(s, in, "lane_departure");
}
std::string keep_lane_expected(const CriterionSpec& s) {
  return fmt::format("body at most {} m beyond the lane markings {}", number(s.max.value_or(0)), mode_text(s));
}

// Counted contacts of the actor so far (with the given bodies only, if any).
Frame no_collision_frame(const CriterionSpec& s, const StepInput& in) {
  Frame f;
  f.measured = true;
  const std::string me = std::to_string(in.actor);
  double count = 0;
  for (const auto& c : in.run.contacts) {
    if (!c.counted || (c.a != me && c.b != me)) continue;
    const std::string& other = c.a == me ? c.b : c.a;
    if (!s.with.empty() && std::find(s.with.begin(), s.with.end(), other) == s.with.end()) continue;
    if (count == 0) f.partner = other;
    ++count;
  }
  f.value = count;
  f.ok = count == 0;
  return f;
}
std::string no_collision_expected(const CriterionSpec& s) {
  if (s.with.empty()) return "no collision";
  std::string who;
  for (const auto& w : s.with) who += (who.empty() ? "" : ", ") + w;
  return "no collision with " + who;
}

// The ego's collisions are counted while the run goes on; whether one was preventable is
// judged after the reference run (run/reference_run.cpp), which sets the result.
Frame no_preventable_collision_frame(const CriterionSpec& s, const StepInput& in) {
  Frame f = no_collision_frame(s, in);
  f.ok = true;
  return f;
}
std::string no_preventable_collision_expected(const CriterionSpec&) {
  return "no collision the R157 reference driver avoids (--reference-run)";
}

// 1 once the scene (or an ending scene) has been reached.
Frame reach_scene_frame(const CriterionSpec& s, const StepInput& in) {
  Frame f;
  f.measured = true;
  bool reached = false;
  if (s.scene) {
    for (const auto& v : in.run.visits) reached = reached || v.id == *s.scene;
  } else {
    reached = in.run.ending_reached;
  }
  f.value = reached ? 1.0 : 0.0;
  f.ok = reached;
  return f;
}
std::string reach_scene_expected(const CriterionSpec& s) {
  return s.scene ? fmt::format("reach scene {}", *s.scene) : std::string("reach an ending scene");
}

}  // namespace

const std::vector<CriterionType>& criterion_types() {
  static const std::vector<CriterionType> types{
      {"metric", "", Mode::AllOf, metric_frame, metric_expected},
      {"no_collision", "collisions", Mode::AllOf, no_collision_frame, no_collision_expected},
      {"reach_scene", "scene", Mode::AnyOf, reach_scene_frame, reach_scene_expected},
      {"max_speed", "speed", Mode::AllOf, speed_frame, speed_expected},
      {"standstill", "standstill", Mode::AllOf, standstill_frame, standstill_expected},
      {"keep_lane", "lane_departure", Mode::AllOf, keep_lane_frame, keep_lane_expected},
      {"no_preventable_collision", "preventable_collision", Mode::AllOf, no_preventable_collision_frame,
       no_preventable_collision_expected},
  };
  return types;
}

const CriterionType* find_criterion_type(std::string_view name) {
  for (const auto& t : criterion_types())
    if (t.name == name) return &t;
  return nullptr;
}

}  // namespace orch::criteria

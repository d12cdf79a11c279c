#include "engine/motion.hpp"

#include <algorithm>
#include <cmath>

namespace orch::engine {

double LateralMove::value_at(double t) const {
  if (duration <= 0 || t >= start + duration) return to;
  if (t <= start) return from;
  const double u = (t - start) / duration;
  const double shape = u * u * u * (10 - 15 * u + 6 * u * u);
  return from + (to - from) * shape;
}

double LateralMove::rate_at(double t) const {
  if (duration <= 0 || t <= start || t >= start + duration) return 0;
  const double u = (t - start) / duration;
  const double dshape = 30 * u * u * (1 - u) * (1 - u);
  return (to - from) * dshape / duration;
}

ScriptedMotion::ScriptedMotion(const WaypointRoute& route, double s, double lateral, double speed,
                               double heading_offset, double length, double lane_extension)
    : route_(&route), s_(s), lateral_(lateral), speed_(speed), heading_offset_(heading_offset),
      length_(length), lane_extension_(lane_extension), desired_speed_(speed) {}

double ScriptedMotion::s_max() const {
  // The front may reach the end of the lane, which runs lane_extension past the last point.
  return route_->line.length() + std::max(0.0, lane_extension_ - length_ / 2);
}
double ScriptedMotion::s_min() const { return -std::max(0.0, lane_extension_ - length_ / 2); }

void ScriptedMotion::plan_lateral(const std::vector<LateralLeg>& legs, double t) {
  active_lateral_.reset();
  pending_lateral_ = legs;
  std::reverse(pending_lateral_.begin(), pending_lateral_.end());  // pop from the back
  if (!pending_lateral_.empty()) {
    const LateralLeg leg = pending_lateral_.back();
    pending_lateral_.pop_back();
    active_lateral_ = LateralMove{lateral_, leg.to, t, leg.duration};
  }
}

void ScriptedMotion::change_route(const WaypointRoute& route, double target_offset, double t, double duration) {
  const Vec2 here = position();
  const auto p = route.line.project(here);
  route_ = &route;
  s_ = p.s;
  lateral_ = p.lateral;
  at_end_ = false;
  plan_lateral({{target_offset, duration}}, t);
}

void ScriptedMotion::plan_walk(const std::vector<std::pair<Vec2, double>>& legs, double t) {
  walk_pending_.assign(legs.rbegin(), legs.rend());
  walk_active_.reset();
  if (!free_position_) {
    free_position_ = position();
    free_heading_ = heading();
  }
  if (!walk_pending_.empty()) {
    auto [target, duration] = walk_pending_.back();
    walk_pending_.pop_back();
    walk_active_ = WalkLeg{*free_position_, target, t, duration};
  }
}

void ScriptedMotion::advance(double t, double dt) {
  if (free_position_) {
    advance_walk(t, dt);
    return;
  }
  advance_longitudinal(dt);
  advance_lateral(t + dt, dt);
}

void ScriptedMotion::advance_longitudinal(double dt) {
  const double before = speed_;
  double v = std::max(0.0, desired_speed_);
  if (desired_accel_ > 0) {
    const double step = desired_accel_ * dt;
    v = std::clamp(v, before - step, before + step);
  }
  if (at_end_) v = 0;
  // The lane ends: brake so as to stop at its end rather than hit an invisible wall. Braking
  // starts when the deceleration needed reaches kEndOfLaneDecel.
  const double remaining = s_max() - s_;
  if (!at_end_ && before > 0 && remaining > 0) {
    const double needed = before * before / (2 * remaining);
    if (needed >= kEndOfLaneDecel) {
      running_out_ = true;
      v = std::min(v, std::max(0.0, before - needed * dt));
    }
  }
  // Constant acceleration over the step: the distance is the mean speed times dt.
  double next_s = s_ + 0.5 * (before + v) * dt;
  if (next_s >= s_max()) {
    next_s = s_max();
    v = 0;
    at_end_ = true;
  }
  s_ = std::max(next_s, s_min());
  speed_ = v;
  accel_ = (v - before) / dt;
}

void ScriptedMotion::advance_lateral(double t_next, double dt) {
  const double before = lateral_;
  while (active_lateral_ && active_lateral_->done_at(t_next)) {
    // Finish this leg exactly at its end time and start the next one there.
    const double end = active_lateral_->start + active_lateral_->duration;
    lateral_ = active_lateral_->to;
    active_lateral_.reset();
    if (!pending_lateral_.empty()) {
      const LateralLeg leg = pending_lateral_.back();
      pending_lateral_.pop_back();
      active_lateral_ = LateralMove{lateral_, leg.to, end, leg.duration};
    }
  }
  if (active_lateral_) lateral_ = active_lateral_->value_at(t_next);
  lateral_rate_ = (lateral_ - before) / dt;
}

void ScriptedMotion::advance_walk(double t, double dt) {
  const double t_next = t + dt;
  const Vec2 before = *free_position_;
  while (walk_active_ && t_next >= walk_active_->start + walk_active_->duration - 1e-9) {
    const double end = walk_active_->start + walk_active_->duration;
    free_position_ = walk_active_->to;
    walk_active_.reset();
    if (!walk_pending_.empty()) {
      auto [target, duration] = walk_pending_.back();
      walk_pending_.pop_back();
      walk_active_ = WalkLeg{*free_position_, target, end, duration};
    }
  }
  if (walk_active_) {
    const double u = (t_next - walk_active_->start) / walk_active_->duration;
    free_position_ = walk_active_->from + std::clamp(u, 0.0, 1.0) * (walk_active_->to - walk_active_->from);
  }
  const Vec2 moved = *free_position_ - before;
  const double v = moved.norm() / dt;
  if (moved.norm() > 1e-9) free_heading_ = std::atan2(moved.y(), moved.x());
  accel_ = (v - speed_) / dt;
  speed_ = v;
}

Vec2 ScriptedMotion::position() const {
  if (free_position_) return *free_position_;
  return route_->line.offset_point(s_, lateral_);
}

double ScriptedMotion::heading() const {
  if (free_position_) return free_heading_;
  // Yaw toward the lateral motion: a car changing lanes points where it is going.
  const double drift = std::atan2(lateral_rate_, std::max(speed_, 1.0));
  return wrap_angle(route_->line.heading_at(s_) + drift + heading_offset_);
}

}  // namespace orch::engine

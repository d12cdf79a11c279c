#include "scenario_executor_engine/motion.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace orch::engine {

double LateralMove::value_at(double t) const {
  // Same end as done_at: times built from summed steps may miss the exact end by rounding.
  if (duration <= 0 || t >= start + duration - 1e-9) return to;
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

// The front may reach the end of the lane, which runs lane_extension past the route's ends.
double ScriptedMotion::s_max() const { return route_->line.length() + std::max(0.0, lane_extension_ - length_ / 2); }
double ScriptedMotion::s_min() const { return -std::max(0.0, lane_extension_ - length_ / 2); }
double ScriptedMotion::room_ahead() const { return direction_ > 0 ? s_max() - s_ : s_ - s_min(); }

void ScriptedMotion::plan_lateral(const std::vector<LateralLeg>& legs, double t) {
  route_leg_.reset();
  pending_route_legs_.clear();
  active_lateral_.reset();
  pending_lateral_.assign(legs.rbegin(), legs.rend());
  if (!pending_lateral_.empty()) {
    const LateralLeg leg = pending_lateral_.back();
    pending_lateral_.pop_back();
    active_lateral_ = LateralMove{lateral_, leg.to, t, leg.duration};
  }
}

void ScriptedMotion::switch_route(const WaypointRoute& route) {
  const Vec2 here = position();
  const Vec2 travel(std::cos(heading() - heading_offset_), std::sin(heading() - heading_offset_));
  const auto p = route.line.project(here);
  route_ = &route;
  s_ = p.s;
  direction_ = route.line.tangent_at(p.s).dot(travel) >= 0 ? 1 : -1;
  lateral_ = direction_ * p.lateral;
  at_end_ = false;
}

void ScriptedMotion::change_route(const WaypointRoute& route, double target_offset, double t, double duration) {
  switch_route(route);
  plan_lateral({{target_offset, duration}}, t);
}

void ScriptedMotion::plan_route_legs(const std::vector<RouteLegTarget>& legs, double t) {
  active_lateral_.reset();
  pending_lateral_.clear();
  route_leg_.reset();
  pending_route_legs_.assign(legs.rbegin(), legs.rend());
  if (!pending_route_legs_.empty()) {
    const RouteLegTarget leg = pending_route_legs_.back();
    pending_route_legs_.pop_back();
    start_route_leg(leg, t);
  }
}

void ScriptedMotion::start_route_leg(const RouteLegTarget& leg, double t) {
  if (leg.route != route_) switch_route(*leg.route);
  route_leg_ = ActiveRouteLeg{s_, leg.s, t, leg.duration};
  active_lateral_ = LateralMove{lateral_, direction_ * leg.lateral, t, leg.duration};
}

void ScriptedMotion::plan_walk(const std::vector<std::pair<Vec2, double>>& legs, double t) {
  if (!free_position_) {
    free_heading_ = heading();
    free_position_ = position();
  }
  walk_active_.reset();
  walk_pending_.assign(legs.rbegin(), legs.rend());
  if (!walk_pending_.empty()) {
    auto [target, duration] = walk_pending_.back();
    walk_pending_.pop_back();
    walk_active_ = WalkLeg{*free_position_, target, t, duration};
  }
}

void ScriptedMotion::cancel_moves() {
  walk_active_.reset();
  walk_pending_.clear();
  if (route_leg_) {
    route_leg_.reset();
    pending_route_legs_.clear();
    active_lateral_.reset();
    pending_lateral_.clear();
  }
}

void ScriptedMotion::advance(double t, double dt) {
  if (free_position_) {
    advance_walk(t, dt);
    return;
  }
  if (route_leg_) advance_route_leg(t + dt, dt);
  else advance_longitudinal(dt);
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
  // The lane ends: brake so as to stop at its end rather than hit an invisible wall.
  // Braking starts when the deceleration needed reaches kEndOfLaneDecel.
  const double room = room_ahead();
  if (!at_end_ && before > 0 && room > 0) {
    const double needed = before * before / (2 * room);
    if (needed >= kEndOfLaneDecel) {
      running_out_ = true;
      v = std::min(v, std::max(0.0, before - needed * dt));
    }
  }
  // Constant acceleration over the step: the distance is the mean speed times dt.
  double travelled = 0.5 * (before + v) * dt;
  if (travelled >= room) {
    travelled = std::max(0.0, room);
    v = 0;
    at_end_ = true;
  }
  s_ += direction_ * travelled;
  speed_ = v;
  accel_ = (v - before) / dt;
}

void ScriptedMotion::advance_route_leg(double t_next, double dt) {
  const double before_speed = speed_;
  const double s_before = s_;
  while (route_leg_ && t_next >= route_leg_->start_time + route_leg_->duration - 1e-9) {
    const double end = route_leg_->start_time + route_leg_->duration;
    s_ = route_leg_->end_s;
    if (active_lateral_) lateral_ = active_lateral_->to;  // the leg arrives exactly
    route_leg_.reset();
    if (!pending_route_legs_.empty()) {
      const RouteLegTarget leg = pending_route_legs_.back();
      pending_route_legs_.pop_back();
      start_route_leg(leg, end);
    }
  }
  if (route_leg_) {
    const double u = route_leg_->duration > 0 ? (t_next - route_leg_->start_time) / route_leg_->duration : 1.0;
    s_ = route_leg_->start_s + std::clamp(u, 0.0, 1.0) * (route_leg_->end_s - route_leg_->start_s);
  }
  speed_ = std::abs(s_ - s_before) / dt;
  // The last leg's speed carries on after it (see Engine: KeepSpeed).
  desired_speed_ = speed_;
  desired_accel_ = 0;
  accel_ = (speed_ - before_speed) / dt;
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
  return route_->line.offset_point(s_, direction_ * lateral_);
}

double ScriptedMotion::heading() const {
  if (free_position_) return free_heading_;
  // Yaw toward the lateral motion: a car changing lanes points where it is going.
  const double drift = std::atan2(lateral_rate_, std::max(speed_, 1.0));
  const double along = route_->line.heading_at(s_) + (direction_ < 0 ? std::numbers::pi : 0.0);
  return wrap_angle(along + drift + heading_offset_);
}

}  // namespace orch::engine

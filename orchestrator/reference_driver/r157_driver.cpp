#include "reference_driver/r157_driver.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/checked_numeric.hpp"

namespace orch::reference_driver {

namespace {
constexpr double kEps = 1e-9;
// Gains of the normal following controller (constant time gap): the model's own.
constexpr double kGapGain = 0.2;     // 1/s^2 per m of gap error
constexpr double kSpeedGain = 0.6;   // 1/s per m/s of speed difference
constexpr double kCruiseGain = 0.5;  // 1/s towards the set speed
// Below this the constant-time-gap law alone closes up to a slower leader; above it the
// driver brakes to match the leader's speed with the standstill gap left.
constexpr double kMatchSpeedFrom = 0.5;  // m/s^2
constexpr double kStandstill = 0.1;      // m/s
// "Full wrap": the narrower body within the wider one laterally, up to this much (esmini's
// ReferenceDriver uses the same overlap tolerance).
constexpr double kWrapTolerance = 0.2;  // m
// A risk of a vehicle already perceived reuses that perception (one threat, one perception),
// except a leader that starts braking hard: that is a new event to perceive.
constexpr const char* kDecelerating = "decelerating lead vehicle";
}  // namespace

const char* to_string(Phase phase) {
  switch (phase) {
    case Phase::Drive: return "drive";
    case Phase::Perceive: return "perceive";
    case Phase::React: return "react";
    case Phase::Brake: return "brake";
  }
  return "?";
}

namespace {
double gap_between(const DriverView& v, const PerceivedObject& o) {
  return (o.s - o.length / 2) - (v.ego.s + v.ego.length / 2);
}
bool overlaps_path(const DriverView& v, const PerceivedObject& o, double pedestrian_margin) {
  const double margin = o.kind == ObjectKind::Pedestrian ? pedestrian_margin : 0.0;
  return std::abs(o.d - v.ego.d) < (o.width + v.ego.width) / 2 + margin;
}
}  // namespace

Ahead object_ahead(const DriverView& v, double range, double pedestrian_margin) {
  Ahead best;
  best.gap = std::numeric_limits<double>::infinity();
  for (const auto& o : v.objects) {
    if (o.s <= v.ego.s || !overlaps_path(v, o, pedestrian_margin)) continue;
    const double gap = gap_between(v, o);
    if (gap > range || gap >= best.gap) continue;
    best = {&o, gap};
  }
  return best;
}

void Exposure::add(const DriverView& v, double range) {
  const Ahead a = object_ahead(v, range, 0.0);
  if (!a.object) return;
  const double gap = std::max(a.gap, 0.0);
  if (!min_gap || gap < *min_gap) min_gap = gap;
  const double closing = v.ego.speed - a.object->speed_s;
  if (closing > kEps && (!min_ttc || gap / closing < *min_ttc)) min_ttc = gap / closing;
}

double R157Driver::gap_to(const DriverView& v, const PerceivedObject& o) const { return gap_between(v, o); }

bool R157Driver::in_path(const DriverView& v, const PerceivedObject& o) const {
  return overlaps_path(v, o, p_.pedestrian_margin);
}

// A pedestrian moving towards the ego's path that reaches it before the ego passes it.
bool R157Driver::entering_path(const DriverView& v, const PerceivedObject& o) const {
  if (o.kind != ObjectKind::Pedestrian || in_path(v, o)) return false;
  const double side = o.d > v.ego.d ? 1.0 : -1.0;
  const double towards = -side * o.speed_d;
  if (towards <= 0.1) return false;
  const double lateral = std::abs(o.d - v.ego.d) - (o.width + v.ego.width) / 2 - p_.pedestrian_margin;
  const double t_enter = lateral / towards;
  const double gap = gap_to(v, o);
  const double t_reach = gap / std::max(v.ego.speed, 0.1);
  return t_enter <= t_reach + p_.risk_perception_time + p_.brake_reaction_time;
}

const PerceivedObject* R157Driver::find(const DriverView& v, const std::string& id) const {
  for (const auto& o : v.objects)
    if (o.id == id) return &o;
  return nullptr;
}

// Normal driving: towards the set speed, the minimum following distance to the leader and a
// comfortable stop behind anything slower in the path (or the end of the path).
double R157Driver::normal_accel(const DriverView& v, const Ahead& ahead) const {
  const double speed = v.ego.speed;
  double a = kCruiseGain * (v.set_speed - speed);
  auto follow = [&](double gap, double lead_speed) {
    a = std::min(a, kGapGain * (gap - p_.min_following_distance(speed)) + kSpeedGain * (lead_speed - speed));
    // The deceleration that matches the leader's speed with the standstill gap left.
    if (speed > lead_speed) {
      const double room = std::max(gap - p_.min_standstill_gap, 0.01);
      const double needed = (speed * speed - lead_speed * lead_speed) / (2 * room);
      if (needed > kMatchSpeedFrom) a = std::min(a, -needed);
    }
  };
  if (ahead.object) follow(ahead.gap, std::max(0.0, ahead.object->speed_s));
  if (v.path_end) {  // the ego's centre stops there
    const double to_end = *v.path_end - v.ego.s;
    if (to_end < p_.perception_range) follow(to_end + p_.min_standstill_gap, 0.0);
  }
  return std::clamp(a, -p_.comfort_deceleration, p_.comfort_acceleration);
}

// A vehicle target is critical while the ego closes in on it with a time to collision
// below critical_ttc (or, for a leader, a time headway below it).
bool R157Driver::critical(const DriverView& v, const PerceivedObject& target) const {
  if (full_stop_) return true;
  const double closing = v.ego.speed - target.speed_s;
  if (closing <= kEps) return false;
  const double gap = std::max(gap_to(v, target), 0.0);
  if (gap / closing < p_.critical_ttc) return true;
  return risk_ != "cut-in" && gap / std::max(v.ego.speed, kEps) < p_.critical_ttc;
}

void R157Driver::update_home_lanes(const DriverView& v) {
  for (const auto& o : v.objects) {
    if (o.kind != ObjectKind::Vehicle) continue;
    const long k = clamped_round<long>(o.d / v.lane_width, -(1L << 30), 1L << 30);
    if (std::abs(o.d - static_cast<double>(k) * v.lane_width) <= p_.wandering_threshold)
      home_lane_[o.id] = static_cast<int>(k);
  }
}

void R157Driver::start_risk(const DriverView& v, const std::string& risk, const PerceivedObject& target, Decision& out) {
  phase_ = Phase::Perceive;
  risk_ = risk;
  target_ = target.id;
  full_stop_ = target.kind != ObjectKind::Vehicle || target.speed_s < 0.5;
  brake_decel_ = 0;
  wrapped_ = false;
  const auto known = perceived_.find(target.id);
  if (known != perceived_.end() && risk != kDecelerating) {
    // The same threat, already perceived (and its brake reaction under way or done): the
    // answer goes on from that risk perception point, without a second delay.
    risk_at_ = known->second;
    reused_ = fmt::format("r157: {} ({}, gap {:.2f} m): perceived at {:.2f} s already", risk, target.id,
                          gap_to(v, target), risk_at_);
    return;
  }
  reused_.clear();
  risk_at_ = v.time;
  perceived_[target.id] = v.time;
  out.events.push_back(fmt::format("r157: {} ({}, gap {:.2f} m): risk perceived", risk, target.id, gap_to(v, target)));
}

// A perceived threat is forgotten when it is out of sight, or while driving normally once the
// ego no longer closes in on it and keeps at least the minimum following distance.
void R157Driver::forget_resolved_threats(const DriverView& v) {
  for (auto it = perceived_.begin(); it != perceived_.end();) {
    const PerceivedObject* o = find(v, it->first);
    const bool resolved = !o || (phase_ == Phase::Drive && o->speed_s >= v.ego.speed - kEps &&
                                 gap_to(v, *o) >= p_.min_following_distance(v.ego.speed));
    it = resolved ? perceived_.erase(it) : std::next(it);
  }
}

// Annex 4 App. 3 Table 1: "after full wrap of ego vehicle and cut-in vehicle".
bool R157Driver::fully_wraps(const DriverView& v, const PerceivedObject& o) const {
  return std::abs(o.d - v.ego.d) <= std::abs(o.width - v.ego.width) / 2 + kWrapTolerance;
}

// The nearest object in the ego's path beyond `leader` (what a cut-out reveals).
const PerceivedObject* R157Driver::revealed_beyond(const DriverView& v, const PerceivedObject& leader) const {
  const PerceivedObject* best = nullptr;
  for (const auto& o : v.objects) {
    if (o.id == leader.id || o.s <= leader.s || !in_path(v, o) || gap_to(v, o) > p_.perception_range) continue;
    if (!best || o.s < best->s) best = &o;
  }
  return best;
}

void R157Driver::detect(const DriverView& v, const Ahead& ahead, Decision& out) {
  // Standing (or nearly): nothing to brake for; normal driving keeps the standstill gap.
  if (v.ego.speed < kStandstill) {
    last_leader_ = ahead.object ? ahead.object->id : "";
    return;
  }
  const double range = p_.perception_range;
  // Cut-in: a vehicle whose lane is next to the ego's has left its lane centre towards the
  // ego's lane by more than the wandering threshold.
  for (const auto& o : v.objects) {
    if (o.kind != ObjectKind::Vehicle || o.s <= v.ego.s || gap_to(v, o) > range) continue;
    const auto home = home_lane_.find(o.id);
    if (home == home_lane_.end() || std::abs(home->second) != 1) continue;
    const double k = home->second;
    if ((k * v.lane_width - o.d) * k > p_.wandering_threshold) {
      // Handled once: it has no home lane until it keeps to a lane centre again (the ego's:
      // from then on a move out of it is a cut-out; its own: a new cut-in).
      home_lane_.erase(o.id);
      return start_risk(v, "cut-in", o, out);
    }
  }
  // A pedestrian in or entering the path that comfortable braking no longer stops for (one
  // farther away is a standing object ahead: normal driving stops behind it).
  const double comfortable_stop = v.ego.speed * v.ego.speed / (2 * p_.comfort_deceleration);
  for (const auto& o : v.objects)
    if (o.kind == ObjectKind::Pedestrian && o.s > v.ego.s && gap_to(v, o) - p_.min_standstill_gap < comfortable_stop &&
        (in_path(v, o) || entering_path(v, o)))
      return start_risk(v, "pedestrian in the path", o, out);
  if (!ahead.object) {
    last_leader_.clear();
    return;
  }
  const PerceivedObject& lead = *ahead.object;
  // Cut-out (Table 1: "deviation of the centre of a vehicle over 0.375 m from the centre of the
  // driving lane"): the leader, which kept to the ego's lane centre, is more than the
  // wandering threshold out of it while something stands or drives beyond it in the path.
  const auto lead_home = home_lane_.find(lead.id);
  if (lead.kind == ObjectKind::Vehicle && lead_home != home_lane_.end() && lead_home->second == 0 &&
      std::abs(lead.d) > p_.wandering_threshold && !cut_out_seen_.contains(lead.id)) {
    if (const PerceivedObject* revealed = revealed_beyond(v, lead)) {
      cut_out_seen_.insert(lead.id);
      last_leader_ = lead.id;
      return start_risk(v, "cut-out", *revealed, out);
    }
  }
  // A leader that left the path without being seen at its lane centre before (it entered the
  // view off-centre): the cut-out is perceived when it revealed the next object.
  if (!last_leader_.empty() && last_leader_ != lead.id && !cut_out_seen_.contains(last_leader_)) {
    const PerceivedObject* previous = find(v, last_leader_);
    if (previous && std::abs(previous->d - v.ego.d) > p_.wandering_threshold && previous->s < lead.s) {
      cut_out_seen_.insert(last_leader_);
      last_leader_ = lead.id;
      return start_risk(v, "cut-out", lead, out);
    }
  }
  last_leader_ = lead.id;
  if (lead.kind == ObjectKind::Vehicle && lead.accel_s < -p_.lead_deceleration_threshold && lead.speed_s > 0.5)
    return start_risk(v, kDecelerating, lead, out);
  // Something in the path that comfortable braking no longer stops for.
  const double speed = v.ego.speed;
  const double lead_speed = std::max(0.0, lead.speed_s);
  if (speed > lead_speed) {
    const double room = std::max(ahead.gap - p_.min_standstill_gap, 0.01);
    if ((speed * speed - lead_speed * lead_speed) / (2 * room) > p_.comfort_deceleration)
      return start_risk(v, "obstacle in the path", lead, out);
  }
}

void R157Driver::advance_phase(const DriverView& v, Decision& out) {
  const double since = v.time - risk_at_ + kEps;
  const PerceivedObject* target = find(v, target_);
  auto end_risk = [&](const std::string& why) {
    // A known threat judged again not critical: nothing new to tell (it may be every step).
    const bool quiet = !reused_.empty() && phase_ != Phase::Brake;
    if (!quiet) out.events.push_back(fmt::format("r157: {} ({}): {}", risk_, target_, why));
    reused_.clear();
    // Braked for and resolved: a later risk of the same vehicle is a new threat. Judged not
    // critical: still the same threat while it stays in sight.
    if (phase_ == Phase::Brake) perceived_.erase(target_);
    phase_ = Phase::Drive;
    brake_decel_ = 0;
    wrapped_ = false;
  };
  if (!target) return end_risk("out of sight");
  if (phase_ == Phase::Perceive && since >= p_.risk_perception_time) phase_ = Phase::React;
  if (phase_ == Phase::React && since >= p_.risk_perception_time + p_.brake_reaction_time) {
    if (!critical(v, *target)) return end_risk("not critical, no braking");
    phase_ = Phase::Brake;
    // Braking goes on from the deceleration the ego already has (it may be braking
    // comfortably): the jerk-limited ramp starts there, never from zero.
    brake_decel_ = std::max(0.0, -last_accel_);
    if (!reused_.empty()) out.events.push_back(reused_);
    reused_.clear();
    out.events.push_back(fmt::format("r157: {} ({}): braking", risk_, target_));
    return;
  }
  if (phase_ != Phase::Brake) return;
  if (risk_ == "cut-in" && !wrapped_ && target->kind == ObjectKind::Vehicle && fully_wraps(v, *target)) {
    wrapped_ = true;
    out.events.push_back(fmt::format("r157: {} ({}): full wrap, braking up to {:.2f} m/s^2", risk_, target_,
                                     p_.wrap_deceleration));
  }
  if (full_stop_) {
    // Stopped: normal driving takes over again and keeps the standstill gap to whatever is
    // still in the path (it waits behind a pedestrian or an obstacle).
    if (v.ego.speed <= kEps) return end_risk("stopped");
    const bool still_there = in_path(v, *target) || entering_path(v, *target);
    if (!still_there && target->kind == ObjectKind::Pedestrian) return end_risk("left the path");
    if (!still_there && target->s < v.ego.s) return end_risk("passed");
    return;
  }
  if (v.ego.speed - target->speed_s <= kEps || target->s <= v.ego.s) return end_risk("no longer closing in");
}

Decision R157Driver::step(const DriverView& v) {
  Decision out;
  update_home_lanes(v);
  forget_resolved_threats(v);
  const Ahead ahead = object_ahead(v, p_.perception_range, p_.pedestrian_margin);
  if (phase_ == Phase::Drive) detect(v, ahead, out);
  if (phase_ != Phase::Drive) advance_phase(v, out);
  if (phase_ == Phase::Drive) last_leader_ = ahead.object ? ahead.object->id : "";

  const double dt = v.step;
  const double speed = v.ego.speed;
  double a = normal_accel(v, ahead);
  double dv = a * dt;
  switch (phase_) {
    case Phase::Drive:
      break;
    case Phase::Perceive:
    case Phase::React:
      // Appendix 3: no answer to the risk before the brake acts; the driver goes on as
      // before but no longer speeds up (no anticipation either: that is the model).
      a = std::min(last_accel_, 0.0);
      dv = a * dt;
      break;
    case Phase::Brake: {
      // The deceleration builds up with the model's jerk to its maximum (the profile of
      // Appendix 3 alone); exact for the ramp. After a full wrap the second stage builds up
      // to 0.85 G in the same time (Table 1: 0.6 s to either).
      const double cap = wrapped_ ? std::max(p_.wrap_deceleration, p_.max_deceleration) : p_.max_deceleration;
      const double jerk = wrapped_ ? p_.brake_jerk * cap / p_.max_deceleration : p_.brake_jerk;
      const double from = brake_decel_;
      brake_decel_ = std::min(brake_decel_ + jerk * dt, std::max(cap, from));
      dv = -(from + brake_decel_) / 2 * dt;
      a = -brake_decel_;
      break;
    }
  }
  out.speed = std::max(0.0, speed + dv);
  out.accel = dt > 0 ? (out.speed - speed) / dt : a;
  out.phase = phase_;
  last_accel_ = out.accel;
  return out;
}

}  // namespace orch::reference_driver

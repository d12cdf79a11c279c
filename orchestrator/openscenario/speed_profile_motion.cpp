#include "openscenario/speed_profile_motion.hpp"

#include <algorithm>
#include <cmath>

namespace orch::openscenario {

SpeedProfileRun start_speed_profile(const SpeedProfileAction& a, double t, double speed, double reference) {
  SpeedProfileRun run;
  double at = t, from = speed;
  for (const SpeedProfileEntry& e : a.entries) {
    const double to = e.speed + (a.relative_to ? reference : 0.0);
    double duration = 0;
    if (e.time) {
      duration = *e.time;
    } else {
      const std::optional<double> limit = to > from ? a.max_acceleration : a.max_deceleration;
      if (limit) duration = std::abs(to - from) / *limit;
    }
    run.segments.push_back({at, duration, from, to, DynamicsShape::Linear});
    at += duration;
    from = to;
  }
  return run;
}

double profile_speed(const SpeedProfileRun& run, double t) {
  for (const SpeedProfile& s : run.segments)
    if (t < s.start + s.duration) return t <= s.start ? s.from : s.at(t);
  return run.segments.back().to;
}

namespace {

bool step_position(SpeedProfileRun& run, EntityState& state, double t) {
  while (!state.speed_profile || state.speed_profile->done(t)) {
    if (state.speed_profile) {
      state.speed = state.speed_profile->to;
      state.speed_profile.reset();
    }
    if (run.next >= run.segments.size()) return true;
    const SpeedProfile& segment = run.segments[run.next++];
    if (segment.duration <= 0) {
      state.speed = segment.to;
      continue;
    }
    state.speed_profile = segment;
  }
  return false;
}

bool step_follow(const SpeedProfileAction& a, SpeedProfileRun& run, EntityState& state, double t, double dt) {
  const double end = run.segments.back().start + run.segments.back().duration;
  const double last = run.segments.back().to;
  if (dt <= 0) return false;
  // The acceleration that would put it on the profile one step on, within the limits.
  double wanted = (profile_speed(run, t + dt) - state.speed) / dt;
  if (a.max_acceleration) wanted = std::min(wanted, *a.max_acceleration);
  if (a.max_deceleration) wanted = std::max(wanted, -*a.max_deceleration);
  const double up = a.max_acceleration_rate ? *a.max_acceleration_rate * dt : INFINITY;
  const double down = a.max_deceleration_rate ? *a.max_deceleration_rate * dt : INFINITY;
  run.acceleration = std::clamp(wanted, run.acceleration - down, run.acceleration + up);
  double next = state.speed + run.acceleration * dt;
  if (a.max_speed) next = std::min(next, *a.max_speed);
  // Past the profile's end: done once it reaches (or passes) the last speed.
  if (t + dt >= end - 1e-9 && (next - last) * (state.speed - last) <= 0) {
    state.speed = last;
    run.acceleration = 0;
    return true;
  }
  state.speed = next;
  return false;
}

}  // namespace

bool step_speed_profile(const SpeedProfileAction& a, SpeedProfileRun& run, EntityState& state, double t, double dt) {
  return a.follow ? step_follow(a, run, state, t, dt) : step_position(run, state, t);
}

}  // namespace orch::openscenario

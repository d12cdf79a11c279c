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

// Follow mode: the profile's lines (segments with a duration, then the last speed held) with
// their corners rounded by jerk-limited changes of acceleration. The entity keeps the
// acceleration of the line it is on; towards the next line it changes its acceleration at
// maxAccelerationRate / maxDecelerationRate, starting that change when it would end on the
// next line (so the corner is rounded on both sides and no speed of the profile is passed);
// one it is already late for (the action's start) it starts at once.
struct Line {
  double start = 0, from = 0, slope = 0;
  [[nodiscard]] double at(double t) const { return from + slope * (t - start); }
};

std::vector<Line> lines_of(const SpeedProfileAction& a, const SpeedProfileRun& run) {
  std::vector<Line> lines;
  const auto limited = [&](double slope) {
    if (a.max_acceleration) slope = std::min(slope, *a.max_acceleration);
    if (a.max_deceleration) slope = std::max(slope, -*a.max_deceleration);
    return slope;
  };
  for (const SpeedProfile& s : run.segments)
    if (s.duration > 0) lines.push_back({s.start, s.from, limited((s.to - s.from) / s.duration)});
  const SpeedProfile& last = run.segments.back();
  lines.push_back({last.start + last.duration, last.to, 0.0});
  return lines;
}

bool step_follow(const SpeedProfileAction& a, SpeedProfileRun& run, EntityState& state, double t, double dt) {
  if (dt <= 0) return false;
  const std::vector<Line> lines = lines_of(a, run);
  const double up = a.max_acceleration_rate.value_or(INFINITY);
  const double down = a.max_deceleration_rate.value_or(INFINITY);
  double v = state.speed, acc = run.acceleration, left = dt, now = t;
  bool waited = false;  // it has just come to where the change begins
  while (left > 1e-12 && run.next < lines.size()) {
    const Line& next = lines[run.next];
    const double change = next.slope - acc;
    const double rate = change > 0 ? up : down;
    const double ramp = std::isinf(rate) ? 0.0 : std::abs(change) / rate;
    // Where it would end if it began the change now, against the next line there.
    const double gap = v + (acc + next.slope) / 2 * ramp - next.at(now + ramp);
    const bool begin = waited || change == 0 || (change > 0 ? gap <= 1e-9 : gap >= -1e-9);
    waited = false;
    if (!begin) {
      // On this line the gap closes at the rate acc - next.slope: begin where it reaches 0,
      // if that is within this step (else keep this line's acceleration for the step).
      const double wait = -gap / (acc - next.slope);
      if (!(wait > 0 && wait < left)) break;
      v += acc * wait;
      left -= wait;
      now += wait;
      waited = true;
      continue;
    }
    const double tau = std::min(left, ramp);
    const double jerk = change > 0 ? rate : -rate;
    v += acc * tau + (std::isinf(rate) ? 0.0 : 0.5 * jerk * tau * tau);
    acc = tau < ramp ? acc + jerk * tau : next.slope;
    left -= tau;
    now += tau;
    if (tau >= ramp) ++run.next;  // on the next line: the corner after it comes next
  }
  v += acc * left;
  if (a.max_speed) v = std::min(v, *a.max_speed);
  run.acceleration = acc;
  state.speed = v;
  if (run.next >= lines.size()) {  // on the last speed, held
    state.speed = lines.back().from;
    run.acceleration = 0;
    return true;
  }
  return false;
}

}  // namespace

bool step_speed_profile(const SpeedProfileAction& a, SpeedProfileRun& run, EntityState& state, double t, double dt) {
  return a.follow ? step_follow(a, run, state, t, dt) : step_position(run, state, t);
}

}  // namespace orch::openscenario

#include "openscenario/synchronize.hpp"

#include <algorithm>
#include <cmath>

namespace orch::openscenario {
namespace {

constexpr double kTiny = 1e-10;

// The speed now on the straight speed line that ends at v1 after time t and distance s.
double speed_on_line(double v1, double t, double s) {
  if (t < 0.001 || s < 0.001) return 0;
  return 2 * s / t - v1;
}

// Two phases of constant acceleration: from v0 to vx in x, then vx to v1 in t - x, covering s.
// Returns the first phase's acceleration and vx (nullopt acceleration 0: no solution in ]0, t[).
struct Apex {
  double acceleration = 0, vx = 0;
};
Apex two_phase_apex(double s, double t, double v0, double v1) {
  if (std::abs(v1 - v0) < kTiny) {  // symmetric: the apex halfway
    const double vx = (s - t / 2 * v0) / (t / 2);
    return {(vx - v0) / (t / 2), vx};
  }
  const double root = std::sqrt(2.0) * std::sqrt(std::max(0.0, 2 * s * s - 2 * (v1 + v0) * t * s + (v1 * v1 + v0 * v0) * t * t));
  for (const double sign : {1.0, -1.0}) {
    const double x = -(sign * root + 2 * s - 2 * v1 * t) / (2 * (v1 - v0));
    const double vx = (2 * s - sign * root) / (2 * t);
    if (x > 0 && x < t) return {(vx - v0) / x, vx};
  }
  return {};
}

}  // namespace

SynchronizeStep synchronize_step(SynchronizeProgress& p, const SynchronizeMeasures& m) {
  bool done = m.distance < m.tolerance + kTiny || m.master_distance < m.tolerance_master + kTiny ||
              m.distance > p.last_distance || m.master_distance > p.last_master_distance;
  p.last_distance = m.distance;
  p.last_master_distance = m.master_distance;
  // Measured to the tolerance circles.
  double s = std::max(m.distance - m.tolerance, kTiny);
  const double master_s = std::max(m.master_distance - m.tolerance_master, kTiny);
  double t = kSynchronizeNever;
  if (m.master_speed > kTiny) {
    t = master_s / m.master_speed;
    if (t < m.dt) done = true;  // the master arrives within this step
  }
  if (done) return {true, m.final_speed.value_or(m.speed)};

  if (!m.final_speed) {  // reach the average speed s / T with one constant acceleration
    const double end_speed = 2 * (s / t) - m.speed;
    return {false, m.speed + (end_speed - m.speed) / t * m.dt};
  }
  const double v1 = *m.final_speed;
  if (m.steady_distance && p.mode != SynchronizeMode::SteadyState) {
    const double steady_time = *m.steady_distance / v1;
    if (s - *m.steady_distance < kTiny || t - steady_time < kTiny) {
      p.mode = SynchronizeMode::SteadyState;
      p.bend = SynchronizeBend::None;
    } else {
      s -= *m.steady_distance;
      t -= steady_time;
    }
  }
  switch (p.mode) {
    case SynchronizeMode::SteadyState:
      return {false, v1};
    case SynchronizeMode::Waiting:
      if (t >= kSynchronizeNever) return {false, m.speed};
      p.mode = SynchronizeMode::Start;
      break;
    case SynchronizeMode::StopNow: {
      const double v = m.speed - kSynchronizeHardBrake * m.dt;
      if (v < 0) {
        p.mode = SynchronizeMode::Waiting;  // until the master moves
        return {false, 0.0};
      }
      return {false, v};
    }
    case SynchronizeMode::Stopped:
      if (t < 2 * s / v1) p.mode = SynchronizeMode::Linear;  // time to go again
      else return {false, 0.0};
      break;
    default:
      break;
  }
  if (p.mode == SynchronizeMode::Linear)
    return {false, t > kSynchronizeNever - 1 ? 0.0 : std::max(0.0, speed_on_line(std::max(0.0, v1), t, s))};
  if (p.mode == SynchronizeMode::NonLinear && t < kSynchronizeNever &&
      std::abs(m.speed - (2 * s / t - v1)) < 0.1) {
    p.mode = SynchronizeMode::Linear;  // on the line: the last phase, keep the speed this step
    return {false, m.speed};
  }
  if (p.mode == SynchronizeMode::Start) {
    p.mode = SynchronizeMode::NonLinear;
    p.bend = (v1 + m.speed) / 2 < s / t ? SynchronizeBend::Convex : SynchronizeBend::Concave;
  }
  const double v0 = m.speed_along;
  Apex apex = two_phase_apex(s, t, v0, v1);
  if ((p.bend == SynchronizeBend::Concave && apex.acceleration > 0) ||
      (p.bend == SynchronizeBend::Convex && apex.acceleration < 0)) {
    p.mode = SynchronizeMode::Linear;  // past the apex: keep the speed this step
    apex.acceleration = 0;
  }
  if (p.mode == SynchronizeMode::NonLinear && apex.vx < 0) {  // brake to a stop, then wait
    const double stop_time = 2 * v0 * s / (v0 * v0 + v1 * v1);
    apex.acceleration = std::abs(stop_time) > kTiny ? -v0 / stop_time : 0.0;
    if (stop_time * v0 / 2 > s / 2) {  // the stop needs more than half the way: brake hard now
      apex.acceleration = -kSynchronizeHardBrake;
      p.mode = SynchronizeMode::StopNow;
    }
    if (v0 + apex.acceleration * m.dt < 0) {
      p.mode = SynchronizeMode::Stopped;
      return {false, 0.0};
    }
  }
  return {false, m.speed + apex.acceleration * m.dt};
}

}  // namespace orch::openscenario

#pragma once
// Kinematics of one body from consecutive samples (docs/evaluation.md "Kinematics"):
//   accel      = (v1 - v0) / dt                      m/s^2, + = speeding up
//   jerk       = (a1 - a0) / dt                      m/s^3 (needs two accelerations)
//   yaw_rate   = wrap(h1 - h0) / dt                  rad/s, + = turning left
//   lat_accel  = v1 * yaw_rate                       m/s^2, + = to the left
//   standstill = time spent with v < kStandstillSpeed without a break, s
#include <optional>

namespace orch::metrics {

inline constexpr double kStandstillSpeed = 0.1;  // m/s

struct KinematicSample {
  double time = 0;
  double speed = 0;    // m/s
  double heading = 0;  // rad, counter-clockwise from +x
};

struct Kinematics {
  std::optional<double> accel;
  std::optional<double> jerk;
  std::optional<double> yaw_rate;
  std::optional<double> lat_accel;
  double standstill = 0;
};

// `before` is the previous sample of the same body (none on its first step), `previous` what
// this function returned for it.
Kinematics kinematics_step(const KinematicSample* before, const Kinematics* previous, const KinematicSample& now);

}  // namespace orch::metrics

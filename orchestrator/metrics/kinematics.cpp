#include "metrics/kinematics.hpp"

#include "core/polyline.hpp"

namespace orch::metrics {

Kinematics kinematics_step(const KinematicSample* before, const Kinematics* previous, const KinematicSample& now) {
  Kinematics k;
  const double dt = before ? now.time - before->time : 0.0;
  if (dt > 0) {
    k.accel = (now.speed - before->speed) / dt;
    k.yaw_rate = wrap_angle(now.heading - before->heading) / dt;
    k.lat_accel = now.speed * *k.yaw_rate;
    if (previous && previous->accel) k.jerk = (*k.accel - *previous->accel) / dt;
  }
  if (now.speed < kStandstillSpeed) k.standstill = (previous ? previous->standstill : 0.0) + (before ? dt : 0.0);
  return k;
}

}  // namespace orch::metrics

#pragma once
// SpeedProfileAction (OpenSCENARIO 1.2+): the entity's speed along the profile's entries.
// followingMode "position" changes the speed linearly from entry to entry, each in its time
// (the standard: the entity follows the profile exactly); "follow" tracks that same profile
// within the DynamicConstraints: acceleration and deceleration, their rates of change (jerk)
// and maxSpeed (the standard: the entity follows the profile as well as its constraints let
// it): corners rounded symmetrically by jerk-limited changes of acceleration, as esmini does.
#include <cstddef>
#include <vector>

#include "openscenario/entity_motion.hpp"
#include "openscenario/model.hpp"

namespace orch::openscenario {

struct SpeedProfileRun {
  std::vector<SpeedProfile> segments;  // linear, one after the other from the action's start
  std::size_t next = 0;     // position mode: the next segment to run; follow: the next line to join
  double acceleration = 0;  // follow mode: the entity's acceleration now
};

// The segments from `t`: from `speed` (the entity's now) to each entry's speed (+ `reference`,
// the referenced entity's speed, when the profile is relative), an entry without a time as
// fast as maxAcceleration / maxDeceleration allow (a step without them).
SpeedProfileRun start_speed_profile(const SpeedProfileAction& a, double t, double speed, double reference);
// The profile's speed at `t` (the last entry's after its end).
double profile_speed(const SpeedProfileRun& run, double t);
// After the entity moved to `t`: sets its speed (and, in position mode, its speed_profile) for
// the next step of `dt`. True when the profile is done: its last entry's time has passed
// (follow mode: when the entity holds the last speed).
bool step_speed_profile(const SpeedProfileAction& a, SpeedProfileRun& run, EntityState& state, double t, double dt);

}  // namespace orch::openscenario

#pragma once
// SynchronizeAction (OpenSCENARIO 1.3, 7.4.3.4): the entity adjusts its speed so that it
// reaches its target position when the master entity reaches the master's target position,
// optionally at a final speed (absolute, or relative to the master's), optionally held for a
// steady-state distance or time before the target. Pure control law over measured distances;
// the storyboard measures them (action_start.cpp).
//
// The law follows the peer player (esmini), the reference of the differential test, since the
// standard gives only the goal: each step, with s the distance left (to the tolerance
// circle), T the master's time left (its distance left / its speed along the road), v0 the
// entity's speed and v1 the final speed:
//  - no final speed: a constant acceleration that ends at the average speed s / T;
//  - a final speed, one phase ("linear"): the speed on the straight line to (T, v1):
//    v = 2 s / T - v1;
//  - two phases ("non-linear"): a constant acceleration (convex: rush, concave: linger) to
//    an apex speed vx at time x, then linear to (T, v1), with s and T split between the
//    phases (the smaller positive root x in ]0, T[ of the two-phase system);
//  - when vx would be negative: brake to a stop, wait, and start again on the line;
//  - steady state: the last `steady distance` (or time x v1) at the final speed.
// The action ends when the entity or the master is within its tolerance of its target,
// when a distance starts growing (target passed), or when the master arrives within a step.
#include <limits>
#include <optional>

#include "opendrive/road_network.hpp"

namespace orch::openscenario {

enum class SynchronizeMode { Start, NonLinear, Linear, Stopped, StopNow, Waiting, SteadyState };
enum class SynchronizeBend { None, Convex, Concave };

struct SynchronizeProgress {
  SynchronizeMode mode = SynchronizeMode::Start;
  SynchronizeBend bend = SynchronizeBend::None;
  double last_distance = std::numeric_limits<double>::infinity();
  double last_master_distance = std::numeric_limits<double>::infinity();
};

struct SynchronizeMeasures {
  double distance = 0;         // entity to its target, along its road or path (m, >= 0)
  double master_distance = 0;  // master to its target
  double master_speed = 0;     // the master's speed along its road (m/s)
  double speed = 0;            // the entity's speed
  double speed_along = 0;      // the entity's speed along its road
  double dt = 0;
  std::optional<double> final_speed;      // m/s, evaluated this step
  std::optional<double> steady_distance;  // m before the target at the final speed
  double tolerance = 0, tolerance_master = 0;
};

struct SynchronizeStep {
  bool done = false;
  double speed = 0;  // the entity's speed from now on
};

// Kept as esmini's constants: a hard stop's deceleration and "no arrival in sight".
inline constexpr double kSynchronizeHardBrake = 8.0;  // m/s^2
inline constexpr double kSynchronizeNever = 1e10;     // s

SynchronizeStep synchronize_step(SynchronizeProgress& progress, const SynchronizeMeasures& m);

}  // namespace orch::openscenario

namespace orch::openscenario {

// A target position as the running action measures towards it: resolved when it starts.
struct SynchronizeTarget {
  opendrive::Pose2 pose;
  std::optional<opendrive::RoadCoordinate> road;  // when it lies on a road
};

struct SynchronizeRun {
  SynchronizeProgress progress;
  SynchronizeTarget master_target, target;
  std::optional<double> steady_distance;  // the steady state as a distance (time x final speed at the start)
};

// The tolerance of a target whose action gives none: 0 (the standard gives no default; esmini
// 3.6 uses 0, its log says "dist (0.00) < tolerance (0.00)").
inline constexpr double kSynchronizeTolerance = 0.0;  // m

}  // namespace orch::openscenario

#pragma once
// FollowTrajectoryAction with followingMode "follow": the entity's controller tracks the
// trajectory as a target path under the entity's own dynamics, instead of being put on it
// ("position"). A pure-pursuit controller on a kinematic bicycle at the reference point
// (the rear axle centre of a vehicle), one step of dt:
//   lookahead   L_d = max(kFollowMinLookahead, kFollowLookaheadTime * v, 1 / k_max)
//               (never inside the tightest turning circle)
//   goal        the path point L_d beyond the entity's nearest point (past the end: on the
//               last segment's extension)
//   curvature   k = 2 sin(alpha) / |goal - p|   (alpha: the goal's bearing from the heading,
//               at most +-pi/2: a goal behind turns the entity round, a U-turn on a circle
//               of diameter |goal - p|; with no steering limit, no axles, on the spot),
//               |k| <= k_max = tan(maxSteering) / wheelbase and <= kFollowMaxLateralAcceleration / v^2
//   speed       timed: v* = v_due + e / kFollowSpeedTau, e = due distance - nearest point's
//               distance; untimed: the speed the storyboard sets; v* within [0, maxSpeed]
//               and slow enough for the corners ahead: a corner at x metres whose heading
//               changes by dh over kFollowMinLookahead allows v_c = sqrt(a_lat L_min / dh)
//               there, so sqrt(v_c^2 + 2 maxDeceleration x) now; and v* <= sqrt(a_lat / |k|)
//               for the turn it is making; v changes by at most maxAcceleration dt /
//               maxDeceleration dt (k and L_d from the speed before the step)
//   motion      heading += v k dt, position += v dt along the mean heading of the step.
// So a sharp corner is rounded and a schedule the entity cannot keep is kept late.
// An entity given no steering limit (no axles: a pedestrian, an object; then no lateral
// acceleration limit is assumed either) that is on its path keeps to it exactly: v dt along
// it, the speed as above. The standard (1.3, FollowingMode follow: "as good as possible by
// observing the dynamic constraints of the entity") gives it none to observe; esmini moves
// every follow-mode entity so (pedestrian.xosc).
// Where a timed Polyline is due between its vertices the standard does not say; esmini's law
// (vertex_schedule): from the entity's speed at the start, one constant acceleration per
// segment that reaches the next vertex at its time (speed continuous at the vertices); one
// that would have to reverse stops on the vertex early instead and waits there; a repeated
// vertex is a stop. The follower tracks that as its due distance (other shapes: linear in
// time between their points, as esmini).
#include <optional>
#include <utility>
#include <vector>

#include "opendrive/plan_view.hpp"
#include "openscenario/model.hpp"
#include "openscenario/trajectory_motion.hpp"

namespace orch::openscenario {

inline constexpr double kFollowMinLookahead = 3.0;             // m
inline constexpr double kFollowLookaheadTime = 0.8;            // s
inline constexpr double kFollowMaxLateralAcceleration = 4.0;   // m/s^2, also without axles
inline constexpr double kFollowSpeedTau = 1.0;                 // s to close a schedule error
inline constexpr double kFollowMaxPreview = 200.0;             // m looked ahead for corners
inline constexpr double kFollowPreviewStep = 0.5;              // m
inline constexpr double kFollowOnPath = 0.01;                  // m: "on its path"

// The entity's limits: Performance (absent: none), the front axle's maxSteering over the
// wheelbase (front minus rear positionX; absent axles: no steering limit) and the lateral
// acceleration limit.
FollowLimits follow_limits(const Entity& entity);

// Distance along the path of its point nearest (x, y), searched in [from, to].
double nearest_distance(const PathMotion& path, double x, double y, double from, double to);

// Makes `path` a followed one for an entity at `pose` moving at `speed`: it starts from its
// nearest point at or beyond the path's initial distance. `vertices_timed`: the path is a
// timed Polyline's (its timetable the vertices): due by vertex_schedule.
void start_following(PathMotion& path, const opendrive::Pose2& pose, double speed, const FollowLimits& limits,
                     bool vertices_timed = false);

// esmini's schedule through the timetable's (due, distance) vertices from `speed` (above).
std::vector<SchedulePiece> vertex_schedule(const std::vector<std::pair<double, double>>& timetable, double speed);
// The distance due at simulation time `t` (before the first vertex: its distance).
double scheduled_distance(const std::vector<SchedulePiece>& schedule, double t);

// Moves the entity from t - dt to t along the followed path (see above); `profile_speed` is
// its speed profile's value when one runs. Updates pose, speed and path.distance; returns
// the distance driven.
double follow_step(PathMotion& path, opendrive::Pose2& pose, double& speed, std::optional<double> profile_speed,
                   double t, double dt);

}  // namespace orch::openscenario

#pragma once
// A FollowTrajectoryAction's path as the storyboard moves an entity along it: the trajectory
// (Polyline vertices, or a Clothoid sampled every kClothoidStep metres) as inertial points
// with their distance along the path and, when timed, the simulation time each is due.
// Pure geometry; positions are resolved by the caller when the action starts.
#include <limits>
#include <optional>
#include <utility>
#include <vector>

#include "opendrive/plan_view.hpp"
#include "openscenario/model.hpp"

namespace orch::openscenario {

struct PathPoint {
  double x = 0, y = 0;
  double distance = 0;          // along the path from its first point
  std::optional<double> due;    // simulation time (s) the entity is here (timed paths)
  // The curve's own heading here (a clothoid's tangent), when the points sample a curve: the
  // entity's heading between two such points goes from one to the other, not along the
  // chord (a chord's heading is half a piece's turn off at the path's end, 0.01 rad on
  // trailer_connect.xosc's reversing quarter circle, and a trajectory relative to the
  // entity's pose after it inherits that).
  std::optional<double> heading;
  // The point's height in the world frame, when every position of the shape gives one (a
  // WorldPosition's z: esmini's parking_demo.xosc flies a camera 10-15 m up); else on the road.
  std::optional<double> z = std::nullopt;
};

// followingMode "follow": the entity's own limits and the tracking state (trajectory_follow.hpp).
struct FollowLimits {
  static constexpr double kNone = std::numeric_limits<double>::infinity();
  double max_speed = kNone, max_acceleration = kNone, max_deceleration = kNone;
  double max_curvature = kNone;  // tan(maxSteering) / wheelbase, for vehicles with axles
  double max_lateral_acceleration = kNone;
};
// A timed Polyline followed: where the entity is due, one constant acceleration per segment
// between vertices (esmini's law, trajectory_follow.hpp), as pieces from `start` (simulation
// time) on: distance `from` + speed * tau + acceleration * tau^2 / 2, tau up to `stop`
// (the piece's standstill, when it arrives early) and the next piece's start.
struct SchedulePiece {
  double start = 0, from = 0, speed = 0, acceleration = 0;
  double stop = std::numeric_limits<double>::infinity();  // tau at which it stands
};
struct PathFollower {
  FollowLimits limits;
  double speed = 0;           // the entity's actual speed
  double wanted_speed = 0;    // untimed paths: the speed the storyboard last set
  std::vector<SchedulePiece> schedule;  // timed Polylines: where it is due (else the points' dues)
};

struct PathMotion {
  std::vector<PathPoint> points;  // at least two, distances increasing
  bool timed = false;
  // Timed paths: (due, distance) of every point given, also of those dropped as repeats (a
  // vertex repeated with a later time is a stop there; the last time ends the path).
  std::vector<std::pair<double, double>> timetable;
  double distance = 0;  // where the entity is now (follow: its nearest point on the path)
  std::optional<PathFollower> follower;  // followingMode "follow" (else "position": put on the path)

  [[nodiscard]] double length() const { return points.back().distance; }
  // Reference point and heading (of the segment) at `d` along the path, clamped to it.
  [[nodiscard]] opendrive::Pose2 pose_at(double d) const;
  // Height in the world frame at `d` (linear between points), when the points have one.
  [[nodiscard]] std::optional<double> z_at(double d) const;
  // Timed paths: the distance due at simulation time `t` (linear between points; the first
  // point before its time, the last after it).
  [[nodiscard]] double distance_at(double t) const;
  [[nodiscard]] bool done(double t) const;
};

inline constexpr double kClothoidStep = 0.25;  // m
inline constexpr double kFollowEnd = 0.1;       // m: a followed path is done this close to its end

// Points of a clothoid from `start`: curvature k0 + k' s for s in [0, length].
std::vector<PathPoint> clothoid_points(const opendrive::Pose2& start, double k0, double k_prime, double length);
// Points of a ClothoidSpline: each segment from its resolved PositionStart (`starts[i]`) or
// where the one before ends (the first: `entity`, the entity's pose when the action starts),
// its heading turned by hOffset. Timed splines: `due` is the spline's own time, constant
// speed within a segment from its timeStart to the next one's (the last: timeEnd).
std::vector<PathPoint> clothoid_spline_points(const ClothoidSplineShape& spline,
                                              const std::vector<std::optional<opendrive::Pose2>>& starts,
                                              const opendrive::Pose2& entity);
// The positions a trajectory's shape names, in the order shape_points takes them resolved:
// Polyline vertices, Nurbs control points, the ClothoidSpline segments' PositionStarts (those
// given), a Clothoid's start.
std::vector<Position> shape_positions(const Trajectory& trajectory);
// The path of a trajectory (closed ones back to their start) from its shape_positions
// resolved (`resolved`, same order); `entity` starts a ClothoidSpline whose first segment has
// no PositionStart. `due` is the shape's own time (vertex, control point or spline time; a
// Clothoid's startTime to stopTime at constant speed), to be mapped to simulation time by the
// caller. Throws MapError for a Nurbs the formula cannot take.
std::vector<PathPoint> shape_points(const Trajectory& trajectory, const std::vector<opendrive::Pose2>& resolved,
                                    const opendrive::Pose2& entity);
// A closed trajectory (Trajectory `closed`, "True if trajectory is closed": the standard says
// no more) returns to where it began: a straight segment from its last point to its first is
// added (none when they meet already). Timed: that segment is due at the speed of the path's
// last timed piece (a piece with length and duration; none: the path's mean speed).
void close_path(std::vector<PathPoint>& points);
// Fills in distances; points closer than 1 mm to the one before are dropped.
PathMotion make_path(std::vector<PathPoint> points, bool timed);

}  // namespace orch::openscenario

#include "openscenario/trajectory_follow.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace orch::openscenario {
namespace {

// The path point `d` along it; beyond its end, on the last segment's extension (a goal
// that keeps the heading steady while the entity reaches the end).
opendrive::Pose2 extended_pose(const PathMotion& path, double d) {
  const opendrive::Pose2 end = path.pose_at(path.length());
  if (d <= path.length()) return path.pose_at(d);
  const double beyond = d - path.length();
  return {end.x + beyond * std::cos(end.heading), end.y + beyond * std::sin(end.heading), end.heading};
}

double wrapped(double angle) {  // to (-pi, pi]
  angle = std::fmod(angle + M_PI, 2 * M_PI);
  if (angle < 0) angle += 2 * M_PI;
  return angle - M_PI;
}

// Path heading at `d` (of the segment there; extended past the end).
double heading_at(const PathMotion& path, double d) { return extended_pose(path, d).heading; }

// The highest speed now from which the entity can slow to every corner's speed ahead in
// time: the path's curvature at x is taken over kFollowMinLookahead (so a polyline vertex
// counts as a turn over that length), a corner's speed is sqrt(a_lat / k), and one x metres
// ahead allows sqrt(v_corner^2 + 2 maxDeceleration x) now.
double corner_speed(const PathMotion& path, const FollowLimits& limits, double speed) {
  const double braking = std::isinf(limits.max_deceleration) ? 0.0 : speed * speed / (2 * limits.max_deceleration);
  const double preview = std::min(kFollowMaxPreview, braking + kFollowMinLookahead);
  double allowed = std::numeric_limits<double>::infinity();
  for (double x = 0; x <= preview && path.distance + x < path.length(); x += kFollowPreviewStep) {
    const double d = path.distance + x;
    const double turn = std::abs(wrapped(heading_at(path, d + kFollowMinLookahead / 2) -
                                         heading_at(path, std::max(0.0, d - kFollowMinLookahead / 2))));
    if (turn < 1e-9) continue;
    const double corner = limits.max_lateral_acceleration * kFollowMinLookahead / turn;  // v^2
    const double slowing = std::isinf(limits.max_deceleration) ? 0.0 : 2 * limits.max_deceleration * x;
    allowed = std::min(allowed, std::sqrt(corner + slowing));
  }
  return allowed;
}

// Never shorter than the tightest turning radius: a goal inside the circle the entity
// cannot turn on makes it circle round the goal instead of reaching the path.
double lookahead(const FollowLimits& limits, double speed) {
  const double radius = std::isinf(limits.max_curvature) ? 0.0 : 1.0 / limits.max_curvature;
  return std::max({kFollowMinLookahead, kFollowLookaheadTime * speed, radius});
}

// The goal L_d beyond the entity's nearest point on the path: its distance and its bearing
// from the entity's heading.
std::pair<double, double> goal_from(const PathMotion& path, const FollowLimits& limits, const opendrive::Pose2& pose,
                                    double speed) {
  const opendrive::Pose2 goal = extended_pose(path, path.distance + lookahead(limits, speed));
  return {std::hypot(goal.x - pose.x, goal.y - pose.y), wrapped(std::atan2(goal.y - pose.y, goal.x - pose.x) - pose.heading)};
}

// Pure pursuit: the curvature of the circle through the entity's reference point, tangent to
// its heading, that reaches the goal.
double pursuit_curvature(const PathMotion& path, const FollowLimits& limits, const opendrive::Pose2& pose,
                         double speed) {
  auto [to_goal, alpha] = goal_from(path, limits, pose, speed);
  // A goal behind the entity (it faces away from the path: placed facing the other way):
  // 2 sin(alpha) / L falls to 0 as the goal comes straight behind, and the entity would drive
  // away from the path for ever (esmini's pedestrian.xosc did, for 3,600 s). Turn towards the
  // goal's side as for a goal abeam instead: a U-turn on a circle of diameter L.
  if (std::abs(alpha) > M_PI / 2) alpha = alpha < 0 ? -M_PI / 2 : M_PI / 2;
  return to_goal > 1e-9 ? 2 * std::sin(alpha) / to_goal : 0.0;
}

// On its path: within 1 cm of its nearest point (an entity placed beside it steers onto it).
bool on_path(const PathMotion& path, const opendrive::Pose2& pose) {
  const opendrive::Pose2 nearest = path.pose_at(path.distance);
  return std::hypot(nearest.x - pose.x, nearest.y - pose.y) < kFollowOnPath;
}

}  // namespace

FollowLimits follow_limits(const Entity& entity) {
  FollowLimits limits;
  if (entity.performance) {
    limits.max_speed = entity.performance->max_speed;
    limits.max_acceleration = entity.performance->max_acceleration;
    limits.max_deceleration = entity.performance->max_deceleration;
  }
  if (entity.front_axle && entity.rear_axle) {
    const double wheelbase = entity.front_axle->position_x - entity.rear_axle->position_x;
    if (wheelbase > 0 && entity.front_axle->max_steering > 0)
      limits.max_curvature = std::tan(std::min(entity.front_axle->max_steering, 1.5)) / wheelbase;
  }
  // No steering limit given (no axles: a pedestrian, an object): none assumed for the
  // lateral acceleration either, so it follows the path's geometry exactly (follow_step).
  if (!std::isinf(limits.max_curvature)) limits.max_lateral_acceleration = kFollowMaxLateralAcceleration;
  return limits;
}

std::vector<SchedulePiece> vertex_schedule(const std::vector<std::pair<double, double>>& timetable, double speed) {
  std::vector<SchedulePiece> pieces;
  double v = std::max(0.0, speed);
  for (std::size_t i = 1; i < timetable.size(); ++i) {
    const auto [t0, s0] = timetable[i - 1];
    const double span = timetable[i].first - t0;
    const double ds = timetable[i].second - s0;
    SchedulePiece piece{t0, s0, v, 0.0};
    if (ds < 1e-9 || span <= 0) {  // a stop at a repeated vertex (or no time to get there)
      piece.speed = 0;
      v = 0;
    } else {
      piece.acceleration = 2 * (ds - v * span) / (span * span);
      if (v + piece.acceleration * span < 0) {  // slowing to the vertex's time would reverse:
        piece.acceleration = -v * v / (2 * ds);  // stop on the vertex early and wait there
        piece.stop = v / -piece.acceleration;
        v = 0;
      } else {
        v += piece.acceleration * span;
      }
    }
    pieces.push_back(piece);
  }
  return pieces;
}

double scheduled_distance(const std::vector<SchedulePiece>& schedule, double t) {
  if (schedule.empty() || t <= schedule.front().start) return schedule.empty() ? 0.0 : schedule.front().from;
  auto piece = std::upper_bound(schedule.begin(), schedule.end(), t,
                                [](double time, const SchedulePiece& p) { return time < p.start; });
  const SchedulePiece& p = *(piece - 1);
  const double tau = std::min(t - p.start, p.stop);
  return p.from + p.speed * tau + p.acceleration * tau * tau / 2;
}

double nearest_distance(const PathMotion& path, double x, double y, double from, double to) {
  from = std::clamp(from, 0.0, path.length());
  to = std::clamp(to, from, path.length());
  double best = from;
  double best_squared = std::numeric_limits<double>::infinity();
  for (std::size_t i = 1; i < path.points.size(); ++i) {
    const PathPoint& a = path.points[i - 1];
    const PathPoint& b = path.points[i];
    if (b.distance < from || a.distance > to) continue;
    const double span = b.distance - a.distance;
    const double along = ((x - a.x) * (b.x - a.x) + (y - a.y) * (b.y - a.y)) / span;
    const double d = std::clamp(a.distance + along, std::max(a.distance, from), std::min(b.distance, to));
    const double f = (d - a.distance) / span;
    const double dx = a.x + f * (b.x - a.x) - x;
    const double dy = a.y + f * (b.y - a.y) - y;
    if (dx * dx + dy * dy < best_squared - 1e-12) {
      best_squared = dx * dx + dy * dy;
      best = d;
    }
  }
  return best;
}

void start_following(PathMotion& path, const opendrive::Pose2& pose, double speed, const FollowLimits& limits,
                     bool vertices_timed) {
  path.distance = nearest_distance(path, pose.x, pose.y, path.distance, path.length());
  path.follower = PathFollower{limits, speed, speed, {}};
  if (path.timed && vertices_timed) path.follower->schedule = vertex_schedule(path.timetable, speed);
}

double follow_step(PathMotion& path, opendrive::Pose2& pose, double& speed, std::optional<double> profile_speed,
                   double t, double dt) {
  PathFollower& f = *path.follower;
  const FollowLimits& limits = f.limits;
  // The speed the storyboard asks for: a running profile's, or a speed it set since the last
  // step (a step SpeedAction writes the entity's speed directly).
  if (profile_speed) f.wanted_speed = *profile_speed;
  else if (speed != f.speed) f.wanted_speed = speed;
  double wanted = f.wanted_speed;
  if (path.timed && dt > 0) {
    const auto due = [&](double time) {
      return f.schedule.empty() ? path.distance_at(time) : std::min(path.length(), scheduled_distance(f.schedule, time));
    };
    wanted = (due(t) - due(t - dt)) / dt + (due(t - dt) - path.distance) / kFollowSpeedTau;
  }
  // No steering limit (see follow_limits) and on the path: it keeps to the path exactly.
  if (std::isinf(limits.max_curvature) && on_path(path, pose)) {
    const double v = f.speed + std::clamp(std::clamp(wanted, 0.0, limits.max_speed) - f.speed,
                                          -limits.max_deceleration * dt, limits.max_acceleration * dt);
    const double beyond = std::max(0.0, path.distance + v * dt - path.length());  // on past the end, as "position"
    path.distance = std::min(path.length(), path.distance + v * dt);
    const double heading = pose.heading;
    pose = path.pose_at(path.distance);
    pose.x += beyond * std::cos(pose.heading);
    pose.y += beyond * std::sin(pose.heading);
    pose.heading = v * dt < 1e-9 ? heading : std::fmod(pose.heading + 2 * M_PI, 2 * M_PI);  // standing: as it stood
    f.speed = v;
    speed = v;
    return v * dt;
  }
  // An entity with no steering limit (no axles: a pedestrian, an object) facing away from
  // its goal turns round on the spot, as a person does, instead of walking a U-turn.
  if (std::isinf(limits.max_curvature)) {
    const double alpha = goal_from(path, limits, pose, f.speed).second;
    if (std::abs(alpha) > M_PI / 2) pose.heading = std::fmod(pose.heading + alpha + 2 * M_PI, 2 * M_PI);
  }
  // Steering: towards the goal L_d beyond the nearest point (L_d from the speed so far).
  const double pursuit = pursuit_curvature(path, limits, pose, f.speed);
  // Slow enough for the corners ahead and for the turn the entity is making.
  double ceiling = std::min(limits.max_speed, corner_speed(path, limits, f.speed));
  if (std::abs(pursuit) > 1e-9) ceiling = std::min(ceiling, std::sqrt(limits.max_lateral_acceleration / std::abs(pursuit)));
  wanted = std::clamp(wanted, 0.0, ceiling);
  const double v = f.speed + std::clamp(wanted - f.speed, -limits.max_deceleration * dt, limits.max_acceleration * dt);
  double bound = limits.max_curvature;
  if (v > 1e-9) bound = std::min(bound, limits.max_lateral_acceleration / (v * v));
  const double curvature = std::clamp(pursuit, -bound, bound);

  const double turn = v * curvature * dt;
  const double mean_heading = pose.heading + turn / 2;
  pose.x += v * dt * std::cos(mean_heading);
  pose.y += v * dt * std::sin(mean_heading);
  pose.heading = std::fmod(pose.heading + turn, 2 * M_PI);
  if (pose.heading < 0) pose.heading += 2 * M_PI;

  path.distance = nearest_distance(path, pose.x, pose.y, path.distance - 1.0,
                                   path.distance + v * dt + lookahead(limits, v));
  f.speed = v;
  speed = v;
  return v * dt;
}

}  // namespace orch::openscenario

#include "openscenario/trajectory_motion.hpp"

#include <algorithm>
#include <cmath>

#include "core/checked_numeric.hpp"
#include "core/errors.hpp"
#include "openscenario/nurbs.hpp"

namespace orch::openscenario {

std::vector<PathPoint> clothoid_points(const opendrive::Pose2& start, double k0, double k_prime, double length) {
  const opendrive::Geometry geometry{0.0, start, length, opendrive::Spiral{k0, k0 + k_prime * length}};
  const int pieces = pieces_covering(length, kClothoidStep, 2, 1 << 30);
  std::vector<PathPoint> points;
  for (int i = 0; i <= pieces; ++i) {
    const opendrive::Pose2 p = opendrive::evaluate(geometry, length * i / pieces);
    points.push_back({p.x, p.y, 0.0, std::nullopt, p.heading});
  }
  return points;
}

std::vector<PathPoint> clothoid_spline_points(const ClothoidSplineShape& spline,
                                              const std::vector<std::optional<opendrive::Pose2>>& starts,
                                              const opendrive::Pose2& entity) {
  std::vector<PathPoint> points;
  opendrive::Pose2 end = entity;
  for (std::size_t i = 0; i < spline.segments.size(); ++i) {
    const ClothoidSplineSegment& segment = spline.segments[i];
    opendrive::Pose2 start = i < starts.size() && starts[i] ? *starts[i] : end;
    start.heading += segment.heading_offset;
    std::vector<PathPoint> piece =
        clothoid_points(start, segment.curvature_start,
                        (segment.curvature_end - segment.curvature_start) / segment.length, segment.length);
    if (segment.time_start) {
      const double to = i + 1 < spline.segments.size() ? spline.segments[i + 1].time_start.value_or(0.0)
                                                       : spline.time_end.value_or(0.0);
      for (std::size_t j = 0; j < piece.size(); ++j)
        piece[j].due = *segment.time_start + (to - *segment.time_start) * static_cast<double>(j) /
                                                 static_cast<double>(piece.size() - 1);
    }
    end = opendrive::evaluate(opendrive::Geometry{0.0, start, segment.length,
                                                  opendrive::Spiral{segment.curvature_start, segment.curvature_end}},
                              segment.length);
    // A segment that starts where the one before ends repeats that point: keep one.
    if (!points.empty() && std::hypot(piece.front().x - points.back().x, piece.front().y - points.back().y) < 1e-3)
      piece.erase(piece.begin());
    points.insert(points.end(), piece.begin(), piece.end());
  }
  return points;
}

void close_path(std::vector<PathPoint>& points) {
  if (points.size() < 2) return;
  const PathPoint first = points.front(), last = points.back();
  const double gap = std::hypot(first.x - last.x, first.y - last.y);
  if (gap < 1e-3) return;
  PathPoint closing{first.x, first.y, 0.0, std::nullopt, std::nullopt, first.z};
  if (last.due) {
    double speed = 0;
    for (std::size_t i = points.size() - 1; i > 0 && speed <= 0; --i) {
      const PathPoint &a = points[i - 1], &b = points[i];
      const double length = std::hypot(b.x - a.x, b.y - a.y);
      if (a.due && b.due && *b.due > *a.due && length > 1e-3) speed = length / (*b.due - *a.due);
    }
    if (speed <= 0 && first.due && *last.due > *first.due) {  // the mean speed
      double length = 0;
      for (std::size_t i = 1; i < points.size(); ++i)
        length += std::hypot(points[i].x - points[i - 1].x, points[i].y - points[i - 1].y);
      speed = length / (*last.due - *first.due);
    }
    closing.due = speed > 0 ? *last.due + gap / speed : *last.due;
  }
  points.push_back(closing);
}

PathMotion make_path(std::vector<PathPoint> points, bool timed) {
  PathMotion path;
  path.timed = timed;
  for (PathPoint& p : points) {
    if (!path.points.empty()) {
      const PathPoint& last = path.points.back();
      const double step = std::hypot(p.x - last.x, p.y - last.y);
      if (step < 1e-3) {
        if (timed && p.due) path.timetable.emplace_back(*p.due, last.distance);
        continue;
      }
      p.distance = last.distance + step;
    } else {
      p.distance = 0;
    }
    if (timed && p.due) path.timetable.emplace_back(*p.due, p.distance);
    path.points.push_back(p);
  }
  if (path.points.size() < 2) throw MapError("a trajectory whose points all lie within 1 mm of each other");
  return path;
}

namespace {

// The points a distance d along the path lies between, and the fraction of the way from a to b.
struct PathSegmentAt {
  const PathPoint& a;
  const PathPoint& b;
  double f;
};
PathSegmentAt path_segment_at(const std::vector<PathPoint>& points, double d) {
  const auto next = std::upper_bound(points.begin() + 1, points.end() - 1, d,
                                     [](double value, const PathPoint& p) { return value < p.distance; });
  const PathPoint& b = *next;
  const PathPoint& a = *(next - 1);
  return {a, b, (d - a.distance) / (b.distance - a.distance)};
}

}  // namespace

opendrive::Pose2 PathMotion::pose_at(double d) const {
  const auto [a, b, f] = path_segment_at(points, std::clamp(d, 0.0, length()));
  double heading = std::atan2(b.y - a.y, b.x - a.x);
  if (a.heading && b.heading)  // along the curve's tangent, the short way round
    heading = *a.heading + f * std::remainder(*b.heading - *a.heading, 2 * M_PI);
  return {a.x + f * (b.x - a.x), a.y + f * (b.y - a.y), heading};
}

std::optional<double> PathMotion::z_at(double d) const {
  if (!points.front().z) return std::nullopt;
  const auto [a, b, f] = path_segment_at(points, std::clamp(d, 0.0, length()));
  return *a.z + f * (*b.z - *a.z);
}

double PathMotion::distance_at(double t) const {
  if (t <= *points.front().due) return 0.0;
  for (std::size_t i = 1; i < points.size(); ++i) {
    const PathPoint& a = points[i - 1];
    const PathPoint& b = points[i];
    if (t <= *b.due) {
      const double span = *b.due - *a.due;
      return span <= 0 ? b.distance : a.distance + (b.distance - a.distance) * (t - *a.due) / span;
    }
  }
  return length();
}

bool PathMotion::done(double t) const {
  // The last time given ends a timed path (a vertex repeated at the end is a stop until then).
  const double end_due = !timed ? 0.0 : timetable.empty() ? points.back().due.value_or(0.0) : timetable.back().first;
  // Followed: when the entity gets there, late or not, and not before the end's time.
  if (follower) return distance >= length() - kFollowEnd && (!timed || t >= end_due - 1e-9);
  if (timed) return t >= end_due - 1e-9;
  return distance >= length() - 1e-9;
}

std::vector<Position> shape_positions(const Trajectory& trajectory) {
  std::vector<Position> out;
  if (const auto* polyline = std::get_if<PolylineShape>(&trajectory.shape)) {
    for (const TrajectoryVertex& v : polyline->vertices) out.push_back(v.position);
  } else if (const auto* nurbs = std::get_if<NurbsShape>(&trajectory.shape)) {
    for (const NurbsControlPoint& c : nurbs->points) out.push_back(c.position);
  } else if (const auto* spline = std::get_if<ClothoidSplineShape>(&trajectory.shape)) {
    for (const ClothoidSplineSegment& segment : spline->segments)
      if (segment.start) out.push_back(*segment.start);
  } else {
    out.push_back(std::get<ClothoidShape>(trajectory.shape).start);
  }
  return out;
}

namespace {

// The heights in the world frame the positions give (a WorldPosition's z), all or none: a
// shape with a point on the road and one in the air has no height the standard defines
// between them, so it stays on the road.
std::vector<std::optional<double>> world_heights(const std::vector<Position>& positions) {
  std::vector<std::optional<double>> out;
  for (const Position& p : positions) {
    const auto* world = std::get_if<position::WorldPosition>(&p);
    if (world == nullptr || !world->z) return std::vector<std::optional<double>>(positions.size());
    out.push_back(world->z);
  }
  return out;
}

}  // namespace

std::vector<PathPoint> shape_points(const Trajectory& trajectory, const std::vector<opendrive::Pose2>& resolved,
                                    const opendrive::Pose2& entity) {
  std::vector<PathPoint> points;
  if (const auto* polyline = std::get_if<PolylineShape>(&trajectory.shape)) {
    const std::vector<std::optional<double>> z = world_heights(shape_positions(trajectory));
    for (std::size_t i = 0; i < resolved.size(); ++i)
      points.push_back({resolved[i].x, resolved[i].y, 0.0, polyline->vertices[i].time, std::nullopt, z[i]});
  } else if (const auto* nurbs = std::get_if<NurbsShape>(&trajectory.shape)) {
    const std::vector<std::optional<double>> z = world_heights(shape_positions(trajectory));
    std::vector<NurbsControl> controls;
    for (std::size_t i = 0; i < resolved.size(); ++i)
      controls.push_back({resolved[i].x, resolved[i].y, nurbs->points[i].weight, nurbs->points[i].time, z[i]});
    points = nurbs_points(controls, nurbs->knots, nurbs->order);
  } else if (const auto* spline = std::get_if<ClothoidSplineShape>(&trajectory.shape)) {
    std::vector<std::optional<opendrive::Pose2>> starts;
    std::size_t next = 0;
    for (const ClothoidSplineSegment& segment : spline->segments)
      starts.push_back(segment.start ? std::optional(resolved[next++]) : std::nullopt);
    points = clothoid_spline_points(*spline, starts, entity);
  } else {
    const auto& c = std::get<ClothoidShape>(trajectory.shape);
    points = clothoid_points(resolved.front(), c.curvature, c.curvature_dot, c.length);
    if (c.start_time && c.stop_time) {  // constant speed from startTime to stopTime
      for (std::size_t i = 0; i < points.size(); ++i) {
        const double f = static_cast<double>(i) / static_cast<double>(points.size() - 1);
        points[i].due = *c.start_time + f * (*c.stop_time - *c.start_time);
      }
    }
  }
  if (trajectory.closed) close_path(points);
  return points;
}

}  // namespace orch::openscenario

#pragma once
// A 2-D polyline with arc length, the shape every route and lane is made of. Projection
// uses a uniform grid over the segments so that finding the nearest point on a 10 km,
// 10,000-point route costs a handful of segment tests, not a full scan.
#include <Eigen/Core>
#include <cstddef>
#include <optional>
#include <unordered_map>
#include <vector>

namespace orch {

using Vec2 = Eigen::Vector2d;

// Radians counter-clockwise from +x, wrapped to (-pi, pi].
double wrap_angle(double radians);
inline Vec2 left_normal(const Vec2& unit_tangent) { return {-unit_tangent.y(), unit_tangent.x()}; }
// Whether p lies inside the closed polygon (even-odd rule; fewer than 3 corners: no inside).
bool inside_polygon(const Vec2& p, const std::vector<Vec2>& polygon);

class Polyline {
 public:
  struct Projection {
    double s = 0;         // arc length of the nearest point
    double lateral = 0;   // signed distance, + = left of the direction of travel
    double distance = 0;  // unsigned distance to the nearest point
    std::size_t segment = 0;
    bool before_start = false;  // the point lies behind the first point (s clamped to 0)
    bool after_end = false;     // the point lies beyond the last point (s clamped to length)
  };

  Polyline() = default;
  // Points are kept as given (indices matter to callers); zero-length segments are allowed.
  explicit Polyline(std::vector<Vec2> points);

  [[nodiscard]] std::size_t size() const { return points_.size(); }
  [[nodiscard]] bool empty() const { return points_.size() < 2; }
  [[nodiscard]] double length() const { return cumulative_.empty() ? 0.0 : cumulative_.back(); }
  [[nodiscard]] const std::vector<Vec2>& points() const { return points_; }
  [[nodiscard]] const Vec2& point(std::size_t i) const { return points_[i]; }
  [[nodiscard]] double s_at_index(std::size_t i) const { return cumulative_[i]; }
  // Arc length of a fractional index (33.3 = a third of the way from point 33 to 34).
  [[nodiscard]] double s_at_fractional_index(double index) const;

  // Position at arc length s; beyond the ends the first/last segment is extended straight.
  [[nodiscard]] Vec2 point_at(double s) const;
  // Unit direction of travel at s (of the segment containing s).
  [[nodiscard]] Vec2 tangent_at(double s) const;
  [[nodiscard]] double heading_at(double s) const;
  // point_at(s) moved `lateral` metres to the left (+) or right (-).
  [[nodiscard]] Vec2 offset_point(double s, double lateral) const;

  [[nodiscard]] Projection project(const Vec2& p) const;
  // The nearest point if it lies within `radius` m, else nullopt: never scans the whole line.
  [[nodiscard]] std::optional<Projection> project_within(const Vec2& p, double radius) const;
  // Nearest point searched only within [s_hint - window, s_hint + window]; for tracking a
  // moving actor from step to step.
  [[nodiscard]] Projection project_near(const Vec2& p, double s_hint, double window) const;

  // A sub-polyline between arc lengths [s0, s1] (s0 < s1), cut exactly at both ends.
  [[nodiscard]] Polyline slice(double s0, double s1) const;
  // Douglas-Peucker simplification keeping every point within `tolerance` of the result.
  [[nodiscard]] Polyline simplified(double tolerance) const;

 private:
  [[nodiscard]] std::size_t segment_at(double s) const;
  [[nodiscard]] Projection project_on_segment(const Vec2& p, std::size_t seg) const;
  [[nodiscard]] Projection finish(Projection best, const Vec2& p) const;
  void build_grid();
  // The grid cell of a coordinate, or nullopt beyond the grid's reach (or NaN / infinite).
  [[nodiscard]] std::optional<long long> cell_of(double v) const;
  [[nodiscard]] static long long cell_key(long long cx, long long cy) { return cx * 1000003LL + cy; }
  void nearest_in(const std::vector<std::size_t>& segments, const Vec2& p, Projection& best) const;
  void nearest_of_all(const Vec2& p, Projection& best) const;

  std::vector<Vec2> points_;
  std::vector<double> cumulative_;
  double cell_ = 16.0;
  std::unordered_map<long long, std::vector<std::size_t>> grid_;
  // Segments the grid does not index (a coordinate beyond its reach, or a bounding box of
  // too many cells): few in any real shape, and checked by every projection.
  std::vector<std::size_t> unindexed_;
};

}  // namespace orch

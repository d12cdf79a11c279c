#include "openscenario/trajectory_position.hpp"

#include <fmt/format.h>

#include "core/errors.hpp"
#include "openscenario/nurbs.hpp"
#include "openscenario/trajectory_motion.hpp"

namespace orch::openscenario {
namespace {

class ShapePath final : public position::TrajectoryPath {
 public:
  explicit ShapePath(Trajectory trajectory) : trajectory_(std::move(trajectory)) {}
  [[nodiscard]] std::string name() const override { return trajectory_.name; }

  [[nodiscard]] std::vector<Position> positions() const override {
    std::vector<Position> out;
    if (const auto* polyline = std::get_if<PolylineShape>(&trajectory_.shape)) {
      for (const TrajectoryVertex& v : polyline->vertices) out.push_back(v.position);
    } else if (const auto* nurbs = std::get_if<NurbsShape>(&trajectory_.shape)) {
      for (const NurbsControlPoint& c : nurbs->points) out.push_back(c.position);
    } else if (const auto* spline = std::get_if<ClothoidSplineShape>(&trajectory_.shape)) {
      for (const ClothoidSplineSegment& segment : spline->segments)
        if (segment.start) out.push_back(*segment.start);
    } else {
      out.push_back(std::get<ClothoidShape>(trajectory_.shape).start);
    }
    return out;
  }

  [[nodiscard]] std::vector<opendrive::Pose2> points(const std::vector<opendrive::Pose2>& resolved) const override {
    std::vector<PathPoint> points;
    if (std::holds_alternative<PolylineShape>(trajectory_.shape)) {
      for (const opendrive::Pose2& p : resolved) points.push_back({p.x, p.y, 0.0, std::nullopt, std::nullopt});
    } else if (const auto* nurbs = std::get_if<NurbsShape>(&trajectory_.shape)) {
      std::vector<NurbsControl> controls;
      for (std::size_t i = 0; i < resolved.size(); ++i)
        controls.push_back({resolved[i].x, resolved[i].y, nurbs->points[i].weight, std::nullopt});
      points = nurbs_points(controls, nurbs->knots, nurbs->order);
    } else if (const auto* spline = std::get_if<ClothoidSplineShape>(&trajectory_.shape)) {
      // A FollowTrajectoryAction starts a first segment without PositionStart where its actor
      // is; a position has no such entity.
      if (!spline->segments.front().start)
        throw MapError(fmt::format("trajectory \"{}\": its first ClothoidSplineSegment has no PositionStart, so it "
                                   "starts nowhere as a TrajectoryPosition's trajectory (give it one)",
                                   trajectory_.name));
      std::vector<std::optional<opendrive::Pose2>> starts;
      std::size_t next = 0;
      for (const ClothoidSplineSegment& segment : spline->segments)
        starts.push_back(segment.start ? std::optional(resolved[next++]) : std::nullopt);
      points = clothoid_spline_points(*spline, starts, *starts.front());
    } else {
      const auto& c = std::get<ClothoidShape>(trajectory_.shape);
      points = clothoid_points(resolved.front(), c.curvature, c.curvature_dot, c.length);
    }
    if (trajectory_.closed) close_path(points);
    std::vector<opendrive::Pose2> out;
    for (const PathPoint& p : points) out.push_back({p.x, p.y, 0.0});
    return out;
  }

 private:
  Trajectory trajectory_;
};

}  // namespace

std::shared_ptr<const position::TrajectoryPath> trajectory_path_of(Trajectory trajectory) {
  return std::make_shared<const ShapePath>(std::move(trajectory));
}

}  // namespace orch::openscenario

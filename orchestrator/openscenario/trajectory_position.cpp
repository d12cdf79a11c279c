#include "openscenario/trajectory_position.hpp"

#include <fmt/format.h>

#include "core/errors.hpp"
#include "openscenario/trajectory_motion.hpp"

namespace orch::openscenario {
namespace {

class ShapePath final : public position::TrajectoryPath {
 public:
  explicit ShapePath(Trajectory trajectory) : trajectory_(std::move(trajectory)) {}
  [[nodiscard]] std::string name() const override { return trajectory_.name; }

  [[nodiscard]] std::vector<Position> positions() const override { return shape_positions(trajectory_); }

  [[nodiscard]] std::vector<opendrive::Pose2> points(const std::vector<opendrive::Pose2>& resolved) const override {
    // A FollowTrajectoryAction starts a first segment without PositionStart where its actor
    // is; a position has no such entity.
    if (const auto* spline = std::get_if<ClothoidSplineShape>(&trajectory_.shape); spline && !spline->segments.front().start)
      throw MapError(fmt::format("trajectory \"{}\": its first ClothoidSplineSegment has no PositionStart, so it "
                                 "starts nowhere as a TrajectoryPosition's trajectory (give it one)",
                                 trajectory_.name));
    std::vector<opendrive::Pose2> out;
    for (const PathPoint& p : shape_points(trajectory_, resolved, {})) out.push_back({p.x, p.y, 0.0});
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

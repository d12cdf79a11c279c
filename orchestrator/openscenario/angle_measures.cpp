#include "openscenario/angle_measures.hpp"

#include <algorithm>
#include <cmath>

#include "core/errors.hpp"
#include "core/polyline.hpp"

namespace orch::openscenario {
namespace {

// Heading of the centre line of `lane` at s: the reference line's, turned by the slope of
// the lane centre's t (a lane widening or narrowing, a lane offset), from the centre's
// inertial points half a metre either side of s.
double lane_heading(const opendrive::Road& road, int lane, double s) {
  constexpr double kHalfBase = 0.5;
  const double from = std::max(0.0, s - kHalfBase);
  const double to = std::min(road.length, s + kHalfBase);
  if (lane == 0 || to - from < 1e-6) return road.plan_view.pose(s).heading;
  try {
    const opendrive::Pose2 a = road.world(from, road.lane_center_t(lane, from));
    const opendrive::Pose2 b = road.world(to, road.lane_center_t(lane, to));
    return std::atan2(b.y - a.y, b.x - a.x);
  } catch (const MapError&) {  // the lane ends within the half metre: the road's frame
    return road.plan_view.pose(s).heading;
  }
}

}  // namespace

double angle_difference(double a, double b) { return wrap_angle(a - b); }

std::optional<double> entity_angle(const EntityState& entity, const std::string& angle_type,
                                   const std::string& coordinate_system, const opendrive::RoadNetwork& roads) {
  const opendrive::Road* road = entity.road_id.empty() ? nullptr : roads.find(entity.road_id);
  if (coordinate_system == "world" || coordinate_system == "entity") {
    if (angle_type == "heading") return entity.pose.heading;
    if (road == nullptr) return 0.0;  // no road under it: level
    const opendrive::SurfacePose surface = opendrive::surface_pose(*road, entity.s, entity.t, entity.pose.heading);
    return angle_type == "pitch" ? surface.pitch : surface.roll;
  }
  if (road == nullptr) return std::nullopt;
  if (angle_type != "heading") return 0.0;  // standing on the surface: level with it
  const double reference =
      coordinate_system == "lane" ? lane_heading(*road, entity.lane, entity.s) : road->plan_view.pose(entity.s).heading;
  return angle_difference(entity.pose.heading, reference);
}

}  // namespace orch::openscenario

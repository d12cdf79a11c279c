#include "openscenario/lane_offset.hpp"

#include <algorithm>
#include <cmath>

namespace orch::openscenario {

double relative_lane_offset(const EntityState& state, const EntityState& reference, double value,
                            const opendrive::RoadNetwork& roads) {
  const opendrive::Road& ref_road = roads.road(reference.road_id);
  const double ref_s = std::clamp(reference.s, 0.0, ref_road.length);
  // The reference entity's left is +t when it faces along s, -t when it faces against s.
  const double along = std::cos(reference.pose.heading - ref_road.world(ref_s, reference.t).heading);
  double target_t = reference.t + (along >= 0 ? value : -value);
  const opendrive::Road& road = roads.road(state.road_id);
  const double s = std::clamp(state.s, 0.0, road.length);
  if (reference.road_id != state.road_id) {  // another road: the same point, seen from this one
    const opendrive::Pose2 target = ref_road.world(ref_s, target_t);
    target_t = opendrive::project(road, target.x, target.y).t;
  }
  return target_t - road.lane_center_t(state.lane, s);
}

}  // namespace orch::openscenario

#pragma once
// Angles of entities for AngleCondition and RelativeAngleCondition (OpenSCENARIO 1.3): an
// entity's heading, pitch or roll in the world frame or relative to its road or lane.
#include <optional>
#include <string>

#include "openscenario/entity_motion.hpp"
#include "opendrive/road_network.hpp"

namespace orch::openscenario {

// a - b on the circle, in (-pi, pi] (core wrap_angle).
double angle_difference(double a, double b);

// `angle_type`: heading, pitch or roll; `coordinate_system`: world (inertial), road (relative
// to the reference line at the entity's s), lane (relative to the centre line of the entity's
// lane there; the road's frame where it has no lane). Pitch (+ nose down) and roll (+ right
// side down) in world are those of the road surface under the entity (it stands on it),
// relative to the road or lane 0. None for road / lane when the entity is on no road.
std::optional<double> entity_angle(const EntityState& entity, const std::string& angle_type,
                                   const std::string& coordinate_system, const opendrive::RoadNetwork& roads);

}  // namespace orch::openscenario

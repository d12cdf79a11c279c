#pragma once
// The target of a LaneOffsetAction whose LaneOffsetTarget is a RelativeTargetLaneOffset.
#include "opendrive/road_network.hpp"
#include "openscenario/entity_motion.hpp"

namespace orch::openscenario {

// The lane offset (from the centre of `state`'s lane, as EntityState::offset) that puts
// `state` `value` m beside `reference`. The standard gives the value as the "lane offset
// with respect to the reference entity's current lane position", in the reference entity's
// coordinate system (positive to its left): the target is the reference's lateral position
// plus the value, whatever lane `state` is in. OSC-ALKS 4.6_2's side vehicle, told -1.75
// relative to the ego, ends 1.75 m right of the ego's reference point, beside it (not
// 1.75 m right of its own lane's centre, away from the ego).
double relative_lane_offset(const EntityState& state, const EntityState& reference, double value,
                            const opendrive::RoadNetwork& roads);

}  // namespace orch::openscenario

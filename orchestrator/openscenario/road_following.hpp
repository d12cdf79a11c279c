#pragma once
// How a storyboard entity follows the OpenDRIVE links as it drives: across lane sections
// (its lane id follows the lane links) and past its road's end onto the lane that
// continues it (opendrive/lane_graph.hpp), with the distance left over. Where a lane
// continues on several (a junction), the entity's route plan decides (route_plan below),
// else the straightest continuation. Where nothing continues, it stays at the road's end.
#include <cstddef>

#include "map/position_resolver.hpp"
#include "opendrive/road_network.hpp"
#include "openscenario/entity_motion.hpp"

namespace orch::openscenario {

// After `state.s` moved along its lane from `s_before` in section `section_before`: renumbers
// the lane across the sections passed and drives on past the road's end. Pose not updated.
void follow_links(EntityState& state, const opendrive::RoadNetwork& roads, std::size_t section_before,
                  double s_before);

// Where the entity's lane has narrowed to width 0 (a lane that ends without a lane section
// of its own: esmini's multi_intersections.xodr road 209, lane -2 from s = 59), it goes on in
// the nearest lane of the same type that still has a width (by the distance between its
// place and that lane's centre), keeping its offset; not during a lane change or a lane
// offset (their target is set). OpenDRIVE does not say where a lane of width 0 leaves its
// traffic; esmini does this (an entity is never on a lane of width 0: it snaps to the
// nearest lane of a drivable type with a width, in the step the width reaches 0).
void leave_vanished_lane(EntityState& state, const opendrive::RoadNetwork& roads);

// True when the entity stands at the end of its road in its direction of travel and no
// lane continues its lane there (EndOfRoadCondition).
bool at_dead_end(const EntityState& state, const opendrive::RoadNetwork& roads);

// True when `at` (a position located on the roads) is off the road (OffroadCondition): on no
// lane, or on a lane of OpenDRIVE type "none" (a lane that is no part of the road's surface:
// esmini's jolengatan.xodr draws 6 m of it beside the border). Border, shoulder and sidewalk
// lanes are the road's, as esmini counts them (measured: an entity on each fires no
// OffroadCondition there, one on a "none" lane does); the standard does not define it.
bool off_road(const position::ResolvedPosition& at, const opendrive::RoadNetwork& roads);

}  // namespace orch::openscenario

#pragma once
// How a storyboard entity follows the OpenDRIVE links as it drives: across lane sections
// (its lane id follows the lane links) and past its road's end onto the lane that
// continues it (opendrive/lane_graph.hpp), with the distance left over. Where a lane
// continues on several (a junction), the entity's route plan decides (route_plan below),
// else the straightest continuation. Where nothing continues, it stays at the road's end.
#include <cstddef>

#include "opendrive/road_network.hpp"
#include "openscenario/entity_motion.hpp"

namespace orch::openscenario {

// After `state.s` moved along its lane from section `section_before`: renumbers the lane
// across the sections passed and drives on past the road's end. Pose not updated.
void follow_links(EntityState& state, const opendrive::RoadNetwork& roads, std::size_t section_before);

// True when the entity stands at the end of its road in its direction of travel and no
// lane continues its lane there (EndOfRoadCondition).
bool at_dead_end(const EntityState& state, const opendrive::RoadNetwork& roads);

}  // namespace orch::openscenario

#pragma once
// The SUMO route of a vehicle that drives OpenDRIVE lanes: the edges netconvert made of
// them (sumo_lanes.hpp), in order. Connecting roads inside junctions have no edges of their
// own (netconvert makes them the junction's internal lanes) and are skipped.
#include <string>
#include <vector>

#include "opendrive/lane_graph.hpp"
#include "opendrive/sumo_lanes.hpp"

namespace orch::opendrive {

// The edges from `lane` of `road_id` at s (the rest of that road, each lane section's piece)
// through the lanes of `then`, in order. The route ends before the first edge SUMO's net
// does not connect to the one before (SUMO refuses a broken route), so it always holds at
// least the start edge when SUMO has a lane there (else it is empty).
std::vector<std::string> sumo_route(const SumoLaneIndex& lanes, const RoadNetwork& roads, const std::string& road_id,
                                    int lane, double s, const std::vector<LaneEntry>& then);

}  // namespace orch::opendrive

#pragma once
// The lane-level graph of an OpenDRIVE road network: from a lane at the road end it drives
// towards, the lanes it continues on (across a road link, or through a junction's
// connections onto connecting roads), and the lane a lane becomes in the next lane section.
// Direction of travel: right lanes drive along s, left lanes against it (right-hand
// traffic; mirrored on roads with rule="LHT"), so a lane id fixes its direction.
#include <optional>
#include <string>
#include <vector>

#include "opendrive/road_network.hpp"

namespace orch::opendrive {

// +1 when traffic on `lane` drives along s, -1 against it.
int lane_direction(const Road& road, int lane);

// Where a lane continues: `lane` of `road_id` (its id in the lane section at the entry),
// entered at s (0 or the road's length) driving in `direction`.
struct LaneEntry {
  std::string road_id;
  int lane = 0;
  double s = 0.0;
  int direction = 1;
  std::string junction;  // the junction whose connection this is; "" for a road link
};

// The lanes `lane` (its id in the lane section at the road end it drives towards) of
// `road_id` continues on past that end, in the order the file gives them. A lane without
// a lane link continues on the lane of the same id when the next road has one in the
// matching direction (files that omit lane links on plain road-to-road joints).
std::vector<LaneEntry> next_lanes(const RoadNetwork& roads, const std::string& road_id, int lane);

// The id `lane` has in section `from + direction` (sections along s), following the lane
// links; nullopt when the lane ends there.
std::optional<int> lane_in_next_section(const Road& road, std::size_t from, int lane, int direction);

// Index of the section holding s (the last starting at or before it).
std::size_t section_index(const Road& road, double s);

// Heading change (rad, in (-pi, pi], positive = left) from driving out of `lane` of
// `road_id` to driving out of `next`'s road at its far end: how much a choice turns.
double turn_angle(const RoadNetwork& roads, const std::string& road_id, int lane, const LaneEntry& next);

// The default choice where a lane continues on several lanes (a junction without a route):
// the one turning least (straight on); among equal turns (within 1e-6 rad) the first in the file.
std::optional<LaneEntry> straightest_next(const RoadNetwork& roads, const std::string& road_id, int lane);

// Heading of travel on `lane` of `road` at s (the road heading, turned by pi against s).
double travel_heading(const Road& road, int lane, double s);

}  // namespace orch::opendrive

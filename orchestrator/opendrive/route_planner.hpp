#pragma once
// Route planning on the lane graph (lane_graph.hpp): the lanes an entity drives from a
// point on a lane to a point on another road, by one of OpenSCENARIO's route strategies.
// Lane changes are not part of a plan: the plan starts on the entity's lane and follows lane
// links and junction connections; a lane change the route needs is the storyboard's.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "opendrive/lane_graph.hpp"
#include "opendrive/road_network.hpp"

namespace orch::opendrive {

// OpenSCENARIO RouteStrategy. Edge weight of driving through a road on a lane:
//   Shortest: its length; Fastest: length / speed limit of the lane (its speed record, else
//   the road's <type><speed>, else speed_for_road_type); LeastIntersections: junctions
//   passed first, then length; Random: length times a factor in [0.5, 1.5) hashed from the
//   road and lane ids (FNV-1a): an arbitrary but fixed choice, the same in every run.
enum class RouteStrategy { Shortest, Fastest, LeastIntersections, Random };

struct RoutePoint {
  std::string road_id;
  double s = 0.0;
  int lane = 0;
};

// The lanes entered after leaving `from`'s road, in order, up to and including the road of
// `to` (empty when `to` lies ahead on `from`'s own lane's road). `to` counts as reached on
// any lane of its road that drives in the direction of `to.lane`. nullopt: unreachable.
std::optional<std::vector<LaneEntry>> plan_route(const RoadNetwork& roads, const RoutePoint& from,
                                                 const RoutePoint& to, RouteStrategy strategy);

// The lanes an entity without a route drives on from `lane` of `road_id` (its id at the road
// end it drives towards, as for next_lanes): straightest_next
// repeatedly, until no lane follows, a lane would repeat (a ring), or `max_roads` roads.
std::vector<LaneEntry> default_continuation(const RoadNetwork& roads, const std::string& road_id, int lane,
                                            std::size_t max_roads = 64);

// The id of `lane` (as it is in the section at s) in the section where the road is left
// in the lane's direction; nullopt when the lane ends before.
std::optional<int> lane_at_road_exit(const Road& road, int lane, double s);

// Speed limit (m/s) on `lane` of `road` at the start of section `section`.
double lane_speed_limit(const Road& road, std::size_t section, int lane);

}  // namespace orch::opendrive

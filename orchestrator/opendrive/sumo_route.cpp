#include "opendrive/sumo_route.hpp"

#include <algorithm>

namespace orch::opendrive {

namespace {

// Appends the edges of `lane` of `road` from s to the road's end in the lane's direction.
// Returns false when an edge is not connected to the route so far.
bool append_road(const SumoLaneIndex& lanes, const Road& road, int lane, double s, std::vector<std::string>& edges) {
  const int direction = lane_direction(road, lane);
  std::size_t section = section_index(road, std::clamp(s, 0.0, road.length));
  while (true) {
    const double begin = road.sections[section].s;
    const double end = section + 1 < road.sections.size() ? road.sections[section + 1].s : road.length;
    if (const auto found = lanes.find(road.id, lane, 0.5 * (begin + end)); found) {
      if (edges.empty() || edges.back() != found->edge) {
        if (!edges.empty() && !lanes.connected(edges.back(), found->edge)) return false;
        edges.push_back(found->edge);
      }
    }
    if ((direction > 0 && section + 1 >= road.sections.size()) || (direction < 0 && section == 0)) return true;
    const auto next = lane_in_next_section(road, section, lane, direction);
    if (!next) return false;
    lane = *next;
    section = direction > 0 ? section + 1 : section - 1;
  }
}

}  // namespace

std::vector<std::string> sumo_route(const SumoLaneIndex& lanes, const RoadNetwork& roads, const std::string& road_id,
                                    int lane, double s, const std::vector<LaneEntry>& then) {
  std::vector<std::string> edges;
  if (!append_road(lanes, roads.road(road_id), lane, s, edges)) return edges;
  for (const LaneEntry& e : then)
    if (!append_road(lanes, roads.road(e.road_id), e.lane, e.s, edges)) break;
  return edges;
}

}  // namespace orch::opendrive

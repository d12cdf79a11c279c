#include "openscenario/random_route.hpp"

#include <algorithm>
#include <cstdint>

#include <fmt/format.h>

#include "core/stable_hash.hpp"
#include "opendrive/lane_graph.hpp"
#include "opendrive/route_planner.hpp"

namespace orch::openscenario {

void plan_random_route(EntityState& state, const opendrive::RoadNetwork& roads, const std::string& entity,
                       std::uint64_t seed) {
  state.route.clear();
  state.route_passed = 0;
  state.route_plan.clear();
  state.route_plan_next = 0;
  state.route_plan_loop.reset();
  ++state.route_version;
  if (!state.placed || state.road_id.empty() || roads.find(state.road_id) == nullptr) return;
  const opendrive::Road& road = roads.road(state.road_id);
  std::optional<int> exit = opendrive::lane_at_road_exit(road, state.lane, std::clamp(state.s, 0.0, road.length));
  std::string at = state.road_id;
  for (std::size_t forks = 0; exit && state.route_plan.size() < kRandomRouteMaxRoads;) {
    const std::vector<opendrive::LaneEntry> next = opendrive::next_lanes(roads, at, *exit);
    if (next.empty()) break;
    std::size_t pick = 0;
    if (next.size() > 1)
      pick = stable_hash(fmt::format("{}/{}/{}/{}/{}", seed, entity, at, *exit, forks++)) % next.size();
    const opendrive::LaneEntry& entry = next[pick];
    state.route_plan.push_back(entry);
    at = entry.road_id;
    exit = opendrive::lane_at_road_exit(roads.road(at), entry.lane, entry.s);
  }
}

}  // namespace orch::openscenario

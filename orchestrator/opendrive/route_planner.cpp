#include "opendrive/route_planner.hpp"

#include <cmath>
#include <functional>
#include <queue>
#include <set>

#include "core/stable_hash.hpp"
#include "opendrive/sumo_net.hpp"

namespace orch::opendrive {

namespace {

// Junction passes outweigh any length for LeastIntersections (roads are far shorter).
constexpr double kJunctionWeight = 1e7;

// Weight of driving `distance` metres on `lane` of `road` (entered as `entry` when it came
// from a link, for the junction count).
double weight(RouteStrategy strategy, const Road& road, int lane, double s, double distance, bool in_junction) {
  switch (strategy) {
    case RouteStrategy::Shortest: return distance;
    case RouteStrategy::Fastest: return distance / lane_speed_limit(road, section_index(road, s), lane);
    case RouteStrategy::LeastIntersections: return distance + (in_junction ? kJunctionWeight : 0.0);
    case RouteStrategy::Random: {
      const double factor = 0.5 + static_cast<double>(stable_hash(road.id + "/" + std::to_string(lane)) % 1000) / 1000.0;
      return distance * factor;
    }
  }
  return distance;
}

struct Node {
  LaneEntry entry;
  std::size_t parent = 0;  // index of the node before; npos for the first
};

struct Item {
  double cost = 0;
  std::size_t node = 0;
  bool goal = false;
  bool operator>(const Item& o) const {
    if (cost != o.cost) return cost > o.cost;
    return node > o.node;  // deterministic among equal costs: the earlier found first
  }
};

}  // namespace

double lane_speed_limit(const Road& road, std::size_t section, int lane) {
  if (section < road.sections.size())
    if (const Lane* l = road.sections[section].lane(lane); l != nullptr && !l->speeds.empty() && l->speeds.front().max_mps > 0)
      return l->speeds.front().max_mps;
  if (road.type_speed_mps && *road.type_speed_mps > 0) return *road.type_speed_mps;
  return speed_for_road_type(road.type);
}

std::optional<int> lane_at_road_exit(const Road& road, int lane, double s) {
  const int direction = lane_direction(road, lane);
  std::size_t section = section_index(road, s);
  if (road.sections.empty() || road.sections[section].lane(lane) == nullptr) return std::nullopt;
  while ((direction > 0 && section + 1 < road.sections.size()) || (direction < 0 && section > 0)) {
    const auto next = lane_in_next_section(road, section, lane, direction);
    if (!next) return std::nullopt;
    lane = *next;
    section = direction > 0 ? section + 1 : section - 1;
  }
  return lane;
}

std::optional<std::vector<LaneEntry>> plan_route(const RoadNetwork& roads, const RoutePoint& from,
                                                 const RoutePoint& to, RouteStrategy strategy) {
  const Road& start = roads.road(from.road_id);
  const Road& goal_road = roads.road(to.road_id);
  const int goal_direction = lane_direction(goal_road, to.lane);
  const int start_direction = lane_direction(start, from.lane);
  if (from.road_id == to.road_id && start_direction == goal_direction &&
      (to.s - from.s) * start_direction >= -1e-6)
    return std::vector<LaneEntry>{};

  std::vector<Node> nodes;
  std::set<std::pair<std::string, int>> settled;  // (road, lane) reached at the lowest cost
  std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
  const auto expand = [&](const Road& road, int lane, double s, double cost, std::size_t parent) {
    const auto exit = lane_at_road_exit(road, lane, s);
    if (!exit) return;
    const double rest = lane_direction(road, lane) > 0 ? road.length - s : s;
    const bool in_junction = parent != std::string::npos && !nodes[parent].entry.junction.empty();
    const double through = cost + weight(strategy, road, lane, s, rest, in_junction);
    for (LaneEntry& e : next_lanes(roads, road.id, *exit)) {
      nodes.push_back({std::move(e), parent});
      queue.push({through, nodes.size() - 1, false});
    }
  };
  expand(start, from.lane, from.s, 0.0, std::string::npos);
  while (!queue.empty()) {
    const Item item = queue.top();
    queue.pop();
    const LaneEntry entry = nodes[item.node].entry;  // a copy: expand() grows `nodes`
    if (item.goal) {
      std::vector<LaneEntry> path;
      for (std::size_t n = item.node; n != std::string::npos; n = nodes[n].parent) path.push_back(nodes[n].entry);
      return std::vector<LaneEntry>(path.rbegin(), path.rend());
    }
    if (!settled.emplace(entry.road_id, entry.lane).second) continue;
    const Road& road = roads.road(entry.road_id);
    if (entry.road_id == to.road_id && entry.direction == goal_direction) {
      queue.push({item.cost + weight(strategy, road, entry.lane, entry.s, std::abs(to.s - entry.s), !entry.junction.empty()),
                  item.node, true});
      continue;
    }
    expand(road, entry.lane, entry.s, item.cost, item.node);
  }
  return std::nullopt;
}

std::vector<LaneEntry> default_continuation(const RoadNetwork& roads, const std::string& road_id, int lane,
                                            std::size_t max_roads) {
  std::vector<LaneEntry> out;
  std::set<std::pair<std::string, int>> seen{{road_id, lane}};
  std::string road = road_id;
  int current = lane;
  while (out.size() < max_roads) {
    const auto next = straightest_next(roads, road, current);
    if (!next || !seen.emplace(next->road_id, next->lane).second) break;
    out.push_back(*next);
    const auto exit = lane_at_road_exit(roads.road(next->road_id), next->lane, next->s);
    if (!exit) break;
    road = next->road_id;
    current = *exit;
  }
  return out;
}

}  // namespace orch::opendrive

#pragma once
// The names of the SUMO edges the map builder makes (net_plan.cpp): a corridor's edge is
// named after the routes that drive it, in SUMO's id alphabet.
#include <set>
#include <string>
#include <vector>

namespace orch {

// `id` with the characters SUMO does not accept in ids replaced by '_'.
std::string sumo_safe_id(const std::string& id);

// A route driving a corridor, as its name needs it.
struct NamedRoute {
  double lateral = 0;      // offset across the corridor (+ left)
  std::size_t index = 0;   // the route's place in the waypoint file
  std::string id;
};

// The corridor's edge name: its routes' ids from right to left (pieces of one lane in file
// order) joined by '+', the outermost two when that is long; unique among `used` (~2, ~3, ...),
// which it joins.
std::string corridor_name(std::vector<NamedRoute> routes, std::set<std::string>& used);

}  // namespace orch

#include "openscenario/route_plan.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "core/errors.hpp"
#include "opendrive/lane_graph.hpp"

namespace orch::openscenario {

namespace {

using opendrive::LaneEntry;
using opendrive::RoutePoint;

// The id `lane`, entered at `entry_s`, has at s further along (lane links across sections).
int lane_further_on(const opendrive::Road& road, int lane, double entry_s, double s) {
  std::size_t section = opendrive::section_index(road, entry_s);
  const std::size_t target = opendrive::section_index(road, s);
  while (section != target) {
    const int step = target > section ? 1 : -1;
    const auto next = opendrive::lane_in_next_section(road, section, lane, step);
    if (!next) return lane;
    lane = *next;
    section = step > 0 ? section + 1 : section - 1;
  }
  return lane;
}

// The entity's own lane first, then the other lanes of its road driving its way, nearest first.
std::vector<int> start_lanes(const opendrive::Road& road, double s, int lane) {
  std::vector<int> lanes{lane};
  const opendrive::LaneSection& section = road.section_at(s);
  std::vector<int> others;
  for (const auto* side : {&section.left, &section.right})
    for (const opendrive::Lane& l : *side)
      if (l.id != lane && opendrive::lane_direction(road, l.id) == opendrive::lane_direction(road, lane))
        others.push_back(l.id);
  std::stable_sort(others.begin(), others.end(),
                   [&](int a, int b) { return std::abs(a - lane) < std::abs(b - lane); });
  lanes.insert(lanes.end(), others.begin(), others.end());
  return lanes;
}

// One leg; returns the plan and the lane the entity arrives on at the target's s.
std::pair<std::vector<LaneEntry>, int> plan_leg(const opendrive::RoadNetwork& roads, const RoutePoint& from,
                                                const RouteTarget& to) {
  const opendrive::Road& road = roads.road(from.road_id);
  const RoutePoint goal{to.at.road_id, to.at.s, to.at.lane};
  for (const int lane : start_lanes(road, from.s, from.lane)) {
    auto plan = opendrive::plan_route(roads, {from.road_id, from.s, lane}, goal, to.strategy);
    if (!plan) continue;
    const opendrive::Road& arrival = roads.road(goal.road_id);
    const int arriving = plan->empty() ? lane_further_on(arrival, lane, from.s, goal.s)
                                       : lane_further_on(arrival, plan->back().lane, plan->back().s, goal.s);
    return {std::move(*plan), arriving};
  }
  throw MapError(fmt::format(
      "{} (road {}, lane {}, s {:.2f}) cannot be reached from road {}, lane {}, s {:.2f}: no lane links or junction "
      "connections of the road network lead there in the direction of travel",
      to.what, to.at.road_id, to.at.lane, to.at.s, from.road_id, from.lane, from.s));
}

}  // namespace

opendrive::RouteStrategy route_strategy(const std::string& word) {
  if (word == "fastest") return opendrive::RouteStrategy::Fastest;
  if (word == "leastIntersections") return opendrive::RouteStrategy::LeastIntersections;
  if (word == "random") return opendrive::RouteStrategy::Random;
  return opendrive::RouteStrategy::Shortest;
}

void plan_entity_route(EntityState& state, const opendrive::RoadNetwork& roads,
                       const std::vector<RouteTarget>& targets, bool closed) {
  state.route_plan.clear();
  state.route_plan_next = 0;
  state.route_plan_loop.reset();
  ++state.route_version;
  if (!state.placed || targets.empty()) return;
  RoutePoint from{state.road_id, std::clamp(state.s, 0.0, roads.road(state.road_id).length), state.lane};
  const auto append = [&](const RouteTarget& to) {
    auto [plan, arriving] = plan_leg(roads, from, to);
    state.route_plan.insert(state.route_plan.end(), plan.begin(), plan.end());
    from = {to.at.road_id, to.at.s, arriving};
  };
  for (std::size_t i = std::min(state.route_passed, targets.size()); i < targets.size(); ++i) {
    append(targets[i]);
    if (i == 0) state.route_plan_loop = state.route_plan.size();  // a closed route repeats from the first target
  }
  if (!closed) {
    state.route_plan_loop.reset();
    return;
  }
  if (!state.route_plan_loop) {  // the first target was passed already: the loop starts after the return leg
    append(targets.front());
    state.route_plan_loop = state.route_plan.size();
    for (std::size_t i = 1; i < targets.size(); ++i) append(targets[i]);
  }
  append(targets.front());
  if (*state.route_plan_loop >= state.route_plan.size()) state.route_plan_loop.reset();  // nothing to repeat
}

std::vector<LaneEntry> lanes_ahead(const EntityState& state, const opendrive::RoadNetwork& roads) {
  const std::size_t next = std::min(state.route_plan_next, state.route_plan.size());
  std::vector<LaneEntry> out(state.route_plan.begin() + static_cast<std::ptrdiff_t>(next), state.route_plan.end());
  if (state.route_plan_loop) {
    const auto loop = state.route_plan.begin() + static_cast<std::ptrdiff_t>(*state.route_plan_loop);
    for (int round = 0; round < 2; ++round) out.insert(out.end(), loop, state.route_plan.end());
    return out;
  }
  const opendrive::Road& road = roads.road(out.empty() ? state.road_id : out.back().road_id);
  const auto exit = out.empty() ? opendrive::lane_at_road_exit(road, state.lane, std::clamp(state.s, 0.0, road.length))
                                : opendrive::lane_at_road_exit(road, out.back().lane, out.back().s);
  if (!exit) return out;
  for (LaneEntry& e : opendrive::default_continuation(roads, road.id, *exit)) out.push_back(std::move(e));
  return out;
}

}  // namespace orch::openscenario

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

// The entity's own lane first, then the other lanes of its road driving its way (`way`: +1
// along s, -1 against; an entity changed into the oncoming lane keeps going its way),
// nearest first; for an entity standing `across` its road (parked), after those the lanes
// driving the other way, nearest to it first: its heading gives it no direction of travel.
std::vector<int> start_lanes(const opendrive::Road& road, double s, int lane, double t, int way, bool across) {
  std::vector<int> lanes{lane};
  const opendrive::LaneSection& section = road.section_at(s);
  std::vector<int> others, opposite;
  for (const auto* side : {&section.left, &section.right})
    for (const opendrive::Lane& l : *side)
      if (l.id != lane) {
        if (opendrive::lane_direction(road, l.id) == way) others.push_back(l.id);
        else if (across) opposite.push_back(l.id);
      }
  const auto nearest = [&](int a, int b) {
    return std::abs(road.lane_center_t(a, s) - t) < std::abs(road.lane_center_t(b, s) - t);
  };
  if (opendrive::lane_direction(road, lane) == way)  // beside its own lane: by lane id, as ever
    std::stable_sort(others.begin(), others.end(),
                     [&](int a, int b) { return std::abs(a - lane) < std::abs(b - lane); });
  else
    std::stable_sort(others.begin(), others.end(), nearest);
  std::stable_sort(opposite.begin(), opposite.end(), nearest);
  lanes.insert(lanes.end(), others.begin(), others.end());
  lanes.insert(lanes.end(), opposite.begin(), opposite.end());
  return lanes;
}

// Whether a heading is across the road at s: more than 60 degrees off its reference line, either way.
bool across_road(const opendrive::Road& road, double s, double heading) {
  return std::abs(std::cos(heading - road.plan_view.pose(s).heading)) < 0.5;
}

// One leg; returns the plan and the lane the entity arrives on at the target's s.
// `t`, `way` and `across`: where the entity stands on its road, the way it drives (0: its
// lane's) and whether it stands across it (the first leg only; a later leg starts on the
// lane the one before arrived on, its way).
std::pair<std::vector<LaneEntry>, int> plan_leg(const opendrive::RoadNetwork& roads, const RoutePoint& from,
                                                const RouteTarget& to, double t = 0, int way = 0, bool across = false) {
  const opendrive::Road& road = roads.road(from.road_id);
  const RoutePoint goal{to.at.road_id, to.at.s, to.at.lane};
  if (way == 0) way = opendrive::lane_direction(road, from.lane);
  for (const int lane : start_lanes(road, from.s, from.lane, t, way, across)) {
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
  const opendrive::Road& road = roads.road(state.road_id);
  RoutePoint from{state.road_id, std::clamp(state.s, 0.0, road.length), state.lane};
  bool first_leg = true;
  const auto append = [&](const RouteTarget& to) {
    const bool across = first_leg && across_road(road, from.s, state.pose.heading);
    const int way = first_leg ? travel_direction(state, road) : 0;
    first_leg = false;
    auto [plan, arriving] = plan_leg(roads, from, to, state.t, way, across);
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

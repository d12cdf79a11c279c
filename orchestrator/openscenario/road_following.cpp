#include "openscenario/road_following.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include "opendrive/lane_graph.hpp"

namespace orch::openscenario {

namespace {

constexpr double kAtEnd = 1e-6;  // m

// The lane `lane` becomes when section `to` is entered: its lane link, else the same id,
// else (the lane ended: a lane drop without links) the outermost lane of that side.
int lane_entering(const opendrive::Road& road, std::size_t from, std::size_t to, int lane) {
  const int step = to > from ? 1 : -1;
  if (const auto linked = opendrive::lane_in_next_section(road, from, lane, step)) return *linked;
  const opendrive::LaneSection& section = road.sections[to];
  const auto& side = lane > 0 ? section.left : section.right;
  if (side.empty()) return lane;
  return std::abs(lane) <= static_cast<int>(side.size()) ? lane : side.back().id;
}

// How much longer a path at lateral position t is than the reference line at s (curves).
double stretch(const opendrive::Road& road, double s, double t) {
  return std::max(1.0 - road.plan_view.curvature(s) * t, 0.1);
}

// The route plan's next lane among `candidates` (same road and lane, else same road), or
// the straightest one when the plan has none of them.
std::optional<opendrive::LaneEntry> choose(EntityState& state, const opendrive::RoadNetwork& roads,
                                          const std::vector<opendrive::LaneEntry>& candidates) {
  if (candidates.empty()) return std::nullopt;
  if (state.route_plan_next < state.route_plan.size()) {
    const opendrive::LaneEntry& want = state.route_plan[state.route_plan_next];
    auto it = std::find_if(candidates.begin(), candidates.end(),
                           [&](const auto& c) { return c.road_id == want.road_id && c.lane == want.lane; });
    if (it == candidates.end())
      it = std::find_if(candidates.begin(), candidates.end(), [&](const auto& c) { return c.road_id == want.road_id; });
    if (it != candidates.end()) {
      ++state.route_plan_next;
      if (state.route_plan_next == state.route_plan.size() && state.route_plan_loop)
        state.route_plan_next = *state.route_plan_loop;
      return *it;
    }
  }
  return opendrive::straightest_next(roads, state.road_id, state.lane);
}

}  // namespace

void follow_links(EntityState& state, const opendrive::RoadNetwork& roads, std::size_t section_before,
                  double s_before) {
  std::size_t section = section_before;
  for (int hops = 0; hops < 64; ++hops) {  // a bound against zero-length loops
    const opendrive::Road& road = roads.road(state.road_id);
    const std::size_t now = opendrive::section_index(road, std::clamp(state.s, 0.0, road.length));
    while (section != now && section < road.sections.size()) {
      const std::size_t next = now > section ? section + 1 : section - 1;
      state.lane = lane_entering(road, section, next, state.lane);
      section = next;
    }
    const int direction = travel_direction(state, road);
    const double over = direction > 0 ? state.s - road.length : -state.s;
    if (over <= 0) return;
    // An entity driving against its lane's direction (it changed into the oncoming lane) has
    // no continuation in the lane graph: it stays at the road's end, standing.
    const bool with_lane = direction == opendrive::lane_direction(road, state.lane);
    const auto next = with_lane ? choose(state, roads, opendrive::next_lanes(roads, road.id, state.lane)) : std::nullopt;
    if (!next) {
      // Stuck at the end: standing, as in esmini (lane_change_simple.xosc counts on a car
      // "stuck at end of road" having speed zero until an action sets a new one). Not in the
      // step it gets there: it keeps its speed until a step finds it at the end already, so
      // an action the arrival triggers (EndOfRoadCondition, duration 0: a TeleportAction back
      // to the road's start) finds the speed it came with, as in esmini (its car teleported
      // so drives on at 25 m/s). The standard says nothing of an entity at a dead end.
      const bool arrived_now = hops > 0 || (direction > 0 ? s_before < road.length : s_before > 0.0);
      state.s = direction > 0 ? road.length : 0.0;
      if (!arrived_now) state.speed = 0;
      return;
    }
    // Offsets are measured along t (to the left of the road): against the travel direction
    // they flip when the next road runs the other way.
    if (next->direction != direction) {
      state.offset = -state.offset;
      if (state.lateral_profile) {
        state.lateral_profile->from = -state.lateral_profile->from;
        state.lateral_profile->to = -state.lateral_profile->to;
      }
    }
    const opendrive::Road& to = roads.road(next->road_id);
    // The distance left is along the entity's own path (entity_motion.cpp): s on the old
    // road's end to path metres, then to s on the new road at the entity's lateral place.
    const double path_left = over * stretch(road, direction > 0 ? road.length : 0.0, state.t);
    state.road_id = next->road_id;
    state.lane = next->lane;
    if (state.direction != 0) state.direction = next->direction;
    state.t = to.lane_center_t(next->lane, next->s) + state.offset;
    state.s = next->s + next->direction * path_left / stretch(to, next->s, state.t);
    section = next->direction > 0 ? 0 : to.sections.size() - 1;
  }
}

void leave_vanished_lane(EntityState& state, const opendrive::RoadNetwork& roads) {
  constexpr double kVanished = 1e-9;  // m: a lane this narrow holds no entity
  if (state.road_id.empty() || state.lane == 0 || state.lateral_profile) return;
  const opendrive::Road& road = roads.road(state.road_id);
  const double s = std::clamp(state.s, 0.0, road.length);
  const opendrive::LaneSection& section = road.section_at(s);
  const opendrive::Lane* lane = section.lane(state.lane);
  if (lane == nullptr || lane->width(s - section.s) > kVanished) return;
  const double t = road.lane_center_t(state.lane, s) + state.offset;
  std::optional<int> nearest;
  double best = 0;
  for (const auto* side : {&section.left, &section.right})
    for (const opendrive::Lane& other : *side) {
      if (other.type != lane->type || other.width(s - section.s) <= kVanished) continue;
      const double d = std::abs(road.lane_center_t(other.id, s) - t);
      if (!nearest || d < best) {
        nearest = other.id;
        best = d;
      }
    }
  if (nearest) state.lane = *nearest;
}

bool at_dead_end(const EntityState& state, const opendrive::RoadNetwork& roads) {
  const opendrive::Road* road = roads.find(state.road_id);
  if (road == nullptr || state.lane == 0) return false;
  const int direction = travel_direction(state, *road);
  const bool at_end = direction > 0 ? state.s >= road->length - kAtEnd : state.s <= kAtEnd;
  return at_end && opendrive::next_lanes(roads, road->id, state.lane).empty();
}

bool off_road(const position::ResolvedPosition& at, const opendrive::RoadNetwork& roads) {
  if (!at.lane || !at.road) return true;
  const opendrive::Road* road = roads.find(at.road->road_id);
  if (road == nullptr) return true;
  const opendrive::Lane* lane = road->section_at(at.road->s).lane(*at.lane);
  return lane == nullptr || lane->type == "none";
}

}  // namespace orch::openscenario

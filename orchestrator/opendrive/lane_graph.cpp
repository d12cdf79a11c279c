#include "opendrive/lane_graph.hpp"

#include <cmath>

namespace orch::opendrive {

namespace {

double wrap_angle(double a) {
  a = std::fmod(a + M_PI, 2 * M_PI);
  if (a <= 0) a += 2 * M_PI;
  return a - M_PI;
}

// The lane `lane` of `road` exists at the end where an entry at `contact` comes in and
// drives in the direction that end implies (into the road).
std::optional<LaneEntry> entry_on(const RoadNetwork& roads, const std::string& road_id, int lane,
                                  ContactPoint contact, const std::string& junction) {
  const Road* road = roads.find(road_id);
  if (road == nullptr || lane == 0 || road->sections.empty()) return std::nullopt;
  const bool at_start = contact != ContactPoint::End;
  const LaneSection& section = at_start ? road->sections.front() : road->sections.back();
  if (section.lane(lane) == nullptr) return std::nullopt;
  const int direction = at_start ? 1 : -1;
  if (lane_direction(*road, lane) != direction) return std::nullopt;
  return LaneEntry{road->id, lane, at_start ? 0.0 : road->length, direction, junction};
}

// Whether connecting road `c` touches `incoming` at the junction (its linked end names it).
bool touches(const Road& connecting, ContactPoint contact, const std::string& incoming) {
  const RoadLink& link = contact == ContactPoint::End ? connecting.successor : connecting.predecessor;
  return link.kind != RoadLink::Kind::Road || link.id == incoming;
}

}  // namespace

int lane_direction(const Road& road, int lane) {
  const bool right = lane < 0;
  return (right != road.left_hand_traffic) ? 1 : -1;
}

std::size_t section_index(const Road& road, double s) {
  std::size_t i = 0;
  while (i + 1 < road.sections.size() && road.sections[i + 1].s <= s + 1e-9) ++i;
  return i;
}

std::optional<int> lane_in_next_section(const Road& road, std::size_t from, int lane, int direction) {
  const std::size_t to = direction > 0 ? from + 1 : from - 1;
  if (from >= road.sections.size() || (direction < 0 && from == 0) || to >= road.sections.size()) return std::nullopt;
  const Lane* here = road.sections[from].lane(lane);
  if (here == nullptr) return std::nullopt;
  const std::optional<int> linked = direction > 0 ? here->successor : here->predecessor;
  const int next = linked.value_or(lane);
  if (next == 0 || road.sections[to].lane(next) == nullptr) return std::nullopt;
  return next;
}

std::vector<LaneEntry> next_lanes(const RoadNetwork& roads, const std::string& road_id, int lane) {
  std::vector<LaneEntry> out;
  const Road& road = roads.road(road_id);
  if (road.sections.empty()) return out;
  const int direction = lane_direction(road, lane);
  const LaneSection& section = direction > 0 ? road.sections.back() : road.sections.front();
  const Lane* here = section.lane(lane);
  if (here == nullptr) return out;
  const RoadLink& link = direction > 0 ? road.successor : road.predecessor;
  const std::optional<int> lane_link = direction > 0 ? here->successor : here->predecessor;
  if (link.kind == RoadLink::Kind::Road) {
    // A road link's contact point is mandatory in the standard; without it the usual case.
    const ContactPoint contact =
        link.contact != ContactPoint::None ? link.contact : (direction > 0 ? ContactPoint::Start : ContactPoint::End);
    if (auto e = entry_on(roads, link.id, lane_link.value_or(lane), contact, "")) out.push_back(*e);
    return out;
  }
  if (link.kind != RoadLink::Kind::Junction) return out;
  const Junction* junction = roads.junction(link.id);
  if (junction == nullptr) return out;
  for (const JunctionConnection& c : junction->connections) {
    if (c.incoming_road != road.id) continue;
    const Road* connecting = roads.find(c.connecting_road);
    if (connecting == nullptr || !touches(*connecting, c.contact, road.id)) continue;
    std::optional<int> to;
    for (const LaneLinkPair& l : c.lane_links)
      if (l.from == lane) to = l.to;
    if (!to && c.lane_links.empty()) to = lane;  // no lane links: lanes keep their ids
    if (!to) continue;
    if (auto e = entry_on(roads, c.connecting_road, *to, c.contact, junction->id)) out.push_back(*e);
  }
  return out;
}

double travel_heading(const Road& road, int lane, double s) {
  const double h = road.plan_view.pose(s).heading;
  return lane_direction(road, lane) > 0 ? h : h + M_PI;
}

double turn_angle(const RoadNetwork& roads, const std::string& road_id, int lane, const LaneEntry& next) {
  const Road& road = roads.road(road_id);
  const double out_s = lane_direction(road, lane) > 0 ? road.length : 0.0;
  const Road& to = roads.road(next.road_id);
  const double far_s = next.direction > 0 ? to.length : 0.0;
  return wrap_angle(travel_heading(to, next.lane, far_s) - travel_heading(road, lane, out_s));
}

std::optional<LaneEntry> straightest_next(const RoadNetwork& roads, const std::string& road_id, int lane) {
  std::optional<LaneEntry> best;
  double best_turn = 0;
  for (const LaneEntry& e : next_lanes(roads, road_id, lane)) {
    const double turn = std::abs(turn_angle(roads, road_id, lane, e));
    if (!best || turn < best_turn - 1e-6) {
      best = e;
      best_turn = turn;
    }
  }
  return best;
}

}  // namespace orch::opendrive

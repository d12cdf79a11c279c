#include "openscenario/entity_measures.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "sim/box.hpp"

namespace orch::openscenario {
namespace {

// The gap between two boxes along one axis, given the signed distance `d` of `to`'s
// reference point from `from`'s and each box's extent [low, high] along that axis.
double gap(double d, double from_low, double from_high, double to_low, double to_high) {
  if (d >= 0) return std::max(0.0, d + to_low - from_high);
  return std::max(0.0, -d - to_high + from_low);
}

// The body moved on at its speed and heading for `h` seconds (and along its road by as much).
EntityState moved_on(const EntityState& state, const opendrive::RoadNetwork& roads, double h) {
  EntityState later = state;
  later.pose.x += state.speed * std::cos(state.pose.heading) * h;
  later.pose.y += state.speed * std::sin(state.pose.heading) * h;
  if (!state.road_id.empty()) later.s += travel_direction(state, roads.road(state.road_id)) * state.speed * h;
  return later;
}

sim::Box box_of(const Body& body) {
  const opendrive::Pose2& p = body.state->pose;
  const double c = std::cos(p.heading), s = std::sin(p.heading);
  const BoundingBox& b = *body.box;
  return {Vec2(p.x + b.center_x * c - b.center_y * s, p.y + b.center_x * s + b.center_y * c), p.heading, b.length,
          b.width};
}

// Freespace distance in the frame of `from` (coordinateSystem entity): `to`'s box as it is
// turned, its corners projected on from's axes (a box turned against from's heading reaches
// further along and across than its unturned extents), the gap between the extents along
// each axis; the Euclidean one is the true distance between the boxes (the standard:
// "distance is measured between closest bounding box points").
double freespace_in_entity_frame(const Body& from, const Body& to, const std::string& distance_type) {
  const sim::Box a = box_of(from), b = box_of(to);
  if (distance_type != "longitudinal" && distance_type != "lateral") return sim::box_distance(a, b);
  const double h = from.state->pose.heading;
  const Vec2 axis = distance_type == "longitudinal" ? Vec2(std::cos(h), std::sin(h)) : Vec2(-std::sin(h), std::cos(h));
  const Vec2 origin(from.state->pose.x, from.state->pose.y);
  double low = std::numeric_limits<double>::infinity(), high = -low;
  for (const Vec2& c : sim::box_corners(b)) {
    const double d = (c - origin).dot(axis);
    low = std::min(low, d);
    high = std::max(high, d);
  }
  const BoundingBox& fb = *from.box;
  const double centre = distance_type == "longitudinal" ? fb.center_x : fb.center_y;
  const double half = (distance_type == "longitudinal" ? fb.length : fb.width) / 2;
  return std::max({0.0, low - (centre + half), (centre - half) - high});
}

}  // namespace

double time_to_collision(const Body& from, const Body& to, const opendrive::RoadNetwork& roads,
                         const std::string& distance_type, const std::string& coordinate_system, bool freespace) {
  const double now = relative_distance(from, to, distance_type, coordinate_system, freespace);
  if (freespace && now <= 0) return 0.0;
  const EntityState a = moved_on(*from.state, roads, kTtcHorizon);
  const EntityState b = moved_on(*to.state, roads, kTtcHorizon);
  const double later = relative_distance({&a, from.box}, {&b, to.box}, distance_type, coordinate_system, freespace);
  const double closing = (now - later) / kTtcHorizon;
  if (closing <= 1e-9) return std::numeric_limits<double>::infinity();
  return now / closing;
}

std::optional<double> distance_ahead(const Body& from, const Body& to, const opendrive::RoadNetwork& roads,
                                     const std::string& distance_type, const std::string& coordinate_system,
                                     bool freespace) {
  double along = 0;
  if (coordinate_system == "entity") {
    const double h = from.state->pose.heading;
    along = (to.state->pose.x - from.state->pose.x) * std::cos(h) + (to.state->pose.y - from.state->pose.y) * std::sin(h);
  } else {
    const int direction =
        from.state->road_id.empty() ? 1 : travel_direction(roads.road(from.state->road_id), from.state->lane);
    along = (to.state->s - from.state->s) * direction;
  }
  if (along <= 1e-6) return std::nullopt;  // level with it to rounding: not ahead either
  return relative_distance(from, to, distance_type, coordinate_system, freespace);
}

bool boxes_overlap(const Body& a, const Body& b) { return sim::boxes_touch(box_of(a), box_of(b)); }

double relative_distance(const Body& from, const Body& to, const std::string& distance_type,
                         const std::string& coordinate_system, bool freespace) {
  if (freespace && coordinate_system == "entity") return freespace_in_entity_frame(from, to, distance_type);
  double along = 0;
  double across = 0;
  if (coordinate_system == "entity") {
    const double dx = to.state->pose.x - from.state->pose.x;
    const double dy = to.state->pose.y - from.state->pose.y;
    const double h = from.state->pose.heading;
    along = dx * std::cos(h) + dy * std::sin(h);
    across = -dx * std::sin(h) + dy * std::cos(h);
  } else {  // road / lane: differences of s and of t on the shared road
    along = to.state->s - from.state->s;
    across = to.state->t - from.state->t;
  }
  if (freespace) {
    const BoundingBox& a = *from.box;
    const BoundingBox& b = *to.box;
    along = gap(along, a.center_x - a.length / 2, a.center_x + a.length / 2, b.center_x - b.length / 2,
                b.center_x + b.length / 2);
    across = gap(across, a.center_y - a.width / 2, a.center_y + a.width / 2, b.center_y - b.width / 2,
                 b.center_y + b.width / 2);
  }
  if (distance_type == "longitudinal") return std::abs(along);
  if (distance_type == "lateral") return std::abs(across);
  return std::hypot(along, across);
}

namespace {

// The lane `steps` lanes to the left of `lane` for a body driving `direction` along s (lane
// ids grow to the left along s; 0 is the reference line, not a lane).
int lane_beside(int lane, int steps, int direction) {
  int id = lane;
  for (int i = 0; i < std::abs(steps); ++i) {
    id += (steps > 0 ? 1 : -1) * direction;
    if (id == 0) id += (steps > 0 ? 1 : -1) * direction;
  }
  return id;
}

}  // namespace

bool lanes_clear(const RelativeClearanceCondition& c, const Body& self, const std::vector<Body>& others,
                 const opendrive::RoadNetwork& roads) {
  const EntityState& me = *self.state;
  const opendrive::Road* road = roads.find(me.road_id);
  if (road == nullptr) return false;
  const int direction = travel_direction(me, *road);
  const opendrive::LaneSection& section = road->section_at(me.s);
  // The lanes of the area: the ranges' (none: every lane of the section), existing at s.
  std::vector<int> lanes;
  const auto consider = [&](int id) {
    if (id == 0 || section.lane(id) == nullptr) return;
    if (!c.opposite_lanes && travel_direction(*road, id) != direction) return;
    if (std::find(lanes.begin(), lanes.end(), id) == lanes.end()) lanes.push_back(id);
  };
  if (c.lanes.empty()) {
    for (const opendrive::Lane& l : section.left) consider(l.id);
    for (const opendrive::Lane& l : section.right) consider(l.id);
  } else {
    for (const RelativeLaneRange& r : c.lanes)
      for (int k = r.from; k <= r.to; ++k) consider(lane_beside(me.lane, k, direction));
  }
  if (lanes.empty()) return false;
  // Along s: distanceBackward behind to distanceForward ahead, in its direction of travel.
  const double low = direction > 0 ? me.s - c.distance_backward : me.s - c.distance_forward;
  const double high = direction > 0 ? me.s + c.distance_forward : me.s + c.distance_backward;
  for (const Body& other : others) {
    const EntityState& o = *other.state;
    if (!o.placed || o.road_id != me.road_id) continue;
    double s_low = o.s, s_high = o.s, t_low = o.t, t_high = o.t;
    if (c.freespace) {  // the box's extent along s and t (its heading taken along the road)
      const int way = travel_direction(o, *road);
      const BoundingBox& b = *other.box;
      const double back = b.center_x - b.length / 2, front = b.center_x + b.length / 2;
      s_low = o.s + std::min(way * back, way * front);
      s_high = o.s + std::max(way * back, way * front);
      const double right = b.center_y - b.width / 2, left = b.center_y + b.width / 2;
      t_low = o.t + std::min(way * right, way * left);
      t_high = o.t + std::max(way * right, way * left);
    }
    if (s_high < low || s_low > high) continue;
    for (int id : lanes) {
      if (!c.freespace) {
        if (o.lane == id) return false;
        continue;
      }
      const double at = std::clamp(o.s, 0.0, road->length);
      if (road->section_at(at).lane(id) == nullptr) continue;  // that lane ends before the other's s
      const auto [inner, outer] = road->lane_borders(id, at);
      if (t_high >= std::min(inner, outer) && t_low <= std::max(inner, outer)) return false;
    }
  }
  return true;
}

}  // namespace orch::openscenario

#include "map/lane_map.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <pugixml.hpp>

#include "core/errors.hpp"

namespace orch {

namespace {

constexpr const char* kRouteParam = "orch.route";  // written by map build (net_builder.cpp)
constexpr double kSumoDefaultLaneWidth = 3.2;      // SUMO omits width="..." at its default
constexpr double kMinInternalLength = 0.2;         // m

// SUMO shapes: "x,y x,y ..." or "x,y,z ..."; heights are dropped (the map is planar).
Polyline parse_shape(const char* text, const std::string& lane_id, const std::string& net_file) {
  std::vector<Vec2> pts;
  const char* p = text;
  while (*p) {
    while (*p == ' ') ++p;
    if (!*p) break;
    char* end = nullptr;
    const double x = std::strtod(p, &end);
    if (end == p || *end != ',') throw MapError(fmt::format("{}: lane \"{}\" has a malformed shape", net_file, lane_id));
    p = end + 1;
    const double y = std::strtod(p, &end);
    if (end == p) throw MapError(fmt::format("{}: lane \"{}\" has a malformed shape", net_file, lane_id));
    p = end;
    if (*p == ',') {  // a height: skip it
      std::strtod(p + 1, &end);
      p = end;
    }
    pts.emplace_back(x, y);
  }
  try {
    return Polyline(std::move(pts));
  } catch (const std::invalid_argument&) {
    throw MapError(fmt::format("{}: lane \"{}\" has a shape of less than two distinct points", net_file, lane_id));
  }
}

LaneInfo read_lane(const pugi::xml_node& lane, const std::string& edge_id, const std::string& net_file) {
  LaneInfo info;
  info.id = lane.attribute("id").as_string();
  info.edge = edge_id;
  info.index = lane.attribute("index").as_int();
  info.length = lane.attribute("length").as_double();
  info.width = lane.attribute("width").as_double(kSumoDefaultLaneWidth);
  info.speed = lane.attribute("speed").as_double();
  info.shape = parse_shape(lane.attribute("shape").as_string(), info.id, net_file);
  if (info.length <= 0) throw MapError(fmt::format("{}: lane \"{}\" has no positive length", net_file, info.id));
  // "orch.route" names the route the lane was built from, "orch.route.1", ... further
  // routes that drive it (junction maps).
  for (const pugi::xml_node param : lane.children("param")) {
    const std::string_view key = param.attribute("key").as_string();
    if (key == kRouteParam || (key.rfind(kRouteParam, 0) == 0 && key.size() > std::strlen(kRouteParam) &&
                               key[std::strlen(kRouteParam)] == '.'))
      info.routes.emplace_back(param.attribute("value").as_string());
  }
  return info;
}

// A junction's interior lane of real length (netconvert writes 0.1 m stubs where two
// edges of one road meet; those are passed through, not mapped).
bool is_real_internal(const pugi::xml_node& lane) {
  return lane.attribute("length").as_double() >= kMinInternalLength;
}

// A point beside a lane beats a point beyond its ends, then the nearer lane wins.
bool better_place(const LanePlace& a, const LanePlace& b) {
  const bool a_beyond = a.distance > std::abs(a.lateral) + 1e-6;
  const bool b_beyond = b.distance > std::abs(b.lateral) + 1e-6;
  if (a_beyond != b_beyond) return !a_beyond;
  return a.distance < b.distance;
}

}  // namespace

LaneMap LaneMap::build(const std::string& net_file, const WaypointFile& waypoints) {
  pugi::xml_document doc;
  const pugi::xml_parse_result parsed = doc.load_file(net_file.c_str());
  if (!parsed)
    throw MapError(fmt::format("cannot read SUMO net {}: {} (at byte {})", net_file, parsed.description(), parsed.offset));
  const pugi::xml_node net = doc.child("net");
  if (!net) throw MapError(fmt::format("{} is not a SUMO net (no <net> element)", net_file));

  LaneMap map;
  std::unordered_map<std::string, int> index_of;  // lane id -> index into lanes_
  for (const pugi::xml_node edge : net.children("edge")) {
    // Crossings and walking areas carry no routes; junction interiors do (the routes' own
    // shapes through the junction, junction_plan.hpp).
    const std::string_view function = edge.attribute("function").as_string();
    const bool internal = function == "internal";
    if (!function.empty() && function != "normal" && !internal) continue;
    const std::string edge_id = edge.attribute("id").as_string();
    for (const pugi::xml_node lane : edge.children("lane")) {
      if (internal && !is_real_internal(lane)) continue;
      index_of[lane.attribute("id").as_string()] = static_cast<int>(map.lanes_.size());
      map.lanes_.push_back(read_lane(lane, edge_id, net_file));
      map.lanes_.back().internal = internal;
      map.junctions_ = map.junctions_ || internal || map.lanes_.back().routes.size() > 1;
    }
  }
  // Where each lane leads: through the junction's interior lane when it has one.
  for (const pugi::xml_node c : net.children("connection")) {
    const auto from = index_of.find(fmt::format("{}_{}", c.attribute("from").as_string(), c.attribute("fromLane").as_int()));
    if (from == index_of.end()) continue;
    auto to = index_of.find(c.attribute("via").as_string());
    if (to == index_of.end())
      to = index_of.find(fmt::format("{}_{}", c.attribute("to").as_string(), c.attribute("toLane").as_int()));
    if (to == index_of.end()) continue;
    auto& next = map.lanes_[static_cast<std::size_t>(from->second)].next;
    if (std::find(next.begin(), next.end(), to->second) == next.end()) next.push_back(to->second);
  }
  for (const LaneInfo& lane : map.lanes_) {
    Bounds b{lane.shape.point(0), lane.shape.point(0)};
    for (const Vec2& p : lane.shape.points()) {
      b.lo = b.lo.cwiseMin(p);
      b.hi = b.hi.cwiseMax(p);
    }
    map.bounds_.push_back(b);
  }

  for (const WaypointRoute& route : waypoints.routes) {
    if (map.junctions_) {
      map.routes_.emplace(route.id, map.walk(route, net_file));
      continue;
    }
    RouteLanes rl;
    rl.route_id = route.id;
    std::vector<std::pair<double, int>> along;  // (arc length of the lane's middle on the route, lane)
    for (std::size_t i = 0; i < map.lanes_.size(); ++i) {
      const LaneInfo& lane = map.lanes_[i];
      if (std::find(lane.routes.begin(), lane.routes.end(), route.id) == lane.routes.end()) continue;
      const double s = route.line.project(lane.shape.point_at(lane.shape.length() / 2)).s;
      along.emplace_back(s, static_cast<int>(i));
    }
    if (along.empty())
      throw MapError(fmt::format("route \"{}\" of {} has no lanes in {}: the net was not built from this waypoint "
                                 "file (run `orchestrator map build`)", route.id, waypoints.path, net_file));
    std::sort(along.begin(), along.end());
    for (const auto& [s, lane] : along) rl.lanes.push_back(lane);
    rl.points.reserve(route.points.size());
    for (std::size_t i = 0; i < route.points.size(); ++i) {
      rl.points.push_back(map.nearest_of(rl.lanes, route.line.point(i), i == 0 ? -1 : rl.points.back().lane));
      const int lane = rl.points.back().lane;
      rl.visits.push_back(static_cast<int>(std::find(rl.lanes.begin(), rl.lanes.end(), lane) - rl.lanes.begin()));
    }
    map.routes_.emplace(route.id, std::move(rl));
  }
  return map;
}

const RouteLanes* LaneMap::route(std::string_view route_id) const {
  const auto it = routes_.find(std::string(route_id));
  return it == routes_.end() ? nullptr : &it->second;
}

const RouteLanes& LaneMap::route_or_throw(const WaypointRoute& r) const {
  const RouteLanes* rl = route(r.id);
  if (!rl) throw MapError(fmt::format("route \"{}\" is not part of this map", r.id));
  return *rl;
}

LanePlace LaneMap::place_on_lane(int lane, const Vec2& p) const {
  const LaneInfo& info = lanes_[static_cast<std::size_t>(lane)];
  const Polyline::Projection proj = info.shape.project(p);
  LanePlace place;
  place.lane = lane;
  place.lane_pos = std::clamp(proj.s / info.geometry_factor(), 0.0, info.length);
  place.lateral = proj.lateral;
  place.distance = proj.distance;
  return place;
}

LanePlace LaneMap::nearest_of(const std::vector<int>& candidates, const Vec2& p, int first) const {
  LanePlace best;
  best.distance = std::numeric_limits<double>::infinity();
  if (first >= 0) best = place_on_lane(first, p);
  for (const int lane : candidates) {
    if (lane == first) continue;
    // A lane whose bounding box is farther than the best so far cannot beat it.
    const Bounds& b = bounds_[static_cast<std::size_t>(lane)];
    const Vec2 outside = (b.lo - p).cwiseMax(p - b.hi).cwiseMax(Vec2::Zero());
    if (best.lane >= 0 && outside.norm() > best.distance) continue;
    const LanePlace place = place_on_lane(lane, p);
    if (best.lane < 0 || better_place(place, best)) best = place;
  }
  return best;
}

LanePlace LaneMap::place_on_route(const WaypointRoute& route, double s, double lateral) const {
  const RouteLanes& rl = route_or_throw(route);
  const auto& pts = rl.points;
  const double length = route.line.length();
  if (pts.size() != route.points.size()) return nearest_of(rl.lanes, route.line.offset_point(s, lateral));
  if (s <= 0 || s >= length) {
    const LanePlace& end = s <= 0 ? pts.front() : pts.back();
    return place_on_lane(end.lane, route.line.offset_point(s, lateral));
  }
  // Waypoints lo and hi = lo + 1 with s(lo) <= s < s(hi).
  std::size_t lo = 0;
  std::size_t hi = pts.size() - 1;
  while (hi - lo > 1) {
    const std::size_t mid = (lo + hi) / 2;
    (route.line.s_at_index(mid) <= s ? lo : hi) = mid;
  }
  const LanePlace& a = pts[lo];
  const LanePlace& b = pts[hi];
  if (a.lane != b.lane) {
    // An edge boundary lies between the two waypoints: place exactly on either lane.
    const Vec2 p = route.line.offset_point(s, lateral);
    const LanePlace pa = place_on_lane(a.lane, p);
    const LanePlace pb = place_on_lane(b.lane, p);
    return better_place(pb, pa) ? pb : pa;
  }
  // Lane shapes follow the route within centimetres, so lane coordinates are linear in s
  // between waypoints, and a sideways offset from the route is one from the lane.
  const double s0 = route.line.s_at_index(lo);
  const double s1 = route.line.s_at_index(hi);
  const double f = s1 > s0 ? (s - s0) / (s1 - s0) : 0.0;
  LanePlace place;
  place.lane = a.lane;
  place.lane_pos = a.lane_pos + f * (b.lane_pos - a.lane_pos);
  place.lateral = a.lateral + f * (b.lateral - a.lateral) + lateral;
  place.distance = std::abs(place.lateral);
  return place;
}

std::optional<LanePlace> LaneMap::locate(const Vec2& p, double heading, double max_distance) const {
  const Vec2 direction(std::cos(heading), std::sin(heading));
  std::optional<LanePlace> best;
  for (std::size_t i = 0; i < lanes_.size(); ++i) {
    const Bounds& b = bounds_[i];
    const Vec2 outside = (b.lo - p).cwiseMax(p - b.hi).cwiseMax(Vec2::Zero());
    if (outside.norm() > max_distance) continue;
    const LanePlace place = place_on_lane(static_cast<int>(i), p);
    if (place.distance > max_distance) continue;
    const LaneInfo& lane = lanes_[i];
    if (lane.shape.tangent_at(place.lane_pos * lane.geometry_factor()).dot(direction) <= 0) continue;
    if (!best || better_place(place, *best)) best = place;
  }
  return best;
}

int LaneMap::visit_at(const WaypointRoute& route, const RouteLanes& rl, double s) const {
  if (rl.visits.empty()) return 0;
  if (s <= 0) return rl.visits.front();
  if (s >= route.line.length()) return rl.visits.back();
  std::size_t lo = 0;
  std::size_t hi = rl.visits.size() - 1;
  while (hi - lo > 1) {
    const std::size_t mid = (lo + hi) / 2;
    (route.line.s_at_index(mid) <= s ? lo : hi) = mid;
  }
  // Between two waypoints on different lanes: the lane the point lies on.
  if (rl.visits[lo] == rl.visits[hi]) return rl.visits[lo];
  const LanePlace here = place_on_route(route, s, 0.0);
  return here.lane == rl.lanes[static_cast<std::size_t>(rl.visits[hi])] ? rl.visits[hi] : rl.visits[lo];
}

LanePlace LaneMap::normal_place_on_route(const WaypointRoute& route, double s, double lateral, bool forward) const {
  LanePlace place = place_on_route(route, s, lateral);
  if (place.lane < 0 || !lanes_[static_cast<std::size_t>(place.lane)].internal) return place;
  const RouteLanes& rl = route_or_throw(route);
  for (int v = visit_at(route, rl, s); v >= 0 && v < static_cast<int>(rl.lanes.size()); v += forward ? 1 : -1) {
    const int lane = rl.lanes[static_cast<std::size_t>(v)];
    const LaneInfo& info = lanes_[static_cast<std::size_t>(lane)];
    if (info.internal) continue;
    place.lane = lane;
    place.lane_pos = forward ? std::min(0.1, info.length) : std::max(0.0, info.length - 0.1);
    return place;
  }
  return place;
}

std::vector<std::string> LaneMap::route_edges(const WaypointRoute& route, double s0, double s1) const {
  const RouteLanes& rl = route_or_throw(route);
  auto first = visit_at(route, rl, s0);
  auto last = visit_at(route, rl, s1);
  if (last < first) std::swap(first, last);
  std::vector<std::string> edges;
  for (auto k = first; k <= last; ++k) {
    const LaneInfo& lane = lanes_[static_cast<std::size_t>(rl.lanes[static_cast<std::size_t>(k)])];
    if (lane.internal) continue;  // SUMO routes list normal edges; junctions are implied
    if (edges.empty() || edges.back() != lane.edge) edges.push_back(lane.edge);
  }
  return edges;
}

}  // namespace orch

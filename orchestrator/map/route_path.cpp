#include "map/route_path.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "core/errors.hpp"
#include "opendrive/lane_graph.hpp"

namespace orch::position {

double RoutePath::length() const {
  double total = 0;
  for (const RoutePiece& p : pieces) total += p.length();
  return total;
}

RoutePath route_path(const opendrive::RoadNetwork& roads, const std::vector<opendrive::RoutePoint>& points,
                     const std::vector<opendrive::RouteStrategy>& strategies, const std::string& route_name) {
  RoutePath path;
  if (points.empty()) return path;
  for (std::size_t i = 0; i + 1 < points.size(); ++i) {
    const opendrive::RoutePoint& from = points[i];
    const opendrive::RoutePoint& to = points[i + 1];
    const auto plan = opendrive::plan_route(roads, from, to, strategies.at(i + 1));
    if (!plan)
      throw MapError(fmt::format("route \"{}\": waypoint {} (road {}, lane {}, s {:.3f}) cannot be reached from "
                                 "waypoint {} (road {}, lane {}, s {:.3f}) on the roads' lanes",
                                 route_name, i + 2, to.road_id, to.lane, to.s, i + 1, from.road_id, from.lane, from.s));
    if (plan->empty()) {  // ahead on the same road
      path.pieces.push_back({from.road_id, from.s, to.s, from.lane});
      continue;
    }
    // Leave the waypoint's road at the end its lane drives towards, then each road of the plan
    // end to end, and the last one up to the next waypoint.
    const opendrive::Road& road = roads.road(from.road_id);
    const int direction = opendrive::lane_direction(road, from.lane);
    path.pieces.push_back({from.road_id, from.s, direction > 0 ? road.length : 0.0, from.lane});
    for (std::size_t k = 0; k < plan->size(); ++k) {
      const opendrive::LaneEntry& entry = (*plan)[k];
      const bool last = k + 1 == plan->size();
      const double end = last ? to.s : (entry.direction > 0 ? roads.road(entry.road_id).length : 0.0);
      path.pieces.push_back({entry.road_id, entry.s, end, entry.lane});
    }
  }
  return path;
}

PathPlace place_on_path(const RoutePath& path, double path_s, const std::string& route_name) {
  constexpr double kSlack = 1e-9;
  const double total = path.length();
  if (path.pieces.empty() || path_s < -kSlack || path_s > total + kSlack)
    throw MapError(fmt::format("pathS={:.3f} is outside route \"{}\" (length {:.3f} from its first waypoint)", path_s,
                               route_name, total));
  double before = 0;
  for (const RoutePiece& piece : path.pieces) {
    const double length = piece.length();
    if (path_s <= before + length + kSlack || &piece == &path.pieces.back()) {
      const double along = std::clamp(path_s - before, 0.0, length);
      return {piece.road_id, piece.s_begin + piece.direction() * along, piece.direction(), piece.lane};
    }
    before += length;
  }
  return {};  // unreachable: the last piece returns
}

}  // namespace orch::position

#pragma once
// The path of an OpenSCENARIO Route on the OpenDRIVE roads, for RoutePosition's pathS
// (map/position.hpp): the stretch of each road the route drives, in order, from its first
// waypoint to its last. Between two waypoints the path is the plan of
// opendrive::plan_route by the routeStrategy of the waypoint it leads to (as
// AssignRouteAction's legs, openscenario/route_plan.hpp).
#include <string>
#include <vector>

#include "opendrive/road_network.hpp"
#include "opendrive/route_planner.hpp"

namespace orch::position {

// One road of the path, driven from s_begin to s_end (s_end < s_begin: against s), on
// `lane` (its id where the road is entered).
struct RoutePiece {
  std::string road_id;
  double s_begin = 0, s_end = 0;
  int lane = 0;
  [[nodiscard]] double length() const { return s_end >= s_begin ? s_end - s_begin : s_begin - s_end; }
  [[nodiscard]] int direction() const { return s_end >= s_begin ? 1 : -1; }
};

struct RoutePath {
  std::vector<RoutePiece> pieces;
  [[nodiscard]] double length() const;
};

// A point of the path: road, s and the direction the path drives there.
struct PathPlace {
  std::string road_id;
  double s = 0;
  int direction = 1;
  int lane = 0;  // the lane the path drives on this road (its id at the road's entry)
};

// The path through `points` (the waypoints, each on a lane); strategies[i] is the strategy of
// points[i] (the leg to points[i] is planned by it; strategies[0] is not used). MapError
// naming `route_name` and the waypoint when a leg cannot be driven.
RoutePath route_path(const opendrive::RoadNetwork& roads, const std::vector<opendrive::RoutePoint>& points,
                     const std::vector<opendrive::RouteStrategy>& strategies, const std::string& route_name);

// The point `path_s` metres along the path from its start; MapError outside [0, length].
PathPlace place_on_path(const RoutePath& path, double path_s, const std::string& route_name);

}  // namespace orch::position

#pragma once
// Positions of both scenario languages as one variant, resolved in one place
// (map/position_resolver.hpp):
//  - the ScenarioExecutor format's: a point of a RoadEditor route (WaypointRef) and a
//    distance along a route from another actor (RouteDistance), on the waypoint maps;
//  - OpenSCENARIO's: World, Geo, RelativeWorld, RelativeObject, Road, RelativeRoad, Lane,
//    RelativeLane, Route and Trajectory positions with their Orientation, on OpenDRIVE roads.
// Relative positions name the entity they refer to; the resolver asks the caller for its pose.
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "core/diagnostics.hpp"
#include "opendrive/plan_view.hpp"
#include "opendrive/route_planner.hpp"

namespace orch::position {

// ---- ScenarioExecutor (RoadEditor waypoint maps) ------------------------------------
// A point of a RoadEditor route. wp_idx may be fractional in real files (33.333): the
// position is interpolated between the two neighbouring points.
struct WaypointRef {
  std::string wp_id;
  double wp_idx = 0;
  SourceLocation where;
};
// `distance` metres along `route` (the target's own route when absent) from the point of it
// nearest the target actor; with `surface`, from bumper to bumper (half of both lengths added).
struct RouteDistance {
  std::string target;  // the actor, by the name the caller's pose lookup knows
  double distance = 0;  // + = ahead of the target
  bool surface = false;
  std::optional<WaypointRef> route;
};

// ---- OpenSCENARIO (OpenDRIVE roads) -------------------------------------------------
struct Orientation {
  bool relative = true;  // "relative" (to the road / reference) or "absolute"
  double h = 0;
};
// z: the height of the point in the world frame when the file gives it (a camera flying above
// the road); without it the point is on the road surface (the storyboard keeps the height
// above the road, the map resolves positions in the road plane).
struct WorldPosition { double x = 0, y = 0; std::optional<double> h; std::optional<double> z = std::nullopt; };
// WGS 84 latitude and longitude in degrees, placed through the road network's geoReference
// (opendrive/geo_projection.hpp); a relative Orientation (or none) turns from the heading of
// the road there.
struct GeoPosition { double latitude_deg = 0, longitude_deg = 0; std::optional<Orientation> orientation; };
// dz: height above the reference entity's (OpenSCENARIO's dz; the storyboard keeps it as the
// entity's height above the road, the map resolves positions in the road plane).
struct RelativeWorldPosition { std::string entity; double dx = 0, dy = 0; std::optional<Orientation> orientation; double dz = 0; };
struct RelativeObjectPosition { std::string entity; double dx = 0, dy = 0; std::optional<Orientation> orientation; double dz = 0; };
struct RoadPosition { std::string road_id; double s = 0, t = 0; std::optional<Orientation> orientation; };
struct RelativeRoadPosition { std::string entity; double ds = 0, dt = 0; std::optional<Orientation> orientation; };
struct LanePosition {
  std::string road_id;
  int lane_id = 0;
  double s = 0, offset = 0;
  std::optional<Orientation> orientation;
};
// ds: along the road's s; ds_lane (OpenSCENARIO 1.1 dsLane, instead of ds): the distance
// along the centre line of the reference entity's lane (longer than ds on the outside of a
// curve, shorter on the inside), + in the direction of s.
struct RelativeLanePosition {
  std::string entity;
  int d_lane = 0;
  double ds = 0, offset = 0;
  std::optional<Orientation> orientation;
  std::optional<double> ds_lane = std::nullopt;
};

// RoutePosition: a place on a route (its waypoints, defined below, after Position: a
// waypoint is itself any position). InRoutePosition's three kinds (OpenSCENARIO 1.0-1.3):
//  - FromCurrentEntity: where the entity is (it must be on the route);
//  - FromRoadCoordinates: pathS along the route, t from the road's reference line;
//  - FromLaneCoordinates: pathS along the route, on lane laneId of the road there,
//    laneOffset from that lane's centre.
// pathS is measured along the route's path from its first waypoint (the roads between the
// waypoints as the waypoints' routeStrategy plans them), in the route's direction.
struct RouteWaypoints;
struct InRouteFromEntity { std::string entity; };
struct InRouteFromRoad { double path_s = 0, t = 0; };
struct InRouteFromLane { double path_s = 0; int lane_id = 0; double lane_offset = 0; };
struct RoutePosition {
  std::shared_ptr<const RouteWaypoints> route;
  std::variant<InRouteFromEntity, InRouteFromRoad, InRouteFromLane> in_route;
  std::optional<Orientation> orientation;
};

// TrajectoryPosition (OpenSCENARIO 1.1): `s` metres along a trajectory's path from its
// start, `t` metres to the left of it; a relative Orientation turns from the path's heading
// there. The path (TrajectoryPath, below) is built by the scenario language's code: map/
// knows no trajectory shapes.
class TrajectoryPath;
struct TrajectoryPosition {
  std::shared_ptr<const TrajectoryPath> path;
  double s = 0, t = 0;
  std::optional<Orientation> orientation;
};

// Every position of both languages: each reader produces its own kinds, the resolver
// resolves any of them given the geometry it needs.
using Position = std::variant<WaypointRef, RouteDistance, WorldPosition, RelativeWorldPosition, RelativeObjectPosition,
                              RoadPosition, RelativeRoadPosition, LanePosition, RelativeLanePosition, RoutePosition,
                              TrajectoryPosition, GeoPosition>;

// A trajectory's path for TrajectoryPosition: the positions its shape holds (vertices, control
// points, clothoid starts; checked and resolved by the caller) and its inertial points, in
// order along the path, given those positions resolved (same order). Throws MapError when the
// shape makes no path.
class TrajectoryPath {
 public:
  virtual ~TrajectoryPath() = default;
  [[nodiscard]] virtual std::string name() const = 0;
  [[nodiscard]] virtual std::vector<Position> positions() const = 0;
  [[nodiscard]] virtual std::vector<opendrive::Pose2> points(const std::vector<opendrive::Pose2>& resolved) const = 0;
};

struct RouteWaypoint {
  Position position;
  opendrive::RouteStrategy strategy = opendrive::RouteStrategy::Shortest;
};
struct RouteWaypoints {
  std::string name;
  std::vector<RouteWaypoint> waypoints;  // at least two
};

}  // namespace orch::position

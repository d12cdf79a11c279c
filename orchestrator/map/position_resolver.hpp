#pragma once
// Where a Position (map/position.hpp) is, for both scenario languages:
//  - OpenSCENARIO positions in the OpenDRIVE inertial frame, computed from the OpenDRIVE
//    geometry itself (never from SUMO's lane lengths, which differ from s on curves);
//  - ScenarioExecutor positions on the routes of a RoadEditor waypoint file.
// Pure: the entities a relative position refers to are asked of the caller (Entities), so
// map/ knows neither runtime.
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "map/position.hpp"
#include "map/waypoint_file.hpp"
#include "opendrive/geo_projection.hpp"
#include "opendrive/road_network.hpp"

namespace orch::position {

// A place on a RoadEditor route: arc length s along it.
struct RoutePlace {
  const WaypointRoute* route = nullptr;
  double s = 0;
};

struct ResolvedPosition {
  opendrive::Pose2 pose;  // x, y, heading of the entity's reference point
  // OpenDRIVE: the road point of the position (road, s, t, lane) when it lies on a road.
  std::optional<opendrive::RoadCoordinate> road;
  std::optional<int> lane;
  // Waypoint maps: the route place of the position.
  std::optional<RoutePlace> route;
};

// What a relative position needs to know of the entity (actor) it names.
class Entities {
 public:
  virtual ~Entities() = default;
  // Pose of its reference point; nullopt when it has none yet.
  [[nodiscard]] virtual std::optional<opendrive::Pose2> pose(const std::string& name) const = 0;
  // Waypoint maps (RouteDistance): the route it drives, its length.
  [[nodiscard]] virtual const WaypointRoute* route(const std::string& /*name*/) const { return nullptr; }
  [[nodiscard]] virtual double length(const std::string& /*name*/) const { return 0.0; }
};

// Pose of an entity's reference point by name; nullopt when the entity has none yet.
using EntityPoseLookup = std::function<std::optional<opendrive::Pose2>(const std::string&)>;

// Lane id `d_lane` lanes from `lane` counted in lane ids (positive = towards higher ids),
// skipping the centre lane 0.
int shifted_lane(int lane, int d_lane);

class PositionResolver {
 public:
  explicit PositionResolver(const opendrive::RoadNetwork& roads) : roads_(&roads) {}
  explicit PositionResolver(const WaypointFile& waypoints) : waypoints_(&waypoints) {}
  // Throws MapError (no such road or lane, an entity without a position, a position of the
  // other language's geometry) or ScenarioError (no such route, at the reference) naming
  // what is missing. `own_length`: the length of the entity being placed (RouteDistance
  // measured surface to surface).
  [[nodiscard]] ResolvedPosition resolve(const Position& position, const Entities& entities,
                                         double own_length = 0.0) const;
  [[nodiscard]] ResolvedPosition resolve(const Position& position, const EntityPoseLookup& entity_pose) const;
  // OpenDRIVE: the road point and lane of an inertial point (the nearest road).
  [[nodiscard]] ResolvedPosition locate(const opendrive::Pose2& pose) const;
  // Waypoint maps: the route a WaypointRef names (ScenarioError at the reference if none),
  // and its place on it (past the route's end: the last point).
  [[nodiscard]] const WaypointRoute& route(const WaypointRef& ref) const;
  [[nodiscard]] RoutePlace place(const WaypointRef& ref) const;

 private:
  [[nodiscard]] const opendrive::RoadNetwork& roads() const;
  [[nodiscard]] const WaypointFile& waypoints() const;
  [[nodiscard]] ResolvedPosition resolve_on_route(const RoutePosition& position, const Entities& entities) const;
  [[nodiscard]] ResolvedPosition resolve_on_trajectory(const TrajectoryPosition& position,
                                                       const Entities& entities) const;
  [[nodiscard]] ResolvedPosition resolve_geo(const GeoPosition& position) const;
  const opendrive::RoadNetwork* roads_ = nullptr;
  const WaypointFile* waypoints_ = nullptr;
  // Made on the first GeoPosition (PROJ reads its database then), shared by copies.
  mutable std::shared_ptr<const opendrive::GeoProjection> geo_;
};

}  // namespace orch::position

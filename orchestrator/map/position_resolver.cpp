#include "map/position_resolver.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "core/errors.hpp"
#include "map/route_path.hpp"
#include "opendrive/lane_graph.hpp"

namespace orch::position {
namespace {

using opendrive::Pose2;

// The heading an Orientation gives, relative to `reference` (road or entity heading).
double oriented(const std::optional<Orientation>& orientation, double reference) {
  if (!orientation) return reference;
  return orientation->relative ? reference + orientation->h : orientation->h;
}

// A caller's pose lookup as Entities (OpenDRIVE positions need only poses).
class PoseLookupEntities final : public Entities {
 public:
  explicit PoseLookupEntities(const EntityPoseLookup& lookup) : lookup_(lookup) {}
  [[nodiscard]] std::optional<Pose2> pose(const std::string& name) const override { return lookup_(name); }

 private:
  const EntityPoseLookup& lookup_;
};

ResolvedPosition on_route(const WaypointRoute& route, double s) {
  const Vec2 p = route.line.point_at(s);
  return ResolvedPosition{Pose2{p.x(), p.y(), route.line.heading_at(s)}, std::nullopt, std::nullopt,
                          RoutePlace{&route, s}};
}

// The s reached from s0 by moving `distance` (+ along s) along the centre line of `lane`:
// the centre's inertial points every 0.1 m of s, their chord lengths summed (exact to well
// below a millimetre on the arcs and spirals of real roads), the last step interpolated.
// Past the road's ends: a MapError, as for a ds that leaves the road.
double s_along_lane_centre(const opendrive::Road& road, int lane, double s0, double distance) {
  constexpr double kStep = 0.1;
  const double direction = distance < 0 ? -1.0 : 1.0;
  const auto centre = [&](double s) { return road.world(s, road.lane_center_t(lane, s)); };
  double s = s0;
  double left = std::abs(distance);
  Pose2 at = centre(s);
  while (left > 1e-9) {
    const double next = s + direction * kStep;
    if (next < -1e-9 || next > road.length + 1e-9)
      throw MapError(fmt::format("dsLane={:.3f} from s={:.3f} along lane {} leaves road {} (length {:.3f})", distance,
                                 s0, lane, road.id, road.length));
    const Pose2 ahead = centre(std::clamp(next, 0.0, road.length));
    const double chord = std::hypot(ahead.x - at.x, ahead.y - at.y);
    if (chord >= left) return s + direction * kStep * (left / chord);
    left -= chord;
    s = next;
    at = ahead;
  }
  return s;
}

}  // namespace

const opendrive::RoadNetwork& PositionResolver::roads() const {
  if (!roads_) throw MapError("an OpenSCENARIO position needs OpenDRIVE roads, and this scenario has a waypoint map");
  return *roads_;
}

const WaypointFile& PositionResolver::waypoints() const {
  if (!waypoints_) throw MapError("a waypoint position needs a RoadEditor waypoint map, and this scenario has OpenDRIVE roads");
  return *waypoints_;
}

const WaypointRoute& PositionResolver::route(const WaypointRef& ref) const {
  const WaypointRoute* r = waypoints().find(ref.wp_id);
  if (!r) throw ScenarioError(ref.where, "no route \"" + ref.wp_id + "\" in the map's waypoint file");
  return *r;
}

RoutePlace PositionResolver::place(const WaypointRef& ref) const {
  const WaypointRoute& r = route(ref);
  return {&r, r.s_of(std::min(ref.wp_idx, r.last_index()))};
}

ResolvedPosition PositionResolver::resolve(const Position& position, const EntityPoseLookup& entity_pose) const {
  return resolve(position, PoseLookupEntities(entity_pose));
}

int shifted_lane(int lane, int d_lane) {
  int result = lane + d_lane;
  if (lane < 0 && result >= 0) ++result;
  if (lane > 0 && result <= 0) --result;
  return result;
}

ResolvedPosition PositionResolver::resolve_on_trajectory(const TrajectoryPosition& position,
                                                          const Entities& entities) const {
  std::vector<Pose2> resolved;
  for (const Position& p : position.path->positions()) resolved.push_back(resolve(p, entities).pose);
  const std::vector<Pose2> points = position.path->points(resolved);
  // Along the polyline through the points: the segment holding s, its heading.
  double along = 0;
  for (std::size_t i = 1; i < points.size(); ++i) {
    const double dx = points[i].x - points[i - 1].x;
    const double dy = points[i].y - points[i - 1].y;
    const double length = std::hypot(dx, dy);
    if (length < 1e-9) continue;
    const bool last = i + 1 == points.size();
    if (position.s <= along + length + 1e-9 || (last && position.s <= along + length + 1e-6)) {
      const double f = std::clamp((position.s - along) / length, 0.0, 1.0);
      const double heading = std::atan2(dy, dx);
      const double x = points[i - 1].x + f * dx - std::sin(heading) * position.t;
      const double y = points[i - 1].y + f * dy + std::cos(heading) * position.t;
      return locate(Pose2{x, y, oriented(position.orientation, heading)});
    }
    along += length;
  }
  throw MapError(fmt::format("s={:.3f} is beyond the end of trajectory \"{}\" (length {:.3f})", position.s,
                             position.path->name(), along));
}

ResolvedPosition PositionResolver::resolve_geo(const GeoPosition& position) const {
  if (!geo_) geo_ = std::make_shared<const opendrive::GeoProjection>(roads().geo_reference());
  const Vec2 p = geo_->local({position.latitude_deg, position.longitude_deg});
  ResolvedPosition r = locate(Pose2{p.x(), p.y(), 0.0});
  r.pose.heading = oriented(position.orientation, r.road ? r.road->road_heading : 0.0);
  return r;
}

ResolvedPosition PositionResolver::locate(const Pose2& pose) const {
  ResolvedPosition r{pose, roads().to_road(pose.x, pose.y), std::nullopt, std::nullopt};
  if (r.road) r.lane = roads().road(r.road->road_id).lane_at(r.road->s, r.road->t);
  return r;
}

ResolvedPosition PositionResolver::resolve(const Position& position, const Entities& entities,
                                           double own_length) const {
  const auto pose_of = [&](const std::string& entity) {
    const auto p = entities.pose(entity);
    if (!p) throw MapError(fmt::format("entity \"{}\" has no position yet to place another relative to it", entity));
    return *p;
  };
  const auto on_road = [&](const opendrive::Road& road, double s, double t, double heading) {
    if (s < 0 || s > road.length)
      throw MapError(fmt::format("s={:.3f} is outside road {} (length {:.3f})", s, road.id, road.length));
    Pose2 p = road.world(s, t);
    const double road_heading = p.heading;
    p.heading = heading;
    return ResolvedPosition{p, opendrive::RoadCoordinate{road.id, s, t, road_heading}, road.lane_at(s, t), std::nullopt};
  };
  return std::visit(
      [&](const auto& kind) -> ResolvedPosition {
        using T = std::decay_t<decltype(kind)>;
        if constexpr (std::is_same_v<T, WaypointRef>) {
          const RoutePlace at = place(kind);
          return on_route(*at.route, at.s);
        } else if constexpr (std::is_same_v<T, RouteDistance>) {
          // Along the route from the point of it nearest the target (bumper to bumper:
          // half of both lengths further).
          const Pose2 target = pose_of(kind.target);
          const WaypointRoute* r = kind.route ? &route(*kind.route) : entities.route(kind.target);
          if (!r) throw MapError(fmt::format("actor {} drives no route to measure a distance along", kind.target));
          double offset = kind.distance;
          if (kind.surface) {
            const double halves = (own_length + entities.length(kind.target)) / 2;
            offset += offset >= 0 ? halves : -halves;
          }
          return on_route(*r, r->line.project(Vec2{target.x, target.y}).s + offset);
        } else if constexpr (std::is_same_v<T, WorldPosition>) {
          return locate(Pose2{kind.x, kind.y, kind.h.value_or(0.0)});
        } else if constexpr (std::is_same_v<T, RelativeWorldPosition>) {
          const Pose2 e = pose_of(kind.entity);
          return locate(Pose2{e.x + kind.dx, e.y + kind.dy, oriented(kind.orientation, e.heading)});
        } else if constexpr (std::is_same_v<T, RelativeObjectPosition>) {
          const Pose2 e = pose_of(kind.entity);
          const double c = std::cos(e.heading);
          const double s = std::sin(e.heading);
          return locate(Pose2{e.x + c * kind.dx - s * kind.dy, e.y + s * kind.dx + c * kind.dy,
                              oriented(kind.orientation, e.heading)});
        } else if constexpr (std::is_same_v<T, RoadPosition>) {
          const opendrive::Road& road = roads().road(kind.road_id);
          const double heading = road.plan_view.pose(kind.s).heading;
          return on_road(road, kind.s, kind.t, oriented(kind.orientation, heading));
        } else if constexpr (std::is_same_v<T, RelativeRoadPosition>) {
          const ResolvedPosition from = locate(pose_of(kind.entity));
          if (!from.road) throw MapError(fmt::format("entity \"{}\" is on no road", kind.entity));
          const opendrive::Road& road = roads().road(from.road->road_id);
          const double s = from.road->s + kind.ds;
          return on_road(road, s, from.road->t + kind.dt, oriented(kind.orientation, road.plan_view.pose(s).heading));
        } else if constexpr (std::is_same_v<T, LanePosition>) {
          const opendrive::Road& road = roads().road(kind.road_id);
          // A relative Orientation of a LanePosition turns from the lane's driving direction
          // (the road's s, turned round on a lane that drives against it), as esmini reads
          // it; the standard is ambiguous here: its Orientation says "aligned with the
          // direction of the reference lane or road s-axis", LanePosition's orientation "the
          // referenced road's s and t coordinates". Real files are written so (esmini's
          // left-hand-traffic_by_heading.xosc: h=pi on lane 3 to drive with s; a pedestrian on
          // lane 3 with h=0 walking against s). The Relative*Position and RoadPosition keep the
          // road's s, as in esmini.
          const double along = road.plan_view.pose(kind.s).heading +
                               (opendrive::lane_direction(road, kind.lane_id) < 0 ? std::numbers::pi : 0.0);
          return on_road(road, kind.s, road.lane_center_t(kind.lane_id, kind.s) + kind.offset,
                         oriented(kind.orientation, along));
        } else if constexpr (std::is_same_v<T, RoutePosition>) {
          return resolve_on_route(kind, entities);
        } else if constexpr (std::is_same_v<T, TrajectoryPosition>) {
          return resolve_on_trajectory(kind, entities);
        } else if constexpr (std::is_same_v<T, GeoPosition>) {
          return resolve_geo(kind);
        } else {  // RelativeLanePosition
          const ResolvedPosition from = locate(pose_of(kind.entity));
          if (!from.road || !from.lane)
            throw MapError(fmt::format("entity \"{}\" is on no lane", kind.entity));
          const opendrive::Road& road = roads().road(from.road->road_id);
          const double s = kind.ds_lane ? s_along_lane_centre(road, *from.lane, from.road->s, *kind.ds_lane)
                                        : from.road->s + kind.ds;
          const int lane = shifted_lane(*from.lane, kind.d_lane);
          if (s < 0 || s > road.length)
            throw MapError(fmt::format("s={:.3f} is outside road {} (length {:.3f})", s, road.id, road.length));
          return on_road(road, s, road.lane_center_t(lane, s) + kind.offset,
                         oriented(kind.orientation, road.plan_view.pose(s).heading));
        }
      },
      position);
}

ResolvedPosition PositionResolver::resolve_on_route(const RoutePosition& position, const Entities& entities) const {
  if (const auto* current = std::get_if<InRouteFromEntity>(&position.in_route)) {
    // The entity's own place (the standard: it is on the route); an Orientation turns it.
    const auto pose = entities.pose(current->entity);
    if (!pose)
      throw MapError(fmt::format("entity \"{}\" has no position yet to place another relative to it", current->entity));
    return locate(Pose2{pose->x, pose->y, oriented(position.orientation, pose->heading)});
  }
  const RouteWaypoints& route = *position.route;
  std::vector<opendrive::RoutePoint> points;
  std::vector<opendrive::RouteStrategy> strategies;
  for (std::size_t i = 0; i < route.waypoints.size(); ++i) {
    const ResolvedPosition w = resolve(route.waypoints[i].position, entities);
    if (!w.road || !w.lane || *w.lane == 0)
      throw MapError(fmt::format("route \"{}\": waypoint {} (x {:.3f}, y {:.3f}) is on no lane of the road network",
                                 route.name, i + 1, w.pose.x, w.pose.y));
    points.push_back({w.road->road_id, w.road->s, *w.lane});
    strategies.push_back(route.waypoints[i].strategy);
  }
  const RoutePath path = route_path(roads(), points, strategies, route.name);
  const bool by_lane = std::holds_alternative<InRouteFromLane>(position.in_route);
  const double path_s = by_lane ? std::get<InRouteFromLane>(position.in_route).path_s
                                : std::get<InRouteFromRoad>(position.in_route).path_s;
  const PathPlace at = place_on_path(path, path_s, route.name);
  const opendrive::Road& road = roads().road(at.road_id);
  // Facing the way the route drives (the road's heading, turned round where the route runs
  // against s); an Orientation is relative to that.
  const double along = road.plan_view.pose(at.s).heading + (at.direction < 0 ? std::numbers::pi : 0.0);
  double t = 0;
  if (by_lane) {
    const auto& lane = std::get<InRouteFromLane>(position.in_route);
    t = road.lane_center_t(lane.lane_id, at.s) + lane.lane_offset;
  } else {
    t = std::get<InRouteFromRoad>(position.in_route).t;
  }
  Pose2 p = road.world(at.s, t);
  const double road_heading = p.heading;
  p.heading = oriented(position.orientation, along);
  return ResolvedPosition{p, opendrive::RoadCoordinate{road.id, at.s, t, road_heading}, road.lane_at(at.s, t),
                          std::nullopt};
}

}  // namespace orch::position

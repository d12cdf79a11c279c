// Position: the ten kinds of OpenSCENARIO 1.0-1.3, resolved on OpenDRIVE roads
// (map/position_resolver.hpp).
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "openscenario/reader_context.hpp"
#include "openscenario/trajectory_position.hpp"

namespace orch::openscenario::reading {
namespace {

std::optional<Orientation> read_orientation(Element& owner) {
  auto element = owner.optional_child("Orientation");
  if (!element) return std::nullopt;
  Orientation o;
  o.relative = element->optional_choice<bool>("type", {{"relative", true}, {"absolute", false}}).value_or(true);
  o.h = element->optional_number("h").value_or(0.0);
  // Pitch and roll are read (they must be numbers) but not used: positions are resolved in
  // the road plane (x, y, heading); a road's elevation and superelevation give them where
  // the map resolves z, pitch and roll (docs/openscenario.md).
  for (const char* angle : {"p", "r"}) (void)element->optional_number(angle);
  element->finish();
  return o;
}

thread_local Context* context_in_use = nullptr;

RoutePosition read_route_position(Element& p) {
  if (!context_in_use) p.fail("a RoutePosition is read only within a scenario file");
  RoutePosition r;
  Element ref = p.child("RouteRef");
  r.route = read_route_ref(ref, *context_in_use);
  r.orientation = read_orientation(p);
  Element holder = p.child("InRoutePosition");
  Element in = holder.one_of({"FromCurrentEntity", "FromRoadCoordinates", "FromLaneCoordinates"});
  holder.finish();
  const auto path_s = [&in] {
    const double s = in.number("pathS");
    if (s < 0) in.fail_attribute("pathS", "pathS cannot be negative (it is measured from the route's first waypoint)");
    return s;
  };
  if (in.name() == "FromCurrentEntity") {
    r.in_route = InRouteFromEntity{in.text("entityRef")};
  } else if (in.name() == "FromRoadCoordinates") {
    r.in_route = InRouteFromRoad{path_s(), in.number("t")};
  } else {
    r.in_route = InRouteFromLane{path_s(), in.integer("laneId"), in.optional_number("laneOffset").value_or(0.0)};
  }
  in.finish();
  return r;
}

// TrajectoryPosition (1.1): s along the trajectory's path (not negative), t to its left
// (default 0), an optional Orientation (relative: to the path's heading at s).
TrajectoryPosition read_trajectory_position(Element& p) {
  if (!context_in_use) p.fail("a TrajectoryPosition is read only within a scenario file");
  TrajectoryPosition r;
  r.s = p.number("s");
  if (r.s < 0) p.fail_attribute("s", "s cannot be negative (it is measured from the trajectory's start)");
  r.t = p.optional_number("t").value_or(0.0);
  r.orientation = read_orientation(p);
  Element ref = p.child("TrajectoryRef");
  r.path = trajectory_path_of(read_trajectory_ref(ref, *context_in_use));
  return r;
}

// GeoPosition: 1.2 gives degrees (latitudeDeg, longitudeDeg); 1.0 and 1.1 radians (latitude,
// longitude, deprecated since 1.2 but valid). Height, altitude and verticalRoadSelection are
// read but not used: positions are resolved in the road plane, on its surface.
GeoPosition read_geo_position(Element& p) {
  const auto angle = [&p](const char* degrees, const char* radians, double limit) {
    if (p.has(degrees) && p.has(radians))
      p.fail_attribute(radians, fmt::format("{} and {} give the same angle twice: give one", degrees, radians));
    const char* given = p.has(degrees) ? degrees : radians;
    if (!p.has(given))
      p.fail(fmt::format("a GeoPosition needs {} (degrees, OpenSCENARIO 1.2) or {} (radians, 1.0 and 1.1)", degrees,
                         radians));
    const double value = given == degrees ? p.number(degrees) : p.number(radians) * 180.0 / std::numbers::pi;
    if (std::abs(value) > limit)
      p.fail_attribute(given, fmt::format("{} degrees is outside [-{}, {}]", value, limit, limit));
    return value;
  };
  GeoPosition g;
  g.latitude_deg = angle("latitudeDeg", "latitude", 90.0);
  g.longitude_deg = angle("longitudeDeg", "longitude", 180.0);
  p.ignore_attributes({"height", "altitude", "verticalRoadSelection"});
  g.orientation = read_orientation(p);
  return g;
}

Position read_kind(Element& p) {
  const std::string_view kind = p.name();
  if (kind == "GeoPosition") return read_geo_position(p);
  if (kind == "TrajectoryPosition") return read_trajectory_position(p);
  if (kind == "WorldPosition") {
    WorldPosition w{p.number("x"), p.number("y"), p.optional_number("h"), p.optional_number("z")};
    p.ignore_attributes({"p", "r"});
    return w;
  }
  if (kind == "RelativeWorldPosition") {
    return RelativeWorldPosition{p.text("entityRef"), p.number("dx"), p.number("dy"), read_orientation(p),
                                 p.optional_number("dz").value_or(0.0)};
  }
  if (kind == "RelativeObjectPosition") {
    return RelativeObjectPosition{p.text("entityRef"), p.number("dx"), p.number("dy"), read_orientation(p),
                                  p.optional_number("dz").value_or(0.0)};
  }
  if (kind == "RoadPosition")
    return RoadPosition{p.text("roadId"), p.number("s"), p.number("t"), read_orientation(p)};
  if (kind == "RelativeRoadPosition")
    return RelativeRoadPosition{p.text("entityRef"), p.number("ds"), p.number("dt"), read_orientation(p)};
  if (kind == "RoutePosition") return read_route_position(p);
  if (kind == "LanePosition")
    return LanePosition{p.text("roadId"), p.integer("laneId"), p.number("s"), p.optional_number("offset").value_or(0.0),
                        read_orientation(p)};
  // RelativeLanePosition: ds (along the road's s) or dsLane (1.1+: along the centre line of
  // the reference entity's lane); the standard makes them mutually exclusive, 1.0 has only ds.
  RelativeLanePosition r{p.text("entityRef"), p.integer("dLane"), 0.0, p.optional_number("offset").value_or(0.0),
                         read_orientation(p), std::nullopt};
  if (p.has("ds") && p.has("dsLane")) p.fail_attribute("dsLane", "ds and dsLane are mutually exclusive: give one");
  if (p.has("dsLane")) r.ds_lane = p.number("dsLane");
  else if (p.has("ds")) r.ds = p.number("ds");
  else p.fail("a RelativeLanePosition needs ds or dsLane");
  return r;
}

}  // namespace

ContextInUse::ContextInUse(Context& context) : previous_(context_in_use) { context_in_use = &context; }
ContextInUse::~ContextInUse() { context_in_use = previous_; }

Position read_position(Element& position) {
  Element p = position.one_of({"WorldPosition", "RelativeWorldPosition", "RelativeObjectPosition", "RoadPosition",
                               "RelativeRoadPosition", "LanePosition", "RelativeLanePosition", "RoutePosition",
                               "TrajectoryPosition", "GeoPosition"});
  position.finish();
  Position result = read_kind(p);
  p.finish();
  return result;
}

}  // namespace orch::openscenario::reading

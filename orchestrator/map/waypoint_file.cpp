#include "map/waypoint_file.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <optional>

#include "core/errors.hpp"
#include "json/object_file.hpp"
#include "map/waypoint_file_stream.hpp"

namespace orch {

double WaypointRoute::speed_at(double s) const {
  if (points.empty()) return 0;
  std::size_t lo = 0;
  std::size_t hi = points.size() - 1;
  // Last point whose arc length is <= s (points are in driving order).
  while (lo < hi) {
    const std::size_t mid = (lo + hi + 1) / 2;
    if (line.s_at_index(mid) <= s) lo = mid;
    else hi = mid - 1;
  }
  return points[lo].v;
}

const WaypointRoute* WaypointFile::find(std::string_view route_id) const {
  for (const auto& r : routes)
    if (r.id == route_id) return &r;
  return nullptr;
}

std::vector<std::string> WaypointFile::route_ids() const {
  std::vector<std::string> ids;
  for (const auto& r : routes) ids.push_back(r.id);
  return ids;
}

// Ends a route read by either path: its polyline, or why it has none.
std::optional<std::string> complete_route(WaypointRoute& route, std::vector<Vec2> xy) {
  if (xy.size() < 2) return fmt::format("route \"{}\" needs at least two points", route.id);
  try {
    route.line = Polyline(std::move(xy));
  } catch (const std::invalid_argument&) {
    return fmt::format("route \"{}\" has all its points in one place", route.id);
  }
  return std::nullopt;
}

// The file's point (x, y up, z towards the viewer; v in km/h) in the map frame.
WaypointPoint map_point(double x, std::optional<double> y, double z, std::optional<double> v) {
  return {x, -z, y.value_or(0.0), v.value_or(0.0) / 3.6};
}

// The reader for every file: a value tree with line numbers, so that every problem is
// reported with its place.
WaypointFile read_waypoint_file_with_messages(const std::string& path) {
  JsonObjectFile json(path, "waypoint file");
  const JsonDocument& doc = json.doc();
  Diagnostics& diags = json.diags();
  WaypointFile file;
  file.path = path;
  ObjectReader& top = json.top();
  file.id = top.string("id", Need::Optional).value_or("");
  file.map_id = top.string("mapId", Need::Optional).value_or("");
  const auto* routes = top.array("waypoints", Need::Required);
  const auto* props = top.array("properties", Need::Optional);
  top.finish();

  if (routes) {
    const std::string routes_ptr = top.child("waypoints");
    for (std::size_t i = 0; i < routes->size(); ++i) {
      const std::string rptr = json_pointer_child(routes_ptr, i);
      ObjectReader r(doc, (*routes)[i], rptr, diags, "waypoint route");
      WaypointRoute route;
      route.id = r.string("id", Need::Required).value_or("");
      const auto* points = r.array("points", Need::Required);
      r.finish();
      if (!route.id.empty() && file.find(route.id))
        r.error("id", fmt::format("route id \"{}\" is used twice", route.id));
      if (!points) continue;
      std::vector<Vec2> xy;
      for (std::size_t k = 0; k < points->size(); ++k) {
        ObjectReader p(doc, (*points)[k], json_pointer_child(r.child("points"), k), diags, "waypoint");
        const auto x = p.number("x", Need::Required, Quantity::Coordinate);
        const auto y = p.number("y", Need::Optional, Quantity::Coordinate);
        const auto z = p.number("z", Need::Required, Quantity::Coordinate);
        const auto v = p.number("v", Need::Optional, Quantity::SpeedKmh);
        p.finish();
        if (!x || !z) continue;
        route.points.push_back(map_point(*x, y, *z, v));
        xy.emplace_back(route.points.back().x, route.points.back().y);
      }
      if (const auto problem = complete_route(route, std::move(xy))) {
        r.error("points", *problem);
        continue;
      }
      file.routes.push_back(std::move(route));
    }
  }
  if (props) {
    for (std::size_t i = 0; i < props->size(); ++i) {
      ObjectReader p(doc, (*props)[i], json_pointer_child(top.child("properties"), i), diags, "property");
      WaypointProperty prop;
      prop.id = p.string("id", Need::Optional).value_or("");
      prop.name = p.string("name", Need::Optional).value_or("");
      prop.index = p.number("index", Need::Optional).value_or(0);
      prop.waypoint_id = p.string("waypointId", Need::Optional).value_or("");
      p.finish();
      file.properties.push_back(prop);
    }
  }
  json.throw_if_errors();
  if (file.routes.empty()) throw ScenarioError(doc.where("/waypoints"), "the waypoint file has no routes");
  return file;
}

WaypointFile load_waypoint_file(const std::string& path) {
  // A waypoint file holds tens of thousands of points (2 MB for ALKS_Road): read in one pass
  // when it is well formed, and again with the value tree only to say what is wrong.
  if (auto file = read_well_formed_waypoint_file(path)) return std::move(*file);
  return read_waypoint_file_with_messages(path);
}

}  // namespace orch

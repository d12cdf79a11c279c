#pragma once
// A RoadEditor "Export Waypoint" file: named routes of points drawn along lanes.
// Coordinates are converted on load to the map frame used everywhere else:
// map x = file x, map y = -file z (three.js is Y-up), height = file y.
#include <string>
#include <string_view>
#include <vector>

#include "core/polyline.hpp"

namespace orch {

struct WaypointPoint {
  double x = 0;       // map frame, m
  double y = 0;       // map frame, m
  double height = 0;  // m
  double v = 0;       // target speed at this point, m/s (the file says km/h)
};

struct WaypointRoute {
  std::string id;
  std::vector<WaypointPoint> points;
  Polyline line;  // the points in the map frame, in driving order

  // Arc length of a (possibly fractional) waypoint index, clamped to the route.
  [[nodiscard]] double s_of(double wp_idx) const { return line.s_at_fractional_index(wp_idx); }
  // Target speed (m/s) at arc length s: the value of the point at or before s.
  [[nodiscard]] double speed_at(double s) const;
  [[nodiscard]] double last_index() const { return static_cast<double>(points.size() - 1); }
};

struct WaypointProperty {
  std::string id;
  std::string name;
  double index = 0;
  std::string waypoint_id;
};

struct WaypointFile {
  std::string path;
  std::string id;      // e.g. "WayPoint_ALKS.Road"
  std::string map_id;  // the file's own "mapId", e.g. "ALKS.Road"
  std::vector<WaypointRoute> routes;
  std::vector<WaypointProperty> properties;

  [[nodiscard]] const WaypointRoute* find(std::string_view route_id) const;
  [[nodiscard]] std::vector<std::string> route_ids() const;
};

// Throws ScenarioError (file, line, JSON pointer) when the file is not a valid waypoint file.
WaypointFile load_waypoint_file(const std::string& path);

}  // namespace orch

#pragma once
// Building synthetic and shipped maps for the map integration tests (real netconvert).
#include <pugixml.hpp>

#include <filesystem>
#include <string>
#include <vector>

#include "core/files.hpp"
#include "map/lane_map.hpp"
#include "map/map_registry.hpp"
#include "map/net_builder.hpp"
#include "map/waypoint_file.hpp"
#include "unit/synthetic_roads.hpp"

namespace orch::test {

inline std::filesystem::path shipped_map_dir(const std::string& id) {
  return std::filesystem::path(ORCH_SOURCE_DIR) / "sumo_nets" / id;
}

// A map folder in a temp dir, built from synthetic routes.
struct BuiltMap {
  MapManifest manifest;
  WaypointFile waypoints;
  NetBuildReport report;

  [[nodiscard]] std::string net() const { return manifest.net_path().string(); }
  [[nodiscard]] LaneMap lanes() const { return LaneMap::build(net(), waypoints); }
};

inline BuiltMap build_synthetic(const TempDir& dir, const std::string& id, const std::vector<SyntheticRoute>& routes) {
  BuiltMap m;
  m.manifest.id = id;
  m.manifest.dir = dir.path() / id;
  std::filesystem::create_directories(m.manifest.dir);
  m.manifest.waypoint_file = write_waypoint_file(m.manifest.dir, id, routes).filename().string();
  m.manifest.net_file = id + ".net.xml";
  save_map_manifest(m.manifest);
  m.waypoints = load_waypoint_file(m.manifest.waypoint_path().string());
  m.report = build_net(m.manifest, m.waypoints);
  return m;
}

// Largest distance between a waypoint and the centre of its lane, over all routes.
inline double max_waypoint_distance(const LaneMap& lanes, const WaypointFile& waypoints) {
  double worst = 0;
  for (const auto& r : waypoints.routes)
    for (const auto& p : lanes.route(r.id)->points) worst = std::max(worst, p.distance);
  return worst;
}

// The net's normal (non-internal) edges, in file order.
inline std::vector<pugi::xml_node> normal_edges(const pugi::xml_document& doc) {
  std::vector<pugi::xml_node> out;
  for (const auto e : doc.child("net").children("edge"))
    if (std::string(e.attribute("function").as_string()).empty()) out.push_back(e);
  return out;
}

// Connections between normal edges as "from_lane->to_lane" strings, e.g. "a#0_1->a#1_1".
inline std::vector<std::string> lane_connections(const pugi::xml_document& doc) {
  std::vector<std::string> out;
  for (const auto c : doc.child("net").children("connection")) {
    const std::string from = c.attribute("from").as_string();
    if (!from.empty() && from[0] == ':') continue;
    out.push_back(from + "_" + c.attribute("fromLane").as_string() + "->" + c.attribute("to").as_string() + "_" +
                  c.attribute("toLane").as_string());
  }
  return out;
}

}  // namespace orch::test

#pragma once
// Finds maps by id or alias. A map is a folder under sumo_nets/ with a map.json naming its
// waypoint file and SUMO net; a scenario's map_id may be the folder's id or any alias
// (such as the waypoint file's own mapId).
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "map/junction_plan.hpp"

namespace orch {

// Edge length limit of maps created by `map build --waypoints` (net_plan.hpp says why).
inline constexpr double kDefaultMaxEdgeLength = 250.0;  // m

struct MapManifest {
  std::string id;
  std::vector<std::string> aliases;
  std::string description;
  std::filesystem::path dir;        // folder holding map.json
  std::string waypoint_file;        // relative to dir
  std::string net_file;             // relative to dir
  double lane_extension = 20.0;     // m the lanes reach beyond the first/last waypoint
  double simplify_tolerance = 0.02; // m, lane shapes vs. waypoints
  // m, longer stretches become several edges (net_plan.hpp); 0 = never. New map folders get
  // kDefaultMaxEdgeLength; a map.json without the setting keeps its single long edges.
  double max_edge_length = 0;
  // Junction types and right of way set by the user (docs/maps.md; "junctions" in map.json).
  JunctionSettings junctions;

  [[nodiscard]] std::filesystem::path waypoint_path() const { return dir / waypoint_file; }
  [[nodiscard]] std::filesystem::path net_path() const { return dir / net_file; }
};

// Reads DIR/map.json; throws MapError / ScenarioError naming the problem.
MapManifest load_map_manifest(const std::filesystem::path& dir);
// Writes DIR/map.json (atomically).
void save_map_manifest(const MapManifest& manifest);

class MapRegistry {
 public:
  // Every immediate subfolder with a map.json in each search directory.
  explicit MapRegistry(const std::vector<std::filesystem::path>& search_dirs);
  // The default search path: $ORCH_MAPS (colon-separated), then the source tree's sumo_nets.
  static std::vector<std::filesystem::path> default_search_dirs();

  [[nodiscard]] const MapManifest* find(std::string_view id_or_alias) const;
  [[nodiscard]] std::vector<std::string> ids() const;  // ids and aliases, for "did you mean"
  [[nodiscard]] const std::vector<MapManifest>& maps() const { return maps_; }

 private:
  std::vector<MapManifest> maps_;
};

}  // namespace orch

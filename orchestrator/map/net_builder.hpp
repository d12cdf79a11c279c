#pragma once
// `map build`: turns a RoadEditor waypoint file into a SUMO network whose lanes lie under
// the routes. Parallel routes in the same direction become lanes of one edge (ordered right
// to left); routes in the opposite direction become edges of their own; where the set of
// parallel routes changes along the road, the road is split into consecutive edges. The
// plain XML (nodes, edges, connections) is generated here and SUMO's netconvert builds the
// net from it.
#include <filesystem>
#include <string>
#include <vector>

#include "map/map_registry.hpp"
#include "map/waypoint_file.hpp"

namespace orch {

struct NetBuildReport {
  int corridors = 0;  // groups of parallel routes
  int junctions = 0;
  int edges = 0;
  int lanes = 0;
  std::vector<int> edges_by_lanes;  // [n] = edges with n lanes
  std::filesystem::path picture;    // map.svg: the net with the routes over it
  std::vector<std::string> notes;  // human-readable remarks (routes left alone, ...)
};

// Builds manifest.net_path() from manifest.waypoint_path(). The plain XML is kept next to
// it in a "plain/" folder so that the net can be rebuilt and inspected. Throws MapError
// with netconvert's own message when netconvert fails.
NetBuildReport build_net(const MapManifest& manifest, const WaypointFile& waypoints);

}  // namespace orch

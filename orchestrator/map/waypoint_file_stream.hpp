#pragma once
// The two readers of a waypoint file (waypoint_file.cpp: with a value tree and messages;
// waypoint_file_stream.cpp: one streaming pass) and what they share, so that both give the
// same WaypointFile for the same text.
#include <optional>
#include <string>
#include <vector>

#include "map/waypoint_file.hpp"

namespace orch {

// The file's point (x, y up, z towards the viewer; v in km/h) in the map frame.
WaypointPoint map_point(double x, std::optional<double> y, double z, std::optional<double> v);
// Ends a route: its polyline from `xy`, or why it cannot have one.
std::optional<std::string> complete_route(WaypointRoute& route, std::vector<Vec2> xy);

// The file read with a value tree: every problem reported with its line and pointer.
WaypointFile read_waypoint_file_with_messages(const std::string& path);
// The file read in one streaming pass, without a value tree; nullopt as soon as anything is
// not as a well-formed waypoint file has it (then the caller reads it again with messages).
std::optional<WaypointFile> read_well_formed_waypoint_file(const std::string& path);

}  // namespace orch

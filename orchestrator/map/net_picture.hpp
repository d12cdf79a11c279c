#pragma once
// A picture of a planned net with the waypoint routes drawn over it (`map build` writes it
// as map.svg beside the net), so that a user sees at once whether the map matches the
// drawing: lanes grey at their width, junction interiors lighter, junctions named, each
// route a coloured line from a dot at its first waypoint. Hovering a lane or a route in a
// browser shows its id (SVG <title>). Coordinates are metres in the map frame.
#include <string>

#include "map/net_plan.hpp"
#include "map/waypoint_file.hpp"

namespace orch {

// Deterministic: the same plan and routes give the same bytes.
std::string net_picture_svg(const NetPlan& plan, const WaypointFile& routes);

}  // namespace orch

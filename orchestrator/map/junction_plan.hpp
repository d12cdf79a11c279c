#pragma once
// The junction step of `map build`, part 3: the SUMO junctions themselves. Every zone
// (junction_zones.hpp) becomes one SUMO node "J<n>"; every passage of a route through it
// becomes a connection from the lane before to the lane after, whose shape is the route's
// own points, so SUMO's internal lanes are the routes as drawn (not netconvert's curves).
// The node's shape runs through the corners of the lane ends it joins, in the order of their
// angle around the node, so that it touches each lane only at its end and netconvert keeps
// the lane shapes exactly (netconvert cuts a lane where its junction's shape crosses it).
// Where that shape would still cross one of its lanes (a lane leaving in the middle of a
// turn curves across the line to its neighbour's corner), it runs through the lane ends'
// centres, or out from the middle to each lane end and back, whichever cuts least.
//
// Right of way: a priority junction by default. Edges carry their number of lanes as SUMO
// priority, so the wider road has priority and netconvert picks the straightest pair among
// equals as the main road. map.json's "junctions" list sets a junction's type and which
// routes' roads have priority (docs/maps.md).
#include <optional>
#include <string>
#include <vector>

#include "core/polyline.hpp"
#include "map/net_plan.hpp"
#include "map/waypoint_file.hpp"

namespace orch {

// The SUMO junction types a user may choose (netconvert's names).
inline constexpr const char* kJunctionTypes[] = {"priority", "right_before_left", "allway_stop", "traffic_light"};

struct JunctionOverride {
  std::string id;              // "J3", or empty when `at` names the junction
  std::optional<Vec2> at;      // the junction nearest to this point (within kJunctionPickRadius)
  std::string type;            // one of kJunctionTypes, empty: unchanged
  std::vector<std::string> priority_routes;  // the roads these routes drive have priority
};
inline constexpr double kJunctionPickRadius = 30.0;  // m

struct JunctionSettings {
  std::vector<JunctionOverride> overrides;
};

}  // namespace orch

#pragma once
// Second step of `map build`: the SUMO network as plain values (nodes, edges with custom
// lane shapes, connections), computed from the waypoint routes alone. Pure geometry, no
// files and no SUMO, so that the algorithm can be tested on its own; net_builder.cpp
// writes it as netconvert's plain XML.
//
// Per corridor (route_corridors.hpp) the road is cut wherever a route starts or ends, so
// each stretch has a constant set of routes, and stretches longer than max_edge_length are
// cut into equal pieces; each stretch becomes one edge whose lanes are
// those routes ordered right to left (lane 0 = rightmost relative to the direction of
// travel). Lane shapes are the routes themselves, extended straight by `lane_extension`
// beyond their first and last waypoint, except where one lane is drawn as consecutive
// routes: those meet halfway between the last and first waypoint and are connected.
//
// Naming scheme (readable in sumo-gui and TraCI; characters SUMO forbids in ids become '_'):
//   corridor name  the corridor's route ids, right to left, joined with '+'
//                  ("Waypoint03+Waypoint02+Waypoint01"); "<rightmost>..<leftmost>" when
//                  that would exceed 60 characters; "~2", "~3" appended if two corridors
//                  would share a name.
//   edge           <corridor name>#<n>, n = 0, 1, ... in driving order
//   lane           SUMO's own: <edge>_<index>, index 0 = rightmost
//   node           <corridor name>@<k>, k = 0, 1, ... the cuts in driving order
//
// Branches, merges, crossings, lanes shared by several routes and closed loops are the
// junction step's (junction_zones.hpp, junction_pieces.hpp, junction_plan.hpp): it cuts the
// routes at their junctions and hands the pieces between junctions to this planner.
// What it does not model, and what happens instead:
//   - heights: lanes are planar (the file's y is dropped);
//   - left-hand traffic: lane 0 is always the rightmost lane (SUMO's right-hand default).
#include <string>
#include <vector>

#include "map/corridor_names.hpp"  // sumo_safe_id, used with the plan
#include "core/polyline.hpp"
#include "map/waypoint_file.hpp"

namespace orch {

inline constexpr double kDefaultLaneWidth = 3.5;     // m, a lane with no neighbour
inline constexpr double kFallbackLaneSpeed = 13.89;  // m/s (50 km/h) when a route has no v
// Cuts closer than this along a corridor are merged into one, so that routes that start or
// end "together" (a few metres apart on a curve) do not produce a string of tiny edges.
inline constexpr double kMaxCutMerge = 10.0;  // m

struct NetPlanSettings {
  double lane_extension = 20.0;     // m beyond the first and last waypoint of each route
  double simplify_tolerance = 0.02; // m, Douglas-Peucker on the lane shapes
  // Longer stretches are cut into equal edges no longer than this (0: never). SUMO's
  // sublane model scans every vehicle of a lane for each vehicle's followers
  // (MSLane::getFollowersOnConsecutive), so a step costs O(n^2) in the vehicles per lane:
  // measured on a 10 km, 3-lane road with 820 vehicles, 177 ms per step with one edge,
  // 32 ms with 500 m edges (docs/performance.md).
  double max_edge_length = 0;       // m
};

struct PlannedLane {
  std::string route_id;  // the waypoint route the lane lies under
  std::vector<std::string> routes;  // every route driving the lane (route_id first); empty = route_id only
  int piece = -1;        // junction maps: the lane piece it was planned from (junction_pieces.hpp)
  double width = kDefaultLaneWidth;
  double speed = kFallbackLaneSpeed;  // m/s
  Polyline shape;
};

struct PlannedNode {
  std::string id;
  Vec2 position;
  // Custom junction shape: a line across the road through the exact lane ends (there and
  // back, so that the polygon netconvert closes it into has no other edges). netconvert
  // cuts every lane shape, custom ones included, where it enters the junction shape; with
  // its own junction shapes (or any shape with an area) that cuts 0.1-0.3 m off the lanes
  // and leaves waypoints beside no lane. A shape that touches the lanes only at their ends
  // leaves them exactly as planned.
  std::vector<Vec2> shape;
  std::string type;  // SUMO junction type ("priority", "traffic_light", ...); empty: netconvert's choice
};

struct PlannedEdge {
  std::string id;
  std::string from;
  std::string to;
  std::vector<PlannedLane> lanes;  // index 0 = rightmost
  // Centre line of the road: SUMO derives the directions of connections from it.
  std::vector<Vec2> shape;
  int priority = -1;  // SUMO edge priority at junctions (-1: not written)
};

struct PlannedConnection {
  std::string from;
  std::string to;
  int from_lane = 0;
  int to_lane = 0;
  std::vector<Vec2> shape;  // through a junction: the route's own points (SUMO's internal lane)
};

struct NetPlan {
  int corridors = 0;
  int junctions = 0;
  std::vector<PlannedNode> nodes;
  std::vector<PlannedEdge> edges;  // corridor by corridor, each in driving order
  std::vector<PlannedConnection> connections;
  std::vector<std::string> notes;  // remarks for the user (single routes, fallbacks, ...)
};

struct JunctionSettings;  // junction_plan.hpp

// Throws MapError when the routes cannot be cut consistently (see the notes in the text).
// Waypoint files whose routes cross, branch, merge, share lanes or close on themselves get
// junctions (junction_plan.hpp); the others are planned as corridors only.
NetPlan plan_net(const WaypointFile& waypoints, const NetPlanSettings& settings);
NetPlan plan_net(const WaypointFile& waypoints, const NetPlanSettings& settings, const JunctionSettings& junctions);

// What the junction step tells the corridor planner about each of its lines (one per
// route of `lines`): the routes driving it, and the junctions its ends lie at ("" = a free
// end, extended by lane_extension).
struct CorridorLine {
  std::vector<std::string> routes;
  std::string start_node;
  std::string end_node;
  // Free ends: how far the lane may reach beyond them (< 0: lane_extension). Shorter where
  // the straight extension would run into another road.
  double start_extension = -1;
  double end_extension = -1;
  // A lane of its own, never a neighbouring lane of another line's road (a dead-end lane
  // made for a route that starts or ends inside a junction: its end lies at that junction,
  // where the lanes beside it go on).
  bool solitary = false;
};
// Plans the corridors of `lines` into `out` (edges, own nodes, connections within corridors).
void plan_corridors(const WaypointFile& lines, const std::vector<CorridorLine>* info, const NetPlanSettings& settings,
                    NetPlan& out);


}  // namespace orch

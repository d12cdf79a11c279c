#pragma once
// The junction step of `map build`, part 2b: routes through one junction between the same
// two lanes along different paths. SUMO has one connection per pair of lanes, so a second
// route from lane A to lane B through a junction would drive the first one's path there,
// metres from its own waypoints (a route leaning off a shared lane and back, a turn drawn
// with another radius, a shallow 5-way junction). Instead its passage is cut where it lies
// farthest from the first path and a short lane of its own goes in there (a *detour lane*,
// kDetourLength, from the junction back to it: the corridor planner cuts it in the middle
// by a node of its own): A -> detour and detour -> B are pairs of lanes of its own, each
// connected along its own points. Every path stays in the one junction, so SUMO's right of
// way between the detour and every other path through the junction is still decided there
// (splitting the junction where the paths part would have to cut every other route crossing
// either path too). Further routes along an existing detour drive its lane.
#include "map/junction_pieces.hpp"
#include "map/waypoint_file.hpp"

namespace orch {

inline constexpr double kDetourLength = 2.0;  // m, the detour lane (two edges of 1 m)
inline constexpr double kConnectionSimplify = 0.02;  // m, a connection's shape (as the lane shapes)
// m: a second route through a junction between the same lanes lying farther than this from
// the first one's path (as the connection is built: simplified by kConnectionSimplify) gets a
// detour lane; closer, it drives the first path. With the net's centimetres (0.005 m) and
// netconvert's own end points, this keeps it within `map check`'s 0.10 m of that path (it was
// 0.25 m: a turn drawn 0.2 m wide of another drove the other's path, 0.2 m off its own).
inline constexpr double kMaxSharedPathMiss = 0.09;

// Gives every passage that shares its pair of lanes with an earlier passage along another
// path a detour lane (appended to out.pieces, `detour` set; the passage split in two).
void add_detour_lanes(const WaypointFile& wf, JunctionPieces& out);

}  // namespace orch

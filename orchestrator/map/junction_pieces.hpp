#pragma once
// The junction step of `map build`, part 2: the routes cut at their passages through the
// junctions (junction_zones.hpp) into pieces, the stretches between junctions that become
// ordinary lanes. Pieces drawn along the same lane (one lies within a few centimetres of
// the other over its whole length) become one lane driven by several routes: a shared
// first or last stretch before a branch, the common lane after a merge, the middle stretch
// two routes overlap on, a loop driven twice.
#include <string>
#include <vector>

#include "map/junction_zones.hpp"
#include "map/waypoint_file.hpp"

namespace orch {

// m: netconvert keeps a lane's shape points at least this far apart and drops nearer ones
// (its POSITION_EPS).
inline constexpr double kNetconvertPointGap = 0.1;

struct RoutePiece {
  WaypointRoute line;               // the stretch's points; id "<route>" or "<route>.<k>"
  std::size_t route = 0;            // the waypoint route it was cut from
  std::vector<std::string> routes;  // waypoint routes that drive this lane (its own first)
  int from_zone = -1;               // the junction the lane starts at (-1: the route's own start)
  int to_zone = -1;                 // ... ends at (-1: the route's own end)
  bool loose_end = false;           // a dead-end lane for a route starting or ending inside a junction
  bool detour = false;              // a detour lane inside a junction (junction_detours.hpp)
};

// One passage of a route through a junction, between the pieces before and after it.
struct JunctionPassage {
  std::size_t route = 0;
  int zone = 0;
  double s0 = 0;      // arc length on the route (s1 > length: across a closed route's start)
  double s1 = 0;
  int before = -1;    // lane piece (index into JunctionPieces::pieces), -1: none
  int after = -1;
};

struct JunctionPieces {
  std::vector<RoutePiece> pieces;          // distinct lanes, coincident pieces merged
  std::vector<JunctionPassage> passages;   // route by route, in driving order
  int merged = 0;                          // pieces folded into another (one lane, several routes)
};

// The points of `route` between arc lengths a < b (b may exceed the length of a closed
// route: the stretch then runs across its closing point), cut exactly at both ends.
std::vector<WaypointPoint> stretch(const WaypointRoute& route, double a, double b);
// A lane piece's line from its points.
WaypointRoute make_line(std::string id, std::vector<WaypointPoint> pts);

JunctionPieces cut_into_pieces(const WaypointFile& waypoints, const JunctionZones& zones);

}  // namespace orch

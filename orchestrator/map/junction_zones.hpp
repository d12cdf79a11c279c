#pragma once
// The junction step of `map build`, part 1: where the net needs SUMO junctions. Wherever a
// waypoint route comes closer than a lane width to another route (or to itself, further
// along) at an angle, or drifts apart from a route it shared a lane with (a branch) or onto
// one (a merge), both routes are "in a junction" there. Each route gets passages: stretches
// of its line inside a junction, with a margin so that the lanes end before the routes
// touch. Passages that touch each other's conflicts form one zone, which becomes one SUMO
// junction. Lanes that must end together (one lane driven by several routes, neighbouring
// lanes of one road) get aligned passage ends. Between passages lie the pieces that become
// ordinary lanes (junction_pieces.hpp).
#include <vector>

#include "map/waypoint_file.hpp"

namespace orch {

inline constexpr double kSameLaneDistance = 0.35;  // m; closer and aligned: one lane
// m: the farthest a waypoint may lie from the lane planned for it, so that it lies within
// `map check`'s 0.10 m of that lane in the net: lane shapes are simplified by 0.02 m and
// written to the net in centimetres (up to 0.005 m): 0.075 + 0.02 + 0.005 = 0.10.
inline constexpr double kPlannedLaneMiss = 0.075;
// m: routes on one lane lying farther apart than this cannot all lie within kPlannedLaneMiss
// of one lane (their best fit lies in the middle, half of this from each): they get paths
// of their own there (junction_zones.cpp, add_spread_conflicts).
inline constexpr double kMaxSameLaneSpread = 2 * kPlannedLaneMiss;
inline constexpr double kConflictReach = 3.5;      // m; closer at an angle: a junction
inline constexpr double kZoneMargin = 1.5;         // m of a passage before/after each conflict
inline constexpr double kMinPieceLength = 6.0;     // m; shorter stretches between passages join them

// A stretch of one route inside a junction, [s0, s1] in arc length along the route's line.
// On a closed route a passage across the closing point has s1 > length (it wraps).
struct Passage {
  double s0 = 0;
  double s1 = 0;
  int zone = -1;  // 0.. in the order zones are first met (route by route, along each route)
};

struct JunctionZones {
  std::vector<std::vector<Passage>> passages;  // per route (file order), sorted by s0
  int count = 0;
  [[nodiscard]] bool empty() const { return count == 0; }
};

// A route is closed when its last waypoint lies on its first one.
bool is_closed_route(const WaypointRoute& route);

JunctionZones find_junction_zones(const WaypointFile& waypoints);

}  // namespace orch

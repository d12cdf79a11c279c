#pragma once
// First step of `map build`: which waypoint routes are neighbouring lanes of one
// carriageway. Two routes are parallel when they run in the same direction side by side at
// a lane's spacing (2-6 m) that stays the same wherever both exist; parallel routes,
// transitively, form a corridor, which becomes one chain of SUMO edges. Routes in the
// opposite direction are never parallel, so each direction gets edges of its own.
#include <cstddef>
#include <string>
#include <vector>

#include "core/polyline.hpp"
#include "map/waypoint_file.hpp"

namespace orch {

// Thresholds of the parallel test; lane widths on public roads are 2.5-4.5 m.
inline constexpr double kMinLaneSpacing = 2.0;          // m; closer routes share a lane
inline constexpr double kMaxLaneSpacing = 6.0;          // m; farther routes are other roads
inline constexpr double kMaxSpacingVariation = 1.0;     // m along the overlap (max - min)
inline constexpr double kMinParallelOverlap = 30.0;     // m, or half the shorter route
inline constexpr double kMinCoincidentOverlap = 5.0;    // m on the same lane
inline constexpr double kMinParallelStub = 5.0;         // m: the least overlap of neighbouring lanes
inline constexpr double kSameDirectionCos = 0.94;       // cos 20 deg between the tangents

struct RouteRelation {
  enum class Kind {
    None,        // not beside each other (other road, opposite direction, crossing, branching)
    Parallel,    // neighbouring lanes
    Coincident,  // drawn along the same lane (closer than kMinLaneSpacing)
  };
  Kind kind = Kind::None;
  double lateral = 0;  // median offset of `a` from `b`, m, + = a lies left of b
  double overlap = 0;  // m of `a` that lies beside `b`
};

// How route line `a` lies relative to route line `b`, judged from a's points.
RouteRelation relate_routes(const Polyline& a, const Polyline& b);

// Groups of route indices (into waypoints.routes), each in file order, corridors ordered by
// their first route. Unions are made strongest overlap first and never put two coincident
// routes into one corridor (they would become two lanes on top of each other); such routes
// and other remarks are appended to `notes`.
// `solitary[i]`: route i is a lane of its own, never a neighbour of another.
std::vector<std::vector<std::size_t>> find_corridors(const WaypointFile& waypoints,
                                                     std::vector<std::string>& notes,
                                                     const std::vector<bool>& solitary = {});

}  // namespace orch

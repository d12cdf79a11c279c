#pragma once
// How well a route's waypoints in a junction passage fit the lanes and paths it could drive
// there without a lane of its own (junction_pieces.cpp: routes starting or ending inside a
// junction get a dead-end lane of their own where they fit none).
#include <vector>

#include "map/junction_pieces.hpp"

namespace orch {

// m: `map check`'s tolerance. A route ending (starting) inside a junction whose waypoints on
// the lane it would continue on (come from) lie farther from it gets a dead-end lane of its own
// instead, where its passage is long enough for one.
inline constexpr double kLaneFit = 0.10;

// The largest distance from lane `l` of the route's waypoints in passage jp that lie along
// it (past its start where the route ends on it, before its end where the route starts).
double farthest_on(const WaypointRoute& route, const JunctionPassage& jp, const Polyline& l, bool at_end);

// Whether the waypoints of passage jp lie within kLaneFit of the path through the zone of some
// other route that goes on through it on lane piece k (after it where jp starts there, before
// it where jp ends there): the connection the route would drive without a lane of its own.
bool fits_a_path_on(const WaypointFile& wf, const std::vector<JunctionPassage>& passages, const JunctionPassage& jp,
                    int k, bool loose_end);

// Whether the waypoints of passage jp lie within kLaneFit of the path of some other route
// through the zone from lane piece `from` to lane piece `to` (the connection jp would drive
// between them), or no other route drives between the two.
bool fits_a_path_between(const WaypointFile& wf, const std::vector<JunctionPassage>& passages,
                         const JunctionPassage& jp, int from, int to);

}  // namespace orch

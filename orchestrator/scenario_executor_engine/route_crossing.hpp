#pragma once
// Along-road distance between two actors whose routes have no common path but meet: they
// cross at a junction, or one joins the other's lane (a merge). There is no road between
// them to measure along; the format's "traveled" distance is then defined through the
// conflict point X where the target's route first comes onto the actor's route:
//
//     gap = d_actor(X) - d_target(X)
//
// each d measured along the actor's own route from its centre to X (+ while X lies ahead).
// + means the target is nearer to X than the actor (it is "ahead" on the way there, or has
// passed it); - that the actor gets there first. Where the routes meet more than once, the
// meeting nearest to both actors counts. docs/scenario-format.md "Conditions".
#include <map>
#include <optional>
#include <utility>
#include <vector>

#include "map/waypoint_file.hpp"

namespace orch::engine {

struct RouteMeeting {
  double s_route = 0;   // arc length of X on the actor's route
  double s_other = 0;   // ... on the target's route
};

// Places where `other` comes onto `route` (within a lane's half width of its line), one per
// stretch, in the order of `other`. Empty when they never meet.
std::vector<RouteMeeting> route_meetings(const WaypointRoute& route, const WaypointRoute& other);

// Meetings are computed once per pair of routes.
class RouteMeetings {
 public:
  const std::vector<RouteMeeting>& between(const WaypointRoute& route, const WaypointRoute& other);

 private:
  std::map<std::pair<const WaypointRoute*, const WaypointRoute*>, std::vector<RouteMeeting>> cache_;
};

// The conflict-point gap above, or nullopt when the target lies on or beside the actor's
// route (then the ordinary along-road distance applies) or the routes never meet.
std::optional<double> conflict_point_gap(const WaypointRoute& route, const Vec2& actor, const WaypointRoute& other,
                                         const Vec2& target, RouteMeetings& meetings);

}  // namespace orch::engine

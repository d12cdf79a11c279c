#pragma once
// RandomRouteAction (1.3, RoutingAction): the entity drives a random route from where it is.
// The standard gives the action no content and leaves the route to the simulator; here it is a
// random walk over the OpenDRIVE lane graph: at every fork (a lane continuing on several, a
// junction's connections) one of the lanes is taken, each as likely, the choice a hash of the
// run's seed (--seed), the entity's name, the road and lane of the fork and how many forks came
// before. So a run makes the same route for the same seed every time, another seed may make
// another, and two entities at the same fork may choose differently. The walk ends where no lane follows or after
// kMaxRoads roads; the entity then goes on straight as without a route (route_plan.hpp).
#include <cstdint>
#include <string>

#include "opendrive/road_network.hpp"
#include "openscenario/entity_motion.hpp"

namespace orch::openscenario {

inline constexpr std::size_t kRandomRouteMaxRoads = 256;

// Replaces state's route plan (and its waypoints) by a random walk from its road and lane,
// drawn from `seed` (the run's).
void plan_random_route(EntityState& state, const opendrive::RoadNetwork& roads, const std::string& entity,
                       std::uint64_t seed);

}  // namespace orch::openscenario

#pragma once
// The lanes an entity drives for AssignRouteAction / AcquirePositionAction: each leg, from
// where the entity is through the waypoints it has not passed, planned on the OpenDRIVE
// lane graph by the waypoint's routeStrategy (opendrive/route_planner.hpp); the plan is
// followed where a lane continues on several (road_following.hpp).
#include <string>
#include <vector>

#include "opendrive/road_network.hpp"
#include "opendrive/route_planner.hpp"
#include "openscenario/entity_motion.hpp"

namespace orch::openscenario {

// "shortest", "fastest", "leastIntersections", "random" (the reader checked the word).
opendrive::RouteStrategy route_strategy(const std::string& word);

struct RouteTarget {
  EntityState::Waypoint at;
  opendrive::RouteStrategy strategy = opendrive::RouteStrategy::Shortest;
  std::string what;  // "waypoint 2 of route \"R\" of \"Car\" (/OpenSCENARIO/..., line 53)"
};

// Fills state.route_plan (route_plan_next = 0) with the legs from the entity's position to
// targets[state.route_passed], then on to each later target; `closed`: also from the last
// target back to the first, and the plan repeats from the first target on. A leg that the
// entity's lane cannot drive is planned from another lane of its road driving the entity's
// way (the storyboard's lane changes take it there), and for an entity standing across its road
// (more than 60 degrees off it: parked, esmini's parking_demo.xosc) also from a lane driving
// the other way, nearest first (esmini starts a route from wherever the entity is); when none
// can, MapError naming the target.
void plan_entity_route(EntityState& state, const opendrive::RoadNetwork& roads,
                       const std::vector<RouteTarget>& targets, bool closed);

// The lanes the entity will drive after its current road: the rest of its route plan (a
// closed route's loop twice over), then, for an open route or none, the default
// continuation (opendrive::default_continuation: straight on until the network ends).
std::vector<opendrive::LaneEntry> lanes_ahead(const EntityState& state, const opendrive::RoadNetwork& roads);

}  // namespace orch::openscenario

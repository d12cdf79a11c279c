#pragma once
// Trailers (OpenSCENARIO 1.3) as the storyboard runs them: a connected trailer follows its
// tractor. Its coupler point (TrailerCoupler dx ahead of its reference point) stays on the
// tractor's hitch point (TrailerHitch dx from the tractor's reference point) and its body is
// drawn after it like a bar: the reference point (the rear axle) moves straight toward the
// hitch, so the trailer turns in behind its tractor as a real single-axle trailer does. Where
// a vehicle gives no TrailerHitch / TrailerCoupler, the rear / front of its bounding box is used.
#include <map>
#include <string>

#include "opendrive/road_network.hpp"
#include "openscenario/entity_motion.hpp"
#include "openscenario/model.hpp"

namespace orch::openscenario {

// Which trailer each tractor tows now (ConnectTrailerAction, DisconnectTrailerAction, and the
// Trailer written in a vehicle at the start).
using TrailerLinks = std::map<std::string, std::string>;

// The links the entities declare at the start.
TrailerLinks initial_trailer_links(const Scenario& scenario);

// Connects `trailer` to `tractor`: a trailer not placed yet is placed straight behind it;
// the trailer's own motion (speed, lateral, trajectory, route) ends: it is towed.
void connect_trailer(const Scenario& scenario, std::map<std::string, EntityState>& entities, TrailerLinks& links,
                     const std::string& tractor, const std::string& trailer, const opendrive::RoadNetwork& roads);
// The trailers connected from the start: each chain is lined up straight behind its front
// vehicle, along its heading (where Init teleported a trailer does not matter, as in esmini:
// a trailer's place is its tractor's), and towed from then on.
void align_initial_trailers(const Scenario& scenario, std::map<std::string, EntityState>& entities,
                            TrailerLinks& links, const opendrive::RoadNetwork& roads);
// The tractor's trailer stays where it is, at rest (it has no drive of its own).
void disconnect_trailer(std::map<std::string, EntityState>& entities, TrailerLinks& links, const std::string& tractor);

// Whether `entity` is a trailer connected to a tractor now: it has no motion of its own (it
// is not advanced by its speed; only pulled, else it would run ahead of its bar).
bool is_towed(const TrailerLinks& links, const std::string& entity);

// Moves every connected trailer after its tractor moved (`dt` the step; 0 at the start),
// along chains (a trailer towing another) from the front.
void pull_trailers(const Scenario& scenario, std::map<std::string, EntityState>& entities, const TrailerLinks& links,
                   const opendrive::RoadNetwork& roads, double dt);

}  // namespace orch::openscenario

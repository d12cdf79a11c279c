#pragma once
// A SynchronizeAction's target (TargetPosition, TargetPositionMaster) given as a LanePosition
// or RoadPosition past its road's end: the standard gives `s` the range [0..inf[ and does not
// say what a position beyond the road's length means, and esmini (the peer player) truncates s
// to the road's length with a message ("Invalid s value 455 for road 2 of length 304.19,
// truncating"; its ltap-od-relative-speed.xosc relies on it). So do we, with a warning naming
// the action's line. Other positions past a road's end stay errors (scenario_check.hpp): they
// would place an entity off its road.
#include "core/diagnostics.hpp"
#include "opendrive/road_network.hpp"
#include "openscenario/model.hpp"

namespace orch::openscenario {

// Truncates such targets in `scenario` (Init and storyboard); one warning each.
Diagnostics truncate_synchronize_targets(Scenario& scenario, const opendrive::RoadNetwork& roads);

}  // namespace orch::openscenario

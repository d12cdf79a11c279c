#pragma once
// Checks a loaded scenario against itself, the model catalog and its map's waypoint file:
// actor ids (unique, defined, placed), model ids, wp_id / wp_idx, scene ids (unique,
// next_scenes targets exist), scenes that can never be reached, a graph with no ending
// scene, start positions relative to actors that form a cycle.
#include "core/diagnostics.hpp"
#include "map/waypoint_file.hpp"
#include "scenario_executor/catalog.hpp"
#include "scenario_executor/model.hpp"

namespace orch {

struct ValidationOptions {
  // A target waypoint (end_position, position/time_headway conditions) past the end of its
  // route is a warning and means the route's last point; strict makes it an error.
  bool strict = false;
};

// A WaypointFile without routes stands for "the map is unknown": the waypoint checks are
// skipped and everything else is still checked (validate reports the unknown map itself).
Diagnostics check_scenario(const scenario::Scenario& s, const WaypointFile& waypoints, const Catalog& catalog,
                           const ValidationOptions& options = {});

}  // namespace orch

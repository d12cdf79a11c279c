#include "openscenario/scenario_check.hpp"

#include <fmt/format.h>

#include "core/errors.hpp"
#include "opendrive/xodr_reader.hpp"
#include "openscenario/synchronize_targets.hpp"
#include "openscenario/traffic_signals.hpp"

namespace orch::openscenario {
namespace {

// The absolute positions of the storyboard (teleports, added entities, positions to acquire,
// route waypoints) with the place they are written at.
void collect(const PrivateAction& action, const Place& place,
             std::vector<std::pair<const Position*, Place>>& positions) {
  if (const auto* teleport = std::get_if<TeleportAction>(&action)) positions.emplace_back(&teleport->position, place);
  if (const auto* add = std::get_if<AddEntityAction>(&action)) positions.emplace_back(&add->position, place);
  if (const auto* acquire = std::get_if<AcquirePositionAction>(&action)) positions.emplace_back(&acquire->position, place);
  if (const auto* sync = std::get_if<SynchronizeAction>(&action)) {
    positions.emplace_back(&sync->master_position, place);
    positions.emplace_back(&sync->position, place);
  }
  if (const auto* route = std::get_if<AssignRouteAction>(&action))
    for (const Position& p : route->waypoints) positions.emplace_back(&p, place);
}

void check_position(const Position& position, const opendrive::RoadNetwork& roads, const std::string& file,
                    const Place& place, Diagnostics& diags) {
  const SourceLocation where{file, place.path, place.line};
  try {
    if (const auto* lane = std::get_if<LanePosition>(&position)) {
      const opendrive::Road& road = roads.road(lane->road_id);
      if (lane->s < 0 || lane->s > road.length)
        diags.error(where, fmt::format("s={} is outside road {} (length {})", lane->s, road.id, road.length));
      else
        (void)road.lane_center_t(lane->lane_id, lane->s);
    } else if (const auto* on_road = std::get_if<RoadPosition>(&position)) {
      const opendrive::Road& road = roads.road(on_road->road_id);
      if (on_road->s < 0 || on_road->s > road.length)
        diags.error(where, fmt::format("s={} is outside road {} (length {})", on_road->s, road.id, road.length));
    }
  } catch (const MapError& e) {
    diags.error(where, e.what());
  }
}

}  // namespace

Diagnostics check_scenario_file(const std::string& path, const LoadOptions& options) {
  Diagnostics diags;
  try {
    Scenario scenario = load_scenario(path, options);
    diags.append(scenario.warnings);
    if (scenario.road_file.empty()) return diags;
    const opendrive::RoadNetwork roads = opendrive::read_xodr_file(scenario.road_file);
    diags.append(truncate_synchronize_targets(scenario, roads));
    std::vector<std::pair<const Position*, Place>> positions;
    for (const InitAction& a : scenario.storyboard.init) collect(a.action, a.place, positions);
    for (const Story& story : scenario.storyboard.stories)
      for (const Act& act : story.acts)
        for (const ManeuverGroup& g : act.groups)
          for (const Maneuver& m : g.maneuvers)
            for (const Event& e : m.events)
              for (const Action& a : e.actions) collect(a.action, a.place, positions);
    for (const auto& [position, place] : positions) check_position(*position, roads, path, place, diags);
    try {  // a TrafficSignalGroupState needs its controller's signal group in the road network
      (void)TrafficSignals(scenario.signal_controllers, roads.signal_controllers());
    } catch (const MapError& e) {
      diags.error(SourceLocation{path, "", 0}, e.what());
    }
  } catch (const ScenarioError& e) {
    diags.append(e.diagnostics());
  }
  return diags;
}

}  // namespace orch::openscenario

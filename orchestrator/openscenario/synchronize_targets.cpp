#include "openscenario/synchronize_targets.hpp"

#include <fmt/format.h>

namespace orch::openscenario {
namespace {

void truncate(Position& position, const char* which, const opendrive::RoadNetwork& roads, const std::string& file,
              const Place& place, Diagnostics& diags) {
  const auto cut = [&](const std::string& road_id, double& s) {
    const opendrive::Road* road = roads.find(road_id);
    if (!road || s <= road->length) return;  // an unknown road stays the resolver's error
    diags.warning({file, place.path, place.line},
                  fmt::format("SynchronizeAction {}: s={} is beyond the end of road {} (length {:.2f}); truncated to "
                              "{:.2f} as esmini does (the standard gives s the range [0..inf[ and does not say what a "
                              "position past the road's end means)",
                              which, s, road->id, road->length, road->length));
    s = road->length;
  };
  if (auto* lane = std::get_if<LanePosition>(&position)) cut(lane->road_id, lane->s);
  else if (auto* on_road = std::get_if<RoadPosition>(&position)) cut(on_road->road_id, on_road->s);
}

void truncate_action(PrivateAction& action, const Place& place, const opendrive::RoadNetwork& roads,
                     const std::string& file, Diagnostics& diags) {
  auto* sync = std::get_if<SynchronizeAction>(&action);
  if (!sync) return;
  truncate(sync->master_position, "TargetPositionMaster", roads, file, place, diags);
  truncate(sync->position, "TargetPosition", roads, file, place, diags);
}

}  // namespace

Diagnostics truncate_synchronize_targets(Scenario& scenario, const opendrive::RoadNetwork& roads) {
  Diagnostics diags;
  for (InitAction& a : scenario.storyboard.init) truncate_action(a.action, a.place, roads, scenario.file, diags);
  for (Story& story : scenario.storyboard.stories)
    for (Act& act : story.acts)
      for (ManeuverGroup& g : act.groups)
        for (Maneuver& m : g.maneuvers)
          for (Event& e : m.events)
            for (Action& a : e.actions) truncate_action(a.action, a.place, roads, scenario.file, diags);
  return diags;
}

}  // namespace orch::openscenario

// Fuzz target: arbitrary bytes as a scenario file, through the whole pure pipeline a run
// takes before and while SUMO steps: JSON (with lines) -> loader -> validator -> engine on a
// fake world for up to 300 steps of 0.05 s. Bad input must end in ScenarioError or a
// diagnostic; a valid scenario must run. Anything else (another exception, a crash, a
// sanitizer report, a hang) is a bug. The shipped maps are loaded once per process.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <iostream>
#include <map>
#include <memory>
#include <string>

#include "core/errors.hpp"
#include "scenario_executor_engine/engine.hpp"
#include "json/json_document.hpp"
#include "map/lane_map.hpp"
#include "map/map_registry.hpp"
#include "scenario_executor/catalog.hpp"
#include "scenario_executor/loader.hpp"
#include "scenario_executor/validator.hpp"
#include "support/fake_world.hpp"

namespace {

struct LoadedMap {
  orch::WaypointFile waypoints;
  orch::LaneMap lanes;
  double lane_extension;
};

// Maps by id and alias, as the runner finds them (the source tree's sumo_nets).
const LoadedMap* map_for(const std::string& id) {
  static const orch::MapRegistry registry({ORCH_FUZZ_MAPS_DIR});
  static std::map<std::string, std::unique_ptr<LoadedMap>> cache;
  const orch::MapManifest* m = registry.find(id);
  if (!m) return nullptr;
  auto& slot = cache[m->id];
  if (!slot) {
    orch::WaypointFile wps = orch::load_waypoint_file(m->waypoint_path().string());
    orch::LaneMap lanes = orch::LaneMap::build(m->net_path().string(), wps);
    slot = std::make_unique<LoadedMap>(LoadedMap{std::move(wps), std::move(lanes), m->lane_extension});
  }
  return slot.get();
}

[[noreturn]] void bug(const char* stage, const std::exception& e) {
  std::cerr << "scenario_pipeline_fuzz: unexpected exception in " << stage << ": " << e.what() << "\n";
  std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const orch::Catalog catalog = orch::Catalog::embedded();
  std::optional<orch::LoadedScenario> loaded;
  try {
    loaded = orch::load_scenario(
        orch::JsonDocument::parse(std::string(reinterpret_cast<const char*>(data), size), "fuzz.json"));
  } catch (const orch::ScenarioError& e) {
    // Invalid JSON, a repeated key, too deep: the message must name the file.
    if (std::string(e.what()).rfind("fuzz.json", 0) != 0) std::abort();
    return 0;
  } catch (const std::exception& e) {
    bug("loading", e);
  }
  if (!loaded->scenario) return 0;
  const orch::scenario::Scenario& s = *loaded->scenario;
  const LoadedMap* map = map_for(s.map_id);
  if (!map) return 0;
  try {
    if (orch::check_scenario(s, map->waypoints, catalog).has_errors()) return 0;
  } catch (const std::exception& e) {
    bug("validation", e);
  }
  // Valid: it runs, as it would on SUMO. The ego drives its start route at 15 m/s.
  try {
    const auto& start = *s.opening.ego.start.waypoint;
    const orch::WaypointRoute* route = map->waypoints.find(start.wp_id);
    if (!route) std::abort();  // the validator lets no unknown route through
    orch::engine::Engine engine(s, orch::engine::MapContext{map->waypoints, map->lanes, map->lane_extension}, catalog,
                                orch::engine::EngineOptions{0.05, false});
    orch::test::FakeWorld world(engine, *route, 0.05);
    world.ego_speed = 15;
    world.start(route->s_of(start.wp_idx));
    for (int i = 0; i < 300 && engine.state() == orch::engine::RunState::Running; ++i) world.step();
  } catch (const orch::OrchError&) {
    // The runner turns these into verdict error with the reason: an accepted outcome.
  } catch (const std::exception& e) {
    bug("the engine", e);
  }
  return 0;
}

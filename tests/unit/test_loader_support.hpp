#pragma once
// Small scenario texts with known line numbers, a synthetic waypoint file, and matchers
// for diagnostics, for the loader, validator and catalog tests.
#include <gtest/gtest.h>

#include <string>

#include "core/diagnostics.hpp"
#include "json/json_document.hpp"
#include "map/waypoint_file.hpp"
#include "scenario_executor/catalog.hpp"
#include "scenario_executor/loader.hpp"
#include "scenario_executor/validator.hpp"

namespace orch::loader_test {

inline LoadedScenario load_text(const std::string& text) { return load_scenario(JsonDocument::parse(text, "s.json")); }

// A valid scenario around one scene. Lines 1-9 are fixed; `scene` starts on line 10.
// Actors: 0 ego (prius), 1 vehicle (audi.tt), 2 pedestrian, 3 obstacle (barrel), all
// placed; the opening goes to scene 1; the ending scene is 9. The scene given should be
// scene 1 with next_scenes [9].
inline std::string with_scene(const std::string& scene) {
  return R"({
"map_id": "tiny",
"actors": {"ego": {"actor_id": 0, "model_id": "vehicle.toyota.prius"}, "others": [{"actor_id": 1, "model_id": "vehicle.audi.tt"}, {"actor_id": 2, "model_id": "walker.pedestrian.0001"}, {"actor_id": 3, "model_id": "static.prop.barrel"}]},
"scenario": {
"opening_scene": {"ego": {"start_position": {"wp_id": "Waypoint02", "wp_idx": 5}},
"others": [{"actor_id": 1, "start_position": {"type": "waypoint", "wp_id": "Waypoint01", "wp_idx": 20}}, {"actor_id": 2, "start_position": {"type": "waypoint", "wp_id": "Waypoint03", "wp_idx": 50}},
{"actor_id": 3, "start_position": {"type": "waypoint", "wp_id": "Waypoint02", "wp_idx": 80}}],
"next_scenes": [1]},
"scenes": [
)" + scene + R"(
],
"ending_scenes": [{"scene_id": 9}]
},
"stop_conditions": {"or": [{"simulation_time": {"comparison": ">=", "value": 60}}]}
}
)";
}

// Scene 1 with these actions (a JSON array) and no conditions.
inline std::string with_actions(const std::string& actions) {
  return with_scene(R"({"scene_id": 1, "actions": )" + actions + R"(, "next_scenes": [9]})");
}

// Scene 1 with this conditions object and no actions.
inline std::string with_conditions(const std::string& conditions) {
  return with_scene(R"({"scene_id": 1, "conditions": )" + conditions + R"(, "next_scenes": [9]})");
}

// Straight routes 4 m apart along +x, one point per metre, `points` points each.
inline WaypointRoute straight_route(const std::string& id, double y, int points) {
  WaypointRoute r;
  r.id = id;
  std::vector<Vec2> xy;
  for (int i = 0; i < points; ++i) {
    r.points.push_back({static_cast<double>(i), y, 0, 60 / 3.6});
    xy.emplace_back(i, y);
  }
  r.line = Polyline(xy);
  return r;
}

// Waypoint01..03 with 101 points each (last index 100).
inline WaypointFile tiny_waypoints() {
  WaypointFile f;
  f.path = "tiny.waypoint.json";
  f.routes = {straight_route("Waypoint01", 4, 101), straight_route("Waypoint02", 0, 101),
              straight_route("Waypoint03", -4, 101)};
  return f;
}

// Loads the text (which must load without errors) and checks it against tiny_waypoints().
inline Diagnostics check_text(const std::string& text, ValidationOptions options = {}) {
  const auto loaded = load_text(text);
  EXPECT_FALSE(loaded.diagnostics.has_errors()) << loaded.diagnostics.format();
  if (!loaded.scenario) return loaded.diagnostics;
  static const Catalog catalog = Catalog::embedded();
  return check_scenario(*loaded.scenario, tiny_waypoints(), catalog, options);
}

// The diagnostic of this severity at exactly this pointer whose message holds `text`.
inline const Diagnostic* find(const Diagnostics& d, Severity severity, const std::string& pointer,
                              const std::string& text) {
  for (const auto& item : d.items())
    if (item.severity == severity && item.where.pointer == pointer && item.message.find(text) != std::string::npos)
      return &item;
  return nullptr;
}

// Success when there is such an error on exactly that line; the failure lists all messages.
inline testing::AssertionResult has_error(const Diagnostics& d, const std::string& pointer, int line,
                                          const std::string& text) {
  const Diagnostic* found = find(d, Severity::Error, pointer, text);
  if (!found) return testing::AssertionFailure() << "no error at " << pointer << " saying \"" << text << "\" in:\n"
                                                 << d.format();
  if (found->where.line != line)
    return testing::AssertionFailure() << "error at " << pointer << " is on line " << found->where.line
                                       << ", expected " << line;
  if (found->where.file != "s.json") return testing::AssertionFailure() << "file is " << found->where.file;
  return testing::AssertionSuccess();
}

inline testing::AssertionResult has_warning(const Diagnostics& d, const std::string& pointer, int line,
                                            const std::string& text) {
  const Diagnostic* found = find(d, Severity::Warning, pointer, text);
  if (!found) return testing::AssertionFailure() << "no warning at " << pointer << " saying \"" << text << "\" in:\n"
                                                 << d.format();
  if (found->where.line != line)
    return testing::AssertionFailure() << "warning at " << pointer << " is on line " << found->where.line
                                       << ", expected " << line;
  return testing::AssertionSuccess();
}

}  // namespace orch::loader_test

#pragma once
// Builds in-memory scenarios and waypoint routes for tests of pure logic.
#include <gtest/gtest.h>

#include <string>

#include "json/json_document.hpp"
#include "map/waypoint_file.hpp"
#include "scenario_executor/loader.hpp"

namespace orch::test {

// Loads scenario JSON text; fails the test on load errors.
inline scenario::Scenario scenario_from(const std::string& text) {
  auto loaded = load_scenario(JsonDocument::parse(text, "test.json"));
  EXPECT_FALSE(loaded.diagnostics.has_errors()) << loaded.diagnostics.format();
  return loaded.scenario ? *loaded.scenario : scenario::Scenario{};
}

// Straight route along +x at height y, one point per metre.
inline WaypointRoute straight_route(const std::string& id, double y, int length, double v_kmh = 80) {
  WaypointRoute r;
  r.id = id;
  std::vector<Vec2> pts;
  for (int i = 0; i <= length; ++i) {
    r.points.push_back({static_cast<double>(i), y, 0, v_kmh / 3.6});
    pts.emplace_back(i, y);
  }
  r.line = Polyline(pts);
  return r;
}

// Three parallel lanes like ALKS_Road: Waypoint01 left (y=-4.5) .. Waypoint03 right (y=-11.5).
inline WaypointFile three_lane_road(int length = 2000) {
  WaypointFile f;
  f.path = "test.waypoint.json";
  f.routes = {straight_route("Waypoint01", -4.5, length), straight_route("Waypoint02", -8.0, length),
              straight_route("Waypoint03", -11.5, length)};
  return f;
}

}  // namespace orch::test

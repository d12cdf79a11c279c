#pragma once
// Generated city maps for the map builder's property tests (test_generated_city_maps.cpp,
// test_generated_city_scripted.cpp): scripts/city_waypoints.py draws the waypoint file of a
// seed, `map build` (in-process) makes its net in a map folder of its own.
#include <fmt/format.h>

#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "core/errors.hpp"
#include "core/process.hpp"
#include "integration/map_fixtures.hpp"

namespace orch::test {

// "7", "1-50", "3,9,12" as seeds.
inline std::vector<int> parse_seeds(const std::string& text) {
  std::vector<int> out;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');) {
    const auto dash = item.find('-', 1);
    if (dash == std::string::npos) {
      out.push_back(std::stoi(item));
      continue;
    }
    for (int s = std::stoi(item.substr(0, dash)); s <= std::stoi(item.substr(dash + 1)); ++s) out.push_back(s);
  }
  return out;
}

// ORCH_CITY_SEEDS when set (scripts/map_soak.py), else the test's fixed set.
inline std::vector<int> city_seeds(std::vector<int> fixed) {
  if (const char* env = std::getenv("ORCH_CITY_SEEDS"); env && *env) return parse_seeds(env);
  return fixed;
}

inline std::string reproduce(int seed) {
  return fmt::format("reproduce: python3 scripts/city_waypoints.py --seed {0} --out /tmp/city_{0}.waypoint.json && "
                     "build/bin/orchestrator map build --waypoints /tmp/city_{0}.waypoint.json --out /tmp/city_{0}",
                     seed);
}

// The map "city_<seed>" in dir/city_<seed>: waypoint file, map.json, net.
inline BuiltMap generate_and_build(const TempDir& dir, int seed) {
  BuiltMap m;
  m.manifest.id = fmt::format("city_{}", seed);
  m.manifest.dir = dir.path() / m.manifest.id;
  m.manifest.max_edge_length = kDefaultMaxEdgeLength;
  std::filesystem::create_directories(m.manifest.dir);
  m.manifest.waypoint_file = m.manifest.id + ".waypoint.json";
  m.manifest.net_file = m.manifest.id + ".net.xml";
  const ProcessResult gen =
      run_process("python3", {std::string(ORCH_SOURCE_DIR) + "/scripts/city_waypoints.py", "--seed",
                              std::to_string(seed), "--out", m.manifest.waypoint_path().string()});
  if (gen.exit_code != 0) throw OrchError("city_waypoints.py failed: " + gen.output);
  save_map_manifest(m.manifest);
  m.waypoints = load_waypoint_file(m.manifest.waypoint_path().string());
  m.report = build_net(m.manifest, m.waypoints);
  return m;
}

}  // namespace orch::test

#pragma once
// Background traffic for a map (docs/background-traffic.md): SUMO route files with plain
// <flow> definitions, generated from the map's net (never hand-written) and run by SUMO's
// own driver models. Every lane of every direction gets traffic:
//   - an entry flow per lane at the start of each road (Poisson arrivals at the level's
//     rate, so the seed changes the traffic), from t = 1 s;
//   - a fill at t = 1..2 s: vehicles at random free places along every lane, as many as
//     the level's steady state holds (rate / lane speed), so the road is busy from the
//     start instead of after the time a car needs to drive its length.
// Starting at 1 s leaves the first step to the scenario's actors: SUMO inserts them at
// t = 0 where the scenario puts them, and background vehicles enter only where there is
// room (SUMO's insertion checks), never on top of an actor.
//
// Background vehicles have the type "orch.background" (passenger car, SUMO's default
// Krauss driver with its usual imperfection and speed spread, all drawn from SUMO's
// --seed) and ids "bg.<edge>.<lane>.<n>" / "bgfill.<edge>.<lane>.<n>", which cannot clash
// with "ego" and "actor<N>".
#include <filesystem>
#include <string>
#include <vector>

#include "map/map_registry.hpp"

namespace orch {

struct TrafficLevel {
  const char* name;
  double vehicles_per_hour_per_lane;
};
// Named levels, as `--traffic NAME`; stored pre-generated in each map folder.
inline constexpr TrafficLevel kTrafficLevels[] = {{"light", 400}, {"medium", 1000}, {"dense", 1800}};

// A `--traffic` value: "none", a level name, vehicles per hour per lane, or a route file.
struct TrafficChoice {
  enum class Kind { None, Rate, File };
  Kind kind = Kind::None;
  std::string label;  // "none", "dense", "1200", or the file as given
  double vehicles_per_hour_per_lane = 0;
  std::filesystem::path file;  // Kind::File
};
// Throws OrchError for text that is none of these (a file must exist).
TrafficChoice parse_traffic(const std::string& text);

struct TrafficSettings {
  double vehicles_per_hour_per_lane = 0;
  // Vehicles per km and lane placed at the start, evenly spaced (any density up to a jam);
  // negative: the steady state of the rate at each lane's speed limit, at random free
  // places (SUMO's departPos="random_free", so the seed changes them).
  double fill_per_km = -1;
  std::string label;  // named in the file's header comment
};

// The route file for a net (its normal edges and their connections), as text.
// Deterministic: the same net and settings give the same bytes.
std::string background_traffic_xml(const std::filesystem::path& net_file, const TrafficSettings& settings);

// DIR/traffic/<level>.rou.xml of a map.
std::filesystem::path map_traffic_file(const MapManifest& map, const std::string& level);
// Writes the named levels' files into the map folder; returns their paths.
std::vector<std::filesystem::path> write_map_traffic(const MapManifest& map);

// The route file a run uses for `choice`: the map's stored file for a named level (made if
// missing), a file generated into `out_dir` for a rate, the file itself for a file; empty
// for none.
std::filesystem::path traffic_file_for_run(const TrafficChoice& choice, const MapManifest& map,
                                           const std::filesystem::path& out_dir);

}  // namespace orch

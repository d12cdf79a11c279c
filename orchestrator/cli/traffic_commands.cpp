// `orchestrator map traffic` and `orchestrator baseline` (docs/background-traffic.md,
// "Performance").
#include <fmt/format.h>

#include <chrono>
#include <filesystem>

#include "cli/commands.hpp"
#include "cli/common.hpp"
#include "core/errors.hpp"
#include "core/files.hpp"
#include "map/background_traffic.hpp"
#include "run/simulator.hpp"
#include "sumo/sumo_simulator.hpp"

namespace orch::cli {

int map_traffic_command(const MapTrafficOptions& o) {
  const MapRegistry registry = make_registry(o.common);
  std::vector<MapManifest> targets;
  for (const auto& name : o.maps) targets.push_back(resolve_map(registry, name));
  if (o.rate) {
    if (targets.size() != 1 || o.out.empty()) throw OrchError("--rate writes one file: name one map and --out FILE");
    const TrafficSettings settings{*o.rate, o.fill_per_km, fmt::format("{:g}", *o.rate)};
    write_file_atomically(o.out, background_traffic_xml(targets.front().net_path(), settings));
    fmt::print("map \"{}\": {} vehicles/hour/lane -> {}\n", targets.front().id, *o.rate, o.out);
    return 0;
  }
  if (!o.out.empty() || o.fill_per_km >= 0) throw OrchError("--out and --fill-per-km go with --rate");
  if (o.maps.empty()) targets = registry.maps();
  if (targets.empty()) throw MapError("no maps found (see --maps)");
  for (const auto& m : targets) {
    const auto files = write_map_traffic(m);
    fmt::print("map \"{}\": {} traffic levels in {}\n", m.id, files.size(), (m.dir / "traffic").string());
  }
  return 0;
}

namespace {

// The route file for bare SUMO on a net file: a level or rate generated from the net (as
// OpenSCENARIO runs do), a route file as given.
std::string openscenario_traffic_file(const TrafficChoice& choice, const std::string& net, const std::string& out) {
  if (choice.kind == TrafficChoice::Kind::None) return "";
  if (choice.kind == TrafficChoice::Kind::File) return std::filesystem::absolute(choice.file).string();
  const auto file = std::filesystem::absolute(std::filesystem::path(out) / "traffic.rou.xml");
  write_file_atomically(file, background_traffic_xml(net, {choice.vehicles_per_hour_per_lane, -1, choice.label}));
  return file.string();
}

}  // namespace

// SUMO with the map's net and traffic and the orchestrator's SUMO options, stepped and
// nothing else: no scenario, no reads, no trace.
int baseline_command(const BaselineOptions& o) {
  const auto wall_start = std::chrono::steady_clock::now();
  std::filesystem::create_directories(o.out);
  SimulatorConfig config;
  config.step = o.step;
  config.seed = o.seed;
  config.log_file = std::filesystem::absolute(std::filesystem::path(o.out) / "sumo.log").string();
  std::string map_id = o.map;
  if (o.map.ends_with(".net.xml")) {
    // A SUMO net file (e.g. one converted from OpenDRIVE, result.json's "net"): its traffic
    // is generated as `run --traffic` does for OpenSCENARIO runs.
    config.net_file = std::filesystem::absolute(o.map).string();
    const auto traffic = openscenario_traffic_file(parse_traffic(o.traffic), config.net_file, o.out);
    if (!traffic.empty()) config.route_files.push_back(traffic);
  } else {
    const MapRegistry registry = make_registry(o.common);
    const MapManifest map = resolve_map(registry, o.map);
    map_id = map.id;
    config.net_file = std::filesystem::absolute(map.net_path()).string();
    const auto traffic = traffic_file_for_run(parse_traffic(o.traffic), map, o.out);
    if (!traffic.empty()) config.route_files.push_back(traffic.string());
  }
  const auto sim = make_sumo_simulator(o.backend);
  sim->start(config);
  const auto loop_start = std::chrono::steady_clock::now();
  for (int i = 0; i < o.steps; ++i) sim->advance();
  const auto loop_end = std::chrono::steady_clock::now();
  const int vehicles = sim->read({}).other_vehicles;
  sim->close();
  const auto seconds = [](auto a, auto b) { return std::chrono::duration<double>(b - a).count(); };
  fmt::print("baseline: map {} traffic {} backend {}: {} steps of {:g} s, {} vehicles at the end, stepping {:.3f} s, "
             "total {:.3f} s\n",
             map_id, o.traffic, o.backend, o.steps, o.step, vehicles, seconds(loop_start, loop_end),
             seconds(wall_start, std::chrono::steady_clock::now()));
  return 0;
}

}  // namespace orch::cli

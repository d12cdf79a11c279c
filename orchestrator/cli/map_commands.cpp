// `orchestrator map build` and `orchestrator map check`.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <iostream>

#include "cli/commands.hpp"
#include "cli/common.hpp"
#include "core/errors.hpp"
#include "map/background_traffic.hpp"
#include "map/lane_map.hpp"
#include "map/net_builder.hpp"
#include "map/waypoint_file.hpp"

namespace orch::cli {

namespace {

// The waypoint of a route farthest from the centre of its lane.
struct Deviation {
  double distance = 0;
  std::size_t wp_idx = 0;
};

Deviation worst_deviation(const RouteLanes& rl) {
  Deviation worst;
  for (std::size_t i = 0; i < rl.points.size(); ++i)
    if (rl.points[i].distance > worst.distance) worst = {rl.points[i].distance, i};
  return worst;
}

std::string lane_list(const LaneMap& lanes, const RouteLanes& rl) {
  std::string out;
  for (const int lane : rl.lanes) out += (out.empty() ? "" : " ") + lanes.lane(lane).id;
  return out;
}

void add_unique(std::vector<std::string>& list, const std::string& value, const std::string& except) {
  if (!value.empty() && value != except && std::find(list.begin(), list.end(), value) == list.end())
    list.push_back(value);
}

// Waypoints farther than this from their lane centre mean the net does not fit the routes.
constexpr double kBuildTolerance = 0.10;  // m, as the default of `map check`

// Rebuilds one map's net and reports how well its lanes fit the waypoints; false when some
// waypoint lies farther than kBuildTolerance from its lane (geometry the algorithm does
// not handle), so that a bad net never goes unnoticed.
bool build_map(const MapManifest& m) {
  const WaypointFile waypoints = load_waypoint_file(m.waypoint_path().string());
  const NetBuildReport report = build_net(m, waypoints);
  const LaneMap lanes = LaneMap::build(m.net_path().string(), waypoints);
  Deviation worst;
  std::string worst_route;
  for (const WaypointRoute& r : waypoints.routes) {
    const Deviation d = worst_deviation(*lanes.route(r.id));
    if (worst_route.empty() || d.distance > worst.distance) {
      worst = d;
      worst_route = r.id;
    }
  }
  fmt::print("map \"{}\": built {}\n", m.id, m.net_path().string());
  std::string per_edge;
  for (std::size_t n = 1; n < report.edges_by_lanes.size(); ++n)
    if (report.edges_by_lanes[n] > 0)
      per_edge += fmt::format("{}{} with {} lane{}", per_edge.empty() ? "" : ", ", report.edges_by_lanes[n], n,
                              n == 1 ? "" : "s");
  fmt::print("  {} routes -> {} corridors, {} junctions, {} edges ({}), {} lanes; largest waypoint-to-lane-centre "
             "distance {:.4f} m (route {} wp_idx {})\n",
             waypoints.routes.size(), report.corridors, report.junctions, report.edges, per_edge, report.lanes,
             worst.distance, worst_route, worst.wp_idx);
  fmt::print("  picture of the net with the routes over it: {}\n", report.picture.string());
  for (const std::string& note : report.notes) fmt::print("  note: {}\n", note);
  // The background traffic is made from the net: a new net needs new traffic files.
  const auto traffic = write_map_traffic(m);
  fmt::print("  background traffic: {} levels in {}\n", traffic.size(), (m.dir / "traffic").string());
  if (worst.distance <= kBuildTolerance) return true;
  fmt::print("  ERROR: waypoints lie up to {:.2f} m from their lanes (limit {:.2f} m); `orchestrator map check {}` "
             "lists them. The waypoint file has geometry map build does not handle.\n",
             worst.distance, kBuildTolerance, m.id);
  return false;
}

std::filesystem::path first_map_dir(const CommonOptions& c) {
  if (!c.map_dirs.empty()) return c.map_dirs.front();
  return MapRegistry::default_search_dirs().front();
}

// `map build --waypoints FILE`: a new map folder (or an update of the one at --out).
MapManifest create_map_folder(const MapBuildOptions& o, const MapRegistry& registry) {
  const WaypointFile waypoints = load_waypoint_file(o.waypoints);
  const std::string id = o.id.empty() ? waypoints.map_id : o.id;
  if (id.empty()) throw MapError(fmt::format("{} has no \"mapId\"; name the map with --id", o.waypoints));
  if (id.find('/') != std::string::npos || id == "." || id == "..")
    throw MapError(fmt::format("\"{}\" cannot be a map id: it must be usable as a folder name", id));
  const std::filesystem::path dir = o.out.empty() ? first_map_dir(o.common) / id : std::filesystem::path(o.out);
  std::error_code ec;
  const auto same_folder = [&](const MapManifest& other) { return std::filesystem::equivalent(other.dir, dir, ec); };
  // Another map of that id matters only where both would be loaded together: when the new
  // folder lies in one of the folders searched for maps (--maps, else $ORCH_MAPS and sumo_nets/).
  std::vector<std::filesystem::path> search(o.common.map_dirs.begin(), o.common.map_dirs.end());
  if (search.empty()) search = MapRegistry::default_search_dirs();
  const auto searched = [&] {
    for (const auto& d : search)
      if (std::filesystem::equivalent(d, dir.parent_path().empty() ? "." : dir.parent_path(), ec)) return true;
    return false;
  };
  if (const MapManifest* other = registry.find(id); other && !same_folder(*other) && searched())
    throw MapError(fmt::format("a map named \"{}\" already exists in {}, and {} would be loaded beside it; choose "
                               "another --id, or give --out a folder outside the maps folders ({}) and name its "
                               "parent with --maps when running",
                               id, other->dir.string(), dir.string(), [&] {
                                 std::string list;
                                 for (const auto& d : search) list += (list.empty() ? "" : ", ") + d.string();
                                 return list;
                               }()));

  MapManifest m;
  m.max_edge_length = kDefaultMaxEdgeLength;
  if (std::filesystem::exists(dir / "map.json")) m = load_map_manifest(dir);  // keep its settings and aliases
  const std::filesystem::path source(o.waypoints);
  m.id = id;
  m.dir = dir;
  m.waypoint_file = source.filename().string();
  m.net_file = id + ".net.xml";
  if (m.description.empty())
    m.description = fmt::format("RoadEditor waypoint file {}; the SUMO net is generated by `orchestrator map build`",
                                m.waypoint_file);
  std::vector<std::string> aliases;
  for (const auto& a : o.aliases) add_unique(aliases, a, id);
  // Scenarios may name the map by the waypoint file's own ids.
  add_unique(aliases, waypoints.map_id, id);
  add_unique(aliases, waypoints.id, id);
  for (const auto& a : m.aliases) add_unique(aliases, a, id);
  m.aliases = aliases;
  for (const auto& a : m.aliases)
    if (const MapManifest* other = registry.find(a); other && !same_folder(*other))
      std::cerr << fmt::format("warning: the alias \"{}\" also names the map \"{}\" in {}; scenarios using it get "
                               "whichever map is found first\n", a, other->id, other->dir.string());

  std::filesystem::create_directories(dir, ec);
  if (ec) throw MapError(fmt::format("cannot create {}: {}", dir.string(), ec.message()));
  const std::filesystem::path copy = dir / m.waypoint_file;
  if (!std::filesystem::exists(copy) || !std::filesystem::equivalent(source, copy)) {
    std::filesystem::copy_file(source, copy, std::filesystem::copy_options::overwrite_existing, ec);
    if (ec) throw MapError(fmt::format("cannot copy {} to {}: {}", source.string(), copy.string(), ec.message()));
    // The copy is the map's own source file: writable like the rest of the folder, even
    // when the original was read-only.
    using std::filesystem::perms;
    std::filesystem::permissions(copy, perms::owner_read | perms::owner_write | perms::group_read | perms::others_read,
                                 std::filesystem::perm_options::replace, ec);
  }
  save_map_manifest(m);
  return m;
}

}  // namespace

int map_build_command(const MapBuildOptions& o) {
  const MapRegistry registry = make_registry(o.common);
  if (!o.waypoints.empty()) {
    if (!o.maps.empty()) throw MapError("give either maps to rebuild or --waypoints for a new map, not both");
    return build_map(create_map_folder(o, registry)) ? 0 : 1;
  }
  if (!o.id.empty() || !o.aliases.empty() || !o.out.empty())
    throw MapError("--id, --alias and --out describe a new map: use them with --waypoints");
  std::vector<MapManifest> targets;
  for (const auto& name : o.maps) targets.push_back(resolve_map(registry, name));
  if (o.maps.empty()) targets = registry.maps();
  if (targets.empty()) throw MapError("no maps found to build (see --maps)");
  bool all_fit = true;
  for (const auto& m : targets) all_fit = build_map(m) && all_fit;
  return all_fit ? 0 : 1;
}

int map_check_command(const MapCheckOptions& o) {
  const MapRegistry registry = make_registry(o.common);
  std::vector<MapManifest> targets;
  for (const auto& name : o.maps) targets.push_back(resolve_map(registry, name));
  if (o.maps.empty()) targets = registry.maps();
  if (targets.empty()) throw MapError("no maps found to check (see --maps)");

  std::size_t routes = 0;
  std::size_t points = 0;
  double largest = 0;
  std::string largest_at = "-";
  std::vector<std::string> failures;
  std::vector<std::string> errors;
  for (const MapManifest& m : targets) {
    fmt::print("map {} ({})\n", m.id, m.net_path().string());
    try {
      const WaypointFile waypoints = load_waypoint_file(m.waypoint_path().string());
      const LaneMap lanes = LaneMap::build(m.net_path().string(), waypoints);
      std::size_t width = 5;
      for (const auto& r : waypoints.routes) width = std::max(width, r.id.size());
      fmt::print("  {:<{}}  {:>6}  {:>12}  {:>8}  {}\n", "route", width, "points", "max distance", "wp_idx", "lanes");
      for (const WaypointRoute& r : waypoints.routes) {
        const RouteLanes& rl = *lanes.route(r.id);
        const Deviation d = worst_deviation(rl);
        fmt::print("  {:<{}}  {:>6}  {:>10.4f} m  {:>8}  {}\n", r.id, width, r.points.size(), d.distance, d.wp_idx,
                   lane_list(lanes, rl));
        ++routes;
        points += r.points.size();
        if (d.distance > largest || largest_at == "-") {
          largest = d.distance;
          largest_at = fmt::format("map {} route {} wp_idx {}", m.id, r.id, d.wp_idx);
        }
        if (d.distance > o.tolerance)
          failures.push_back(fmt::format("map {} route {}: {:.4f} m at wp_idx {}", m.id, r.id, d.distance, d.wp_idx));
      }
    } catch (const OrchError& e) {
      fmt::print("  error: {}\n", e.what());
      errors.push_back(m.id);
    }
  }
  fmt::print("summary: {} maps, {} routes, {} points; largest distance {:.4f} m ({}); tolerance {:.2f} m\n",
             targets.size(), routes, points, largest, largest_at, o.tolerance);
  for (const auto& f : failures) fmt::print("  over tolerance: {}\n", f);
  if (!errors.empty()) {
    fmt::print("  could not check: {}\n", fmt::join(errors, ", "));
    return 2;  // a broken map is an error, not a failed check
  }
  fmt::print("{}\n", failures.empty() ? "OK" : "FAILED");
  return failures.empty() ? 0 : 1;
}

}  // namespace orch::cli

#include "map/background_traffic.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <pugixml.hpp>
#include <set>
#include <sstream>
#include <string_view>

#include "core/checked_numeric.hpp"
#include "core/xml_text.hpp"
#include "core/errors.hpp"
#include "core/files.hpp"

namespace orch {

namespace {

constexpr double kBegin = 1.0;       // s: background traffic starts after the actors are in
constexpr double kFillWindow = 1.0;  // s over which the fill vehicles are inserted
constexpr double kEnd = 86400.0;     // s: entries run for a day of simulated time (SUMO's default)

struct NetLane {
  double length = 0;  // m
  double speed = 0;   // m/s
  // Open to the background cars (passenger class): false for lanes an `allow` list closes to
  // them, e.g. the hard shoulders of converted OpenDRIVE roads (allow="authority").
  bool for_cars = true;
};

struct NetEdge {
  std::string id;
  std::vector<NetLane> lanes;
  std::vector<std::string> next;  // normal edges reached through connections
  bool has_previous = false;
};

bool lane_open_to_cars(std::string_view allow) {
  if (allow.empty() || allow == "all") return true;
  std::istringstream classes{std::string(allow)};
  std::string c;
  while (classes >> c)
    if (c == "passenger") return true;
  return false;
}

std::vector<NetEdge> read_net_edges(const std::filesystem::path& net_file) {
  pugi::xml_document doc;
  const pugi::xml_parse_result parsed = doc.load_file(net_file.c_str());
  if (!parsed) throw MapError(fmt::format("{}: cannot read the SUMO net: {}", net_file.string(), parsed.description()));
  std::vector<NetEdge> edges;
  std::map<std::string, std::size_t> index;
  for (const pugi::xml_node e : doc.child("net").children("edge")) {
    if (!std::string_view(e.attribute("function").as_string()).empty()) continue;  // internal, walking areas
    NetEdge edge;
    edge.id = e.attribute("id").as_string();
    for (const pugi::xml_node l : e.children("lane"))
      edge.lanes.push_back({l.attribute("length").as_double(), l.attribute("speed").as_double(),
                            lane_open_to_cars(l.attribute("allow").as_string())});
    index[edge.id] = edges.size();
    edges.push_back(std::move(edge));
  }
  for (const pugi::xml_node c : doc.child("net").children("connection")) {
    const auto from = index.find(c.attribute("from").as_string());
    const auto to = index.find(c.attribute("to").as_string());
    if (from == index.end() || to == index.end()) continue;  // via internal lanes
    auto& next = edges[from->second].next;
    if (std::find(next.begin(), next.end(), to->first) == next.end()) next.push_back(to->first);
    edges[to->second].has_previous = true;
  }
  if (edges.empty()) throw MapError(fmt::format("{}: the SUMO net has no edges", net_file.string()));
  return edges;
}

// The road ends (edges without a successor) a vehicle entering `start` can reach, sorted.
std::vector<std::string> sinks_from(const std::vector<NetEdge>& edges, const std::string& start) {
  std::map<std::string, const NetEdge*> by_id;
  for (const auto& e : edges) by_id[e.id] = &e;
  std::set<std::string> seen;
  std::set<std::string> sinks;
  std::vector<std::string> todo{start};
  while (!todo.empty()) {
    const std::string id = todo.back();
    todo.pop_back();
    if (!seen.insert(id).second) continue;
    const NetEdge& e = *by_id.at(id);
    if (e.next.empty()) sinks.insert(id);
    for (const auto& n : e.next) todo.push_back(n);
  }
  return {sinks.begin(), sinks.end()};
}

std::string flow(const std::string& id, const std::string& from, const std::string& to, int lane,
                 const std::string& amount, const char* depart_pos) {
  return fmt::format(
      "    <flow id=\"{}\" type=\"orch.background\" begin=\"{:.2f}\" {} from=\"{}\" to=\"{}\" departLane=\"{}\" "
      "departPos=\"{}\" departSpeed=\"max\"/>\n",
      xml_escape(id), kBegin, amount, xml_escape(from), xml_escape(to), lane, depart_pos);
}

// Distance from the start of its road to the start of each edge, following connections:
// the order in which vehicles are placed front to back.
std::map<std::string, double> road_offsets(const std::vector<NetEdge>& edges) {
  std::map<std::string, const NetEdge*> by_id;
  for (const auto& e : edges) by_id[e.id] = &e;
  std::map<std::string, double> offset;
  std::vector<std::string> todo;
  for (const auto& e : edges)
    if (!e.has_previous) {
      offset[e.id] = 0;
      todo.push_back(e.id);
    }
  while (!todo.empty()) {
    const NetEdge& e = *by_id.at(todo.back());
    todo.pop_back();
    const double end = offset[e.id] + (e.lanes.empty() ? 0.0 : e.lanes.front().length);
    for (const auto& n : e.next)
      if (!offset.count(n) || offset[n] < end) {
        offset[n] = end;
        todo.push_back(n);
      }
  }
  return offset;
}

// Vehicles at evenly spaced places on every lane (a jam is possible: random_free finds no
// room beyond about 30 vehicles per km and lane). Written front to back along each road, so
// that SUMO inserts each one behind the ones already there, at the highest safe speed.
std::string even_fill(const std::vector<NetEdge>& edges, double per_km) {
  struct Placed {
    double along;
    std::string line;
  };
  const auto offset = road_offsets(edges);
  std::vector<Placed> placed;
  for (std::size_t k = 0; k < edges.size(); ++k) {
    const NetEdge& e = edges[k];
    const std::vector<std::string> sinks = sinks_from(edges, e.id);
    if (sinks.empty()) continue;  // a closed ring: no way out for a trip
    const std::string& sink = sinks.front();
    for (int lane = 0; lane < static_cast<int>(e.lanes.size()); ++lane) {
      if (!e.lanes[static_cast<std::size_t>(lane)].for_cars) continue;
      const double length = e.lanes[static_cast<std::size_t>(lane)].length;
      const long n = clamped_round<long>(per_km * length / 1000.0, 0, 1L << 30);
      for (long i = 0; i < n; ++i) {
        const double pos = length * (static_cast<double>(n - i) - 0.5) / static_cast<double>(n);
        placed.push_back({offset.count(e.id) ? offset.at(e.id) + pos : pos,
                          fmt::format("    <trip id=\"bgfill{}_{}.{}\" type=\"orch.background\" depart=\"{:.2f}\" "
                                      "from=\"{}\" to=\"{}\" departLane=\"{}\" departPos=\"{:.2f}\" "
                                      "departSpeed=\"max\"/>\n",
                                      k, lane, i, kBegin, xml_escape(e.id), xml_escape(sink), lane, pos)});
      }
    }
  }
  std::stable_sort(placed.begin(), placed.end(), [](const Placed& a, const Placed& b) { return a.along > b.along; });
  std::string out;
  for (const auto& p : placed) out += p.line;
  return out;
}

}  // namespace

TrafficChoice parse_traffic(const std::string& text) {
  TrafficChoice c;
  c.label = text.empty() ? "none" : text;
  if (text.empty() || text == "none") return c;
  for (const auto& level : kTrafficLevels)
    if (text == level.name) {
      c.kind = TrafficChoice::Kind::Rate;
      c.vehicles_per_hour_per_lane = level.vehicles_per_hour_per_lane;
      return c;
    }
  std::size_t used = 0;
  double rate = -1;
  try {
    rate = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == text.size() && std::isfinite(rate) && rate >= 0) {
    c.kind = rate > 0 ? TrafficChoice::Kind::Rate : TrafficChoice::Kind::None;
    c.vehicles_per_hour_per_lane = rate;
    return c;
  }
  std::error_code ec;
  if (std::filesystem::is_regular_file(text, ec)) {
    c.kind = TrafficChoice::Kind::File;
    c.file = std::filesystem::absolute(text);
    return c;
  }
  throw OrchError(fmt::format("traffic \"{}\": expected none, light, medium, dense, vehicles per hour and lane (a "
                              "number), or an existing SUMO route file",
                              text));
}

std::string background_traffic_xml(const std::filesystem::path& net_file, const TrafficSettings& s) {
  const std::vector<NetEdge> edges = read_net_edges(net_file);
  std::string fills;
  std::string entries;
  for (std::size_t k = 0; k < edges.size(); ++k) {
    const NetEdge& e = edges[k];
    const std::vector<std::string> sinks = sinks_from(edges, e.id);
    // From a closed ring (a loop with no road leaving it) no trip can end: no traffic there.
    if (sinks.empty()) continue;
    for (int lane = 0; lane < static_cast<int>(e.lanes.size()); ++lane) {
      const NetLane& l = e.lanes[static_cast<std::size_t>(lane)];
      if (!l.for_cars) continue;
      // Steady state of the rate at the lane's speed: vehicles/h over km/h = vehicles/km.
      const double per_km = s.fill_per_km >= 0 ? s.fill_per_km
                                               : s.vehicles_per_hour_per_lane / (std::max(l.speed, 1.0) * 3.6);
      const long number = clamped_round<long>(per_km * l.length / 1000.0, 0, 1L << 30);
      if (number > 0 && s.fill_per_km < 0)
        fills += flow(fmt::format("bgfill{}_{}", k, lane), e.id, sinks.front(), lane,
                      fmt::format("end=\"{:.2f}\" number=\"{}\"", kBegin + kFillWindow, number), "random_free");
      if (e.has_previous || s.vehicles_per_hour_per_lane <= 0) continue;
      // Entries at the start of each road, Poisson arrivals shared among its ends.
      const double per_second = s.vehicles_per_hour_per_lane / 3600.0 / static_cast<double>(sinks.size());
      for (std::size_t j = 0; j < sinks.size(); ++j)
        entries += flow(sinks.size() == 1 ? fmt::format("bg{}_{}", k, lane) : fmt::format("bg{}_{}_{}", k, lane, j),
                        e.id, sinks[j], lane, fmt::format("end=\"{:.2f}\" period=\"exp({:.6f})\"", kEnd, per_second),
                        "base");
    }
  }
  std::string out = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  out += fmt::format(
      "<!-- Background traffic for {}, generated by `orchestrator map traffic`; do not edit, regenerate.\n"
      "     Level {}: {:g} vehicles per hour and lane entering each road (Poisson, from t={:g} s), {} at t={:g}..{:g} s "
      "along every lane. -->\n",
      xml_escape(net_file.filename().string()), xml_escape(s.label), s.vehicles_per_hour_per_lane, kBegin,
      s.fill_per_km >= 0 ? fmt::format("{:g} vehicles per km and lane, evenly spaced,", s.fill_per_km)
                         : std::string("the steady state of that rate"),
      kBegin, kBegin + kFillWindow);
  out += "<routes>\n";
  out += "    <vType id=\"orch.background\" vClass=\"passenger\" color=\"170,170,170\"/>\n";
  if (s.fill_per_km >= 0) fills = even_fill(edges, s.fill_per_km);
  out += fills + entries + "</routes>\n";
  return out;
}

std::filesystem::path map_traffic_file(const MapManifest& map, const std::string& level) {
  return map.dir / "traffic" / (level + ".rou.xml");
}

std::vector<std::filesystem::path> write_map_traffic(const MapManifest& map) {
  std::vector<std::filesystem::path> written;
  std::error_code ec;
  std::filesystem::create_directories(map.dir / "traffic", ec);
  if (ec) throw MapError(fmt::format("cannot create {}: {}", (map.dir / "traffic").string(), ec.message()));
  for (const auto& level : kTrafficLevels) {
    const auto path = map_traffic_file(map, level.name);
    write_file_atomically(path, background_traffic_xml(map.net_path(), {level.vehicles_per_hour_per_lane, -1, level.name}));
    written.push_back(path);
  }
  return written;
}

std::filesystem::path traffic_file_for_run(const TrafficChoice& choice, const MapManifest& map,
                                           const std::filesystem::path& out_dir) {
  switch (choice.kind) {
    case TrafficChoice::Kind::None: return {};
    case TrafficChoice::Kind::File: return choice.file;
    case TrafficChoice::Kind::Rate: break;
  }
  const auto stored = map_traffic_file(map, choice.label);
  if (std::filesystem::exists(stored)) return stored;
  const auto generated = std::filesystem::absolute(out_dir / "traffic.rou.xml");
  write_file_atomically(generated,
                        background_traffic_xml(map.net_path(), {choice.vehicles_per_hour_per_lane, -1, choice.label}));
  return generated;
}

}  // namespace orch

#include "map/map_registry.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/errors.hpp"
#include "core/files.hpp"
#include "json/object_file.hpp"

namespace orch {

MapManifest load_map_manifest(const std::filesystem::path& dir) {
  const std::string path = (dir / "map.json").string();
  JsonObjectFile json(path, "map manifest");
  const JsonDocument& doc = json.doc();
  Diagnostics& diags = json.diags();
  ObjectReader& r = json.top();
  MapManifest m;
  m.dir = dir;
  m.id = r.string("id", Need::Required).value_or("");
  if (const auto* aliases = r.array("aliases", Need::Optional)) {
    for (std::size_t i = 0; i < aliases->size(); ++i) {
      if ((*aliases)[i].is_string()) m.aliases.push_back((*aliases)[i].get<std::string>());
      else diags.error(doc.where(json_pointer_child(r.child("aliases"), i)), "an alias must be a string");
    }
  }
  m.description = r.string("description", Need::Optional).value_or("");
  m.waypoint_file = r.string("waypoint_file", Need::Required).value_or("");
  m.net_file = r.string("net_file", Need::Required).value_or("");
  if (const auto* build = r.object("build", Need::Optional)) {
    ObjectReader b(doc, *build, r.child("build"), diags, "build settings");
    m.lane_extension = b.number("lane_extension_m", Need::Optional).value_or(m.lane_extension);
    m.simplify_tolerance = b.number("simplify_tolerance_m", Need::Optional).value_or(m.simplify_tolerance);
    m.max_edge_length = b.number("max_edge_length_m", Need::Optional).value_or(m.max_edge_length);
    b.finish();
  }
  if (const auto* list = r.array("junctions", Need::Optional)) {
    for (std::size_t i = 0; i < list->size(); ++i) {
      ObjectReader j(doc, (*list)[i], json_pointer_child(r.child("junctions"), i), diags, "junction setting");
      if (!j.is_object()) continue;
      JunctionOverride o;
      o.id = j.string("id", Need::Optional).value_or("");
      if (const auto* at = j.array("at", Need::Optional)) {
        if (at->size() == 2 && (*at)[0].is_number() && (*at)[1].is_number())
          o.at = Vec2((*at)[0].get<double>(), (*at)[1].get<double>());
        else
          j.error("at", "expected [x, y] in the map frame (m)");
      }
      if (o.id.empty() && !o.at) j.error("", "a junction setting names its junction by \"id\" or \"at\"");
      o.type = j.choice("type", {std::begin(kJunctionTypes), std::end(kJunctionTypes)}, Need::Optional).value_or("");
      if (const auto* routes = j.array("priority_routes", Need::Optional))
        for (std::size_t k = 0; k < routes->size(); ++k) {
          if ((*routes)[k].is_string()) o.priority_routes.push_back((*routes)[k].get<std::string>());
          else diags.error(doc.where(json_pointer_child(j.child("priority_routes"), k)), "a route id must be a string");
        }
      j.allow({"note"});
      j.finish();
      m.junctions.overrides.push_back(std::move(o));
    }
  }
  // Documentation-only blocks: how map coordinates relate to the waypoint file, provenance.
  r.allow({"transform", "source"});
  json.finish();
  return m;
}

void save_map_manifest(const MapManifest& m) {
  nlohmann::ordered_json j;
  j["id"] = m.id;
  j["aliases"] = m.aliases;
  j["description"] = m.description;
  j["waypoint_file"] = m.waypoint_file;
  j["net_file"] = m.net_file;
  j["transform"] = {{"map_x", "x"}, {"map_y", "-z"}, {"height", "y"},
                    {"note", "SUMO coordinates equal map coordinates (netconvert --offset.disable-normalization)"}};
  j["build"] = {{"lane_extension_m", m.lane_extension},
                {"simplify_tolerance_m", m.simplify_tolerance},
                {"max_edge_length_m", m.max_edge_length}};
  if (!m.junctions.overrides.empty()) {
    j["junctions"] = nlohmann::ordered_json::array();
    for (const auto& o : m.junctions.overrides) {
      nlohmann::ordered_json x;
      if (!o.id.empty()) x["id"] = o.id;
      if (o.at) x["at"] = {o.at->x(), o.at->y()};
      if (!o.type.empty()) x["type"] = o.type;
      if (!o.priority_routes.empty()) x["priority_routes"] = o.priority_routes;
      j["junctions"].push_back(x);
    }
  }
  write_file_atomically(m.dir / "map.json", j.dump(2) + "\n");
}

MapRegistry::MapRegistry(const std::vector<std::filesystem::path>& search_dirs) {
  for (const auto& dir : search_dirs) {
    std::error_code ec;
    if (!std::filesystem::is_directory(dir, ec)) continue;
    std::vector<std::filesystem::path> sub;
    for (const auto& entry : std::filesystem::directory_iterator(dir, ec))
      if (entry.is_directory() && std::filesystem::exists(entry.path() / "map.json")) sub.push_back(entry.path());
    std::sort(sub.begin(), sub.end());
    for (const auto& p : sub) {
      MapManifest m = load_map_manifest(p);
      if (!find(m.id)) maps_.push_back(std::move(m));  // earlier search dirs win
    }
  }
}

std::vector<std::filesystem::path> MapRegistry::default_search_dirs() {
  std::vector<std::filesystem::path> dirs;
  if (const char* env = std::getenv("ORCH_MAPS"); env && *env) {
    std::stringstream ss(env);
    std::string part;
    while (std::getline(ss, part, ':'))
      if (!part.empty()) dirs.emplace_back(part);
  }
  dirs.emplace_back(ORCH_SOURCE_MAPS_DIR);
  return dirs;
}

const MapManifest* MapRegistry::find(std::string_view id) const {
  for (const auto& m : maps_)
    if (m.id == id) return &m;
  for (const auto& m : maps_)
    if (std::find(m.aliases.begin(), m.aliases.end(), id) != m.aliases.end()) return &m;
  return nullptr;
}

std::vector<std::string> MapRegistry::ids() const {
  std::vector<std::string> out;
  for (const auto& m : maps_) {
    out.push_back(m.id);
    out.insert(out.end(), m.aliases.begin(), m.aliases.end());
  }
  return out;
}

}  // namespace orch

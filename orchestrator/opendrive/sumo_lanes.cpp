#include "opendrive/sumo_lanes.hpp"

#include <fmt/format.h>
#include <pugixml.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <set>
#include <vector>

#include "core/errors.hpp"
#include "opendrive/lane_graph.hpp"
#include "opendrive/sumo_net.hpp"

namespace orch::opendrive {

namespace {

// The lane types the conversion drops, read from the same type map netconvert gets.
const std::set<std::string>& discarded_lane_types() {
  static const std::set<std::string> types = [] {
    std::set<std::string> out;
    pugi::xml_document doc;
    const std::string xml = lane_type_map_xml();
    doc.load_buffer(xml.data(), xml.size());
    for (const pugi::xml_node type : doc.child("types").children("type"))
      if (type.attribute("discard").as_bool(false)) out.insert(type.attribute("id").value());
    return out;
  }();
  return types;
}

}  // namespace

SumoLaneIndex::SumoLaneIndex(const RoadNetwork& roads, const std::string& net_file) : roads_(roads) {
  pugi::xml_document doc;
  if (const auto ok = doc.load_file(net_file.c_str()); !ok)
    throw MapError(fmt::format("cannot read the SUMO net {}: {}", net_file, ok.description()));
  for (const pugi::xml_node edge : doc.child("net").children("edge")) {
    if (std::string(edge.attribute("function").value()) == "internal") continue;
    int lanes = 0;
    for ([[maybe_unused]] const pugi::xml_node lane : edge.children("lane")) ++lanes;
    lane_counts_[edge.attribute("id").value()] = lanes;
  }
  for (const pugi::xml_node c : doc.child("net").children("connection"))
    connections_.emplace(c.attribute("from").value(), c.attribute("to").value());
}

bool SumoLaneIndex::connected(const std::string& from, const std::string& to) const {
  return connections_.count({from, to}) > 0;
}

std::optional<SumoLane> SumoLaneIndex::entry_near(const std::string& road_id, int lane_id, double s,
                                                 double spread) const {
  if (const Road* road = roads_.find(road_id); road && !road->sections.empty()) {
    // The lanes of the section outward from `lane_id`'s side first, by distance in lanes.
    const LaneSection& section = road->section_at(s);
    std::vector<int> ids;
    for (const Lane& lane : section.right) ids.push_back(lane.id);
    for (const Lane& lane : section.left) ids.push_back(lane.id);
    std::stable_sort(ids.begin(), ids.end(), [&](int a, int b) {
      const bool a_side = (a < 0) == (lane_id < 0), b_side = (b < 0) == (lane_id < 0);
      if (a_side != b_side) return a_side;
      return std::abs(a - lane_id) < std::abs(b - lane_id);
    });
    for (const int id : ids)
      if (auto lane = find(road_id, id, s)) return lane;
  }
  for (const Road& road : roads_.roads()) {
    if (road.sections.empty()) continue;
    const double at = road.length > 0 ? std::fmod(std::max(0.0, spread), road.length) : 0.0;
    const LaneSection& section = road.section_at(at);
    for (const auto* side : {&section.right, &section.left})
      for (const Lane& lane : *side)
        if (auto found = find(road.id, lane.id, at)) return found;
  }
  return std::nullopt;
}

std::optional<SumoLane> SumoLaneIndex::find(const std::string& road_id, int lane_id, double s) const {
  const Road* road = roads_.find(road_id);
  if (!road || lane_id == 0 || road->sections.empty()) return std::nullopt;
  const LaneSection& section = road->section_at(s);
  const std::string base = (lane_id < 0 ? "-" : "") + road_id;
  // The road's single edge, else the piece "<edge>#<k>" of the lane section holding s:
  // netconvert splits the road's edges at its lane sections and numbers the pieces along s
  // on both sides (checked against netconvert 1.15 in test_opendrive_sumo_lanes.cpp).
  std::string edge;
  const std::size_t section_index = opendrive::section_index(*road, s);
  if (lane_counts_.count(base)) {
    edge = base;
  } else {
    if (const std::string piece = base + "#" + std::to_string(section_index); lane_counts_.count(piece)) edge = piece;
  }
  if (edge.empty()) return std::nullopt;
  // Rank of the lane among the kept lanes of its side, counted outward from the centre.
  const auto& side = lane_id < 0 ? section.right : section.left;
  int rank = 0;
  bool kept = false;
  for (const Lane& lane : side) {
    if (discarded_lane_types().count(lane.type)) {
      if (lane.id == lane_id) return std::nullopt;
      continue;
    }
    if (lane.id == lane_id) {
      kept = true;
      break;
    }
    ++rank;
  }
  const int count = lane_counts_.at(edge);
  if (!kept || rank >= count) return std::nullopt;
  // Edge length is not needed exactly: the position only seeds SUMO's insertion.
  const double section_end = [&] {
    for (const LaneSection& next : road->sections)
      if (next.s > section.s + 1e-9) return next.s;
    return road->length;
  }();
  const double along = lane_id < 0 ? s - section.s : section_end - s;
  return SumoLane{edge, count - 1 - rank, std::max(0.0, along)};
}

}  // namespace orch::opendrive

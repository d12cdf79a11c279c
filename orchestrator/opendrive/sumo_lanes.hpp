#pragma once
// Which SUMO lane netconvert made of an OpenDRIVE lane: the hint SUMO needs to put a scripted
// entity on the right lane. netconvert names an edge after its road: "-<road>" for the right
// lanes (driving along s), "<road>" for the left ones, split into "<edge>#0", "#1", ... along
// s when the road has several lane sections; the lanes whose type the lane type map discards
// (lane_type_map_xml) are dropped and SUMO lane 0 is the outermost of those kept.
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "opendrive/road_network.hpp"

namespace orch::opendrive {

struct SumoLane {
  std::string edge;
  int index = 0;          // SUMO lane index, 0 = rightmost in the driving direction
  double lane_pos = 0.0;  // distance along the edge in its driving direction (approximate)
};

class SumoLaneIndex {
 public:
  // Reads the edges and their lane counts from `net_file`. Throws MapError when it cannot.
  SumoLaneIndex(const RoadNetwork& roads, const std::string& net_file);
  // The SUMO lane of OpenDRIVE lane `lane_id` of `road_id` at `s`; nullopt when netconvert
  // made none of it (a discarded lane type, the centre lane, an unknown road).
  [[nodiscard]] std::optional<SumoLane> find(const std::string& road_id, int lane_id, double s) const;
  // A SUMO lane near a place that has none, where a scripted entity can enter SUMO before it
  // is moved to its place off the lanes: the lane of `road_id` at `s` nearest `lane_id` (a
  // border or a lane of type none beside it), else on any road, `spread` metres along it (so
  // that several such entities do not enter at one point). nullopt: the net has no lane.
  [[nodiscard]] std::optional<SumoLane> entry_near(const std::string& road_id, int lane_id, double s,
                                                   double spread) const;
  [[nodiscard]] const RoadNetwork& roads() const { return roads_; }
  // Whether the net lets a vehicle drive from edge `from` onto edge `to` (a <connection>).
  [[nodiscard]] bool connected(const std::string& from, const std::string& to) const;

 private:
  const RoadNetwork& roads_;
  std::map<std::string, int> lane_counts_;  // edge id -> number of lanes
  std::set<std::pair<std::string, std::string>> connections_;  // (from edge, to edge)
};

}  // namespace orch::opendrive

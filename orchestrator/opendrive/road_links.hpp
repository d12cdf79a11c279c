#pragma once
// OpenDRIVE links as plain values: a road's predecessor / successor (a road or a junction,
// with the contact point), a lane's predecessor / successor lane in the neighbouring lane
// section or road, and junctions with their connections (incoming road, connecting road,
// contact point, lane links). lane_graph.hpp follows them.
#include <optional>
#include <string>
#include <vector>

namespace orch::opendrive {

enum class ContactPoint { None, Start, End };

struct RoadLink {
  enum class Kind { None, Road, Junction };
  Kind kind = Kind::None;
  std::string id;                            // road or junction id
  ContactPoint contact = ContactPoint::None;  // the end of the linked road (roads only)
};

struct LaneLinkPair {
  int from = 0;  // lane of the incoming road
  int to = 0;    // lane of the connecting road
};

struct JunctionConnection {
  std::string id;
  std::string incoming_road;
  std::string connecting_road;  // or, in a direct junction, the linkedRoad
  ContactPoint contact = ContactPoint::Start;  // the end of the connecting road at the incoming road
  std::vector<LaneLinkPair> lane_links;
};

struct Junction {
  std::string id;
  std::vector<JunctionConnection> connections;  // in file order
};

}  // namespace orch::opendrive

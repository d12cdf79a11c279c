#pragma once
// The traffic actions of the OpenSCENARIO model (kept apart from model.hpp, which holds them
// in its PrivateAction variant).

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "map/position.hpp"

namespace orch::openscenario {

using position::Position;

// Traffic actions (GlobalAction/TrafficAction): vehicles SUMO's driver drives, spawned and
// removed around an entity or a position (openscenario/traffic_book.hpp keeps which run; on
// SUMO run/openscenario_traffic.hpp). `name` is the TrafficAction's trafficName ("" when the
// file gives none: no TrafficStopAction can name it). Categories: the TrafficDefinition's
// VehicleCategoryDistribution, or 1.3's TrafficDistribution (its entries' EntityDistributions:
// each vehicle template a share of weight entry x template / their sums, with its bounding
// box's size); empty: cars.
struct TrafficCategoryShare {
  std::string category;  // car, van, truck, bus, motorbike, bicycle, ...
  double weight = 1;
  std::optional<double> length, width, height;  // a TrafficDistribution's vehicle: its BoundingBox
};
struct TrafficSwarmAction {
  std::string name;
  std::string entity;  // CentralObject: the swarm's centre
  double inner_radius = 0, semi_major = 0, semi_minor = 0;
  double offset = 0;  // the ellipse's centre, ahead of the central entity along its heading
  int vehicles = 0;   // numberOfVehicles: at most this many at a time
  std::optional<double> speed;                               // velocity (deprecated in 1.2)
  std::optional<std::pair<double, double>> speed_range;      // InitialSpeedRange (1.2)
  std::optional<std::pair<double, double>> direction_weights;  // DirectionOfTravelDistribution: same, opposite
  std::vector<TrafficCategoryShare> categories;
};
struct TrafficSourceAction {
  std::string name;
  Position position;
  double radius = 0, rate = 0;  // m; vehicles per second
  std::optional<double> speed;  // velocity (deprecated in 1.2)
  std::optional<std::pair<double, double>> speed_range;
  std::vector<TrafficCategoryShare> categories;
};
struct TrafficSinkAction {
  std::string name;
  Position position;
  double radius = 0;
  std::optional<double> rate;  // vehicles per second; absent: every vehicle in the radius at once
};
struct TrafficStopAction { std::string name; };

// TrafficAreaAction (1.3): numberOfEntities vehicles in an area, given as a Polygon (positions
// resolved when the action starts) or as RoadRanges (each a list of RoadCursors: a road, an s,
// the lanes; the range runs from cursor to cursor, at most `length` m). `continuous`: a vehicle
// that leaves the area is replaced; else the area is filled once.
struct TrafficAreaRoadCursor {
  std::string road;
  std::optional<double> s;  // absent: the road's start (first cursor) or end (a later one)
  std::vector<int> lanes;   // absent: every lane
};
struct TrafficAreaRoadRange {
  std::optional<double> length;
  std::vector<TrafficAreaRoadCursor> cursors;  // two or more
};
struct TrafficAreaAction {
  std::string name;
  int entities = 0;
  bool continuous = false;
  std::vector<Position> polygon;                  // three or more; empty: road_ranges
  std::vector<TrafficAreaRoadRange> road_ranges;  // empty: polygon
  std::vector<TrafficCategoryShare> categories;
};  // ends the traffic of that trafficName

}  // namespace orch::openscenario

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
// VehicleCategoryDistribution (empty: cars).
struct TrafficCategoryShare {
  std::string category;  // car, van, truck, bus, motorbike, bicycle, ...
  double weight = 1;
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
struct TrafficStopAction { std::string name; };  // ends the traffic of that trafficName

}  // namespace orch::openscenario

#include "run/reference_ego_setup.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

#include "core/checked_numeric.hpp"
#include "core/errors.hpp"

namespace orch {

using reference_driver::DrivingPath;
using reference_driver::ObjectKind;
using reference_driver::ObjectKinds;
using reference_driver::ReferenceEgo;

namespace {
reference_driver::OwnModel own_model_of(const EgoModelChoice& choice) {
  return choice.cruise() ? reference_driver::OwnModel::Cruise : reference_driver::OwnModel::R157;
}
}  // namespace

reference_driver::R157Parameters r157_parameters(const EgoModelChoice& choice) {
  reference_driver::R157Parameters p;
  try {
    reference_driver::apply_overrides(p, choice.parameters);
  } catch (const std::invalid_argument& e) {
    throw ScenarioError(SourceLocation{"EgoModel", "/Parameters", 0}, e.what());
  }
  return p;
}

std::optional<ReferenceEgo> reference_ego_for(const EgoModelChoice& choice, const engine::Engine& engine,
                                              const LaneMap& lanes, double step) {
  if (!choice.own_model()) return std::nullopt;
  const engine::ActorSlot* ego = nullptr;
  ObjectKinds kinds;
  for (const auto& slot : engine.actors().slots()) {
    if (slot.is_ego()) ego = &slot;
    if (slot.tracked.kind == ActorKind::Pedestrian) kinds[slot.tracked.sumo_id] = ObjectKind::Pedestrian;
    if (slot.tracked.kind == ActorKind::Obstacle) kinds[slot.tracked.sumo_id] = ObjectKind::Obstacle;
  }
  const WaypointRoute* route = ego ? engine.route_of(ego->spec.id) : nullptr;
  if (!route) throw OrchError("--ego-model " + choice.name + ": the ego has no route to drive (the engine has not placed it)");
  DrivingPath path;
  path.line = route->line;
  // The ego's end_position as the engine tells SUMO to stop there: the same place.
  path.stop_to_s = [&lanes, route](const sim::SetStop& stop) -> std::optional<double> {
    for (std::size_t i = 0; i < lanes.lanes().size(); ++i) {
      const LaneInfo& lane = lanes.lanes()[i];
      if (lane.edge != stop.edge || lane.index != stop.lane) continue;
      const Vec2 p = lane.shape.point_at(stop.lane_pos * lane.geometry_factor());
      return route->line.project(p).s;
    }
    return std::nullopt;
  };
  if (const RouteLanes* rl = lanes.route(route->id); rl && !rl->lanes.empty())
    path.lane_width = lanes.lane(rl->lanes.front()).width;
  return ReferenceEgo(r157_parameters(choice), std::move(path), ego->tracked.sumo_id, std::move(kinds), step,
                      route->speed_at(0), own_model_of(choice));
}

DrivingPath lane_path(const opendrive::RoadNetwork& roads, const openscenario::EntityState& start) {
  const opendrive::Road& road = roads.road(start.road_id);
  // The lane's centre line in the lane's driving direction (right lanes along s).
  std::vector<Vec2> points;
  const int n = clamped_floor<int>(road.length, 2, 1 << 30);
  for (int i = 0; i <= n; ++i) {
    const double s = road.length * i / n;
    const opendrive::Pose2 p = roads.lane_pose(start.road_id, start.lane, s, 0.0);
    points.emplace_back(p.x, p.y);
  }
  const bool along_s = (start.lane < 0) != road.left_hand_traffic;
  if (!along_s) std::reverse(points.begin(), points.end());
  DrivingPath path;
  path.line = Polyline(std::move(points));
  const auto [inner, outer] = road.lane_borders(start.lane, start.s);
  path.lane_width = std::abs(outer - inner);
  return path;
}

ObjectKinds object_kinds(const openscenario::Scenario& scenario) {
  ObjectKinds kinds;
  for (const auto& e : scenario.entities) {
    if (e.kind == openscenario::EntityKind::Pedestrian) kinds[e.name] = ObjectKind::Pedestrian;
    if (e.kind == openscenario::EntityKind::MiscObject) kinds[e.name] = ObjectKind::Obstacle;
  }
  return kinds;
}

std::optional<ReferenceEgo> reference_ego_for(const EgoModelChoice& choice, const openscenario::Scenario& scenario,
                                              const opendrive::RoadNetwork& roads, const std::string& ego,
                                              const openscenario::EntityState& start, double step) {
  if (!choice.own_model() || ego.empty() || !start.placed) return std::nullopt;
  return ReferenceEgo(r157_parameters(choice), lane_path(roads, start), ego, object_kinds(scenario), step, start.speed,
                      own_model_of(choice));
}

}  // namespace orch

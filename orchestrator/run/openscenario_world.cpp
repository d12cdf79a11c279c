#include "run/openscenario_world.hpp"

#include <fmt/format.h>

#include <cmath>

#include "core/errors.hpp"
#include "core/suggest.hpp"
#include "reference_driver/ego_model.hpp"

namespace orch {

namespace {

// The controller the OSC-ALKS files give the system under test.
constexpr const char* kSystemUnderTestController = "ALKSController";

// SUMO vehicle shapes for OpenSCENARIO vehicle categories (sumo-gui only).
std::string gui_shape_for(const std::string& category) {
  if (category == "truck" || category == "semitrailer" || category == "trailer") return "truck";
  if (category == "bus") return "bus";
  if (category == "motorbike") return "motorcycle";
  if (category == "bicycle") return "bicycle";
  if (category == "van") return "delivery";
  return "passenger";
}

ModelInfo model_of(const openscenario::Entity& e) {
  ModelInfo m;
  m.id = e.object_name;
  // Every entity is a SUMO vehicle, pedestrians too: SUMO persons need sidewalks, which
  // the roads of OpenSCENARIO files (motorways) often lack; scripted poses need no walking
  // model. Traffic sees them as obstacles on the lane either way.
  m.kind = ActorKind::Vehicle;
  const bool pedestrian = e.kind == openscenario::EntityKind::Pedestrian;
  m.length = e.box.length;
  m.width = e.box.width;
  m.height = e.box.height;
  // Scripted entities may stand on hard shoulders, which the converted nets open to the
  // class "authority" only (sumo_net.hpp); background traffic yields to them all the same.
  m.vclass = "authority";
  m.gui_shape = pedestrian ? "pedestrian" : gui_shape_for(e.category);
  return m;
}

}  // namespace

std::string choose_ego_entity(const openscenario::Scenario& scenario, const std::string& requested) {
  std::vector<std::string> names;
  for (const auto& e : scenario.entities) names.push_back(e.name);
  if (!requested.empty()) {
    if (scenario.entity(requested)) return requested;
    throw ScenarioError(SourceLocation{scenario.file, "/OpenSCENARIO/Entities", 0},
                        fmt::format("--ego {}: no such entity{}", requested, did_you_mean(requested, names)));
  }
  // The system under test's controller, or the R157 reference driver's (reference_driver/ego_model.hpp).
  for (const auto& e : scenario.entities)
    if (e.controller && (e.controller->name == kSystemUnderTestController || e.controller->name == kR157ControllerName))
      return e.name;
  return "";
}

OpenScenarioActors::OpenScenarioActors(const openscenario::Scenario& scenario, const opendrive::SumoLaneIndex& lanes,
                                       std::string ego)
    : lanes_(lanes), ego_(std::move(ego)) {
  for (const auto& e : scenario.entities) {
    Body body;
    body.id = static_cast<engine::ActorId>(names_.size());
    body.model = model_of(e);
    body.centre_x = e.box.center_x;
    body.centre_y = e.box.center_y;
    names_.push_back(e.name);
    bodies_.emplace(e.name, std::move(body));
  }
}

Vec2 OpenScenarioActors::centre_of(const Body& body, const opendrive::Pose2& pose) const {
  const double c = std::cos(pose.heading), s = std::sin(pose.heading);
  return {pose.x + body.centre_x * c - body.centre_y * s, pose.y + body.centre_x * s + body.centre_y * c};
}

Vec2 OpenScenarioActors::reference_point(const engine::ActorState& state) const {
  const Body& body = bodies_.at(name_of(state.id));
  const double c = std::cos(state.heading), s = std::sin(state.heading);
  return {state.position.x() - body.centre_x * c + body.centre_y * s,
          state.position.y() - body.centre_x * s - body.centre_y * c};
}

std::vector<engine::Command> OpenScenarioActors::place(const std::map<std::string, openscenario::EntityState>& entities) {
  std::vector<engine::Command> out;
  for (const auto& [name, state] : entities) {
    if (!state.placed) continue;
    Body& body = bodies_.at(name);
    const bool is_ego = name == ego_;
    if (is_ego && body.spawned) {
      // The storyboard's speed target (the last SpeedAction's), else the speed it had.
      const double desired = state.speed_profile ? state.speed_profile->to : ego_desired_speed_;
      if (desired != ego_desired_speed_) out.push_back(engine::SetMaxSpeed{name, desired});
      ego_desired_speed_ = desired;
      continue;
    }
    const auto hint = lanes_.find(state.road_id, state.lane, state.s);
    const Vec2 centre = centre_of(body, state.pose);
    if (!body.spawned) {
      if (!hint)
        throw MapError(fmt::format("entity {} starts on road {} lane {} at s={:.2f}, of which the SUMO net has no lane",
                                   name, state.road_id, state.lane, state.s));
      engine::TrackedActor actor{body.id, name, body.model.kind, body.model.length, body.model.width};
      engine::SpawnVehicle spawn;
      spawn.actor = actor;
      spawn.model = body.model;
      spawn.route = {hint->edge};
      spawn.edge = hint->edge;
      spawn.lane = hint->index;
      spawn.lane_pos = hint->lane_pos + body.centre_x;
      spawn.speed = state.speed;
      if (is_ego) {
        spawn.scripted = false;
        ego_desired_speed_ = state.speed_profile ? state.speed_profile->to : state.speed;
        spawn.max_speed = ego_desired_speed_;
      }
      out.push_back(std::move(spawn));
      tracked_.push_back(actor);
      body.spawned = true;
    }
    engine::SetPose pose;
    pose.sumo_id = name;
    pose.kind = body.model.kind;
    pose.length = body.model.length;
    pose.position = centre;
    pose.heading = state.pose.heading;
    pose.speed = state.speed;
    pose.edge = hint ? hint->edge : "";
    pose.lane = hint ? hint->index : 0;
    pose.centred = std::abs(state.offset) < 0.5;
    pose.scripted = !is_ego;  // the ego: one placement, then SUMO drives
    out.push_back(std::move(pose));
  }
  return out;
}

}  // namespace orch

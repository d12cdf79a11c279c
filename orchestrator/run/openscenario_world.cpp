#include "run/openscenario_world.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "core/errors.hpp"
#include "core/suggest.hpp"
#include "opendrive/sumo_route.hpp"
#include "openscenario/route_plan.hpp"
#include "run/openscenario_ego_choice.hpp"
#include "run/roadless_net.hpp"

namespace orch {

namespace {

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
  return choose_ego(scenario, requested).entity;
}

OpenScenarioActors::OpenScenarioActors(const openscenario::Scenario& scenario, const opendrive::SumoLaneIndex& lanes,
                                       std::string ego, EgoDrive drive)
    : lanes_(lanes),
      ego_(std::move(ego)),
      ego_driven_(drive != EgoDrive::Storyboard),
      ego_drive_(ego_, drive == EgoDrive::External) {
  for (const auto& e : scenario.entities) {
    Body body;
    body.id = static_cast<sim::ActorId>(names_.size());
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

Vec2 OpenScenarioActors::reference_point(const sim::ActorState& state) const {
  const Body& body = bodies_.at(name_of(state.id));
  const double c = std::cos(state.heading), s = std::sin(state.heading);
  return {state.position.x() - body.centre_x * c + body.centre_y * s,
          state.position.y() - body.centre_x * s - body.centre_y * c};
}


std::vector<std::string> OpenScenarioActors::sumo_route_of(const openscenario::EntityState& state) const {
  return opendrive::sumo_route(lanes_, lanes_.roads(), state.road_id, state.lane, state.s,
                               openscenario::lanes_ahead(state, lanes_.roads()));
}

void OpenScenarioActors::spawn(const std::string& name, Body& body, const openscenario::EntityState& state,
                               std::vector<sim::Command>& out) {
  // An entity on no road (a scenario without one) enters SUMO on the parking road and is moved
  // to its world position by the pose that follows (run/roadless_net.hpp). One where the net
  // has no lane (a border, a lane of type none, off every lane of the roads) enters on a lane
  // near it and is moved off the lanes the same way; SUMO's driver drives on lanes only.
  auto hint = state.road_id.empty() ? lanes_.find(kParkingRoadId, kParkingLane, parking_place(body.id))
                                    : lanes_.find(state.road_id, state.lane, state.s);
  if (!hint && !body.driven) hint = lanes_.entry_near(state.road_id, state.lane, state.s, parking_place(body.id));
  if (!hint)
    throw MapError(fmt::format("entity {} starts on road {} lane {} at s={:.2f}, of which the SUMO net has no lane",
                               name, state.road_id, state.lane, state.s));
  ++body.lives;
  const bool driven_ego = ego_driven_ && name == ego_;
  const std::string first_id = driven_ego ? ego_drive_.sumo_id() : name;
  body.sumo_id = body.lives == 1 ? first_id : fmt::format("{}~{}", first_id, body.lives);
  sim::TrackedActor actor{body.id, body.sumo_id, body.model.kind, body.model.length, body.model.width};
  sim::SpawnVehicle command;
  command.actor = actor;
  command.model = body.model;
  command.route = {hint->edge};
  command.edge = hint->edge;
  command.lane = hint->index;
  command.lane_pos = hint->lane_pos + body.centre_x;
  command.speed = state.speed;
  if (body.driven) {
    command.scripted = false;
    // SUMO drives it: along its route plan and on through the net, not one edge and gone.
    if (auto route = sumo_route_of(state); !route.empty() && route.front() == hint->edge) command.route = std::move(route);
    body.route_version = state.route_version;
    body.desired_speed = storyboard_desired_speed(state, -1);
    command.max_speed = driven_ego ? ego_drive_.spawn_speed(state) : body.desired_speed;
  }
  out.push_back(std::move(command));
  const auto known = std::find_if(tracked_.begin(), tracked_.end(), [&](const auto& t) { return t.id == body.id; });
  if (known == tracked_.end()) tracked_.push_back(actor);
  else *known = actor;
  body.spawned = true;
}

double OpenScenarioActors::height_of(const std::string& name) const {
  const auto it = bodies_.find(name);
  return it == bodies_.end() ? 0.0 : it->second.height;
}

std::vector<sim::Command> OpenScenarioActors::place(const std::map<std::string, openscenario::EntityState>& entities) {
  std::vector<sim::Command> out;
  for (const auto& [name, state] : entities) {
    Body& body = bodies_.at(name);
    body.height = state.height;
    const bool is_ego = ego_driven_ && name == ego_;  // the driven ego; a storyboard one is as any entity
    const bool in_traffic = state.placed && state.visibility.traffic;
    if (!in_traffic) {
      if (body.spawned) {
        out.push_back(sim::RemoveActor{body.sumo_id, body.model.kind});
        body.spawned = false;
      }
      continue;
    }
    // SUMO's driver drives on lanes: an entity on no road (a scenario without one) stays the
    // storyboard's when its controller is activated (docs/openscenario.md, "Without a road").
    const bool hand_over = controllers_ && !body.driven && !is_ego && state.controller_active &&
                           !state.controller.empty() && !state.road_id.empty();
    if (is_ego || hand_over) body.driven = true;
    const bool first = !body.spawned;
    if (first) {
      spawn(name, body, state, out);
    } else if (body.driven && !is_ego) {
      const double desired = storyboard_desired_speed(state, body.desired_speed);
      if (hand_over) out.push_back(sim::ReleaseActor{body.sumo_id, desired});
      else if (desired != body.desired_speed) out.push_back(sim::SetMaxSpeed{body.sumo_id, desired});
      body.desired_speed = desired;
      if (hand_over || body.route_version != state.route_version) set_route(body, state, out);
      continue;
    }
    const auto hint = lanes_.find(state.road_id, state.lane, state.s);
    sim::SetPose pose;
    pose.sumo_id = body.sumo_id;
    pose.kind = body.model.kind;
    pose.length = body.model.length;
    pose.position = centre_of(body, state.pose);
    pose.heading = state.pose.heading;
    pose.speed = state.speed;
    pose.edge = hint ? hint->edge : "";
    pose.lane = hint ? hint->index : 0;
    pose.centred = std::abs(state.offset) < 0.5;
    if (is_ego && !first) {  // who moves the ego this step: openscenario_ego.hpp
      for (auto& c : ego_drive_.commands(state, pose)) out.push_back(std::move(c));
      // A route assigned later (the plug-in, once it drives, gets nothing from the orchestrator).
      if (body.route_version != state.route_version && ego_drive_.driver(state) != OpenScenarioEgo::Driver::Plugin)
        set_route(body, state, out);
      continue;
    }
    pose.scripted = !body.driven;  // SUMO-driven: one placement, then SUMO drives
    out.push_back(std::move(pose));
  }
  return out;
}

void OpenScenarioActors::set_route(Body& body, const openscenario::EntityState& state,
                                   std::vector<sim::Command>& out) {
  body.route_version = state.route_version;
  if (auto route = sumo_route_of(state); !route.empty()) out.push_back(sim::SetRoute{body.sumo_id, std::move(route)});
}

std::vector<std::string> OpenScenarioActors::sumo_driven() const {
  std::vector<std::string> names;
  for (const auto& [name, body] : bodies_)
    if (body.driven && body.spawned) names.push_back(name);
  return names;
}

bool OpenScenarioActors::is_sumo_driven(const std::string& name) const { return bodies_.at(name).driven; }

}  // namespace orch

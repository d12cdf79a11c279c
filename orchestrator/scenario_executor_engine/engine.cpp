#include "scenario_executor_engine/engine.hpp"

#include <fmt/format.h>

#include "scenario_executor_engine/conditions.hpp"

namespace orch::engine {

using namespace orch::scenario;

namespace {
std::string join(const std::vector<std::string>& parts) {
  std::string out;
  for (const auto& p : parts) out += (out.empty() ? "" : "; ") + p;
  return out;
}
}  // namespace

Engine::Engine(const Scenario& s, MapContext map, const Catalog& catalog, EngineOptions options)
    : scenario_(s), map_(map), options_(options), actors_(s, catalog), machine_(s), collisions_(actors_) {}

const WaypointRoute* Engine::route_of(ActorId id) const {
  if (auto it = motions_.find(id); it != motions_.end()) return &it->second.route();
  if (id == scenario_.ego.id) return ego_route_;
  return nullptr;
}

bool Engine::collided(ActorId id) const { return collisions_.touching(id); }

std::optional<ActorId> Engine::actor_named(const std::string& name) const {
  for (const auto& a : actors_.slots())
    if (std::to_string(a.spec.id) == name) return a.spec.id;
  return std::nullopt;
}

std::string Engine::describe_body(const std::string& name) const {
  for (const auto& a : actors_.slots())
    if (std::to_string(a.spec.id) == name) return "actor " + name + (a.is_ego() ? " (ego)" : "");
  return "vehicle " + name;
}

bool Engine::siren(ActorId id) const {
  auto it = sirens_.find(id);
  return it != sirens_.end() && it->second;
}

void Engine::fail(const std::string& reason, double t, StepOutput& out) {
  state_ = RunState::Error;
  end_reason_ = reason;
  out.events.push_back({t, EventKind::Warning, reason});
}

StepOutput Engine::step(const WorldSnapshot& snapshot) {
  StepOutput out = step_scene_graph(snapshot);
  for (Event& e : out.events)
    if (!e.scene) e.scene = machine_.current();
  return out;
}

StepOutput Engine::step_scene_graph(const WorldSnapshot& snapshot) {
  StepOutput out;
  if (state_ != RunState::Running) return out;
  if (!current_.actors.empty()) previous_ = std::move(current_);
  current_ = snapshot;
  const double t = snapshot.time;

  for (auto& a : current_.actors) {
    auto it = motions_.find(a.id);
    if (it == motions_.end()) continue;
    if (!a.present) {
      fail(fmt::format("actor {} is no longer in the simulation (SUMO removed it)", a.id), t, out);
      return out;
    }
    check_placement(a, t, out);
    // SUMO derives a placed vehicle's speed from the distance it was moved; the scenario's
    // own value is exact, and conditions must see exactly what the scenario commanded.
    a.speed = it->second.speed();
    a.accel = it->second.accel();
    // Likewise the lights: SUMO recomputes some signals itself (it blinks an emergency
    // vehicle's blue light on its own); the scenario's lights are what was commanded.
    auto lights = signals_.find(a.id);
    a.signals = lights == signals_.end() ? 0 : lights->second;
    a.siren = siren(a.id);
  }
  update_ego(out);
  for (const Contact& c : collisions_.step(current_)) {
    out.events.push_back({t, EventKind::Warning,
                          fmt::format("collision ({}): {} at ({:.2f}, {:.2f}) and {} at ({:.2f}, {:.2f})",
                                      c.source == "geometry" ? "bodies touch"
                                      : c.counted            ? "reported by SUMO"
                                                             : "reported by SUMO, for information",
                                      describe_body(c.a),
                                      c.position_a.x(), c.position_a.y(), describe_body(c.b), c.position_b.x(),
                                      c.position_b.y())});
    out.events.back().actor = actor_named(c.a);
  }

  for (const LaneChangeConflict& c : conflicts_.step(current_)) {
    out.events.push_back({t, EventKind::Warning,
                          fmt::format("lane change conflict: actor {} changing to {} has vehicle {} {:.1f} m {} it in "
                                      "the target lane (time gap {:.2f} s)",
                                      c.actor, c.target_route, c.vehicle, c.gap, c.vehicle_ahead ? "ahead of" : "behind",
                                      c.time_gap)});
    out.events.back().actor = c.actor;
  }

  ConditionContext ctx{current_, previous_ ? &*previous_ : nullptr, actors_, map_.waypoints,
                       [this](ActorId id) { return route_of(id); }, [this](ActorId id) { return collided(id); },
                       [this](ActorId id) {
                         auto it = motions_.find(id);
                         return it == motions_.end() ? 1 : it->second.direction();
                       },
                       [this](ActorId a, ActorId b) { return collisions_.touching(a, b); }, &meetings_};
  std::vector<std::string> fired;
  const auto transition = machine_.step(t, [&](const Scene& scene) {
    fired.clear();
    return evaluate(scene.conditions, ctx, &fired);
  });
  if (transition) {
    const Scene& to = *transition->to;
    out.events.push_back({t, EventKind::Scene,
                          fmt::format("scene {} -> {}{}{}", transition->from, to.id,
                                      to.description.empty() ? "" : " \"" + to.description + "\"",
                                      fired.empty() ? std::string(" (no conditions)") : ": " + join(fired))});
    if (to.ending) {
      state_ = RunState::EndingReached;
      end_reason_ = fmt::format("ending scene {}{} reached{}", to.id,
                                to.description.empty() ? "" : " \"" + to.description + "\"",
                                fired.empty() ? std::string{} : ": " + join(fired));
      return out;
    }
    enter_scene(to, t, out);
    if (state_ != RunState::Running) return out;
  }
  if (scenario_.stop_conditions) {
    std::vector<std::string> stop_fired;
    if (evaluate(*scenario_.stop_conditions, ctx, &stop_fired) && !scenario_.stop_conditions->items.empty()) {
      state_ = RunState::StopConditionMet;
      end_reason_ = "stop condition met: " + join(stop_fired);
      out.events.push_back({t, EventKind::Scene, end_reason_});
      return out;
    }
  }
  move_scripted_actors(t, out);
  return out;
}

void Engine::enter_scene(const Scene& scene, double t, StepOutput& out) {
  for (const auto& action : scene.actions) {
    start_action(action, t, out);
    if (state_ != RunState::Running) return;
  }
}

void Engine::update_ego(StepOutput& out) {
  const ActorState* ego = current_.find(scenario_.ego.id);
  if (!ego || !ego->present || !ego_route_) return;
  ego_s_ = ego_route_->line.project_near(ego->position, ego_s_, 50.0).s;
  const double v = ego_route_->speed_at(ego_s_);
  if (!options_.external_ego && std::abs(v - ego_max_speed_) > 1e-6) {
    ego_max_speed_ = v;
    out.commands.push_back(SetMaxSpeed{"ego", v});
  }
}

void Engine::move_scripted_actors(double t, StepOutput& out) {
  for (auto& [id, motion] : motions_) {
    resolve_longitudinal(id, motion);
    motion.advance(t, options_.step);
    const ActorSlot* slot = actors_.find(id);
    out.commands.push_back(pose_command(*slot, motion));
    const auto& pose = std::get<SetPose>(out.commands.back());
    if (pose.centred) placed_on_[id] = {pose.edge, pose.lane};
    else placed_on_.erase(id);
    if (motion.running_out_of_road() && !reported_route_end_[id]) {
      reported_route_end_[id] = true;
      out.events.push_back({t + options_.step, EventKind::Warning,
                            fmt::format("actor {} runs out of road at the end of route {}: it brakes to stop there",
                                        id, motion.route().id)});
      out.events.back().actor = id;
    }
  }
}

// A scripted vehicle centred on its route's lane must be where it was put: on a junction's
// interior SUMO could match it to a crossing lane, and then it would be in the wrong
// vehicles' way. Said once per actor and lane.
void Engine::check_placement(const ActorState& a, double t, StepOutput& out) {
  const auto it = placed_on_.find(a.id);
  if (it == placed_on_.end() || (a.edge == it->second.first && a.lane == it->second.second)) return;
  // Where one internal lane of the route ends and the next begins, SUMO may keep the front
  // on the one before for a step: still the route's own lane, not a crossing one.
  if (const auto m = motions_.find(a.id); m != motions_.end())
    if (const RouteLanes* rl = map_.lanes.route(m->second.route().id)) {
      const std::string sumo_lane = fmt::format("{}_{}", a.edge, a.lane);
      for (const int l : rl->lanes)
        if (map_.lanes.lane(l).id == sumo_lane) return;
    }
  const std::string key = fmt::format("{}:{}_{}", a.id, it->second.first, it->second.second);
  if (!misplaced_.insert(key).second) return;
  out.events.push_back({t, EventKind::Warning,
                        fmt::format("SUMO placed actor {} on lane {}_{} instead of its route's lane {}_{}", a.id,
                                    a.edge, a.lane, it->second.first, it->second.second)});
}

SetPose Engine::pose_command(const ActorSlot& slot, const ScriptedMotion& m) const {
  SetPose p;
  p.sumo_id = slot.tracked.sumo_id;
  p.kind = slot.tracked.kind;
  p.length = slot.tracked.length;
  p.position = m.position();
  p.heading = m.heading();
  p.speed = m.speed();
  if (auto it = signals_.find(slot.spec.id); it != signals_.end()) p.signals = it->second;
  if (!m.walking()) {
    // SUMO places a vehicle by its front bumper and matches the lane named by the hint to
    // the front's position: name the lane under the front, or on a short lane inside a
    // junction SUMO would pick a crossing lane of its own choosing.
    const double front_s = m.s() + m.direction() * slot.tracked.length / 2;
    const LanePlace place = map_.lanes.place_on_route(m.route(), front_s, m.route_lateral());
    if (place.lane >= 0) {
      p.edge = map_.lanes.lane(place.lane).edge;
      p.lane = map_.lanes.lane(place.lane).index;
      p.centred = std::abs(place.lateral) < kCentredOnLane;
    }
  } else if (const auto place = map_.lanes.locate(p.position, p.heading)) {
    p.edge = map_.lanes.lane(place->lane).edge;
    p.lane = map_.lanes.lane(place->lane).index;
  }
  return p;
}

}  // namespace orch::engine

// The opening scene: where every actor starts and how fast.
#include <fmt/format.h>

#include <set>

#include "core/errors.hpp"
#include "scenario_executor_engine/engine.hpp"
#include "map/position_resolver.hpp"

namespace orch::engine {

using namespace orch::scenario;

namespace {

// The actors placed so far, for positions relative to them (by id in decimal).
class PlacedActors final : public position::Entities {
 public:
  PlacedActors(const WorldSnapshot& snapshot, const ActorTable& actors,
               std::function<const WaypointRoute*(ActorId)> route_of)
      : snapshot_(snapshot), actors_(actors), route_of_(std::move(route_of)) {}
  [[nodiscard]] std::optional<opendrive::Pose2> pose(const std::string& name) const override {
    const ActorState* a = snapshot_.find(std::stoi(name));
    if (!a) return std::nullopt;
    return opendrive::Pose2{a->position.x(), a->position.y(), a->heading};
  }
  [[nodiscard]] const WaypointRoute* route(const std::string& name) const override { return route_of_(std::stoi(name)); }
  [[nodiscard]] double length(const std::string& name) const override {
    const ActorSlot* slot = actors_.find(std::stoi(name));
    return slot ? slot->model.length : 0.0;
  }

 private:
  const WorldSnapshot& snapshot_;
  const ActorTable& actors_;
  std::function<const WaypointRoute*(ActorId)> route_of_;
};

// A WaypointRef's route and arc length.
position::RoutePlace route_place(const WaypointFile& wps, const WaypointRef& ref) {
  return position::PositionResolver(wps).place(ref);
}

// Initial speed from a start_speed block, evaluated at t = 0 against speeds already known.
double initial_speed(const std::optional<SpeedAction>& start, const std::map<ActorId, double>& known) {
  if (!start) return 0.0;
  if (start->accel.type == AccelType::Specify && start->accel.value > 0) return 0.0;  // accelerates from rest
  double v = start->value;
  if (start->type == SpeedType::Relative) {
    auto it = known.find(start->target.value_or(0));
    v += it != known.end() ? it->second : 0.0;
  }
  return std::max(0.0, v);
}

}  // namespace

double Engine::ego_start_s() const {
  return route_place(map_.waypoints, *scenario_.opening.ego.start.waypoint).s;
}

void Engine::spawn_ego(StepOutput& out) {
  const EgoOpening& o = scenario_.opening.ego;
  ego_route_ = route_place(map_.waypoints, *o.start.waypoint).route;
  ego_s_ = ego_start_s();
  double end_s = ego_route_->line.length();
  if (o.end) {
    const position::RoutePlace end = route_place(map_.waypoints, *o.end);
    const Vec2 end_point = end.route->line.point_at(end.s);
    // The ego drives its own route; an end on another route means the point beside it (on
    // its own route the waypoint itself: a loop passes the point's place more than once).
    end_s = end.route == ego_route_ ? end.s : ego_route_->line.project(end_point).s;
  }
  if (end_s <= ego_s_) {
    out.events.push_back({0, EventKind::Warning, "the ego's end_position is not ahead of its start: it stays where it starts"});
    end_s = ego_s_;
  }
  const ActorSlot& slot = *actors_.find(scenario_.ego.id);
  // Inside a junction SUMO cannot insert it: it starts where the next lane begins.
  const LanePlace place = map_.lanes.normal_place_on_route(*ego_route_, ego_s_, o.start.wp_offset, true);
  if (place.lane < 0) throw MapError("the ego's start position is not on any lane of the map");
  SpawnVehicle spawn;
  spawn.actor = slot.tracked;
  spawn.model = slot.model;
  spawn.color = slot.spec.color;
  spawn.scripted = false;
  spawn.route = map_.lanes.route_edges(*ego_route_, ego_s_, end_s);
  spawn.edge = map_.lanes.lane(place.lane).edge;
  spawn.lane = map_.lanes.lane(place.lane).index;
  spawn.lane_pos = place.lane_pos;
  spawn.speed = 0;
  ego_max_speed_ = ego_route_->speed_at(ego_s_);
  spawn.max_speed = options_.external_ego ? 0 : ego_max_speed_;  // 0: the type's own
  out.commands.push_back(spawn);

  // A start beside the route line or turned away from it: placed once, then SUMO drives.
  const StartPosition& sp = o.start;
  if (std::abs(sp.wp_offset) > 1e-9 || sp.heading) {
    spawn.keep_lateral = true;
    SetPose pose;
    pose.sumo_id = slot.tracked.sumo_id;
    pose.length = slot.tracked.length;
    pose.position = ego_route_->line.offset_point(ego_s_, sp.wp_offset);
    pose.heading = wrap_angle(ego_route_->line.heading_at(ego_s_) + sp.heading.value_or(0.0));
    pose.edge = spawn.edge;
    pose.lane = spawn.lane;
    pose.scripted = false;
    out.commands.back() = spawn;
    out.commands.push_back(pose);
  }

  if (options_.external_ego) return;
  // An end inside a junction: it stops before the junction (SUMO stops on normal lanes only).
  const LanePlace end_place = map_.lanes.normal_place_on_route(*ego_route_, end_s, 0.0, false);
  out.commands.push_back(SetStop{"ego", map_.lanes.lane(end_place.lane).edge, map_.lanes.lane(end_place.lane).index,
                                 end_place.lane_pos, slot.tracked.length});
}

void Engine::place_other(const OtherOpening& o) {
  const ActorSlot& slot = *actors_.find(o.actor);
  const StartPosition& p = o.start;
  if (p.type == StartPositionType::Distance) {
    const ActorId target = p.target.value_or(scenario_.ego.id);
    if (!route_of(target) || !current_.find(target)) throw ScenarioError(p.where, "the start position's target actor is not placed");
  }
  const PlacedActors placed(current_, actors_, [this](ActorId id) { return route_of(id); });
  const position::RoutePlace place =
      *position::PositionResolver(map_.waypoints).resolve(p.position(scenario_.ego.id), placed, slot.model.length).route;
  const WaypointRoute* route = place.route;
  const double s = place.s;
  // A start before its route begins has no lane to stand on (SUMO would hold the vehicle off
  // the network; libsumo 1.15 then crashes when it is read).
  if (s < 0)
    throw ScenarioError(p.where, fmt::format("actor {} would start {:.1f} m before the start of its route {}: "
                                             "choose a smaller distance behind its target, or another start",
                                             o.actor, -s, route->id));
  std::map<ActorId, double> speeds;
  for (const auto& a : current_.actors) speeds[a.id] = a.speed;
  const double v0 = initial_speed(o.start_speed, speeds);
  auto [it, inserted] = motions_.emplace(
      o.actor, ScriptedMotion(*route, s, p.wp_offset, v0, p.heading.value_or(0.0), slot.model.length,
                              map_.lane_extension));
  if (o.start_speed) longitudinal_[o.actor] = HoldSpeed{*o.start_speed};
  else longitudinal_[o.actor] = HoldSpeed{SpeedAction{o.actor, SpeedType::Absolute, std::nullopt, 0.0, {}}};

  ActorState state;
  state.id = o.actor;
  state.present = true;
  state.position = it->second.position();
  state.heading = it->second.heading();
  state.speed = v0;
  current_.actors.push_back(state);
}

void Engine::place_opening_actors(StepOutput& out) {
  spawn_ego(out);
  ActorState ego;
  ego.id = scenario_.ego.id;
  ego.present = true;
  ego.position = ego_route_->line.point_at(ego_s_);
  ego.heading = ego_route_->line.heading_at(ego_s_);
  current_.actors.push_back(ego);

  // Actors placed relative to another actor come after it (the validator rejects cycles).
  std::set<ActorId> placed{scenario_.ego.id};
  std::vector<const OtherOpening*> todo;
  for (const auto& o : scenario_.opening.others) todo.push_back(&o);
  while (!todo.empty()) {
    const std::size_t before = todo.size();
    for (auto it = todo.begin(); it != todo.end();) {
      const StartPosition& p = (*it)->start;
      const bool ready = p.type == StartPositionType::Waypoint || placed.count(p.target.value_or(scenario_.ego.id));
      if (!ready) {
        ++it;
        continue;
      }
      place_other(**it);
      placed.insert((*it)->actor);
      it = todo.erase(it);
    }
    if (todo.size() == before) throw ScenarioError(todo.front()->where, "start positions refer to each other in a cycle");
  }
}

StepOutput Engine::start() {
  StepOutput out;
  current_ = WorldSnapshot{};
  place_opening_actors(out);
  // Scripted actors appear at their poses of the first step, when SUMO inserts them.
  StepOutput moved;
  move_scripted_actors(0.0, moved);
  for (const auto& cmd : moved.commands) {
    const auto& pose = std::get<SetPose>(cmd);
    const ActorSlot& slot = *actors_.find_sumo(pose.sumo_id);
    const ScriptedMotion& m = motions_.at(slot.spec.id);
    // Inserted on a normal lane (SUMO cannot insert inside a junction); the pose command right
    // after puts it where the scenario says.
    const LanePlace place = map_.lanes.normal_place_on_route(m.route(), m.s(), m.route_lateral(), true);
    if (place.lane < 0) throw MapError(fmt::format("actor {} does not start on a lane of the map", slot.spec.id));
    const LaneInfo& lane = map_.lanes.lane(place.lane);
    if (slot.tracked.kind == ActorKind::Pedestrian) {
      out.commands.push_back(SpawnPerson{slot.tracked, slot.model, slot.spec.color, lane.edge, place.lane_pos});
    } else {
      SpawnVehicle v;
      v.actor = slot.tracked;
      v.model = slot.model;
      v.color = slot.spec.color;
      v.scripted = true;
      v.route = map_.lanes.route_edges(m.route(), m.s(), m.route().line.length());
      v.edge = lane.edge;
      v.lane = lane.index;
      v.lane_pos = place.lane_pos;
      v.speed = m.speed();
      out.commands.push_back(v);
    }
    out.commands.push_back(cmd);
  }
  out.events.insert(out.events.end(), moved.events.begin(), moved.events.end());
  out.events.push_back({0, EventKind::Scene,
                        fmt::format("scene 0 (opening): {} actors placed", actors_.slots().size())});
  // The start's events belong to the opening scene, as every step's to the scene it ends in.
  for (Event& e : out.events)
    if (!e.scene) e.scene = machine_.current();
  current_ = WorldSnapshot{};
  return out;
}

}  // namespace orch::engine

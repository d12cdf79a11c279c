#include "reference_driver/reference_ego.hpp"

#include <algorithm>
#include <cmath>

namespace orch::reference_driver {

namespace {

// Where a point lies along and beside the path; beyond the path's ends the end segments go
// on straight (objects past the end of the ego's route are still ahead of it).
struct PathPlace {
  double s = 0;
  double d = 0;
};
PathPlace place_on(const Polyline& line, const Vec2& p, double s_hint, double window) {
  const auto proj = line.project_near(p, s_hint, window);
  if (!proj.after_end && !proj.before_start) return {proj.s, proj.lateral};
  const double s_end = proj.after_end ? line.length() : 0.0;
  const Vec2 t = line.tangent_at(proj.after_end ? line.length() : 0.0);
  const Vec2 rel = p - line.point_at(s_end);
  return {s_end + rel.dot(t), rel.dot(left_normal(t))};
}

// An object's motion split along and across the path at its place.
PerceivedObject in_path_frame(const Polyline& line, double ego_s, double window, const Vec2& position, double heading,
                              double speed, double accel) {
  PerceivedObject o;
  const PathPlace at = place_on(line, position, ego_s, window);
  o.s = at.s;
  o.d = at.d;
  const double relative = heading - line.heading_at(std::clamp(at.s, 0.0, line.length()));
  o.speed_s = speed * std::cos(relative);
  o.speed_d = speed * std::sin(relative);
  o.accel_s = accel * std::cos(relative);
  return o;
}

// The cruise model's speed: towards the set speed whatever is ahead, at the reference
// driver's comfortable acceleration and deceleration (a ScenarioExecutor ego starts standing);
// only the end of its path stops it, at the comfortable deceleration (as SUMO stops the
// built-in ego at its end_position).
double cruise_speed(const DriverView& view, const R157Parameters& p) {
  double wanted = view.set_speed;
  if (view.path_end)
    wanted = std::min(wanted, std::sqrt(2 * p.comfort_deceleration * std::max(0.0, *view.path_end - view.ego.s)));
  return std::clamp(wanted, view.ego.speed - p.comfort_deceleration * view.step,
                    view.ego.speed + p.comfort_acceleration * view.step);
}

}  // namespace

double NearbyMotion::accel(const std::string& id, double time, double speed) {
  auto [it, first] = seen_.try_emplace(id, Seen{time, speed, 0.0});
  Seen& s = it->second;
  if (first || time <= s.time) return s.accel;
  // One step since the last sighting: the speed difference over it (SUMO's own integration);
  // after a gap (out of reach meanwhile) nothing is known.
  const double dt = time - s.time;
  s.accel = dt < 0.5 ? (speed - s.speed) / dt : 0.0;
  s.time = time;
  s.speed = speed;
  return s.accel;
}

void NearbyMotion::sweep(double time) {
  std::erase_if(seen_, [time](const auto& kv) { return kv.second.time < time; });
}

std::optional<DriverView> perceive(const sim::WorldSnapshot& snap, const std::vector<sim::TrackedActor>& tracked,
                                   const ObjectKinds& kinds, const std::string& ego, const DrivingPath& path,
                                   double path_s, double range, NearbyMotion* motion) {
  std::size_t me_at = tracked.size();
  for (std::size_t i = 0; i < tracked.size() && i < snap.actors.size(); ++i)
    if (tracked[i].sumo_id == ego) me_at = i;
  if (me_at == tracked.size() || !snap.actors[me_at].present || path.line.empty()) return std::nullopt;
  const sim::ActorState* me = &snap.actors[me_at];
  DriverView view;
  view.time = snap.time;
  view.lane_width = path.lane_width;
  view.path_end = path.end_s;
  const PathPlace at = place_on(path.line, me->position, path_s < 0 ? path.line.project(me->position).s : path_s, 50.0);
  view.ego = {at.s, at.d, me->speed, tracked[me_at].length, tracked[me_at].width};
  const double window = range + 50.0;
  auto near_enough = [&](const PerceivedObject& o) {
    return !(o.s < view.ego.s - 50.0 || o.s > view.ego.s + range + 10.0 || std::abs(o.d) > 3 * path.lane_width);
  };
  for (std::size_t i = 0; i < snap.actors.size() && i < tracked.size(); ++i) {
    const sim::ActorState& a = snap.actors[i];
    if (!a.present || i == me_at) continue;
    // Cheap first test before projecting: within reach of the ego at all.
    if ((a.position - me->position).norm() > range + 60.0) continue;
    PerceivedObject o = in_path_frame(path.line, view.ego.s, window, a.position, a.heading, a.speed, a.accel);
    if (!near_enough(o)) continue;
    o.id = tracked[i].sumo_id;
    const auto kind = kinds.find(tracked[i].sumo_id);
    o.kind = kind != kinds.end() ? kind->second : ObjectKind::Vehicle;
    o.length = tracked[i].length;
    o.width = tracked[i].width;
    view.objects.push_back(std::move(o));
  }
  for (const auto& n : snap.nearby) {
    if ((n.position - me->position).norm() > range + 60.0) continue;
    const double accel = motion ? motion->accel(n.sumo_id, snap.time, n.speed) : 0.0;
    PerceivedObject o = in_path_frame(path.line, view.ego.s, window, n.position, n.heading, n.speed, accel);
    if (!near_enough(o)) continue;
    o.id = n.sumo_id;
    o.length = n.length;
    o.width = n.width;
    view.objects.push_back(std::move(o));
  }
  if (motion) motion->sweep(snap.time);
  return view;
}

void EgoWatch::step(const sim::WorldSnapshot& snap, const std::vector<sim::TrackedActor>& tracked) {
  const auto view = perceive(snap, tracked, kinds_, ego_, path_, path_s_, range_);
  if (!view) return;
  path_s_ = view->ego.s;
  exposure_.add(*view, range_);
}

ReferenceEgo::ReferenceEgo(R157Parameters parameters, DrivingPath path, std::string ego, ObjectKinds kinds, double step,
                           double set_speed, OwnModel model)
    : driver_(parameters), path_(std::move(path)), ego_(std::move(ego)), kinds_(std::move(kinds)), step_(step),
      set_speed_(set_speed), model_(model) {}

void ReferenceEgo::observe(const std::vector<sim::Command>& commands) {
  for (const auto& c : commands) {
    // A route speed of 0 before the end_position (the waypoints' last speeds) means: stop at
    // the end. The driver does that itself, where SUMO's stop would put the ego, so it keeps
    // its set speed until then.
    if (const auto* m = std::get_if<sim::SetMaxSpeed>(&c); m && m->sumo_id == ego_ && (m->speed > 0 || !path_.end_s))
      set_speed_ = m->speed;
    if (const auto* v = std::get_if<sim::SpawnVehicle>(&c); v && v->actor.sumo_id == ego_ && v->max_speed > 0)
      set_speed_ = v->max_speed;
    if (const auto* st = std::get_if<sim::SetStop>(&c); st && st->sumo_id == ego_ && path_.stop_to_s)
      if (const auto s = path_.stop_to_s(*st)) path_.end_s = *s;
  }
}

std::vector<sim::Command> ReferenceEgo::drive(const sim::WorldSnapshot& snap,
                                                 const std::vector<sim::TrackedActor>& tracked,
                                                 std::vector<std::string>& events) {
  auto view = perceive(snap, tracked, kinds_, ego_, path_, path_s_, driver_.parameters().perception_range,
                       &nearby_motion_);
  if (!view) return {};
  path_s_ = view->ego.s;
  view->step = step_;
  view->set_speed = set_speed_;
  if (model_ == OwnModel::Cruise) return {sim::DriveSpeed{ego_, cruise_speed(*view, driver_.parameters())}};
  const Decision d = driver_.step(*view);
  for (const auto& e : d.events) events.push_back(e);
  return {sim::DriveSpeed{ego_, d.speed}};
}

}  // namespace orch::reference_driver

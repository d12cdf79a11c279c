// Each step of the actions that take time (action_start.hpp): a SynchronizeAction steered
// before the move, and after it every running action checked for its end.
#include <algorithm>

#include "openscenario/action_start.hpp"
#include "openscenario/distance_keeping.hpp"
#include "openscenario/lateral_distance.hpp"
#include "openscenario/synchronize_motion.hpp"

namespace orch::openscenario {
namespace {

// Whether the entity has reached or passed `w` along its road in its direction of travel.
bool reached(const EntityState& state, const EntityState::Waypoint& w, const opendrive::RoadNetwork& roads) {
  if (state.road_id != w.road_id) return false;
  return (state.s - w.s) * travel_direction(roads.road(w.road_id), state.lane) >= -1e-6;
}

}  // namespace

void count_passed_waypoints(EntityState& state, const opendrive::RoadNetwork& roads) {
  while (state.route_passed < state.route.size() && reached(state, state.route[state.route_passed], roads))
    ++state.route_passed;
}

void steer_synchronize(ActionContext& ctx, std::vector<RunningAction>& running) {
  for (RunningAction& r : running)
    if (const auto* synchronize = std::get_if<SynchronizeAction>(r.spec); synchronize && r.synchronize)
      r.synchronized = step_synchronize(*synchronize, *r.synchronize, r.entity, ctx);
}

std::vector<std::string> update_running_actions(ActionContext& ctx, std::vector<RunningAction>& running) {
  for (auto& [name, state] : ctx.entities)
    if (state.placed && !state.route.empty()) count_passed_waypoints(state, ctx.roads);
  std::vector<std::string> ended;
  for (auto it = running.begin(); it != running.end();) {
    EntityState& state = ctx.entities.at(it->entity);
    bool done = false;
    if (it->domain == MotionDomain::Longitudinal) {
      if (std::holds_alternative<SynchronizeAction>(*it->spec)) {
        done = it->synchronized;  // steered before the move (steer_synchronize)
      } else if (const auto* distance = std::get_if<LongitudinalDistanceAction>(it->spec)) {
        if (!has_limits(*distance)) longitudinal_distance(*distance, state, ctx, it->entity);  // continuous: keep it
        else done = approach_distance(*distance, state, ctx, it->entity, it->distance_acceleration) && !it->continuous;
      } else if (const auto* profile = std::get_if<SpeedProfileAction>(it->spec)) {
        done = step_speed_profile(*profile, *it->speed_profile, state, ctx.t, ctx.dt);
      } else if (state.speed_profile && state.speed_profile->done(ctx.t)) {
        state.speed = state.speed_profile->to;
        state.speed_profile.reset();
        done = !it->continuous;
      }  // a relative target follows its reference before each move (follow_relative_speeds)
    } else if (it->domain == MotionDomain::Route) {
      count_passed_waypoints(state, ctx.roads);
      done = !state.placed || state.route_passed >= state.route.size();
    } else if (const auto* lateral = std::get_if<LateralDistanceAction>(it->spec)) {
      done = keep_lateral_distance(*lateral, state, ctx, it->entity, it->lateral_distance) && !it->continuous;
    } else if (std::holds_alternative<FollowTrajectoryAction>(*it->spec)) {
      if (!state.path || state.path->done(ctx.t)) {  // continues along its lane from where the path ended
        state.path.reset();
        state.lateral_rate = 0;
        // On no road (a scenario without one) there is no lane to go on along: it stops where
        // the path ends, as esmini does (the standard does not say; esmini's trailer_connect
        // and truck_with_rotating_axle rely on it, docs/openscenario.md "Without a road").
        if (state.road_id.empty()) state.speed = state.acceleration = 0;
        // The step ends facing along the path's end: an action started now relative to the
        // entity (a chained trajectory) continues from that heading, as in esmini; the lane's
        // heading takes over from the next step on (the standard does not say).
        const double heading = state.pose.heading;
        update_pose(state, ctx.roads);
        state.pose.heading = heading;
        done = true;
      }
    } else if (state.lateral_profile &&
               state.lateral_profile->done(state.lateral_profile->clock(ctx.t, ctx.dt, state.odometer))) {
      state.offset = state.lateral_profile->to;
      state.lateral_profile.reset();
      state.lateral_rate = 0;
      update_pose(state, ctx.roads);
      done = !it->continuous;
    }
    if (!done) {
      ++it;
      continue;
    }
    const std::string name = it->action;
    it = running.erase(it);
    if (std::none_of(running.begin(), running.end(), [&](const RunningAction& r) { return r.action == name; }))
      ended.push_back(name);
  }
  return ended;
}

}  // namespace orch::openscenario

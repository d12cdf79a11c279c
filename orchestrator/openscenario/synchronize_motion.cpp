#include "openscenario/synchronize_motion.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "core/errors.hpp"
#include "opendrive/lane_graph.hpp"
#include "openscenario/route_plan.hpp"
#include "openscenario/trajectory_follow.hpp"

namespace orch::openscenario {
namespace {

EntityPoseLookup poses_of(const ActionContext& ctx) {
  return [&ctx](const std::string& name) -> std::optional<opendrive::Pose2> {
    const auto it = ctx.entities.find(name);
    if (it == ctx.entities.end() || !it->second.placed) return std::nullopt;
    return it->second.pose;
  };
}

SynchronizeTarget target_of(const Position& position, const ActionContext& ctx) {
  const ResolvedPosition r = ctx.resolver.resolve(position, poses_of(ctx));
  return {r.pose, r.road};
}

double straight_distance(const opendrive::Pose2& a, const opendrive::Pose2& b) {
  return std::hypot(a.x - b.x, a.y - b.y);
}

// Distance along a trajectory from the entity to the path point nearest the target.
double along_path(const PathMotion& path, const opendrive::Pose2& target) {
  return std::abs(nearest_distance(path, target.x, target.y, 0.0, path.length()) - path.distance);
}

// The entity's speed along its road's direction of travel (esmini projects it on s).
double speed_along_road(const EntityState& state, const opendrive::RoadNetwork& roads) {
  if (state.road_id.empty() || state.lane == 0) return state.speed;
  const opendrive::Road& road = roads.road(state.road_id);
  const double heading = opendrive::travel_heading(road, state.lane, state.s);
  return state.speed * std::abs(std::cos(state.pose.heading - heading));
}

double resolved_final_speed(const SynchronizeFinalSpeed& f, const EntityState& master) {
  if (!f.relative) return f.value;
  return f.factor ? master.speed * f.value : master.speed + f.value;
}

}  // namespace

double distance_ahead(const EntityState& state, const SynchronizeTarget& target, const opendrive::RoadNetwork& roads) {
  if (state.path) return along_path(*state.path, target.pose);
  if (!target.road || state.road_id.empty()) return straight_distance(state.pose, target.pose);
  if (state.road_id == target.road->road_id) return std::abs(target.road->s - state.s);
  const opendrive::Road& road = roads.road(state.road_id);
  double distance = travel_direction(road, state.lane) > 0 ? road.length - state.s : state.s;
  for (const opendrive::LaneEntry& next : lanes_ahead(state, roads)) {
    const opendrive::Road& on = roads.road(next.road_id);
    if (next.road_id == target.road->road_id) return distance + std::abs(target.road->s - next.s);
    distance += on.length;
  }
  return straight_distance(state.pose, target.pose);
}

SynchronizeRun start_synchronize(const SynchronizeAction& a, ActionContext& ctx) {
  const EntityState& master = ctx.entities.at(a.entity);
  if (!master.placed) throw MapError(fmt::format("the master entity \"{}\" has no position yet", a.entity));
  SynchronizeRun run;
  run.master_target = target_of(a.master_position, ctx);
  run.target = target_of(a.position, ctx);
  if (a.final_speed) {
    if (a.final_speed->steady_distance) run.steady_distance = a.final_speed->steady_distance;
    if (a.final_speed->steady_time)
      run.steady_distance = *a.final_speed->steady_time * resolved_final_speed(*a.final_speed, master);
  }
  return run;
}

bool step_synchronize(const SynchronizeAction& a, SynchronizeRun& run, const std::string& entity, ActionContext& ctx) {
  EntityState& state = ctx.entities.at(entity);
  const EntityState& master = ctx.entities.at(a.entity);
  if (!state.placed || !master.placed) return true;  // deleted: nothing left to synchronize
  SynchronizeMeasures m;
  m.distance = distance_ahead(state, run.target, ctx.roads);
  m.master_distance = distance_ahead(master, run.master_target, ctx.roads);
  m.master_speed = speed_along_road(master, ctx.roads);
  m.speed = state.speed;
  m.speed_along = speed_along_road(state, ctx.roads);
  m.dt = ctx.dt;
  if (a.final_speed) m.final_speed = resolved_final_speed(*a.final_speed, master);
  m.steady_distance = run.steady_distance;
  m.tolerance = a.tolerance.value_or(kSynchronizeTolerance);
  m.tolerance_master = a.tolerance_master.value_or(kSynchronizeTolerance);
  const SynchronizeStep step = synchronize_step(run.progress, m);
  state.speed = step.speed;
  return step.done;
}

}  // namespace orch::openscenario

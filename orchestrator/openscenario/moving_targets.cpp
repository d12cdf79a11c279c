// The runtime's steps before the entities move (action_start.hpp): the first speed of a
// LongitudinalDistanceAction started before the first step, and the targets of SpeedActions
// relative to another entity's speed, taken from it every step.
#include <algorithm>
#include <vector>

#include "openscenario/action_start.hpp"
#include "openscenario/distance_keeping.hpp"

namespace orch::openscenario {

void step_unstepped_distances(ActionContext& ctx, std::vector<RunningAction>& running) {
  for (RunningAction& r : running) {
    const auto* distance = std::get_if<LongitudinalDistanceAction>(r.spec);
    if (distance == nullptr || !r.distance_unstepped || !(ctx.dt > 0)) continue;
    r.distance_unstepped = false;
    (void)approach_distance(*distance, ctx.entities.at(r.entity), ctx, r.entity, r.distance_acceleration);
  }
}

void follow_relative_speeds(ActionContext& ctx, std::vector<RunningAction>& running) {
  // esmini steps the entities in their order in Entities, each seeing the speeds of those
  // before it already updated: the reference's speed in this step when it is declared before
  // the entity, else in the step before. So the entities are taken in that order here too.
  const auto declared = [&](const std::string& name) {
    const auto& all = ctx.scenario.entities;
    return std::find_if(all.begin(), all.end(), [&](const Entity& e) { return e.name == name; }) - all.begin();
  };
  std::vector<RunningAction*> followers;
  for (RunningAction& r : running) {
    const auto* speed = std::get_if<SpeedAction>(r.spec);
    if (speed != nullptr && r.domain == MotionDomain::Longitudinal &&
        std::holds_alternative<RelativeTargetSpeed>(speed->target))
      followers.push_back(&r);
  }
  std::stable_sort(followers.begin(), followers.end(),
                   [&](const RunningAction* a, const RunningAction* b) { return declared(a->entity) < declared(b->entity); });
  for (RunningAction* r : followers) {
    const auto& relative = std::get<RelativeTargetSpeed>(std::get<SpeedAction>(*r->spec).target);
    EntityState& state = ctx.entities.at(r->entity);
    const auto ref = ctx.entities.find(relative.entity);
    if (ref == ctx.entities.end() || !ref->second.placed) continue;
    const EntityState& other = ref->second;
    const double when = declared(relative.entity) < declared(r->entity) ? ctx.t : ctx.t - ctx.dt;
    const double reference = other.speed_profile ? other.speed_profile->at(std::max(when, other.speed_profile->start))
                                                 : other.speed;
    const double target = relative.factor ? reference * relative.value : reference + relative.value;
    if (state.speed_profile)
      state.speed_profile->to = target;  // the transition runs towards it
    else if (r->continuous)
      state.speed = target;
  }
}

}  // namespace orch::openscenario

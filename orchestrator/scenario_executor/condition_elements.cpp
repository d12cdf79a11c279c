// Scene and stop conditions, one row each: the key in the file, the reader, the checker
// (elements.hpp). The behaviour of each is a `measure` overload in engine/conditions.cpp.
#include <fmt/format.h>

#include "scenario_executor/elements.hpp"

namespace orch::scenario_elements {

using namespace orch::scenario;
using scenario_checks::CheckContext;
using scenario_checks::WaypointUse;
using scenario_loading::LoadContext;
namespace checks = scenario_checks;
namespace loading = scenario_loading;

namespace {

// A condition relative to a target that is the actor itself (absent target_actor_id means
// the ego).
void check_not_self(CheckContext& ctx, ActorId actor, ActorId target, const SourceLocation& where,
                    const std::string& message) {
  if (actor == target) ctx.diags.error(where, message);
}

// ---------------------------------------------------------------- position
std::optional<PositionCondition> read_position(LoadContext&, ObjectReader& r) {
  const auto actor = r.integer("actor_id", Need::Required);
  r.choice("type", {"reach"}, Need::Optional);  // "reach" is the only kind, and the default
  const auto waypoint = loading::read_waypoint_ref(r);
  const auto tolerance = r.number("tolerance", Need::Required, Quantity::Length);
  if (!actor || !waypoint || !tolerance) return std::nullopt;
  return PositionCondition{*actor, *waypoint, *tolerance};
}
void check_position(CheckContext& ctx, const PositionCondition& c, const SourceLocation& where) {
  checks::check_waypoint(ctx, c.waypoint, WaypointUse::Target);
  checks::check_not_negative(ctx, c.tolerance, where, "tolerance", "m");
}

// ---------------------------------------------------------------- distance
std::optional<DistanceCondition> read_distance(LoadContext& ctx, ObjectReader& r) {
  DistanceCondition c;
  const auto actor = r.integer("actor_id", Need::Required);
  const auto type = r.choice("type", {"traveled", "straight"}, Need::Optional);
  // Absent target_actor_id: the distance to the ego, as in the reference implementation.
  const auto target = r.integer("target_actor_id", Need::Optional);
  const auto comparison = loading::read_comparison(r, Need::Required);
  const auto value = r.number("value", Need::Required, Quantity::Length);
  const auto measure = loading::read_measure_type(r);
  if (!actor || !comparison || !value || !measure) return std::nullopt;
  c.actor = *actor;
  c.type = type && *type == "straight" ? DistanceType::Straight : DistanceType::Traveled;
  c.target = target.value_or(ctx.ego_id);
  c.comparison = *comparison;
  c.value = *value;
  c.measure = *measure;
  return c;
}
void check_distance(CheckContext& ctx, const DistanceCondition& c, const SourceLocation& where) {
  checks::check_actor_ref(ctx, c.target, where, "target_actor_id");
  check_not_self(ctx, c.actor, c.target, where,
                 fmt::format("distance condition from actor {} to itself (without \"target_actor_id\" the target is "
                             "the ego)",
                             c.actor));
}

// ---------------------------------------------------------------- speed
std::optional<SpeedCondition> read_speed_condition(LoadContext& ctx, ObjectReader& r) {
  SpeedCondition c;
  const auto actor = r.integer("actor_id", Need::Required);
  const auto type = loading::read_speed_type(r);
  const auto target = r.integer("target_actor_id", Need::Optional);
  const auto comparison = loading::read_comparison(r, Need::Required);
  const auto value = r.number("value", Need::Required, Quantity::SpeedKmh);
  if (!actor || !type || !comparison || !value) return std::nullopt;
  c.actor = *actor;
  c.type = *type;
  c.comparison = *comparison;
  c.value = loading::kmh_to_ms(*value);
  if (c.type == SpeedType::Relative) {
    c.target = target.value_or(ctx.ego_id);  // absent: relative to the ego, as in the reference
  } else if (target) {
    r.warning("target_actor_id", "\"target_actor_id\" has no effect on an absolute speed condition");
  }
  return c;
}
void check_speed_condition(CheckContext& ctx, const SpeedCondition& c, const SourceLocation& where) {
  if (!c.target) return;
  checks::check_actor_ref(ctx, *c.target, where, "target_actor_id");
  check_not_self(ctx, c.actor, *c.target, where,
                 fmt::format("relative speed condition of actor {} to itself (without \"target_actor_id\" the target "
                             "is the ego)",
                             c.actor));
}

// ---------------------------------------------------------------- time_headway
std::optional<TimeHeadwayCondition> read_time_headway(LoadContext&, ObjectReader& r) {
  const auto actor = r.integer("actor_id", Need::Required);
  const auto waypoint = loading::read_waypoint_ref(r);
  const auto comparison = loading::read_comparison(r, Need::Required);
  const auto value = r.number("value", Need::Required, Quantity::Time);
  if (!actor || !waypoint || !comparison || !value) return std::nullopt;
  return TimeHeadwayCondition{*actor, *waypoint, *comparison, *value};
}
void check_time_headway(CheckContext& ctx, const TimeHeadwayCondition& c, const SourceLocation&) {
  checks::check_waypoint(ctx, c.waypoint, WaypointUse::Target);
}

// ---------------------------------------------------------------- collision
std::optional<CollisionCondition> read_collision(LoadContext&, ObjectReader& r) {
  const auto actor = r.integer("actor_id", Need::Required);
  const auto target = r.integer("target_actor_id", Need::Optional);
  if (!actor) return std::nullopt;
  return CollisionCondition{*actor, target};
}
void check_collision(CheckContext& ctx, const CollisionCondition& c, const SourceLocation& where) {
  if (!c.target) return;
  checks::check_actor_ref(ctx, *c.target, where, "target_actor_id");
  check_not_self(ctx, c.actor, *c.target, where, fmt::format("collision condition of actor {} with itself", c.actor));
}

// ---------------------------------------------------------------- simulation_time
std::optional<SimulationTimeCondition> read_simulation_time(LoadContext&, ObjectReader& r) {
  const auto comparison = loading::read_comparison(r, Need::Required);
  const auto value = r.number("value", Need::Required, Quantity::Time);
  if (!comparison || !value) return std::nullopt;
  return SimulationTimeCondition{*comparison, *value};
}
void check_simulation_time(CheckContext&, const SimulationTimeCondition&, const SourceLocation&) {}

}  // namespace

const std::vector<ConditionElement>& condition_elements() {
  // The order is the order "did you mean" and messages list them in.
  static const std::vector<ConditionElement> table = {
      row<ConditionKind, read_position, check_position>("position"),
      row<ConditionKind, read_distance, check_distance>("distance"),
      row<ConditionKind, read_speed_condition, check_speed_condition>("speed"),
      row<ConditionKind, read_time_headway, check_time_headway>("time_headway"),
      row<ConditionKind, read_collision, check_collision>("collision"),
      row<ConditionKind, read_simulation_time, check_simulation_time>("simulation_time"),
  };
  return table;
}

}  // namespace orch::scenario_elements

#pragma once
// Scene conditions as pure functions of two consecutive snapshots. No simulator calls: the
// same inputs always give the same answer, which is what makes them unit-testable.
//
// Conventions (docs/scenario-format.md "Conditions"):
// - positions are actor centres; "traveled" distances run along the road (arc length along
//   the actor's route), + when the target is ahead of the actor;
// - a negative distance value asks about a target behind the actor and compares the size of
//   the gap (reference implementation's rule): "< -10" = "behind by less than 10 m";
// - "=" holds when the quantity is within 1e-6 of the value or crossed it since the
//   previous step (continuous quantities are never exactly equal on a fixed step);
// - position "reach" holds when the actor's path during the last step passed within
//   `tolerance` of the waypoint, so fast actors cannot jump over it.
#include <functional>
#include <string>
#include <vector>

#include "scenario_executor_engine/actor_table.hpp"
#include "scenario_executor_engine/route_crossing.hpp"
#include "scenario_executor_engine/sim_names.hpp"
#include "map/waypoint_file.hpp"
#include "scenario_executor/model.hpp"

namespace orch::engine {

struct ConditionContext {
  const WorldSnapshot& now;
  const WorldSnapshot* before = nullptr;  // nullptr on the first step
  const ActorTable& actors;
  const WaypointFile& waypoints;
  // The route an actor is driving now (reference line for along-road measures).
  std::function<const WaypointRoute*(ActorId)> route_of;
  // True when the actor was in a collision during the last step.
  std::function<bool(ActorId)> collided;
  // +1 when the actor drives its route as drawn, -1 against it (in a lane of the opposite
  // side); empty = always +1.
  std::function<int(ActorId)> direction_of;
  // True when the two actors' bodies touched during the last step (collision target_actor_id).
  std::function<bool(ActorId, ActorId)> collided_with;
  // Where routes without a common path meet (route_crossing.hpp); null: not measured.
  RouteMeetings* meetings = nullptr;
};

struct ConditionOutcome {
  bool holds = false;
  // What was measured, for the run log ("speed of actor 0 60.2 km/h >= 60"); only when the
  // condition holds (the log names the conditions that fired; formatting it for every
  // condition every step cost more than evaluating most of them).
  std::string detail;
};

ConditionOutcome evaluate(const scenario::Condition& c, const ConditionContext& ctx);
// An empty group holds. `fired` receives the details of the conditions that made it hold.
bool evaluate(const scenario::ConditionGroup& g, const ConditionContext& ctx, std::vector<std::string>* fired);

// compare() with the "=" crossing rule and a 1e-9 tolerance on the other comparisons, so
// that a value held exactly at its target is not lost to rounding.
bool compare_measure(double now, const double* before, scenario::Comparison c, double value);

// Along-road distance from `from` to `to` on `route` (+ = `to` ahead).
double along_road(const WaypointRoute& route, const Vec2& from, const Vec2& to);

}  // namespace orch::engine

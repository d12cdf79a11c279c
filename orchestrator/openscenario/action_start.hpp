#pragma once
// What each private action does to an entity when it starts, and, for actions that take
// time, each step until it ends (internal to the storyboard runtime).
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "map/position_resolver.hpp"
#include "openscenario/entity_motion.hpp"
#include "openscenario/model.hpp"
#include "openscenario/speed_profile_motion.hpp"
#include "openscenario/synchronize.hpp"
#include "openscenario/trailer_motion.hpp"
#include "openscenario/traffic_book.hpp"
#include "openscenario/traffic_signals.hpp"

namespace orch::openscenario {

// Positions are resolved in map/ (one resolver for both scenario languages).
using position::EntityPoseLookup;
using position::PositionResolver;
using position::ResolvedPosition;
using position::shifted_lane;

// The time of day the last EnvironmentAction set, and when (TimeOfDayCondition). With
// animation the time of day runs on with the simulation time (the standard: "If true, the
// timeofday is animated with progressing simulation time"), else it stays.
struct TimeOfDayClock {
  TimeOfDaySetting setting;
  double set_at = 0;  // simulation time
  [[nodiscard]] double now(double t) const {
    return setting.animation ? setting.date_time + (t - set_at) : setting.date_time;
  }
};

struct ActionContext {
  const Scenario& scenario;
  const opendrive::RoadNetwork& roads;
  const PositionResolver& resolver;
  std::map<std::string, EntityState>& entities;
  std::map<std::string, Parameter>& parameters;  // as ParameterSet/ModifyActions left them
  std::map<std::string, Parameter>& variables;   // as VariableSet/ModifyActions left them
  TrailerLinks& trailers;                        // which trailer each tractor tows now
  double t;
  double dt = 0;  // the step that led to t (0 at the start)
  TrafficSignals* signals = nullptr;  // the signals' states and controllers' phases
  TrafficBook* traffic = nullptr;     // the traffic TrafficActions started (traffic_book.hpp)
  std::optional<TimeOfDayClock>* time_of_day = nullptr;  // set by EnvironmentActions
  std::map<std::string, bool>* monitors = nullptr;        // MonitorDeclarations, set by SetMonitorActions
  std::uint64_t seed = 0;  // the run's (--seed): RandomRouteAction's draws
};

// Route: an AcquirePositionAction waiting for its entity to reach the position.
enum class MotionDomain { Longitudinal, Lateral, Route };

// What a running LateralDistanceAction carries from step to step (lateral_distance.hpp).
struct LateralDistanceRun {
  std::optional<double> kept;  // the distance to keep (set on the first call when the action gives none)
  double speed = 0;            // its lateral speed (the entity's own is reset by each step's move)
  bool waited = false;         // the step after its start passed (it moves from the second step on)
};

// An action still shaping one entity's motion.
struct RunningAction {
  std::string action;  // storyboard name; "" for Init actions
  std::string entity;
  MotionDomain domain = MotionDomain::Longitudinal;
  bool continuous = false;  // never ends on its own (continuous targets)
  const PrivateAction* spec = nullptr;
  std::optional<SynchronizeRun> synchronize;  // a SynchronizeAction's targets and phase
  std::optional<SpeedProfileRun> speed_profile;  // a SpeedProfileAction's segments and progress
  LateralDistanceRun lateral_distance;            // a LateralDistanceAction's distance kept, its speed
  double distance_acceleration = 0;              // a LongitudinalDistanceAction's last acceleration (its jerk limits)
  bool distance_unstepped = false;  // a LongitudinalDistanceAction started before the first step (no step size yet)
  bool synchronized = false;  // a SynchronizeAction done (steer_synchronize, before the step's move)
};

// Starts `action` for `entity` ("" for global actions): immediate actions take effect now; actions that take time
// are added to `running`. Returns the names of running storyboard actions it replaced
// (same entity, same motion domain). Throws MapError when a position cannot be resolved.
std::vector<std::string> start_action(const PrivateAction& action, const std::string& entity,
                                      const std::string& action_name, ActionContext& ctx,
                                      std::vector<RunningAction>& running);

// Before the entities move to ctx.t: the speed of each SynchronizeAction for this step, from
// where the entities are (as esmini's: the entity moves with it in the same step; set after
// the move, it lagged one step behind, 0.15 m at 0.5 s for an NPC starting from standstill in
// esmini's synchronize.xosc).
void steer_synchronize(ActionContext& ctx, std::vector<RunningAction>& running);

// Counts the route waypoints (EntityState::route) the entity has reached or passed along its
// road in its direction of travel (running_actions.cpp).
void count_passed_waypoints(EntityState& state, const opendrive::RoadNetwork& roads);

// Before the entities move to ctx.t: the first speed of each LongitudinalDistanceAction with
// DynamicConstraints started before the first step (Init, or an event at 0 s: no step size
// to limit the change over then), so that it moves the entity in the first step already, as
// one started later moves it in the step after its start (esmini's distance_test.xosc: the
// Dummy 15.25 m/s in the first step, not 15; 0.126 m at 0.5 s when it waited a step).
void step_unstepped_distances(ActionContext& ctx, std::vector<RunningAction>& running);

// Before the entities move to ctx.t: each SpeedAction with a RelativeTargetSpeed takes its
// target from the reference entity's speed, during its transition (the shape runs towards it)
// and, continuous, after it (the entity moves at it): the reference's speed in this step when
// the reference is declared before the entity in Entities, in the step before otherwise. The
// standard gives the target "relative to the speed of the reference entity", not when it is
// taken; this is esmini's, which takes it every step, continuous or not, and steps the
// entities in their declared order (measured with scenarios/openscenario/
// condition_combinations.xosc: a car reaching a lead's 20 m/s in 3 s while the lead brakes to
// 14 m/s arrives at 14 m/s, where a target taken at the start left it at 20 and a continuous
// one then jumped 6 m/s in one step; a follower declared after its reference moves with the
// reference's new speed in the same step, one declared before it a step later).
void follow_relative_speeds(ActionContext& ctx, std::vector<RunningAction>& running);

// After the entities moved to ctx.t: ends the actions whose motion is done (returns their
// names once no actor of theirs is still running them) and keeps continuous ones on target.
std::vector<std::string> update_running_actions(ActionContext& ctx, std::vector<RunningAction>& running);

}  // namespace orch::openscenario

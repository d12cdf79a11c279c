#pragma once
// The storyboard runtime's state and steps (StoryboardRuntime::Impl), shared by its two
// sources: storyboard_runtime.cpp (storyboard elements, init, step) and
// storyboard_conditions.cpp (condition evaluation). Internal: include only from those.
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "openscenario/action_start.hpp"
#include "openscenario/rule.hpp"
#include "openscenario/storyboard_runtime.hpp"

namespace orch::openscenario {

struct StoryboardRuntime::Impl {
  struct Record {
    ElementState state = ElementState::Standby;
    int executions = 0;
    struct Transition {
      std::string what;  // startTransition, endTransition, ...
      long step;         // the step it happened in
      long number;       // counts all transitions of the run: which ones a condition has seen
    };
    std::vector<Transition> transitions;
  };

  struct ConditionMemory {
    std::map<std::string, double> since;  // per entity: since when a duration condition holds
    bool has_previous = false;
    bool previous = false;
    std::vector<std::pair<double, bool>> history;  // edged value per evaluation, for delays
    long transitions_seen = 0;  // the number of the last transition this condition was true for
    std::vector<std::string> holding;  // a ByEntityCondition's triggering entities it held for when last evaluated
  };

  const Scenario& scenario;
  const opendrive::RoadNetwork& roads;
  PositionResolver resolver;
  double t = 0;
  long step_index = 0;
  long transitions_made = 0;
  bool finished = false;
  std::map<std::string, EntityState> entities;
  // The entities as the step left them, kept while events start within one evaluation of the
  // storyboard. The conditions on a state held for a duration (StandStill, EndOfRoad,
  // Offroad) read them: such a state is the motion's, measured once a step, and an event
  // started earlier in the same evaluation does not undo it (lane_change_simple.xosc: a
  // TeleportAction and a SpeedAction, each in its own event, both triggered by the same
  // EndOfRoadCondition; esmini starts both). Other conditions see an earlier event's effect
  // at once, as in esmini (every_condition.xosc: a speed set by one event satisfies
  // another's RelativeSpeedCondition in the same step).
  std::optional<std::map<std::string, EntityState>> frozen;
  [[nodiscard]] const std::map<std::string, EntityState>& held_states() const { return frozen ? *frozen : entities; }
  std::vector<TransitionLog> log;
  std::map<std::pair<std::string, std::string>, Record> records;        // by (type, key)
  std::map<std::pair<std::string, std::string>, std::string> names;     // (type, key) -> name
  std::map<const Condition*, ConditionMemory> memory;
  std::vector<RunningAction> running;
  std::map<std::string, Parameter> parameters;  // values as the parameter actions set them (by key)
  std::map<std::string, Parameter> variables;   // values as the variable actions set them
  TrailerLinks trailers;                        // tractor -> trailer towed now
  TrafficSignals signals;                       // signal states, controller phases
  TrafficBook traffic;                          // traffic started by TrafficActions
  std::optional<TimeOfDayClock> time_of_day;    // the Environment's, once an EnvironmentAction set one
  std::map<std::string, bool> monitors;         // MonitorDeclarations' values now
  // Each storyboard action's place in the file (stories, acts, groups, maneuvers, events,
  // actions in document order; Init actions, key "", come before all): the order in which
  // esmini steps running actions within a step (lane_change_motion_order below).
  std::map<std::string, int> action_order;
  // Per Act (key): the entities that triggered its StartTrigger when it started, the actors
  // its groups with selectTriggeringEntities add to the named ones.
  std::map<std::string, std::vector<std::string>> act_triggering_entities;

  Impl(const Scenario& s, const opendrive::RoadNetwork& r, std::uint64_t run_seed);
  std::uint64_t seed = 0;  // the run's (--seed)

  double last_dt = 0;  // the last step's

  ActionContext context();

  Record& record(const std::string& type, const std::string& name) { return records[{type, name}]; }

  // `key`: the element's (unique) key; the log names it by its name, as the file does.
  void transition(const std::string& type, const std::string& key, const std::string& what, ElementState to);
  bool value_of(const Condition& c, ConditionMemory& m);

  // A parameter's or variable's value now against a condition's.
  static bool compare(const Parameter& p, Rule rule, const std::string& value);

  // Whether `now` has held for `duration` seconds (per entity).
  bool held_for(ConditionMemory& m, const std::string& entity, bool now, double duration);

  // A point as a body without extent (positions in Distance and ReachPosition conditions).
  EntityState point_state(const Position& p);
  bool entity_condition(const ByEntityCondition& c, const std::string& name, ConditionMemory& m);
  bool by_entity(const ByEntityCondition& c, ConditionMemory& m);
  bool evaluate(const Condition& c);
  // Whether the trigger fires; when it does and `triggering` is given, the triggering entities
  // of its true condition groups' ByEntityConditions that held (in order, each once).
  bool fires(const std::optional<Trigger>& trigger, std::vector<std::string>* triggering = nullptr);
  // `selected`: with Actors selectTriggeringEntities, the entities that triggered the Act,
  // actors of its private actions besides the named ones (nullptr: none selected).
  void start_event(const Event& e, const std::vector<std::string>* selected = nullptr);
  void stop_action(const std::string& name);
  void stop_event(const Event& e);
  void start_group(const ManeuverGroup& g);
  void stop_act(const Act& act);
  bool complete(const std::string& type, const std::string& name);

  // Ends every element whose children have all ended, bottom-up.
  void settle();

  // The Storyboard's StopTrigger stops what still executes (the standard 1.3, 8.2: the
  // stopTransition leaves runningState or standbyState when "an issued stop trigger" stops
  // the element; 8.4.2: an Event "transfers to completeState with stopTransition" when "a stop
  // trigger is issued by the enclosing Act or Storyboard"): running actions and running or
  // standby events stop; a maneuver, group, act or story whose children are then all complete
  // has ended (endTransition, as settle() ends it), one still waiting in standby (an Act whose
  // start trigger never fired) stops.
  void stop_storyboard();
  void evaluate_storyboard();
  void run_init();
  // Marks the entities whose LaneChangeAction is stepped before their SpeedAction (see
  // EntityState::lane_change_before_speed).
  void lane_change_motion_order();
  void step(double dt);
};

}  // namespace orch::openscenario

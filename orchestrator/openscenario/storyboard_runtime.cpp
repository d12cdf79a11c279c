#include "openscenario/storyboard_runtime.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "core/errors.hpp"
#include "core/exhaustive.hpp"
#include "openscenario/action_start.hpp"
#include "openscenario/entity_measures.hpp"
#include "openscenario/road_following.hpp"
#include "openscenario/rule.hpp"
#include "openscenario/text_number.hpp"

namespace orch::openscenario {
namespace {

// Where an event sits in the storyboard, for roll-ups and priorities.
struct EventSlot {
  const Event* event;
  const Maneuver* maneuver;
};

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
};

// CollisionCondition ByType names.
std::string object_type(EntityKind kind) {
  switch (kind) {
    case EntityKind::Vehicle: return "vehicle";
    case EntityKind::Pedestrian: return "pedestrian";
    case EntityKind::MiscObject: return "miscellaneous";
  }
  return "";
}

}  // namespace

struct StoryboardRuntime::Impl {
  const Scenario& scenario;
  const opendrive::RoadNetwork& roads;
  PositionResolver resolver;
  double t = 0;
  long step_index = 0;
  long transitions_made = 0;
  bool finished = false;
  std::map<std::string, EntityState> entities;
  std::vector<TransitionLog> log;
  std::map<std::pair<std::string, std::string>, Record> records;        // by (type, key)
  std::map<std::pair<std::string, std::string>, std::string> names;     // (type, key) -> name
  std::map<const Condition*, ConditionMemory> memory;
  std::vector<RunningAction> running;
  std::map<std::string, Parameter> parameters;  // values as the parameter actions set them (by key)
  std::map<std::string, Parameter> variables;   // values as the variable actions set them
  TrailerLinks trailers;                        // tractor -> trailer towed now

  Impl(const Scenario& s, const opendrive::RoadNetwork& r)
      : scenario(s), roads(r), resolver(r), trailers(initial_trailer_links(s)) {
    for (const Parameter& p : s.parameters) parameters[p.name] = p;
    for (const Parameter& p : s.local_parameters) parameters[p.name] = p;  // "<owner>/<name>"
    for (const Parameter& v : s.variables) variables[v.name] = v;
    for (const Story& story : s.storyboard.stories) {
      names[{"story", story.key}] = story.name;
      for (const Act& act : story.acts) {
        names[{"act", act.key}] = act.name;
        for (const ManeuverGroup& g : act.groups) {
          names[{"maneuverGroup", g.key}] = g.name;
          for (const Maneuver& m : g.maneuvers) {
            names[{"maneuver", m.key}] = m.name;
            for (const Event& e : m.events) {
              names[{"event", e.key}] = e.name;
              for (const Action& a : e.actions) names[{"action", a.key}] = a.name;
            }
          }
        }
      }
    }
  }

  double last_dt = 0;  // the last step's

  ActionContext context() {
    return ActionContext{scenario, roads, resolver, entities, parameters, variables, trailers, t, last_dt};
  }

  Record& record(const std::string& type, const std::string& name) { return records[{type, name}]; }

  // `key`: the element's (unique) key; the log names it by its name, as the file does.
  void transition(const std::string& type, const std::string& key, const std::string& what, ElementState to) {
    Record& r = record(type, key);
    r.state = to;
    r.transitions.push_back({what, step_index, ++transitions_made});
    if (r.transitions.size() > 8) r.transitions.erase(r.transitions.begin());
    const auto name = names.find({type, key});
    log.push_back({t, type, name == names.end() ? key : name->second, what});
  }

  // ---- conditions ---------------------------------------------------------------------
  bool value_of(const Condition& c, ConditionMemory& m) {
    return std::visit(
        [&](const auto& kind) -> bool {
          using T = std::decay_t<decltype(kind)>;
          if constexpr (std::is_same_v<T, SimulationTimeCondition>) {
            // Times are k * dt: compare with a tolerance far below one step.
            if (std::abs(t - kind.value) < 1e-9) return satisfies(kind.rule, kind.value, kind.value);
            return satisfies(kind.rule, t, kind.value);
          } else if constexpr (std::is_same_v<T, StoryboardElementStateCondition>) {
            const Record& r = record(kind.type, kind.key.empty() ? kind.ref : kind.key);
            if (kind.state == "standbyState") return r.state == ElementState::Standby;
            if (kind.state == "runningState") return r.state == ElementState::Running;
            if (kind.state == "completeState") return r.state == ElementState::Complete;
            // A transition is seen by a condition once: in its step when evaluated after it,
            // else in the next step (a stop trigger evaluated before the events that end).
            for (const Record::Transition& e : r.transitions)
              if (e.what == kind.state && e.step >= step_index - 1 && e.number > m.transitions_seen) {
                m.transitions_seen = e.number;
                return true;
              }
            return false;
          } else if constexpr (std::is_same_v<T, ParameterCondition>) {
            return compare(parameters.at(kind.parameter), kind.rule, kind.value);  // declared: checked at load
          } else if constexpr (std::is_same_v<T, VariableCondition>) {
            return compare(variables.at(kind.variable), kind.rule, kind.value);
          } else if constexpr (std::is_same_v<T, ByEntityCondition>) {
            return by_entity(kind, m);
          } else {
            static_assert(kUnhandled<T>, "an OpenSCENARIO condition the reader makes needs its evaluation here");
          }
        },
        c.kind);
  }

  // A parameter's or variable's value now against a condition's.
  static bool compare(const Parameter& p, Rule rule, const std::string& value) {
    if (p.type == "string" || p.type == "boolean" || p.type == "dateTime") return satisfies(rule, p.value, value);
    // Both texts were checked as numbers of the type at load.
    return satisfies(rule, parse_whole<double>(p.value).value_or(0.0), parse_whole<double>(value).value_or(0.0));
  }

  // Whether `now` has held for `duration` seconds (per entity).
  bool held_for(ConditionMemory& m, const std::string& entity, bool now, double duration) {
    if (!now) {
      m.since.erase(entity);
      return false;
    }
    const double since = m.since.try_emplace(entity, t).first->second;
    return t - since >= duration - 1e-9;
  }

  // A point as a body without extent (positions in Distance and ReachPosition conditions).
  EntityState point_state(const Position& p) {
    const ResolvedPosition r = resolver.resolve(p, [&](const std::string& name) -> std::optional<opendrive::Pose2> {
      const EntityState& e = entities.at(name);
      return e.placed ? std::optional(e.pose) : std::nullopt;
    });
    EntityState s;
    s.placed = true;
    s.pose = r.pose;
    if (r.road) s.s = r.road->s, s.t = r.road->t;
    return s;
  }

  bool entity_condition(const ByEntityCondition& c, const std::string& name, ConditionMemory& m) {
    const EntityState& self = entities.at(name);
    if (!self.placed) return false;
    const Body me{&self, &scenario.entity(name)->box};
    static const BoundingBox kPoint{};
    return std::visit(
        [&](const auto& k) -> bool {
          using T = std::decay_t<decltype(k)>;
          if constexpr (std::is_same_v<T, SpeedCondition>) return satisfies(k.rule, self.speed, k.value);
          else if constexpr (std::is_same_v<T, AccelerationCondition>) return satisfies(k.rule, self.acceleration, k.value);
          else if constexpr (std::is_same_v<T, TraveledDistanceCondition>) return self.odometer >= k.value - 1e-9;
          else if constexpr (std::is_same_v<T, StandStillCondition>)
            return held_for(m, name, std::abs(self.speed) < 1e-6, k.duration);
          else if constexpr (std::is_same_v<T, EndOfRoadCondition>) {
            return held_for(m, name, at_dead_end(self, roads), k.duration);
          } else if constexpr (std::is_same_v<T, OffroadCondition>)
            return held_for(m, name, !resolver.locate(self.pose).lane.has_value(), k.duration);
          else if constexpr (std::is_same_v<T, ReachPositionCondition>) {
            const EntityState target = point_state(k.position);
            return std::hypot(target.pose.x - self.pose.x, target.pose.y - self.pose.y) <= k.tolerance;
          } else if constexpr (std::is_same_v<T, DistanceCondition>) {
            const EntityState target = point_state(k.position);
            const double d = relative_distance(me, {&target, &kPoint}, k.distance_type, k.coordinate_system, k.freespace);
            return satisfies(k.rule, d, k.value);
          } else if constexpr (std::is_same_v<T, RelativeSpeedCondition>) {
            const EntityState& other = entities.at(k.entity);
            return other.placed && satisfies(k.rule, self.speed - other.speed, k.value);
          } else if constexpr (std::is_same_v<T, TimeHeadwayCondition>) {
            const EntityState& other = entities.at(k.entity);
            if (!other.placed || self.speed <= 0) return false;
            // A reference entity not ahead has no headway (the triggering entity never reaches it).
            const std::optional<double> d = distance_ahead(me, {&other, &scenario.entity(k.entity)->box}, roads,
                                                           k.distance_type, k.coordinate_system, k.freespace);
            return d && satisfies(k.rule, *d / self.speed, k.value);
          } else if constexpr (std::is_same_v<T, TimeToCollisionCondition>) {
            if (k.entity) {
              const EntityState& other = entities.at(*k.entity);
              if (!other.placed) return false;
              return satisfies(k.rule, time_to_collision(me, {&other, &scenario.entity(*k.entity)->box}, roads,
                                                         k.distance_type, k.coordinate_system, k.freespace),
                               k.value);
            }
            const EntityState target = point_state(*k.position);
            return satisfies(k.rule, time_to_collision(me, {&target, &kPoint}, roads, k.distance_type,
                                                       k.coordinate_system, k.freespace),
                             k.value);
          } else if constexpr (std::is_same_v<T, CollisionCondition>) {
            for (const Entity& other : scenario.entities) {
              if (other.name == name || !entities.at(other.name).placed) continue;
              if (k.entity ? other.name != *k.entity : object_type(other.kind) != k.object_type) continue;
              if (boxes_overlap(me, {&entities.at(other.name), &other.box})) return true;
            }
            return false;
          } else if constexpr (std::is_same_v<T, RelativeDistanceCondition>) {
            const EntityState& other = entities.at(k.entity);
            if (!other.placed) return false;
            const double d = relative_distance(me, {&other, &scenario.entity(k.entity)->box}, k.distance_type,
                                               k.coordinate_system, k.freespace);
            return satisfies(k.rule, d, k.value);
          }
          else
            static_assert(kUnhandled<T>, "an OpenSCENARIO entity condition the reader makes needs its evaluation here");
        },
        c.condition);
  }

  bool by_entity(const ByEntityCondition& c, ConditionMemory& m) {
    bool any = false;
    bool all = true;
    for (const std::string& name : c.triggering_entities) {
      const bool holds = entity_condition(c, name, m);
      any = any || holds;
      all = all && holds;
    }
    return c.all ? all : any;
  }

  bool evaluate(const Condition& c) {
    ConditionMemory& m = memory[&c];
    const bool now = value_of(c, m);
    bool edged = now;
    switch (c.edge) {
      case Edge::None: break;
      case Edge::Rising: edged = m.has_previous && !m.previous && now; break;
      case Edge::Falling: edged = m.has_previous && m.previous && !now; break;
      case Edge::RisingOrFalling: edged = m.has_previous && m.previous != now; break;
    }
    m.has_previous = true;
    m.previous = now;
    if (c.delay <= 0) return edged;
    m.history.emplace_back(t, edged);
    // The edged value as it was `delay` seconds ago.
    const double then = t - c.delay + 1e-9;
    bool delayed = false;
    for (const auto& [time, value] : m.history) {
      if (time > then) break;
      delayed = value;
    }
    return delayed;
  }

  bool fires(const std::optional<Trigger>& trigger) {
    if (!trigger) return true;
    bool any = false;
    for (const auto& group : trigger->groups) {  // every condition is evaluated: edges need history
      bool all = true;
      for (const Condition& c : group) all = evaluate(c) && all;
      any = any || all;
    }
    return any;
  }

  // ---- storyboard elements ------------------------------------------------------------
  void start_event(const Event& e) {
    Record& r = record("event", e.key);
    ++r.executions;
    transition("event", e.key, "startTransition", ElementState::Running);
    for (const Action& a : e.actions) {
      transition("action", a.key, "startTransition", ElementState::Running);
      // Global actions have no actors: they run once, for no entity ("").
      const std::vector<std::string> actors = a.actors.empty() ? std::vector<std::string>{""} : a.actors;
      for (const std::string& actor : actors) {
        ActionContext ctx = context();
        // An action that takes over an entity's motion ends the one it replaces.
        for (const std::string& replaced : start_action(a.action, actor, a.key, ctx, running))
          if (record("action", replaced).state == ElementState::Running)
            transition("action", replaced, "stopTransition", ElementState::Complete);
      }
      if (std::none_of(running.begin(), running.end(), [&](const RunningAction& r2) { return r2.action == a.key; }))
        transition("action", a.key, "endTransition", ElementState::Complete);
    }
  }

  void stop_action(const std::string& name) {
    std::erase_if(running, [&](const RunningAction& r) { return r.action == name; });
    if (record("action", name).state == ElementState::Running)
      transition("action", name, "stopTransition", ElementState::Complete);
  }

  void stop_event(const Event& e) {
    for (const Action& a : e.actions) stop_action(a.key);
    transition("event", e.key, "stopTransition", ElementState::Complete);
  }

  void start_group(const ManeuverGroup& g) {
    ++record("maneuverGroup", g.key).executions;
    transition("maneuverGroup", g.key, "startTransition", ElementState::Running);
    for (const Maneuver& m : g.maneuvers) {
      transition("maneuver", m.key, "startTransition", ElementState::Running);
      for (const Event& e : m.events) {
        record("event", e.key) = Record{};
        for (const Action& a : e.actions) record("action", a.key).state = ElementState::Standby;
      }
    }
  }

  void stop_act(const Act& act) {
    for (const ManeuverGroup& g : act.groups) {
      for (const Maneuver& m : g.maneuvers) {
        for (const Event& e : m.events)
          if (record("event", e.key).state != ElementState::Complete) stop_event(e);
        if (record("maneuver", m.key).state != ElementState::Complete)
          transition("maneuver", m.key, "stopTransition", ElementState::Complete);
      }
      if (record("maneuverGroup", g.key).state != ElementState::Complete)
        transition("maneuverGroup", g.key, "stopTransition", ElementState::Complete);
    }
    transition("act", act.key, "stopTransition", ElementState::Complete);
  }

  bool complete(const std::string& type, const std::string& name) {
    return record(type, name).state == ElementState::Complete;
  }

  // Ends every element whose children have all ended, bottom-up.
  void settle() {
    for (const Story& story : scenario.storyboard.stories) {
      bool acts_done = true;
      for (const Act& act : story.acts) {
        if (record("act", act.key).state == ElementState::Running) {
          bool groups_done = true;
          for (const ManeuverGroup& g : act.groups) {
            if (record("maneuverGroup", g.key).state != ElementState::Running) continue;
            bool maneuvers_done = true;
            for (const Maneuver& m : g.maneuvers) {
              if (record("maneuver", m.key).state != ElementState::Running) continue;
              bool events_done = true;
              for (const Event& e : m.events) {
                Record& r = record("event", e.key);
                if (r.state == ElementState::Running &&
                    std::all_of(e.actions.begin(), e.actions.end(), [&](const Action& a) { return complete("action", a.key); })) {
                  const bool again = r.executions < e.maximum_execution_count;
                  transition("event", e.key, "endTransition", again ? ElementState::Standby : ElementState::Complete);
                }
                events_done = events_done && complete("event", e.key);
              }
              if (events_done) transition("maneuver", m.key, "endTransition", ElementState::Complete);
              maneuvers_done = maneuvers_done && complete("maneuver", m.key);
            }
            if (maneuvers_done) {
              const bool again = record("maneuverGroup", g.key).executions < g.maximum_execution_count;
              transition("maneuverGroup", g.key, "endTransition", ElementState::Complete);
              if (again) start_group(g);
            }
            groups_done = groups_done && complete("maneuverGroup", g.key);
          }
          if (groups_done) transition("act", act.key, "endTransition", ElementState::Complete);
        }
        acts_done = acts_done && complete("act", act.key);
      }
      if (acts_done && record("story", story.key).state == ElementState::Running)
        transition("story", story.key, "endTransition", ElementState::Complete);
    }
  }

  // The Storyboard's StopTrigger stops what still executes (the standard 1.3, 8.2: the
  // stopTransition leaves runningState or standbyState when "an issued stop trigger" stops
  // the element; 8.4.2: an Event "transfers to completeState with stopTransition" when "a stop
  // trigger is issued by the enclosing Act or Storyboard"): running actions and running or
  // standby events stop; a maneuver, group, act or story whose children are then all complete
  // has ended (endTransition, as settle() ends it), one still waiting in standby (an Act whose
  // start trigger never fired) stops.
  void stop_storyboard() {
    for (const Story& story : scenario.storyboard.stories) {
      if (record("story", story.key).state != ElementState::Running) continue;
      for (const Act& act : story.acts) {
        const ElementState act_state = record("act", act.key).state;
        if (act_state == ElementState::Standby) transition("act", act.key, "stopTransition", ElementState::Complete);
        if (act_state != ElementState::Running) continue;
        for (const ManeuverGroup& g : act.groups) {
          if (record("maneuverGroup", g.key).state != ElementState::Running) continue;
          for (const Maneuver& m : g.maneuvers) {
            if (record("maneuver", m.key).state != ElementState::Running) continue;
            for (const Event& e : m.events)
              if (record("event", e.key).state != ElementState::Complete) stop_event(e);
            transition("maneuver", m.key, "endTransition", ElementState::Complete);
          }
          transition("maneuverGroup", g.key, "endTransition", ElementState::Complete);
        }
        transition("act", act.key, "endTransition", ElementState::Complete);
      }
      transition("story", story.key, "endTransition", ElementState::Complete);
    }
  }

  void evaluate_storyboard() {
    if (fires(scenario.storyboard.stop_trigger)) {
      finished = true;
      stop_storyboard();
      log.push_back({t, "storyboard", "", "stopTransition"});
      return;
    }
    for (const Story& story : scenario.storyboard.stories) {
      if (record("story", story.key).state != ElementState::Running) continue;
      for (const Act& act : story.acts) {
        const ElementState state = record("act", act.key).state;
        if (state == ElementState::Standby && fires(act.start_trigger)) {
          transition("act", act.key, "startTransition", ElementState::Running);
          for (const ManeuverGroup& g : act.groups) start_group(g);
        } else if (state == ElementState::Running && act.stop_trigger && fires(act.stop_trigger)) {
          stop_act(act);
          continue;
        }
        if (record("act", act.key).state != ElementState::Running) continue;
        for (const ManeuverGroup& g : act.groups)
          for (const Maneuver& m : g.maneuvers) {
            if (record("maneuver", m.key).state != ElementState::Running) continue;
            for (const Event& e : m.events) {
              if (record("event", e.key).state != ElementState::Standby || !fires(e.start_trigger)) continue;
              const auto running_other = [&] {
                return std::any_of(m.events.begin(), m.events.end(), [&](const Event& o) {
                  return &o != &e && record("event", o.key).state == ElementState::Running;
                });
              };
              if (e.priority == Priority::Skip && running_other()) {
                transition("event", e.key, "skipTransition", ElementState::Standby);
                continue;
              }
              if (e.priority == Priority::Overwrite)
                for (const Event& o : m.events)
                  if (&o != &e && record("event", o.key).state == ElementState::Running) stop_event(o);
              start_event(e);
            }
          }
      }
    }
    settle();
  }

  void run_init() {
    // Init actions all take effect at t = 0: routes are planned after every entity is placed,
    // whatever their order in the file (esmini's routing-test.xosc assigns the ego's route
    // before it teleports it; a route planned from no position would be no plan).
    const auto is_routing = [](const InitAction& a) {
      return std::holds_alternative<AssignRouteAction>(a.action) || std::holds_alternative<AcquirePositionAction>(a.action);
    };
    for (const bool routing : {false, true})
      for (const InitAction& a : scenario.storyboard.init) {
        if (is_routing(a) != routing) continue;
        ActionContext ctx = context();
        (void)start_action(a.action, a.entity, "", ctx, running);
      }
    // Trailers connected from the start: towed from here on (lined up behind their tractors).
    align_initial_trailers(scenario, entities, trailers, roads);
    for (const Story& story : scenario.storyboard.stories)
      transition("story", story.key, "startTransition", ElementState::Running);
  }

  void step(double dt) {
    if (finished) return;
    ++step_index;
    last_dt = dt;
    t = static_cast<double>(step_index) * dt;
    for (auto& [name, state] : entities) advance(state, roads, t, dt);
    pull_trailers(scenario, entities, trailers, roads, dt);
    ActionContext ctx = context();
    for (const std::string& ended : update_running_actions(ctx, running))
      if (!ended.empty()) transition("action", ended, "endTransition", ElementState::Complete);
    settle();
    evaluate_storyboard();
  }
};

StoryboardRuntime::StoryboardRuntime(const Scenario& scenario, const opendrive::RoadNetwork& roads)
    : impl_(std::make_unique<Impl>(scenario, roads)) {
  for (const Entity& e : scenario.entities) {
    EntityState& state = impl_->entities[e.name];
    if (e.controller) state.controller = e.controller->name;
  }
  impl_->run_init();
  impl_->evaluate_storyboard();
}

StoryboardRuntime::~StoryboardRuntime() = default;

void StoryboardRuntime::step(double dt) { impl_->step(dt); }
void StoryboardRuntime::observe(const std::string& name, const opendrive::Pose2& pose, double speed,
                                double acceleration) {
  EntityState& e = impl_->entities.at(name);
  if (!e.placed) return;
  e.pose = pose;
  e.speed = speed;
  e.acceleration = acceleration;
  relocate(e, impl_->roads);
}

const std::map<std::string, Parameter>& StoryboardRuntime::parameters() const { return impl_->parameters; }
const std::map<std::string, Parameter>& StoryboardRuntime::variables() const { return impl_->variables; }
const std::map<std::string, std::string>& StoryboardRuntime::trailers() const { return impl_->trailers; }

double StoryboardRuntime::time() const { return impl_->t; }
bool StoryboardRuntime::finished() const { return impl_->finished; }
const std::map<std::string, EntityState>& StoryboardRuntime::entities() const { return impl_->entities; }
const std::vector<TransitionLog>& StoryboardRuntime::log() const { return impl_->log; }
ElementState StoryboardRuntime::state(const std::string& type, const std::string& name) const {
  auto it = impl_->records.find({type, name});  // by key
  for (const auto& [id, element_name] : impl_->names)  // else the first element of that name
    if (it == impl_->records.end() && id.first == type && element_name == name) it = impl_->records.find(id);
  return it == impl_->records.end() ? ElementState::Standby : it->second.state;
}

}  // namespace orch::openscenario

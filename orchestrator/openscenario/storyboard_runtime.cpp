#include "openscenario/storyboard_runtime_impl.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "core/errors.hpp"

namespace orch::openscenario {

StoryboardRuntime::Impl::Impl(const Scenario& s, const opendrive::RoadNetwork& r, std::uint64_t run_seed)
    : scenario(s),
      roads(r),
      resolver(r),
      trailers(initial_trailer_links(s)),
      signals(s.signal_controllers, r.signal_controllers()),
      seed(run_seed) {
  for (const Parameter& p : s.parameters) parameters[p.name] = p;
  for (const Parameter& p : s.local_parameters) parameters[p.name] = p;  // "<owner>/<name>"
  for (const Parameter& v : s.variables) variables[v.name] = v;
  for (const auto& [name, value] : s.monitors) monitors[name] = value;
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
            for (const Action& a : e.actions) {
              names[{"action", a.key}] = a.name;
              action_order.emplace(a.key, static_cast<int>(action_order.size()));
            }
          }
        }
      }
    }
  }
}

ActionContext StoryboardRuntime::Impl::context() {
  return ActionContext{scenario, roads,   resolver, entities, parameters, variables, trailers, t,
                       last_dt,  &signals, &traffic, &time_of_day, &monitors, seed};
}

void StoryboardRuntime::Impl::transition(const std::string& type, const std::string& key,
                                         const std::string& what, ElementState to) {
  Record& r = record(type, key);
  r.state = to;
  r.transitions.push_back({what, step_index, ++transitions_made});
  if (r.transitions.size() > 8) r.transitions.erase(r.transitions.begin());
  const auto name = names.find({type, key});
  log.push_back({t, type, name == names.end() ? key : name->second, what});
}

namespace {
// A global action, or a UserDefinedAction's custom command (read as an AppearanceAction with
// no effect; override_reader.cpp): it takes no actors.
bool runs_without_actors(const PrivateAction& action) {
  if (const auto* a = std::get_if<AppearanceAction>(&action)) return a->element == "CustomCommandAction";
  return std::visit([](const auto& k) { return kIsGlobalAction<std::decay_t<decltype(k)>>; }, action);
}
}  // namespace

void StoryboardRuntime::Impl::start_event(const Event& e, const std::vector<std::string>* selected) {
  if (!frozen) frozen = entities;  // the conditions still to come this step see the step's world
  Record& r = record("event", e.key);
  ++r.executions;
  transition("event", e.key, "startTransition", ElementState::Running);
  for (const Action& a : e.actions) {
    transition("action", a.key, "startTransition", ElementState::Running);
    // Global actions and custom commands have no actors: they run once, for no entity ("").
    // A private action of a group that selects the triggering entities has those as actors
    // besides the named ones (none: it has no actor and ends at once).
    std::vector<std::string> actors = a.actors;
    if (runs_without_actors(a.action)) {
      actors = {""};
    } else if (selected != nullptr) {
      for (const std::string& name : *selected)
        if (std::find(actors.begin(), actors.end(), name) == actors.end()) actors.push_back(name);
    }
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

void StoryboardRuntime::Impl::stop_action(const std::string& name) {
  std::erase_if(running, [&](const RunningAction& r) { return r.action == name; });
  if (record("action", name).state == ElementState::Running)
    transition("action", name, "stopTransition", ElementState::Complete);
}

void StoryboardRuntime::Impl::stop_event(const Event& e) {
  for (const Action& a : e.actions) stop_action(a.key);
  transition("event", e.key, "stopTransition", ElementState::Complete);
}

void StoryboardRuntime::Impl::start_group(const ManeuverGroup& g) {
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

void StoryboardRuntime::Impl::stop_act(const Act& act) {
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

bool StoryboardRuntime::Impl::complete(const std::string& type, const std::string& name) {
  return record(type, name).state == ElementState::Complete;
}

void StoryboardRuntime::Impl::settle() {
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

void StoryboardRuntime::Impl::stop_storyboard() {
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

void StoryboardRuntime::Impl::evaluate_storyboard() {
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
      std::vector<std::string> triggering;
      if (state == ElementState::Standby && fires(act.start_trigger, &triggering)) {
        act_triggering_entities[act.key] = std::move(triggering);
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
            start_event(e, g.select_triggering_entities ? &act_triggering_entities[act.key] : nullptr);
          }
        }
    }
  }
  frozen.reset();
  settle();
}

void StoryboardRuntime::Impl::run_init() {
  // Init actions all take effect at t = 0: routes are planned after every entity is placed,
  // whatever their order in the file (esmini's routing-test.xosc assigns the ego's route
  // before it teleports it; a route planned from no position would be no plan).
  const auto is_routing = [](const InitAction& a) {
    return std::holds_alternative<AssignRouteAction>(a.action) || std::holds_alternative<AcquirePositionAction>(a.action) ||
           std::holds_alternative<RandomRouteAction>(a.action);
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

void StoryboardRuntime::Impl::lane_change_motion_order() {
  const auto order = [&](const std::string& key) {
    const auto it = action_order.find(key);
    return it == action_order.end() ? -1 : it->second;  // Init actions first
  };
  for (auto& [name, state] : entities) {
    std::optional<int> lane_change, speed;
    for (const RunningAction& r : running) {
      if (r.entity != name || r.spec == nullptr) continue;
      if (r.domain == MotionDomain::Lateral && std::holds_alternative<LaneChangeAction>(*r.spec)) lane_change = order(r.action);
      if (r.domain == MotionDomain::Longitudinal && std::holds_alternative<SpeedAction>(*r.spec)) speed = order(r.action);
    }
    state.lane_change_before_speed = lane_change && speed && *lane_change < *speed;
  }
}

void StoryboardRuntime::Impl::step(double dt) {
  if (finished) return;
  ++step_index;
  last_dt = dt;
  t = static_cast<double>(step_index) * dt;
  lane_change_motion_order();
  ActionContext ctx = context();
  steer_synchronize(ctx, running);  // its speed moves the entity in this step
  step_unstepped_distances(ctx, running);  // as theirs (the first step)
  follow_relative_speeds(ctx, running);    // the reference's speed in this step
  for (auto& [name, state] : entities)
    if (!is_towed(trailers, name)) advance(state, roads, t, dt);  // a towed trailer only follows its bar
  pull_trailers(scenario, entities, trailers, roads, dt);
  for (const std::string& ended : update_running_actions(ctx, running))
    if (!ended.empty()) transition("action", ended, "endTransition", ElementState::Complete);
  settle();
  signals.advance(t);  // the phases due now, before the conditions read them
  evaluate_storyboard();
}


StoryboardRuntime::StoryboardRuntime(const Scenario& scenario, const opendrive::RoadNetwork& roads, std::uint64_t seed)
    : impl_(std::make_unique<Impl>(scenario, roads, seed)) {
  for (const Entity& e : scenario.entities) {
    EntityState& state = impl_->entities[e.name];
    if (e.controller) state.controller = e.controller->name;
  }
  impl_->signals.advance(0);
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
const std::map<std::string, bool>& StoryboardRuntime::monitors() const { return impl_->monitors; }
const std::map<std::string, std::string>& StoryboardRuntime::trailers() const { return impl_->trailers; }
const std::map<std::string, std::string>& StoryboardRuntime::signal_states() const { return impl_->signals.states(); }
const TrafficBook& StoryboardRuntime::traffic() const { return impl_->traffic; }
std::string StoryboardRuntime::signal_phase(const std::string& controller) const {
  return impl_->signals.phase(controller);
}

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

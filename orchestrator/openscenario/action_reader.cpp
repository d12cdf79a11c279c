// PrivateAction and GlobalAction: one table entry per action run (name, reader); the
// readers of the motion and controller actions.
#include <algorithm>
#include <type_traits>

#include <fmt/format.h>

#include "core/suggest.hpp"
#include "openscenario/reader_context.hpp"

namespace orch::openscenario::reading {

DynamicsShape read_shape(Element& e) {
  return e.choice<DynamicsShape>("dynamicsShape", {{"step", DynamicsShape::Step},
                                                   {"linear", DynamicsShape::Linear},
                                                   {"cubic", DynamicsShape::Cubic},
                                                   {"sinusoidal", DynamicsShape::Sinusoidal}});
}

TransitionDynamics read_dynamics(Element& e, Context& context) {
  TransitionDynamics d;
  d.shape = read_shape(e);
  d.dimension = e.choice<DynamicsDimension>(
      "dynamicsDimension",
      {{"time", DynamicsDimension::Time}, {"distance", DynamicsDimension::Distance}, {"rate", DynamicsDimension::Rate}});
  d.value = e.number("value");
  // The standard gives `value` the range [0..inf[. Real files write a deceleration as a negative
  // rate (esmini's examples: value="-4"); esmini runs it by its magnitude, and so do we, with a
  // warning. A negative time or distance has no such reading: it stays an error.
  if (d.value < 0 && d.dimension == DynamicsDimension::Rate) {
    context.warnings.warning(e.source().where(e.node(), "value"),
                             fmt::format("a negative rate ({}): the standard gives TransitionDynamics value the "
                                         "range [0..inf[; run with its magnitude {}, as esmini does",
                                         d.value, -d.value));
    d.value = -d.value;
  }
  if (d.value < 0) e.fail_attribute("value", "a transition's time or distance cannot be negative (the standard's range: [0..inf[)");
  // followingMode (1.2): `position` (the default meaning) follows the shape exactly, which is
  // what runs here. `follow` asks for a controller-like following that may lag the shape; the
  // standard gives it no law, so it runs as `position`, with a warning saying so (esmini 2.x
  // does not read it either). An optional attribute never refuses the file.
  const auto mode = e.optional_choice<bool>("followingMode", {{"position", false}, {"follow", true}});
  if (mode.value_or(false))
    context.warnings.warning(e.source().where(e.node(), "followingMode"),
                             "followingMode=\"follow\" (a controller-like following of the transition, whose law "
                             "the standard leaves to the simulator) runs as \"position\": the shape exactly");
  e.finish();
  return d;
}

namespace {

SpeedAction read_speed(Element& e, Context& context) {
  SpeedAction a;
  Element dynamics = e.child("SpeedActionDynamics");
  a.dynamics = read_dynamics(dynamics, context);
  Element holder = e.child("SpeedActionTarget");
  Element target = holder.one_of({"AbsoluteTargetSpeed", "RelativeTargetSpeed"});
  holder.finish();
  if (target.name() == "AbsoluteTargetSpeed") {
    a.target = AbsoluteTargetSpeed{target.number("value")};
  } else {
    a.target = RelativeTargetSpeed{
        target.text("entityRef"), target.number("value"),
        target.choice<bool>("speedTargetValueType", {{"delta", false}, {"factor", true}}),
        target.optional_boolean("continuous").value_or(false)};
  }
  target.finish();
  e.finish();
  return a;
}

// The coordinate system of a distance action (entity unless given).
std::string coordinate_system(Element& e) {
  return e.optional_choice<std::string>("coordinateSystem", {{"entity", "entity"},
                                                             {"lane", "lane"},
                                                             {"road", "road"},
                                                             {"trajectory", "trajectory"}})
      .value_or("entity");
}

// The limits of a distance action's DynamicConstraints. The jerk limits maxAccelerationRate
// and maxDecelerationRate apply to a LongitudinalDistanceAction (distance_keeping.cpp); a
// LateralDistanceAction's are read, not applied.
template <typename DistanceAction>
void read_dynamic_constraints(Element& e, DistanceAction& a, bool must_be_positive) {
  auto constraints = e.optional_child("DynamicConstraints");
  if (!constraints) return;
  a.max_acceleration = constraints->optional_number("maxAcceleration");
  a.max_deceleration = constraints->optional_number("maxDeceleration");
  a.max_speed = constraints->optional_number("maxSpeed");
  if (must_be_positive)
    for (const char* name : {"maxAcceleration", "maxDeceleration", "maxSpeed"})
      if (constraints->has(name) && !(*constraints->optional_number(name) > 0))
        constraints->fail_attribute(name, "must be positive");
  if constexpr (std::is_same_v<DistanceAction, LongitudinalDistanceAction>) {
    a.max_acceleration_rate = constraints->optional_number("maxAccelerationRate");
    a.max_deceleration_rate = constraints->optional_number("maxDecelerationRate");
    for (const char* name : {"maxAccelerationRate", "maxDecelerationRate"})
      if (constraints->has(name) && !(*constraints->optional_number(name) > 0))
        constraints->fail_attribute(name, "must be positive");
  } else {
    constraints->ignore_attributes({"maxAccelerationRate", "maxDecelerationRate"});
  }
  constraints->finish();
}

LongitudinalDistanceAction read_distance(Element& e) {
  LongitudinalDistanceAction a;
  a.entity = e.text("entityRef");
  a.distance = e.optional_number("distance");
  a.time_gap = e.optional_number("timeGap");
  if (a.distance.has_value() == a.time_gap.has_value()) e.fail("give exactly one of distance and timeGap");
  a.freespace = e.boolean("freespace");
  a.continuous = e.boolean("continuous");
  a.coordinate_system = coordinate_system(e);
  a.displacement = e.optional_choice<std::string>("displacement", {{"any", "any"},
                                                                   {"leadingReferencedEntity", "leadingReferencedEntity"},
                                                                   {"trailingReferencedEntity", "trailingReferencedEntity"}})
                       .value_or("trailingReferencedEntity");
  read_dynamic_constraints(e, a, false);
  e.finish();
  return a;
}

SpeedProfileAction read_speed_profile(Element& e) {
  SpeedProfileAction a;
  if (e.has("entityRef")) a.relative_to = e.text("entityRef");
  a.follow = e.choice<bool>("followingMode", {{"position", false}, {"follow", true}});
  if (auto constraints = e.optional_child("DynamicConstraints")) {
    a.max_acceleration = constraints->optional_number("maxAcceleration");
    a.max_deceleration = constraints->optional_number("maxDeceleration");
    a.max_acceleration_rate = constraints->optional_number("maxAccelerationRate");
    a.max_deceleration_rate = constraints->optional_number("maxDecelerationRate");
    a.max_speed = constraints->optional_number("maxSpeed");
    for (const char* name : {"maxAcceleration", "maxDeceleration", "maxAccelerationRate", "maxDecelerationRate"})
      if (constraints->has(name) && !(*constraints->optional_number(name) > 0))
        constraints->fail_attribute(name, "must be positive");
    constraints->finish();
  }
  for (Element entry : e.children("SpeedProfileEntry")) {
    SpeedProfileEntry x;
    x.time = entry.optional_number("time");
    if (x.time && *x.time < 0) entry.fail_attribute("time", "cannot be negative");
    x.speed = entry.number("speed");
    entry.finish();
    a.entries.push_back(x);
  }
  if (a.entries.empty()) e.fail("a SpeedProfileAction needs at least one SpeedProfileEntry");
  e.finish();
  return a;
}

LaneChangeAction read_lane_change(Element& e, Context& context) {
  LaneChangeAction a;
  a.target_lane_offset = e.optional_number("targetLaneOffset");
  Element dynamics = e.child("LaneChangeActionDynamics");
  a.dynamics = read_dynamics(dynamics, context);
  Element holder = e.child("LaneChangeTarget");
  Element target = holder.one_of({"RelativeTargetLane", "AbsoluteTargetLane"});
  holder.finish();
  if (target.name() == "RelativeTargetLane") {
    a.relative_to = target.text("entityRef");
    a.lane = target.integer("value");
  } else {
    a.lane = target.integer("value");
  }
  target.finish();
  e.finish();
  return a;
}

LaneOffsetAction read_lane_offset(Element& e) {
  LaneOffsetAction a;
  a.continuous = e.boolean("continuous");
  Element dynamics = e.child("LaneOffsetActionDynamics");
  a.shape = read_shape(dynamics);
  a.max_lateral_acc = dynamics.optional_number("maxLateralAcc");
  dynamics.finish();
  Element holder = e.child("LaneOffsetTarget");
  Element target = holder.one_of({"AbsoluteTargetLaneOffset", "RelativeTargetLaneOffset"});
  holder.finish();
  if (target.name() == "RelativeTargetLaneOffset") a.relative_to = target.text("entityRef");
  a.value = target.number("value");
  target.finish();
  e.finish();
  return a;
}

// Activating a controller's animation or lighting domain (1.2) changes nothing a SUMO run
// shows (no renderer, no lights): accepted, with a warning; the motion domains run as usual.
void warn_visual_domains(Element& e, Context& context, const char* animation, const char* lighting) {
  for (const char* domain : {animation, lighting})
    if (e.optional_boolean(domain).value_or(false))
      context.warnings.warning(e.source().where(e.node(), domain),
                               fmt::format("{}=\"true\": the controller's {} domain has no effect here (SUMO runs "
                                           "render no animations or lights); the motion domains run as usual",
                                           domain, domain == animation ? "animation" : "lighting"));
}

ActivateControllerAction read_activate(Element& e, Context& context) {
  ActivateControllerAction a{e.optional_boolean("lateral"), e.optional_boolean("longitudinal"), ""};
  // 1.3: which of the entity's ObjectControllers (controllerRef is 1.3's deprecated name for it).
  a.object_controller = e.optional_text("objectControllerRef").value_or(e.optional_text("controllerRef").value_or(""));
  warn_visual_domains(e, context, "animation", "lighting");
  e.finish();
  return a;
}

AssignControllerAction read_assign_controller(Element& e, Context& context) {
  AssignControllerAction a;
  a.lateral = e.optional_boolean("activateLateral");
  a.longitudinal = e.optional_boolean("activateLongitudinal");
  warn_visual_domains(e, context, "activateAnimation", "activateLighting");
  Element source = e.one_of({"Controller", "CatalogReference"});
  if (source.name() == "CatalogReference") {
    Element entry = context.resolve(source, {"Controller"});
    a.controller = read_controller(entry);
    source.finish();
  } else {
    a.controller = read_controller(source);
  }
  e.finish();
  return a;
}

SynchronizeFinalSpeed read_final_speed(Element& holder) {
  Element speed = holder.one_of({"AbsoluteSpeed", "RelativeSpeedToMaster"});
  holder.finish();
  SynchronizeFinalSpeed f;
  f.relative = speed.name() == "RelativeSpeedToMaster";
  f.value = speed.number("value");
  if (f.relative) f.factor = speed.choice<bool>("speedTargetValueType", {{"delta", false}, {"factor", true}});
  // 1.1: the steady state, one of two elements directly in the speed (the SteadyState group).
  if (auto distance = speed.optional_child("TargetDistanceSteadyState")) {
    f.steady_distance = distance->number("distance");
    distance->finish();
  }
  if (auto time = speed.optional_child("TargetTimeSteadyState")) {
    if (f.steady_distance) time->fail("give one steady state: TargetDistanceSteadyState or TargetTimeSteadyState");
    f.steady_time = time->number("time");
    time->finish();
  }
  if ((f.steady_distance && *f.steady_distance < 0) || (f.steady_time && *f.steady_time < 0))
    speed.fail("a steady state's distance or time cannot be negative");
  speed.finish();
  return f;
}

SynchronizeAction read_synchronize(Element& e) {
  SynchronizeAction a;
  a.entity = e.text("masterEntityRef");
  a.tolerance_master = e.optional_number("targetToleranceMaster");
  a.tolerance = e.optional_number("targetTolerance");
  if (a.tolerance_master && *a.tolerance_master < 0) e.fail_attribute("targetToleranceMaster", "a tolerance cannot be negative");
  if (a.tolerance && *a.tolerance < 0) e.fail_attribute("targetTolerance", "a tolerance cannot be negative");
  Element master = e.child("TargetPositionMaster");
  a.master_position = read_position(master);
  Element target = e.child("TargetPosition");
  a.position = read_position(target);
  if (auto final_speed = e.optional_child("FinalSpeed")) a.final_speed = read_final_speed(*final_speed);
  e.finish();
  return a;
}

VisibilityAction read_visibility(Element& e) {
  VisibilityAction a{e.boolean("graphics"), e.boolean("traffic"), e.optional_boolean("sensors").value_or(true)};
  // 1.2: the sensors `sensors` applies to (absent: all). Sensors are not simulated here, so
  // the names are read and checked only, like `sensors` itself.
  if (auto set = e.optional_child("SensorReferenceSet")) {
    std::vector<Element> references = set->children("SensorReference");
    if (references.empty()) set->fail("a SensorReferenceSet needs at least one SensorReference");
    for (Element& r : references) {
      (void)r.text("name");
      r.finish();
    }
    set->finish();
  }
  e.finish();
  return a;
}

// ---- the tables: one entry per action the orchestrator runs --------------------------
// `wrapper` is the element between PrivateAction / GlobalAction and the action ("" when
// the action stands directly in it). A child of a wrapper that is not in the table is an
// error: "not supported" for an element of the standard, else "unknown" with "did you mean".
// Entity references of every action are checked where the storyboard is read (by member:
// `entity`, `relative_to`, positions); what an action does is in action_start.cpp.
using ActionReader = PrivateAction (*)(Element& wrapper, Element& action, Context& context);
struct ActionEntry {
  std::string_view wrapper;
  std::string_view name;
  ActionReader read;
};

const std::vector<ActionEntry> kPrivateActions = {
    {"", "TeleportAction",
     [](Element&, Element& e, Context&) -> PrivateAction {
       Element position = e.child("Position");
       return TeleportAction{read_position(position)};
     }},
    {"", "VisibilityAction", [](Element&, Element& e, Context&) -> PrivateAction { return read_visibility(e); }},
    {"", "SynchronizeAction", [](Element&, Element& e, Context&) -> PrivateAction { return read_synchronize(e); }},
    // OpenSCENARIO 1.0 places ActivateControllerAction directly in PrivateAction.
    {"", "ActivateControllerAction",
     [](Element&, Element& e, Context& c) -> PrivateAction { return read_activate(e, c); }},
    {"LongitudinalAction", "SpeedAction", [](Element&, Element& e, Context& context) -> PrivateAction { return read_speed(e, context); }},
    {"LongitudinalAction", "SpeedProfileAction",
     [](Element&, Element& e, Context&) -> PrivateAction { return read_speed_profile(e); }},
    {"LongitudinalAction", "LongitudinalDistanceAction",
     [](Element&, Element& e, Context&) -> PrivateAction { return read_distance(e); }},
    {"LateralAction", "LaneChangeAction",
     [](Element&, Element& e, Context& context) -> PrivateAction { return read_lane_change(e, context); }},
    {"LateralAction", "LateralDistanceAction",
     [](Element&, Element& e, Context&) -> PrivateAction { return read_lateral_distance(e); }},
    {"LateralAction", "LaneOffsetAction",
     [](Element&, Element& e, Context&) -> PrivateAction { return read_lane_offset(e); }},
    {"ControllerAction", "ActivateControllerAction",
     [](Element&, Element& e, Context& c) -> PrivateAction { return read_activate(e, c); }},
    {"ControllerAction", "AssignControllerAction",
     [](Element&, Element& e, Context& c) -> PrivateAction { return read_assign_controller(e, c); }},
    {"RoutingAction", "AssignRouteAction",
     [](Element&, Element& e, Context& c) -> PrivateAction { return read_assign_route(e, c); }},
    {"RoutingAction", "AcquirePositionAction",
     [](Element&, Element& e, Context&) -> PrivateAction {
       Element position = e.child("Position");
       return AcquirePositionAction{read_position(position)};
     }},
    {"RoutingAction", "RandomRouteAction",
     [](Element&, Element& e, Context&) -> PrivateAction {
       e.finish();  // no content (1.3)
       return RandomRouteAction{};
     }},
    {"RoutingAction", "FollowTrajectoryAction",
     [](Element&, Element& e, Context& c) -> PrivateAction { return read_follow_trajectory(e, c); }},
    {"AppearanceAction", "LightStateAction",
     [](Element&, Element& e, Context&) -> PrivateAction { return read_light_state(e); }},
    {"AppearanceAction", "AnimationAction",
     [](Element&, Element& e, Context& c) -> PrivateAction { return read_animation(e, c); }},
    {"ControllerAction", "OverrideControllerValueAction",
     [](Element&, Element& e, Context& c) -> PrivateAction { return read_controller_override(e, c); }},
    {"TrailerAction", "ConnectTrailerAction",
     [](Element&, Element& e, Context&) -> PrivateAction { return ConnectTrailerAction{e.text("trailerRef")}; }},
    {"TrailerAction", "DisconnectTrailerAction",
     [](Element&, Element&, Context&) -> PrivateAction { return DisconnectTrailerAction{}; }},
};

const std::vector<ActionEntry> kGlobalActions = {
    {"EntityAction", "AddEntityAction",
     [](Element& w, Element& e, Context&) -> PrivateAction {
       Element position = e.child("Position");
       return AddEntityAction{w.text("entityRef"), read_position(position)};
     }},
    {"EntityAction", "DeleteEntityAction",
     [](Element& w, Element&, Context&) -> PrivateAction { return DeleteEntityAction{w.text("entityRef")}; }},
    {"ParameterAction", "SetAction",
     [](Element& w, Element& e, Context&) -> PrivateAction { return read_parameter_set(w, e); }},
    {"ParameterAction", "ModifyAction",
     [](Element& w, Element& e, Context&) -> PrivateAction { return read_parameter_modify(w, e); }},
    {"", "EnvironmentAction",
     [](Element&, Element& e, Context& c) -> PrivateAction { return read_environment_action(e, c); }},
    {"InfrastructureAction", "TrafficSignalAction",
     [](Element&, Element& e, Context& c) -> PrivateAction { return read_traffic_signal_action(e, c); }},
    {"VariableAction", "SetAction",
     [](Element& w, Element& e, Context& c) -> PrivateAction { return read_variable_set(w, e, c); }},
    {"TrafficAction", "TrafficSwarmAction", read_traffic_action},
    {"TrafficAction", "TrafficSourceAction", read_traffic_action},
    {"TrafficAction", "TrafficSinkAction", read_traffic_action},
    {"TrafficAction", "TrafficStopAction", read_traffic_action},
    {"TrafficAction", "TrafficAreaAction", read_traffic_action},
    {"VariableAction", "ModifyAction",
     [](Element& w, Element& e, Context& c) -> PrivateAction { return read_variable_modify(w, e, c); }},
    {"", "SetMonitorAction",
     [](Element&, Element& e, Context& c) -> PrivateAction {
       const std::string monitor = e.text("monitorRef");
       if (std::find(c.monitors.begin(), c.monitors.end(), monitor) == c.monitors.end())
         e.fail_attribute("monitorRef", fmt::format("no monitor named \"{}\" in MonitorDeclarations{}", monitor,
                                                    did_you_mean(monitor, c.monitors)));
       return SetMonitorAction{monitor, e.boolean("value")};
     }},
};

PrivateAction read_from_table(Element& holder, const std::vector<ActionEntry>& table, Context& context) {
  std::vector<std::string> outer;
  for (const ActionEntry& entry : table) {
    const std::string name(entry.wrapper.empty() ? entry.name : entry.wrapper);
    if (std::find(outer.begin(), outer.end(), name) == outer.end()) outer.push_back(name);
  }
  Element kind = holder.one_of(outer);  // an unlisted standard action: "not supported"
  holder.finish();
  for (const ActionEntry& entry : table)
    if (entry.wrapper.empty() && entry.name == kind.name()) {
      PrivateAction result = entry.read(kind, kind, context);
      kind.finish();
      return result;
    }
  std::vector<std::string> inner;
  for (const ActionEntry& entry : table)
    if (entry.wrapper == kind.name()) inner.emplace_back(entry.name);
  // OpenSCENARIO 1.0's ControllerAction holds an AssignControllerAction and an
  // OverrideControllerValueAction together (xsd:all, both required; 1.1 made them a choice),
  // as CARLA ScenarioRunner's files write it: the override is read (no effect on motion) and
  // the assignment runs.
  if (kind.name() == "ControllerAction" && kind.node().child("AssignControllerAction") &&
      kind.node().child("OverrideControllerValueAction")) {
    Element override_action = kind.child("OverrideControllerValueAction");
    (void)read_controller_override(override_action, context);
    override_action.finish();
    std::erase(inner, "OverrideControllerValueAction");
  }
  Element action = kind.one_of(inner);
  for (const ActionEntry& entry : table)
    if (entry.wrapper == kind.name() && entry.name == action.name()) {
      PrivateAction result = entry.read(kind, action, context);
      action.finish();
      kind.finish();
      return result;
    }
  action.fail("unreachable: one_of returned an element outside the table");
}

}  // namespace

PrivateAction read_private_action(Element& private_action, Context& context) {
  return read_from_table(private_action, kPrivateActions, context);
}

PrivateAction read_global_action(Element& global_action, Context& context) {
  return read_from_table(global_action, kGlobalActions, context);
}

LateralDistanceAction read_lateral_distance(Element& e) {
  LateralDistanceAction a;
  a.entity = e.text("entityRef");
  a.distance = e.optional_number("distance");
  if (a.distance && *a.distance < 0) e.fail_attribute("distance", "a distance cannot be negative");
  a.freespace = e.boolean("freespace");
  a.continuous = e.boolean("continuous");
  a.coordinate_system = coordinate_system(e);
  if (a.coordinate_system == "trajectory")
    e.fail_attribute("coordinateSystem", "a lateral distance along a trajectory is not supported");
  a.displacement = e.optional_choice<std::string>("displacement", {{"any", "any"},
                                                                   {"leftToReferencedEntity", "leftToReferencedEntity"},
                                                                   {"rightToReferencedEntity", "rightToReferencedEntity"}})
                       .value_or("any");
  read_dynamic_constraints(e, a, true);
  e.finish();
  return a;
}

}  // namespace orch::openscenario::reading

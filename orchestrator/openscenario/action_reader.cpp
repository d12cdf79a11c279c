// PrivateAction: the longitudinal, lateral, controller and teleport actions run today.
#include <fmt/format.h>

#include "openscenario/reader_context.hpp"

namespace orch::openscenario::reading {

DynamicsShape read_shape(Element& e) {
  return e.choice<DynamicsShape>("dynamicsShape", {{"step", DynamicsShape::Step},
                                                   {"linear", DynamicsShape::Linear},
                                                   {"cubic", DynamicsShape::Cubic},
                                                   {"sinusoidal", DynamicsShape::Sinusoidal}});
}

TransitionDynamics read_dynamics(Element& e) {
  TransitionDynamics d;
  d.shape = read_shape(e);
  d.dimension = e.choice<DynamicsDimension>(
      "dynamicsDimension",
      {{"time", DynamicsDimension::Time}, {"distance", DynamicsDimension::Distance}, {"rate", DynamicsDimension::Rate}});
  d.value = e.number("value");
  if (d.value < 0) e.fail_attribute("value", "a transition's time, distance or rate cannot be negative");
  if (e.has("followingMode")) e.fail_attribute("followingMode", "followingMode is not supported");
  e.finish();
  return d;
}

namespace {

SpeedAction read_speed(Element& e) {
  SpeedAction a;
  Element dynamics = e.child("SpeedActionDynamics");
  a.dynamics = read_dynamics(dynamics);
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

LongitudinalDistanceAction read_distance(Element& e) {
  LongitudinalDistanceAction a;
  a.entity = e.text("entityRef");
  a.distance = e.optional_number("distance");
  a.time_gap = e.optional_number("timeGap");
  if (a.distance.has_value() == a.time_gap.has_value()) e.fail("give exactly one of distance and timeGap");
  a.freespace = e.boolean("freespace");
  a.continuous = e.boolean("continuous");
  a.coordinate_system = e.optional_choice<std::string>("coordinateSystem", {{"entity", "entity"},
                                                                            {"lane", "lane"},
                                                                            {"road", "road"},
                                                                            {"trajectory", "trajectory"}})
                            .value_or("entity");
  a.displacement = e.optional_choice<std::string>("displacement", {{"any", "any"},
                                                                   {"leadingReferencedEntity", "leadingReferencedEntity"},
                                                                   {"trailingReferencedEntity", "trailingReferencedEntity"}})
                       .value_or("trailingReferencedEntity");
  if (auto constraints = e.optional_child("DynamicConstraints")) {
    a.max_acceleration = constraints->optional_number("maxAcceleration");
    a.max_deceleration = constraints->optional_number("maxDeceleration");
    a.max_speed = constraints->optional_number("maxSpeed");
    constraints->ignore_attributes({"maxAccelerationRate", "maxDecelerationRate"});
    constraints->finish();
  }
  e.finish();
  return a;
}

LaneChangeAction read_lane_change(Element& e) {
  LaneChangeAction a;
  a.target_lane_offset = e.optional_number("targetLaneOffset");
  Element dynamics = e.child("LaneChangeActionDynamics");
  a.dynamics = read_dynamics(dynamics);
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

ActivateControllerAction read_activate(Element& e) {
  ActivateControllerAction a{e.optional_boolean("lateral"), e.optional_boolean("longitudinal")};
  for (const char* unsupported : {"animation", "lighting"})
    if (e.optional_boolean(unsupported).value_or(false))
      e.fail_attribute(unsupported, fmt::format("activating {} control is not supported", unsupported));
  e.finish();
  return a;
}

}  // namespace

PrivateAction read_private_action(Element& private_action) {
  Element kind = private_action.one_of({"LongitudinalAction", "LateralAction", "VisibilityAction",
                                        "SynchronizeAction", "ActivateControllerAction", "ControllerAction",
                                        "TeleportAction", "RoutingAction", "AppearanceAction", "TrailerAction"});
  private_action.finish();
  const std::string_view name = kind.name();
  PrivateAction result = ActivateControllerAction{};
  if (name == "TeleportAction") {
    Element position = kind.child("Position");
    result = TeleportAction{read_position(position)};
  } else if (name == "LongitudinalAction") {
    Element action = kind.one_of({"SpeedAction", "LongitudinalDistanceAction", "SpeedProfileAction"});
    if (action.name() == "SpeedAction") result = read_speed(action);
    else if (action.name() == "LongitudinalDistanceAction") result = read_distance(action);
    else action.fail("SpeedProfileAction is an OpenSCENARIO element the orchestrator does not run (not supported)");
  } else if (name == "LateralAction") {
    Element action = kind.one_of({"LaneChangeAction", "LaneOffsetAction", "LateralDistanceAction"});
    if (action.name() == "LaneChangeAction") result = read_lane_change(action);
    else if (action.name() == "LaneOffsetAction") result = read_lane_offset(action);
    else action.fail("LateralDistanceAction is an OpenSCENARIO element the orchestrator does not run (not supported)");
  } else if (name == "ActivateControllerAction") {
    result = read_activate(kind);  // OpenSCENARIO 1.0 places it here
  } else if (name == "ControllerAction") {
    // 1.1+: ActivateControllerAction inside ControllerAction; the others are not run.
    Element action = kind.one_of({"ActivateControllerAction", "AssignControllerAction", "OverrideControllerValueAction"});
    if (action.name() != "ActivateControllerAction")
      action.fail(fmt::format("{} is an OpenSCENARIO element the orchestrator does not run (not supported)",
                              action.name()));
    result = read_activate(action);
  } else {
    kind.fail(fmt::format("{} is an OpenSCENARIO element the orchestrator does not run (not supported)", name));
  }
  kind.finish();
  return result;
}

}  // namespace orch::openscenario::reading

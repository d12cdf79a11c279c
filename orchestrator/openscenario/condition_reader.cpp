// Triggers: ConditionGroups of Conditions, by value or by entity.
#include <fmt/format.h>

#include "openscenario/reader_context.hpp"

namespace orch::openscenario::reading {

Rule read_rule(Element& e) {
  return e.choice<Rule>("rule", {{"equalTo", Rule::EqualTo},
                                 {"greaterThan", Rule::GreaterThan},
                                 {"lessThan", Rule::LessThan},
                                 {"greaterOrEqual", Rule::GreaterOrEqual},
                                 {"lessOrEqual", Rule::LessOrEqual},
                                 {"notEqualTo", Rule::NotEqualTo}});
}

namespace {

[[noreturn]] void unsupported(Element& e) {
  e.fail(fmt::format("{} is an OpenSCENARIO element the orchestrator does not run (not supported)", e.name()));
}

Condition read_by_value(Element& holder, Condition c) {
  Element e = holder.one_of({"SimulationTimeCondition", "StoryboardElementStateCondition", "ParameterCondition",
                             "TimeOfDayCondition", "UserDefinedValueCondition", "TrafficSignalCondition",
                             "TrafficSignalControllerCondition", "VariableCondition"});
  holder.finish();
  if (e.name() == "SimulationTimeCondition") {
    c.kind = SimulationTimeCondition{read_rule(e), e.number("value")};
  } else if (e.name() == "StoryboardElementStateCondition") {
    StoryboardElementStateCondition s;
    s.type = e.choice<std::string>("storyboardElementType", {{"story", "story"},
                                                             {"act", "act"},
                                                             {"maneuverGroup", "maneuverGroup"},
                                                             {"maneuver", "maneuver"},
                                                             {"event", "event"},
                                                             {"action", "action"}});
    s.ref = e.text("storyboardElementRef");
    s.state = e.choice<std::string>(
        "state", {{"startTransition", "startTransition"}, {"endTransition", "endTransition"},
                  {"stopTransition", "stopTransition"}, {"skipTransition", "skipTransition"},
                  {"completeState", "completeState"}, {"runningState", "runningState"},
                  {"standbyState", "standbyState"}});
    c.kind = s;
  } else if (e.name() == "ParameterCondition") {
    c.kind = ParameterCondition{e.text("parameterRef"), read_rule(e), e.text("value")};
  } else {
    unsupported(e);
  }
  e.finish();
  return c;
}

Condition read_by_entity(Element& holder, Condition c) {
  ByEntityCondition by;
  Element triggering = holder.child("TriggeringEntities");
  by.all = triggering.choice<bool>("triggeringEntitiesRule", {{"any", false}, {"all", true}});
  for (Element ref : triggering.children("EntityRef")) {
    by.triggering_entities.push_back(ref.text("entityRef"));
    ref.finish();
  }
  if (by.triggering_entities.empty()) triggering.fail("TriggeringEntities needs at least one EntityRef");
  triggering.finish();
  Element wrapper = holder.child("EntityCondition");
  holder.finish();
  Element e = wrapper.one_of(
      {"EndOfRoadCondition", "CollisionCondition", "OffroadCondition", "TimeHeadwayCondition",
       "TimeToCollisionCondition", "AccelerationCondition", "StandStillCondition", "SpeedCondition",
       "RelativeSpeedCondition", "TraveledDistanceCondition", "ReachPositionCondition", "DistanceCondition",
       "RelativeDistanceCondition", "RelativeClearanceCondition", "AngleCondition", "RelativeAngleCondition"});
  wrapper.finish();
  if (e.name() == "SpeedCondition") {
    by.condition = SpeedCondition{read_rule(e), e.number("value")};
    if (e.has("direction")) e.fail_attribute("direction", "a speed direction is not supported");
  } else if (e.name() == "RelativeDistanceCondition") {
    RelativeDistanceCondition r;
    r.entity = e.text("entityRef");
    r.distance_type = e.choice<std::string>("relativeDistanceType", {{"longitudinal", "longitudinal"},
                                                                     {"lateral", "lateral"},
                                                                     {"cartesianDistance", "cartesianDistance"},
                                                                     {"euclidianDistance", "euclidianDistance"}});
    r.coordinate_system = e.optional_choice<std::string>("coordinateSystem", {{"entity", "entity"},
                                                                              {"lane", "lane"},
                                                                              {"road", "road"},
                                                                              {"trajectory", "trajectory"}})
                              .value_or("entity");
    if (r.coordinate_system == "trajectory") e.fail_attribute("coordinateSystem", "trajectory is not supported");
    r.freespace = e.boolean("freespace");
    r.rule = read_rule(e);
    r.value = e.number("value");
    if (e.has("routingAlgorithm")) e.fail_attribute("routingAlgorithm", "routingAlgorithm is not supported");
    by.condition = r;
  } else {
    unsupported(e);
  }
  e.finish();
  c.kind = by;
  return c;
}

Condition read_condition(Element& e) {
  Condition c;
  c.name = e.text("name");
  c.delay = e.number("delay");
  if (c.delay < 0) e.fail_attribute("delay", "a delay cannot be negative");
  c.edge = e.choice<Edge>("conditionEdge", {{"none", Edge::None},
                                            {"rising", Edge::Rising},
                                            {"falling", Edge::Falling},
                                            {"risingOrFalling", Edge::RisingOrFalling}});
  c.place = e.place();
  Element kind = e.one_of({"ByValueCondition", "ByEntityCondition"});
  e.finish();
  return kind.name() == "ByValueCondition" ? read_by_value(kind, std::move(c)) : read_by_entity(kind, std::move(c));
}

}  // namespace

Trigger read_trigger(Element& trigger) {
  Trigger t;
  for (Element group : trigger.children("ConditionGroup")) {
    std::vector<Condition> conditions;
    for (Element condition : group.children("Condition")) conditions.push_back(read_condition(condition));
    if (conditions.empty()) group.fail("a ConditionGroup needs at least one Condition");
    group.finish();
    t.groups.push_back(std::move(conditions));
  }
  trigger.finish();
  return t;
}

}  // namespace orch::openscenario::reading

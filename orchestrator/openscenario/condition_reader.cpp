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

const std::vector<std::pair<std::string, std::string>> kDistanceTypes = {{"longitudinal", "longitudinal"},
                                                                          {"lateral", "lateral"},
                                                                          {"cartesianDistance", "cartesianDistance"},
                                                                          {"euclidianDistance", "euclidianDistance"}};

std::string read_coordinate_system(Element& e) {
  const std::string system = e.optional_choice<std::string>("coordinateSystem", {{"entity", "entity"},
                                                                                 {"lane", "lane"},
                                                                                 {"road", "road"},
                                                                                 {"trajectory", "trajectory"}})
                                 .value_or("entity");
  if (system == "trajectory") e.fail_attribute("coordinateSystem", "trajectory is not supported");
  return system;
}

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
    ParameterCondition p{e.text("parameterRef"), read_rule(e), e.text("value")};
    const auto type = e.scope().type(p.parameter);
    if (!type) e.fail_attribute("parameterRef", fmt::format("no parameter \"{}\" is declared", p.parameter));
    const std::string problem = check_parameter_value(*type, p.value);
    if (!problem.empty()) e.fail_attribute("value", fmt::format("{} ({} parameter {})", problem, *type, p.parameter));
    c.kind = p;
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
    r.distance_type = e.choice<std::string>("relativeDistanceType", kDistanceTypes);
    r.coordinate_system = read_coordinate_system(e);
    r.freespace = e.boolean("freespace");
    r.rule = read_rule(e);
    r.value = e.number("value");
    if (e.has("routingAlgorithm")) e.fail_attribute("routingAlgorithm", "routingAlgorithm is not supported");
    by.condition = r;
  } else if (e.name() == "TraveledDistanceCondition") {
    by.condition = TraveledDistanceCondition{e.number("value")};
  } else if (e.name() == "StandStillCondition") {
    by.condition = StandStillCondition{e.number("duration")};
  } else if (e.name() == "EndOfRoadCondition") {
    by.condition = EndOfRoadCondition{e.number("duration")};
  } else if (e.name() == "OffroadCondition") {
    by.condition = OffroadCondition{e.number("duration")};
  } else if (e.name() == "AccelerationCondition") {
    if (e.has("direction")) e.fail_attribute("direction", "an acceleration direction is not supported");
    by.condition = AccelerationCondition{read_rule(e), e.number("value")};
  } else if (e.name() == "RelativeSpeedCondition") {
    if (e.has("direction")) e.fail_attribute("direction", "a speed direction is not supported");
    by.condition = RelativeSpeedCondition{e.text("entityRef"), read_rule(e), e.number("value")};
  } else if (e.name() == "ReachPositionCondition") {
    Element position = e.child("Position");
    by.condition = ReachPositionCondition{read_position(position), e.number("tolerance")};
  } else if (e.name() == "TimeHeadwayCondition") {
    TimeHeadwayCondition h;
    h.entity = e.text("entityRef");
    h.freespace = e.boolean("freespace");
    h.coordinate_system = read_coordinate_system(e);
    if (e.has("alongRoute") && e.boolean("alongRoute")) e.fail_attribute("alongRoute", "alongRoute is not supported");
    if (e.has("relativeDistanceType") && e.text("relativeDistanceType") != "longitudinal")
      e.fail_attribute("relativeDistanceType", "only a longitudinal headway is supported");
    h.rule = read_rule(e);
    h.value = e.number("value");
    by.condition = h;
  } else if (e.name() == "DistanceCondition") {
    DistanceCondition d;
    Element position = e.child("Position");
    d.position = read_position(position);
    d.freespace = e.boolean("freespace");
    d.coordinate_system = read_coordinate_system(e);
    d.distance_type = e.optional_choice<std::string>("relativeDistanceType", kDistanceTypes).value_or("euclidianDistance");
    if (e.has("alongRoute") && e.boolean("alongRoute")) e.fail_attribute("alongRoute", "alongRoute is not supported");
    d.rule = read_rule(e);
    d.value = e.number("value");
    by.condition = d;
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

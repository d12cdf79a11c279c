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

// ---- the tables: one entry per condition the orchestrator evaluates ------------------
// A condition of the standard not in a table is an error "not supported" (Element::one_of
// and finish), a misspelt one "unknown" with "did you mean". Entity references are checked
// where the storyboard is read (by member); what a condition means is in storyboard_runtime.cpp.
using ValueReader = decltype(Condition::kind) (*)(Element&);
using EntityReader = decltype(ByEntityCondition::condition) (*)(Element&);

const std::vector<std::pair<std::string, ValueReader>> kValueConditions = {
    {"SimulationTimeCondition",
     [](Element& e) -> decltype(Condition::kind) { return SimulationTimeCondition{read_rule(e), e.number("value")}; }},
    {"StoryboardElementStateCondition",
     [](Element& e) -> decltype(Condition::kind) {
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
       return s;
     }},
    {"ParameterCondition",
     [](Element& e) -> decltype(Condition::kind) {
       ParameterCondition p{e.text("parameterRef"), read_rule(e), e.text("value")};
       const auto type = e.scope().type(p.parameter);
       if (!type) e.fail_attribute("parameterRef", fmt::format("no parameter \"{}\" is declared", p.parameter));
       const std::string problem = check_parameter_value(*type, p.value);
       if (!problem.empty()) e.fail_attribute("value", fmt::format("{} ({} parameter {})", problem, *type, p.parameter));
       return p;
     }},
};

using EntityCondition = decltype(ByEntityCondition::condition);

void no_direction(Element& e) {
  if (e.has("direction")) e.fail_attribute("direction", "a direction is not supported");
}

void no_along_route(Element& e) {
  if (e.has("alongRoute") && e.boolean("alongRoute")) e.fail_attribute("alongRoute", "alongRoute is not supported");
}

EntityCondition read_time_to_collision(Element& e) {
  TimeToCollisionCondition c;
  no_along_route(e);
  c.freespace = e.boolean("freespace");
  c.coordinate_system = read_coordinate_system(e);
  c.distance_type = e.optional_choice<std::string>("relativeDistanceType", kDistanceTypes).value_or("euclidianDistance");
  c.rule = read_rule(e);
  c.value = e.number("value");
  Element holder = e.child("TimeToCollisionConditionTarget");
  Element target = holder.one_of({"EntityRef", "Position"});
  holder.finish();
  if (target.name() == "EntityRef") {
    c.entity = target.text("entityRef");
    target.finish();
  } else {
    c.position = read_position(target);
  }
  return c;
}

EntityCondition read_collision(Element& e) {
  CollisionCondition c;
  Element target = e.one_of({"EntityRef", "ByType"});
  if (target.name() == "EntityRef") {
    c.entity = target.text("entityRef");
  } else {
    c.object_type = target.choice<std::string>("type", {{"vehicle", "vehicle"},
                                                        {"pedestrian", "pedestrian"},
                                                        {"miscellaneous", "miscellaneous"}});
  }
  target.finish();
  return c;
}

const std::vector<std::pair<std::string, EntityReader>> kEntityConditions = {
    {"SpeedCondition",
     [](Element& e) -> EntityCondition {
       no_direction(e);
       return SpeedCondition{read_rule(e), e.number("value")};
     }},
    {"RelativeDistanceCondition",
     [](Element& e) -> EntityCondition {
       RelativeDistanceCondition r;
       r.entity = e.text("entityRef");
       r.distance_type = e.choice<std::string>("relativeDistanceType", kDistanceTypes);
       r.coordinate_system = read_coordinate_system(e);
       r.freespace = e.boolean("freespace");
       r.rule = read_rule(e);
       r.value = e.number("value");
       if (e.has("routingAlgorithm")) e.fail_attribute("routingAlgorithm", "routingAlgorithm is not supported");
       return r;
     }},
    {"TraveledDistanceCondition",
     [](Element& e) -> EntityCondition { return TraveledDistanceCondition{e.number("value")}; }},
    {"StandStillCondition", [](Element& e) -> EntityCondition { return StandStillCondition{e.number("duration")}; }},
    {"EndOfRoadCondition", [](Element& e) -> EntityCondition { return EndOfRoadCondition{e.number("duration")}; }},
    {"OffroadCondition", [](Element& e) -> EntityCondition { return OffroadCondition{e.number("duration")}; }},
    {"AccelerationCondition",
     [](Element& e) -> EntityCondition {
       no_direction(e);
       return AccelerationCondition{read_rule(e), e.number("value")};
     }},
    {"RelativeSpeedCondition",
     [](Element& e) -> EntityCondition {
       no_direction(e);
       return RelativeSpeedCondition{e.text("entityRef"), read_rule(e), e.number("value")};
     }},
    {"ReachPositionCondition",
     [](Element& e) -> EntityCondition {
       Element position = e.child("Position");
       return ReachPositionCondition{read_position(position), e.number("tolerance")};
     }},
    {"TimeHeadwayCondition",
     [](Element& e) -> EntityCondition {
       TimeHeadwayCondition h;
       h.entity = e.text("entityRef");
       h.freespace = e.boolean("freespace");
       h.coordinate_system = read_coordinate_system(e);
       no_along_route(e);
       if (e.has("relativeDistanceType") && e.text("relativeDistanceType") != "longitudinal")
         e.fail_attribute("relativeDistanceType", "only a longitudinal headway is supported");
       h.rule = read_rule(e);
       h.value = e.number("value");
       return h;
     }},
    {"DistanceCondition",
     [](Element& e) -> EntityCondition {
       DistanceCondition d;
       Element position = e.child("Position");
       d.position = read_position(position);
       d.freespace = e.boolean("freespace");
       d.coordinate_system = read_coordinate_system(e);
       d.distance_type =
           e.optional_choice<std::string>("relativeDistanceType", kDistanceTypes).value_or("euclidianDistance");
       no_along_route(e);
       d.rule = read_rule(e);
       d.value = e.number("value");
       return d;
     }},
    {"TimeToCollisionCondition", read_time_to_collision},
    {"CollisionCondition", read_collision},
};

template <class Reader>
auto read_from_table(Element& holder, const std::vector<std::pair<std::string, Reader>>& table) {
  std::vector<std::string> names;
  for (const auto& [name, read] : table) names.push_back(name);
  Element e = holder.one_of(names);  // a condition of the standard not listed: "not supported"
  holder.finish();
  for (const auto& [name, read] : table)
    if (name == e.name()) {
      auto result = read(e);
      e.finish();
      return result;
    }
  e.fail("unreachable: one_of returned an element outside the table");
}

Condition read_by_value(Element& holder, Condition c) {
  c.kind = read_from_table(holder, kValueConditions);
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
  by.condition = read_from_table(wrapper, kEntityConditions);
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

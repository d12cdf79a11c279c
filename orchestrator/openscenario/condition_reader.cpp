// Triggers: ConditionGroups of Conditions, by value or by entity.
#include <fmt/format.h>

#include "openscenario/date_time.hpp"
#include "openscenario/reader_context.hpp"

namespace orch::openscenario::reading {

double read_date_time(Element& e, const char* attribute) {
  const std::string text = e.text(attribute);
  const std::optional<double> value = parse_date_time(text);
  if (!value)
    e.fail_attribute(attribute, fmt::format("\"{}\" is no {}", text, kDateTimeForm));
  return *value;
}

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
  // routingAlgorithm (1.2, the four distance conditions): how the route between the two is
  // found when the distance is measured in road or lane coordinates. Read and checked; the
  // distance is measured as every road distance here (along the shared road, the difference
  // of s), which is the route's length whichever algorithm finds it while both are on one road.
  (void)e.optional_choice<std::string>("routingAlgorithm", {{"assignedRoute", "assignedRoute"},
                                                            {"fastest", "fastest"},
                                                            {"leastIntersections", "leastIntersections"},
                                                            {"shortest", "shortest"},
                                                            {"undefined", "undefined"}});
  return system;
}

// ---- the tables: one entry per condition the orchestrator evaluates ------------------
// A condition of the standard not in a table is an error "not supported" (Element::one_of
// and finish), a misspelt one "unknown" with "did you mean". Entity references are checked
// where the storyboard is read (by member); what a condition means is in storyboard_runtime.cpp.
using ValueReader = decltype(Condition::kind) (*)(Element&, const Context&);
using EntityReader = decltype(ByEntityCondition::condition) (*)(Element&);

const std::vector<std::pair<std::string, ValueReader>> kValueConditions = {
    {"SimulationTimeCondition",
     [](Element& e, const Context&) -> decltype(Condition::kind) {
       return SimulationTimeCondition{read_rule(e), e.number("value")};
     }},
    {"StoryboardElementStateCondition",
     [](Element& e, const Context&) -> decltype(Condition::kind) {
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
     [](Element& e, const Context&) -> decltype(Condition::kind) {
       const auto [key, type] = runtime_parameter(e, "parameterRef");
       ParameterCondition p{key, read_rule(e), e.text("value")};
       const std::string problem = check_parameter_value(type, p.value);
       if (!problem.empty()) e.fail_attribute("value", fmt::format("{} ({} parameter {})", problem, type, p.parameter));
       return p;
     }},
    {"VariableCondition",
     [](Element& e, const Context& context) -> decltype(Condition::kind) {
       const auto [name, type] = declared_variable(e, context);
       VariableCondition v{name, read_rule(e), e.text("value")};
       const std::string problem = check_parameter_value(type, v.value);
       if (!problem.empty()) e.fail_attribute("value", fmt::format("{} ({} variable {})", problem, type, name));
       return v;
     }},
    // UserDefinedValueCondition compares a value the simulation environment supplies from
    // outside the scenario (the standard: "the current value of an externally defined named
    // value"); the standard leaves its source to the tool, and the orchestrator has none:
    // the file needs a source it cannot have here, an error naming the value (never a
    // condition silently false). Parameters (--param) and variables are the scenario's own
    // named values a file can compare instead.
    {"UserDefinedValueCondition",
     [](Element& e, const Context&) -> decltype(Condition::kind) {
       const std::string name = e.text("name");
       (void)read_rule(e);
       (void)e.text("value");
       e.fail(fmt::format("UserDefinedValueCondition compares \"{}\", a value from outside the scenario that the "
                          "simulation environment supplies; the orchestrator has no source of such values. Compare "
                          "a parameter (ParameterCondition, set with --param {}=VALUE) or a variable "
                          "(VariableCondition) instead",
                          name, name));
     }},
    {"TimeOfDayCondition",
     [](Element& e, const Context&) -> decltype(Condition::kind) {
       return TimeOfDayCondition{read_rule(e), read_date_time(e, "dateTime")};
     }},
    {"TrafficSignalCondition",
     [](Element& e, const Context&) -> decltype(Condition::kind) { return read_traffic_signal_condition(e); }},
    {"TrafficSignalControllerCondition",
     [](Element& e, const Context& context) -> decltype(Condition::kind) {
       return read_traffic_signal_controller_condition(e, context);
     }},
};

using EntityCondition = decltype(ByEntityCondition::condition);

// direction (1.2): the speed and acceleration the runtime measures are along the entity's
// path, i.e. longitudinal; lateral and vertical components are not measured.
void no_direction(Element& e) {
  if (e.has("direction") && e.choice<std::string>("direction", {{"longitudinal", "longitudinal"},
                                                                  {"lateral", "lateral"},
                                                                  {"vertical", "vertical"}}) != "longitudinal")
    e.fail_attribute("direction", "only direction=\"longitudinal\" is supported");
}

// alongRoute (1.0; deprecated in 1.1 for coordinateSystem and relativeDistanceType): "true"
// measures the distance along the road, i.e. coordinateSystem="road" with a longitudinal
// distance; "false" the straight line, coordinateSystem="entity" (the default). It is the
// mapping esmini's own examples make where they were rewritten for 1.1 (cut-in_external.xosc:
// alongRoute="true" / "false", cut-in.xosc: coordinateSystem="road" longitudinal / "entity").
// When the file gives coordinateSystem (or relativeDistanceType) too, those win.
void read_along_route(Element& e, std::string& coordinate_system, std::string* distance_type) {
  if (!e.has("alongRoute") || !e.boolean("alongRoute")) return;
  if (!e.has("coordinateSystem")) coordinate_system = "road";
  if (distance_type && !e.has("relativeDistanceType")) *distance_type = "longitudinal";
}

EntityCondition read_time_to_collision(Element& e) {
  TimeToCollisionCondition c;
  c.freespace = e.boolean("freespace");
  c.coordinate_system = read_coordinate_system(e);
  c.distance_type = e.optional_choice<std::string>("relativeDistanceType", kDistanceTypes).value_or("euclidianDistance");
  read_along_route(e, c.coordinate_system, &c.distance_type);
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

// AngleCondition / RelativeAngleCondition (1.3). The angle is compared on the circle, so
// its range is not checked; the tolerance cannot be negative. coordinateSystem "world"
// (1.3) is the inertial frame. "entity" gives an AngleCondition no meaning (an entity's
// angle in its own frame is always 0) and "trajectory" is not run (as in the distance
// conditions): both are errors naming the attribute.
template <class AngleKind>
void read_angle(Element& e, AngleKind& c, const std::string& default_system) {
  c.angle_type = e.choice<std::string>("angleType", {{"heading", "heading"}, {"pitch", "pitch"}, {"roll", "roll"}});
  c.angle = e.number("angle");
  c.tolerance = e.number("angleTolerance");
  if (c.tolerance < 0) e.fail_attribute("angleTolerance", "an angle tolerance cannot be negative");
  c.coordinate_system = e.optional_choice<std::string>("coordinateSystem", {{"entity", "entity"},
                                                                             {"lane", "lane"},
                                                                             {"road", "road"},
                                                                             {"trajectory", "trajectory"},
                                                                             {"world", "world"}})
                            .value_or(default_system);
  if (c.coordinate_system == "trajectory") e.fail_attribute("coordinateSystem", "trajectory is not supported");
}

EntityCondition read_angle_condition(Element& e) {
  AngleCondition c;
  read_angle(e, c, "world");
  if (c.coordinate_system == "entity")
    e.fail_attribute("coordinateSystem",
                     "an AngleCondition cannot use entity (the entity's own frame: its angle is always 0); "
                     "use world, road or lane, or a RelativeAngleCondition");
  return c;
}

EntityCondition read_relative_angle_condition(Element& e) {
  RelativeAngleCondition c;
  c.entity = e.text("entityRef");
  read_angle(e, c, "entity");
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

EntityCondition read_relative_clearance(Element& e) {
  RelativeClearanceCondition c;
  c.opposite_lanes = e.boolean("oppositeLanes");
  c.freespace = e.boolean("freeSpace");
  c.distance_forward = e.optional_number("distanceForward").value_or(0.0);
  c.distance_backward = e.optional_number("distanceBackward").value_or(0.0);
  if (c.distance_forward < 0) e.fail_attribute("distanceForward", "cannot be negative");
  if (c.distance_backward < 0) e.fail_attribute("distanceBackward", "cannot be negative");
  for (Element range : e.children("RelativeLaneRange")) {
    RelativeLaneRange r;
    r.from = range.optional_integer("from").value_or(0);
    r.to = range.optional_integer("to").value_or(0);
    if (r.to < r.from) range.fail_attribute("to", "to must not be less than from");
    range.finish();
    c.lanes.push_back(r);
  }
  for (Element ref : e.children("EntityRef")) {
    c.entities.push_back(ref.text("entityRef"));
    ref.finish();
  }
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
       // Not given: "interpreted as euclideanDistance" (the standard, TimeHeadwayCondition).
       h.distance_type =
           e.optional_choice<std::string>("relativeDistanceType", kDistanceTypes).value_or("euclidianDistance");
       read_along_route(e, h.coordinate_system, &h.distance_type);
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
       read_along_route(e, d.coordinate_system, &d.distance_type);
       d.rule = read_rule(e);
       d.value = e.number("value");
       return d;
     }},
    {"TimeToCollisionCondition", read_time_to_collision},
    {"CollisionCondition", read_collision},
    {"RelativeClearanceCondition", read_relative_clearance},
    {"AngleCondition", read_angle_condition},
    {"RelativeAngleCondition", read_relative_angle_condition},
};

// `read(reader, element)` calls the table's reader (the value readers also take the context).
template <class Reader, class Call>
auto read_from_table(Element& holder, const std::vector<std::pair<std::string, Reader>>& table, const Call& read) {
  std::vector<std::string> names;
  for (const auto& [name, reader] : table) names.push_back(name);
  Element e = holder.one_of(names);  // a condition of the standard not listed: "not supported"
  holder.finish();
  for (const auto& [name, reader] : table)
    if (name == e.name()) {
      auto result = read(reader, e);
      e.finish();
      return result;
    }
  e.fail("unreachable: one_of returned an element outside the table");
}

Condition read_by_value(Element& holder, Condition c, const Context& context) {
  c.kind = read_from_table(holder, kValueConditions, [&](ValueReader r, Element& e) { return r(e, context); });
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
  by.condition = read_from_table(wrapper, kEntityConditions, [](EntityReader r, Element& e) { return r(e); });
  c.kind = by;
  return c;
}

Condition read_condition(Element& e, const Context& context) {
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
  return kind.name() == "ByValueCondition" ? read_by_value(kind, std::move(c), context)
                                            : read_by_entity(kind, std::move(c));
}

}  // namespace

Trigger read_trigger(Element& trigger, const Context& context) {
  Trigger t;
  for (Element group : trigger.children("ConditionGroup")) {
    std::vector<Condition> conditions;
    for (Element condition : group.children("Condition")) conditions.push_back(read_condition(condition, context));
    if (conditions.empty()) group.fail("a ConditionGroup needs at least one Condition");
    group.finish();
    t.groups.push_back(std::move(conditions));
  }
  trigger.finish();
  return t;
}

}  // namespace orch::openscenario::reading

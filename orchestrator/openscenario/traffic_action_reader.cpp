// GlobalAction/TrafficAction: TrafficSwarmAction, TrafficSourceAction, TrafficSinkAction,
// TrafficStopAction and 1.3's TrafficAreaAction, with the TrafficAction's trafficName (1.2);
// which vehicles, by the TrafficDefinition or 1.3's TrafficDistribution. What they do is in
// traffic_book.hpp (the storyboard) and run/openscenario_traffic.hpp (SUMO). Ranges are the
// standard's ([0..inf[ for radii, axes, rates and speeds); a TrafficStopAction must name a
// traffic the file defines (checked once the whole storyboard is read: check_traffic_stops).
#include <algorithm>

#include <fmt/format.h>

#include "core/suggest.hpp"
#include "openscenario/reader_context.hpp"

namespace orch::openscenario::reading {
namespace {

double non_negative(Element& e, const char* attribute) {
  const double v = e.number(attribute);
  if (v < 0) e.fail_attribute(attribute, fmt::format("{} cannot be negative (the standard's range is [0..inf[)", attribute));
  return v;
}

std::optional<double> optional_non_negative(Element& e, const char* attribute) {
  if (!e.has(attribute)) return e.optional_number(attribute);
  return non_negative(e, attribute);
}

// TrafficDefinition: the VehicleCategoryDistribution is used (which vehicles SUMO gets); the
// ControllerDistribution and VehicleRoleDistribution are read and left to SUMO's driver, which
// drives every traffic vehicle (the standard, 6.10: traffic actions "specify the
// initialization or termination of vehicles whose behavior is controlled by external traffic
// simulation models").
std::vector<TrafficCategoryShare> read_definition(Element& parent) {
  std::vector<TrafficCategoryShare> out;
  auto definition = parent.optional_child("TrafficDefinition");
  if (!definition) return out;
  definition->ignore_attributes({"name"});
  if (auto categories = definition->optional_child("VehicleCategoryDistribution")) {
    for (Element entry : categories->children("VehicleCategoryDistributionEntry")) {
      TrafficCategoryShare share{entry.text("category"), non_negative(entry, "weight"), {}, {}, {}};
      entry.finish();
      out.push_back(std::move(share));
    }
    categories->finish();
  }
  definition->ignore_children({"ControllerDistribution", "VehicleRoleDistribution"});
  definition->finish();
  return out;
}

// TrafficDistribution (1.3): entries (weight), each an EntityDistribution of vehicle templates
// (weight, ScenarioObjectTemplate: a Vehicle or a vehicle's CatalogReference). A template's
// share is its entry's weight / the entries' sum x its weight / its distribution's sum; the
// templates' ObjectControllers and the entries' Properties are read and left to SUMO's driver.
std::vector<TrafficCategoryShare> read_distribution(Element& distribution, Context& context) {
  std::vector<TrafficCategoryShare> out;
  std::vector<Element> entries = distribution.children("TrafficDistributionEntry");
  if (entries.empty()) distribution.fail("a TrafficDistribution needs at least one TrafficDistributionEntry");
  double entries_total = 0;
  std::vector<double> entry_weights;
  for (Element& entry : entries) entries_total += entry_weights.emplace_back(non_negative(entry, "weight"));
  if (entries_total <= 0) distribution.fail("the weights of all TrafficDistributionEntries are 0: no vehicle could be chosen");
  for (std::size_t i = 0; i < entries.size(); ++i) {
    Element& entry = entries[i];
    Element entities = entry.child("EntityDistribution");
    std::vector<Element> templates = entities.children("EntityDistributionEntry");
    if (templates.empty()) entities.fail("an EntityDistribution needs at least one EntityDistributionEntry");
    std::vector<TrafficCategoryShare> shares;
    double total = 0;
    for (Element& t : templates) {
      const double weight = non_negative(t, "weight");
      total += weight;
      Element object = t.child("ScenarioObjectTemplate");
      const std::vector<Entity> read = read_entity_template(object, context);
      const Entity& vehicle = read.front();
      if (vehicle.kind != EntityKind::Vehicle)
        t.fail("a traffic action's participants are vehicles SUMO's driver drives: this EntityDistributionEntry's "
               "template is not a Vehicle (a pedestrian or object cannot be traffic here)");
      shares.push_back({vehicle.category, weight, vehicle.box.length, vehicle.box.width, vehicle.box.height});
      t.finish();
    }
    if (total <= 0) entities.fail("the weights of all EntityDistributionEntries are 0: no vehicle could be chosen");
    entities.finish();
    for (TrafficCategoryShare& share : shares) {
      share.weight = entry_weights[i] / entries_total * share.weight / total;
      out.push_back(std::move(share));
    }
    entry.ignore_children({"Properties"});
    entry.finish();
  }
  distribution.finish();
  return out;
}

// Which vehicles: the TrafficDefinition (deprecated in 1.3) or the TrafficDistribution.
std::vector<TrafficCategoryShare> read_vehicles(Element& parent, Context& context) {
  auto distribution = parent.optional_child("TrafficDistribution");
  if (!distribution) return read_definition(parent);
  if (parent.optional_child("TrafficDefinition"))
    distribution->fail("a TrafficDefinition (deprecated) and a TrafficDistribution both say which vehicles; give one "
                       "(the TrafficDistribution)");
  return read_distribution(*distribution, context);
}

std::optional<std::pair<double, double>> read_speed_range(Element& parent) {
  auto range = parent.optional_child("InitialSpeedRange");
  if (!range) return std::nullopt;
  const double lower = non_negative(*range, "lowerLimit"), upper = non_negative(*range, "upperLimit");
  if (upper < lower) range->fail_attribute("upperLimit", fmt::format("upperLimit {} is below lowerLimit {}", upper, lower));
  range->finish();
  return std::pair{lower, upper};
}

TrafficSwarmAction read_swarm(Element& e, std::string name, Context& context) {
  TrafficSwarmAction a;
  a.name = std::move(name);
  a.inner_radius = non_negative(e, "innerRadius");
  a.semi_major = non_negative(e, "semiMajorAxis");
  a.semi_minor = non_negative(e, "semiMinorAxis");
  a.offset = e.optional_number("offset").value_or(0.0);
  a.vehicles = e.integer("numberOfVehicles");
  if (a.vehicles < 0) e.fail_attribute("numberOfVehicles", "numberOfVehicles cannot be negative (an unsignedInt)");
  a.speed = optional_non_negative(e, "velocity");
  Element central = e.child("CentralObject");
  a.entity = central.text("entityRef");
  central.finish();
  a.speed_range = read_speed_range(e);
  if (auto direction = e.optional_child("DirectionOfTravelDistribution")) {
    a.direction_weights = std::pair{non_negative(*direction, "same"), non_negative(*direction, "opposite")};
    if (a.direction_weights->first + a.direction_weights->second <= 0)
      direction->fail("the weights of both directions are 0: no vehicle could be placed");
    direction->finish();
  }
  a.categories = read_vehicles(e, context);
  return a;
}

TrafficSourceAction read_source(Element& e, std::string name, Context& context) {
  TrafficSourceAction a;
  a.name = std::move(name);
  a.radius = non_negative(e, "radius");
  a.rate = non_negative(e, "rate");
  a.speed = optional_non_negative(e, "velocity");
  if (e.has("speed")) {  // 1.3's name of the deprecated velocity
    if (a.speed) e.fail_attribute("speed", "speed (1.3) and velocity (its deprecated name) are both given; give speed");
    a.speed = non_negative(e, "speed");
  }
  Element position = e.child("Position");
  a.position = read_position(position);
  a.speed_range = read_speed_range(e);
  a.categories = read_vehicles(e, context);
  return a;
}

TrafficSinkAction read_sink(Element& e, std::string name) {
  TrafficSinkAction a;
  a.name = std::move(name);
  a.radius = non_negative(e, "radius");
  a.rate = optional_non_negative(e, "rate");
  Element position = e.child("Position");
  a.position = read_position(position);
  read_definition(e);  // which vehicles it removes: every traffic vehicle (docs/openscenario.md)
  return a;
}

// RoadCursor: a road, an s on it (optional), the lanes (Lane id; none: every lane).
TrafficAreaRoadCursor read_cursor(Element& e) {
  TrafficAreaRoadCursor c{e.text("roadId"), e.optional_number("s"), {}};
  if (c.s && *c.s < 0) e.fail_attribute("s", "s cannot be negative");
  for (Element lane : e.children("Lane")) {
    c.lanes.push_back(lane.integer("id"));
    lane.finish();
  }
  e.finish();
  return c;
}

TrafficAreaAction read_area(Element& e, std::string name, Context& context) {
  TrafficAreaAction a;
  a.name = std::move(name);
  a.entities = e.integer("numberOfEntities");
  if (a.entities < 0) e.fail_attribute("numberOfEntities", "numberOfEntities cannot be negative (an unsignedInt)");
  a.continuous = e.boolean("continuous");
  Element area = e.child("TrafficArea");
  auto polygon = area.optional_child("Polygon");
  std::vector<Element> ranges = area.children("RoadRange");
  if (polygon && !ranges.empty()) area.fail("a TrafficArea holds a Polygon or RoadRanges, not both");
  if (!polygon && ranges.empty()) {
    area.finish();  // an unknown child explains the missing area best
    area.fail("expected a Polygon or one or more RoadRanges");
  }
  if (polygon) {
    for (Element position : polygon->children("Position")) a.polygon.push_back(read_position(position));
    if (a.polygon.size() < 3)
      polygon->fail(fmt::format("a Polygon needs at least 3 Positions, it has {}", a.polygon.size()));
    polygon->finish();
  } else {
    for (Element& range : ranges) {
      TrafficAreaRoadRange r;
      r.length = range.optional_number("length");
      if (r.length && *r.length <= 0) range.fail_attribute("length", "a RoadRange's length must be above 0");
      for (Element cursor : range.children("RoadCursor")) r.cursors.push_back(read_cursor(cursor));
      if (r.cursors.size() < 2)
        range.fail(fmt::format("a RoadRange needs at least 2 RoadCursors (where it starts and ends), it has {}",
                               r.cursors.size()));
      range.finish();
      a.road_ranges.push_back(std::move(r));
    }
  }
  area.finish();
  Element distribution = e.child("TrafficDistribution");
  a.categories = read_distribution(distribution, context);
  return a;
}

}  // namespace

PrivateAction read_traffic_action(Element& traffic_action, Element& action, Context& context) {
  std::string name = traffic_action.optional_text("trafficName").value_or("");
  if (action.name() == "TrafficStopAction") {
    if (name.empty())
      traffic_action.fail("a TrafficStopAction needs the TrafficAction's trafficName: the traffic it stops");
    context.traffic_stops.emplace_back(name, traffic_action);
    return TrafficStopAction{std::move(name)};
  }
  if (!name.empty()) context.traffic_names.push_back(name);
  if (action.name() == "TrafficSwarmAction") return read_swarm(action, std::move(name), context);
  if (action.name() == "TrafficSourceAction") return read_source(action, std::move(name), context);
  if (action.name() == "TrafficAreaAction") return read_area(action, std::move(name), context);
  return read_sink(action, std::move(name));
}

void check_traffic_stops(const Context& context) {
  for (const auto& [name, element] : context.traffic_stops)
    if (std::find(context.traffic_names.begin(), context.traffic_names.end(), name) == context.traffic_names.end())
      element.fail_attribute("trafficName",
                             fmt::format("the TrafficStopAction stops traffic \"{}\", which no TrafficAction of the "
                                         "file starts{}", name, did_you_mean(name, context.traffic_names)));
}

}  // namespace orch::openscenario::reading

// GlobalAction/TrafficAction: TrafficSwarmAction, TrafficSourceAction, TrafficSinkAction and
// TrafficStopAction, with the TrafficAction's trafficName (1.2). What they do is in
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
      TrafficCategoryShare share{entry.text("category"), non_negative(entry, "weight")};
      entry.finish();
      out.push_back(std::move(share));
    }
    categories->finish();
  }
  definition->ignore_children({"ControllerDistribution", "VehicleRoleDistribution"});
  definition->finish();
  return out;
}

std::optional<std::pair<double, double>> read_speed_range(Element& parent) {
  auto range = parent.optional_child("InitialSpeedRange");
  if (!range) return std::nullopt;
  const double lower = non_negative(*range, "lowerLimit"), upper = non_negative(*range, "upperLimit");
  if (upper < lower) range->fail_attribute("upperLimit", fmt::format("upperLimit {} is below lowerLimit {}", upper, lower));
  range->finish();
  return std::pair{lower, upper};
}

TrafficSwarmAction read_swarm(Element& e, std::string name) {
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
  a.categories = read_definition(e);
  return a;
}

TrafficSourceAction read_source(Element& e, std::string name) {
  TrafficSourceAction a;
  a.name = std::move(name);
  a.radius = non_negative(e, "radius");
  a.rate = non_negative(e, "rate");
  a.speed = optional_non_negative(e, "velocity");
  Element position = e.child("Position");
  a.position = read_position(position);
  a.speed_range = read_speed_range(e);
  a.categories = read_definition(e);
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
  if (action.name() == "TrafficSwarmAction") return read_swarm(action, std::move(name));
  if (action.name() == "TrafficSourceAction") return read_source(action, std::move(name));
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

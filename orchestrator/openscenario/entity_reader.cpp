// Entities: ScenarioObject with a Vehicle, Pedestrian or MiscObject (inline or from a
// catalog) and its ObjectController; a vehicle's trailer coupling (1.3).
#include <fmt/format.h>

#include <cmath>
#include <utility>

#include "openscenario/reader_context.hpp"

namespace orch::openscenario::reading {
namespace {

// One ScenarioObject (or an inline Trailer): the entity `name`, then the trailers written
// inline in it.
std::vector<Entity> read_scenario_object(Element& scenario_object, Context& context, const std::string& name);

std::map<std::string, std::string> read_properties(Element& owner) {
  std::map<std::string, std::string> properties;
  if (auto list = owner.optional_child("Properties")) {
    for (Element p : list->children("Property")) {
      properties[p.text("name")] = p.text("value");
      p.finish();
    }
    list->ignore_children({"File"});
    list->finish();
  }
  return properties;
}

BoundingBox read_box(Element& owner) {
  Element box = owner.child("BoundingBox");
  Element center = box.child("Center");
  Element dimensions = box.child("Dimensions");
  box.finish();
  BoundingBox b{center.number("x"), center.number("y"), center.number("z"),
                dimensions.number("width"), dimensions.number("length"), dimensions.number("height")};
  center.finish();
  dimensions.finish();
  if (b.width <= 0 || b.length <= 0) dimensions.fail("a bounding box needs a positive width and length");
  // An object is at most a kilometre in size and its box within a kilometre of its reference
  // point: beyond, no road holds it (found by the soak, seed 3406330881: a box centre 1.4 km
  // ahead of the ego's reference point crashed libsumo).
  constexpr double kMaxObjectSize = 1000.0;
  for (const auto& [value, name] : {std::pair{b.width, "width"}, {b.length, "length"}, {b.height, "height"}})
    if (std::abs(value) > kMaxObjectSize)
      dimensions.fail_attribute(name, fmt::format("{} {} m: an object is at most {} m in size", name, value, kMaxObjectSize));
  for (const auto& [value, name] : {std::pair{b.center_x, "x"}, {b.center_y, "y"}, {b.center_z, "z"}})
    if (std::abs(value) > kMaxObjectSize)
      center.fail_attribute(name, fmt::format("{} {} m: a bounding box's centre is at most {} m from its reference point",
                                              name, value, kMaxObjectSize));
  return b;
}

Axle read_axle(Element& axle) {
  Axle a{axle.number("maxSteering"), axle.number("wheelDiameter"), axle.number("trackWidth"),
         axle.number("positionX"), axle.number("positionZ")};
  axle.finish();
  return a;
}

// Trailer (1.3): an entity named by TrailerRef, or one written inline (a ScenarioObject of
// its own, named "<tractor>+" as the peer player esmini names it; "" in a TrailerRef, the
// catalogs' default, is no trailer).
void read_trailer(Element& vehicle, Entity& entity, Context& context, std::vector<Entity>& inline_trailers) {
  auto holder = vehicle.optional_child("Trailer");
  if (!holder) return;
  Element trailer = holder->one_of({"TrailerRef", "Trailer", "EntityRef"});
  holder->finish();
  if (trailer.name() == "Trailer") {
    trailer.ignore_attributes({"name"});  // the ScenarioObject's own name; the entity is "<tractor>+"
    std::vector<Entity> towed = read_scenario_object(trailer, context, entity.name + "+");
    entity.trailer = towed.front().name;
    for (Entity& t : towed) inline_trailers.push_back(std::move(t));
  } else {
    entity.trailer = trailer.text("entityRef");
    trailer.finish();
  }
}

// `object` is read in its own parameter scope (catalog entries: resolve(); inline objects:
// open_scope()), which took its ParameterDeclarations.
void read_object(Element& object, Entity& entity, Context& context, std::vector<Entity>& inline_trailers) {
  entity.object_name = object.text("name");
  entity.properties = read_properties(object);
  entity.box = read_box(object);
  object.ignore_attributes({"model3d", "model", "role"});
  if (object.name() == "Vehicle") {
    entity.kind = EntityKind::Vehicle;
    entity.category = object.choice<std::string>(
        "vehicleCategory", {{"car", "car"}, {"van", "van"}, {"truck", "truck"}, {"trailer", "trailer"},
                            {"semitrailer", "semitrailer"}, {"bus", "bus"}, {"motorbike", "motorbike"},
                            {"bicycle", "bicycle"}, {"train", "train"}, {"tram", "tram"}});
    entity.mass = object.optional_number("mass").value_or(0.0);
    Element performance = object.child("Performance");
    entity.performance = Performance{performance.number("maxSpeed"), performance.number("maxAcceleration"),
                                     performance.number("maxDeceleration")};
    performance.ignore_attributes({"mass", "maxAccelerationRate", "maxDecelerationRate"});
    performance.finish();
    Element axles = object.child("Axles");
    if (auto front = axles.optional_child("FrontAxle")) entity.front_axle = read_axle(*front);  // optional since 1.1 (trailers)
    Element rear = axles.child("RearAxle");
    entity.rear_axle = read_axle(rear);
    axles.ignore_children({"AdditionalAxle"});
    axles.finish();
    if (auto hitch = object.optional_child("TrailerHitch")) {
      entity.trailer_hitch_dx = hitch->number("dx");
      hitch->finish();
    }
    if (auto coupler = object.optional_child("TrailerCoupler")) {
      entity.trailer_coupler_dx = coupler->number("dx");
      coupler->finish();
    }
    read_trailer(object, entity, context, inline_trailers);
  } else if (object.name() == "Pedestrian") {
    entity.kind = EntityKind::Pedestrian;
    entity.category = object.choice<std::string>(
        "pedestrianCategory", {{"pedestrian", "pedestrian"}, {"wheelchair", "wheelchair"}, {"animal", "animal"}});
    entity.mass = object.number("mass");
  } else {
    entity.kind = EntityKind::MiscObject;
    entity.category = object.text("miscObjectCategory");
    entity.mass = object.number("mass");
  }
  object.finish();
}

}  // namespace

Controller read_controller(Element& controller) {
  Controller c{controller.text("name"), read_properties(controller)};
  controller.ignore_children({"ParameterDeclarations"});
  controller.ignore_attributes({"controllerType"});
  controller.finish();
  return c;
}

namespace {
std::vector<Entity> read_scenario_object(Element& scenario_object, Context& context, const std::string& name) {
  static const std::vector<std::string> kObjects = {"Vehicle", "Pedestrian", "MiscObject"};
  std::vector<Entity> out(1);
  std::vector<Entity> inline_trailers;
  Entity& entity = out.front();
  entity.name = name;
  Element object = scenario_object.one_of({"CatalogReference", "Vehicle", "Pedestrian", "MiscObject"});
  if (object.name() == "CatalogReference") {
    Element entry = context.resolve(object, kObjects);
    read_object(entry, entity, context, inline_trailers);
  } else {
    Element scoped = open_scope(object, context, "");
    read_object(scoped, entity, context, inline_trailers);
  }
  // 1.3: an entity may have several ObjectControllers, each named; the first is the one an
  // ActivateControllerAction without objectControllerRef activates.
  std::vector<Element> controllers = scenario_object.children("ObjectController");
  for (Element& holder : controllers) {
    const std::string controller_name = holder.optional_text("name").value_or("");
    if (controllers.size() > 1 && controller_name.empty())
      holder.fail("an entity with several ObjectControllers must name each (its name attribute): "
                  "ActivateControllerAction's objectControllerRef chooses one by it");
    for (const auto& known : entity.object_controllers)
      if (known.first == controller_name)
        holder.fail_attribute("name", fmt::format("a second ObjectController named \"{}\" on entity {}",
                                                  controller_name, name));
    Element controller = holder.one_of({"CatalogReference", "Controller"});
    Controller c;
    if (controller.name() == "CatalogReference") {
      Element entry = context.resolve(controller, {"Controller"});
      c = read_controller(entry);
    } else {
      c = read_controller(controller);
    }
    holder.finish();
    if (!entity.controller) entity.controller = c;
    entity.object_controllers.emplace_back(controller_name, std::move(c));
  }
  scenario_object.finish();
  for (Entity& t : inline_trailers) out.push_back(std::move(t));
  return out;
}
}  // namespace

std::vector<Entity> read_entity(Element& scenario_object, Context& context) {
  const std::string name = scenario_object.text("name");
  return read_scenario_object(scenario_object, context, name);
}

std::vector<Entity> read_entity_template(Element& object_template, Context& context) {
  return read_scenario_object(object_template, context, "");
}

}  // namespace orch::openscenario::reading

// Entities: ScenarioObject with a Vehicle, Pedestrian or MiscObject (inline or from a
// catalog) and its ObjectController.
#include <fmt/format.h>

#include "openscenario/reader_context.hpp"

namespace orch::openscenario::reading {
namespace {

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
  return b;
}

Axle read_axle(Element& axle) {
  Axle a{axle.number("maxSteering"), axle.number("wheelDiameter"), axle.number("trackWidth"),
         axle.number("positionX"), axle.number("positionZ")};
  axle.finish();
  return a;
}

void read_object(Element& object, Entity& entity) {
  entity.object_name = object.text("name");
  entity.properties = read_properties(object);
  entity.box = read_box(object);
  object.ignore_children({"ParameterDeclarations"});
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
    Element front = axles.child("FrontAxle");
    Element rear = axles.child("RearAxle");
    entity.front_axle = read_axle(front);
    entity.rear_axle = read_axle(rear);
    axles.ignore_children({"AdditionalAxle"});
    axles.finish();
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

Entity read_entity(Element& scenario_object, Context& context) {
  static const std::vector<std::string> kObjects = {"Vehicle", "Pedestrian", "MiscObject"};
  Entity entity;
  entity.name = scenario_object.text("name");
  Element object = scenario_object.one_of({"CatalogReference", "Vehicle", "Pedestrian", "MiscObject"});
  if (object.name() == "CatalogReference") {
    Element entry = context.resolve(object, kObjects);
    read_object(entry, entity);
  } else {
    read_object(object, entity);
  }
  if (auto controller_holder = scenario_object.optional_child("ObjectController")) {
    Element controller = controller_holder->one_of({"CatalogReference", "Controller"});
    if (controller.name() == "CatalogReference") {
      Element entry = context.resolve(controller, {"Controller"});
      entity.controller = read_controller(entry);
    } else {
      entity.controller = read_controller(controller);
    }
    controller_holder->finish();
  }
  scenario_object.finish();
  return entity;
}

}  // namespace orch::openscenario::reading

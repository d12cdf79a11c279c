// OverrideControllerValueAction and UserDefinedAction / CustomCommandAction: read with every
// element and attribute checked, run with no effect on motion and a warning at load (what
// they would change is not modelled here). Both are kept as an AppearanceAction (model.hpp:
// an instant action with no effect on motion) naming the element. A file using them
// runs rather than being refused for an action whose meaning the standard leaves to a
// vehicle-dynamics controller or to another simulator.
#include <fmt/format.h>

#include "openscenario/reader_context.hpp"

namespace orch::openscenario::reading {
namespace {

// A pedal's input (1.2): BrakePercent or BrakeForce, each a value and an optional maxRate.
void read_brake_input(Element& e) {
  for (const char* kind : {"BrakePercent", "BrakeForce"})
    if (auto input = e.optional_child(kind)) {
      (void)input->number("value");
      (void)input->optional_number("maxRate");
      input->finish();
    }
}

// Whether the override is active.
bool read_override(Element& o) {
  const bool active = o.boolean("active");
  const std::string_view name = o.name();
  if (name == "OverrideThrottleAction" || name == "OverrideClutchAction") {
    (void)o.number("value");
    (void)o.optional_number("maxRate");  // 1.2
  } else if (name == "OverrideSteeringWheelAction") {
    (void)o.number("value");
    (void)o.optional_number("maxRate");    // 1.2
    (void)o.optional_number("maxTorque");  // 1.2
  } else if (name == "OverrideBrakeAction" || name == "OverrideParkingBrakeAction") {
    (void)o.optional_number("value");  // 1.0/1.1; deprecated in 1.2 for the BrakeInput
    read_brake_input(o);
  } else {  // OverrideGearAction
    (void)o.optional_number("number");  // 1.0/1.1; deprecated in 1.2 for the Gear
    if (auto manual = o.optional_child("ManualGear")) {
      (void)manual->integer("number");
      manual->finish();
    }
    if (auto automatic = o.optional_child("AutomaticGear")) {
      (void)automatic->choice<std::string>("gear", {{"n", "n"}, {"p", "p"}, {"r", "r"}, {"d", "d"}});
      automatic->finish();
    }
  }
  o.finish();
  return active;
}

}  // namespace

AppearanceAction read_controller_override(Element& e, Context& context) {
  // 1.0/1.1 give all six overrides, 1.2 any of them: each at most once, at least one.
  bool any = false;
  bool active = false;
  for (const char* name : {"OverrideThrottleAction", "OverrideBrakeAction", "OverrideClutchAction",
                           "OverrideParkingBrakeAction", "OverrideSteeringWheelAction", "OverrideGearAction"})
    if (auto o = e.optional_child(name)) {
      active = read_override(*o) || active;
      any = true;
    }
  if (!any) e.fail("an OverrideControllerValueAction needs at least one Override...Action (throttle, brake, ...)");
  // Overrides all inactive (CARLA's 1.0 files write six of them next to each assignment)
  // ask for nothing: no warning.
  if (active)
    context.warnings.warning(e.source().where(e.node()),
                           "OverrideControllerValueAction runs with no effect on motion: its pedal, steering wheel and "
                           "gear values are inputs of a vehicle-dynamics controller, and the orchestrator moves entities "
                           "kinematically (the storyboard's actions decide their motion); its transitions are recorded");
  return AppearanceAction{"OverrideControllerValueAction"};
}

AppearanceAction read_user_defined_action(Element& e, Context& context) {
  Element command = e.child("CustomCommandAction");
  e.finish();
  const std::string type = command.text("type");
  command.finish();
  context.warnings.warning(command.source().where(command.node(), "type"),
                           fmt::format("CustomCommandAction type=\"{}\" runs with no effect: the standard leaves a "
                                       "custom command's meaning to the simulator it is written for, and the "
                                       "orchestrator defines none; its transitions are recorded",
                                       type));
  return AppearanceAction{"CustomCommandAction"};
}

}  // namespace orch::openscenario::reading

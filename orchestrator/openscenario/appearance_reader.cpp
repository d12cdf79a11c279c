// AppearanceAction / LightStateAction and EnvironmentAction: every element and attribute is
// checked as the schema has it, and the actions run as instant ones with no effect on any
// entity's motion (SUMO runs render no lights and no weather; model.hpp).
#include <fmt/format.h>

#include "openscenario/reader_context.hpp"

namespace orch::openscenario::reading {
namespace {

std::vector<std::pair<std::string, std::string>> words(const std::vector<std::string>& list) {
  std::vector<std::pair<std::string, std::string>> out;
  for (const std::string& w : list) out.emplace_back(w, w);
  return out;
}

void read_color(Element& color) {
  (void)color.choice<std::string>("colorType", words({"other", "red", "yellow", "green", "blue", "violet", "orange",
                                                      "brown", "black", "grey", "white"}));
  if (auto rgb = color.optional_child("ColorRgb")) {
    for (const char* c : {"red", "green", "blue"}) (void)rgb->number(c);
    rgb->finish();
  }
  if (auto cmyk = color.optional_child("ColorCmyk")) {
    for (const char* c : {"cyan", "magenta", "yellow", "key"}) (void)cmyk->number(c);
    cmyk->finish();
  }
  color.finish();
}

void read_numbers(Element& e, const std::vector<const char*>& names) {
  for (const char* n : names) (void)e.optional_number(n);
}

std::optional<TimeOfDaySetting> read_environment(Element& environment) {
  (void)environment.text("name");
  environment.ignore_children({"ParameterDeclarations"});
  std::optional<TimeOfDaySetting> time_of_day;
  if (auto time = environment.optional_child("TimeOfDay")) {
    TimeOfDaySetting setting;
    setting.animation = time->boolean("animation");
    setting.date_time = read_date_time(*time, "dateTime");
    time->finish();
    time_of_day = setting;
  }
  if (auto weather = environment.optional_child("Weather")) {
    read_numbers(*weather, {"atmosphericPressure", "temperature"});
    (void)weather->optional_choice<std::string>(
        "fractionalCloudCover", words({"zeroOktas", "oneOktas", "twoOktas", "threeOktas", "fourOktas", "fiveOktas",
                                       "sixOktas", "sevenOktas", "eightOktas", "nineOktas"}));
    (void)weather->optional_choice<std::string>("cloudState",
                                                words({"skyOff", "free", "cloudy", "overcast", "rainy"}));
    if (auto sun = weather->optional_child("Sun")) {
      read_numbers(*sun, {"azimuth", "elevation", "illuminance", "intensity"});
      sun->finish();
    }
    if (auto fog = weather->optional_child("Fog")) {
      (void)fog->number("visualRange");
      fog->ignore_children({"BoundingBox"});
      fog->finish();
    }
    if (auto rain = weather->optional_child("Precipitation")) {
      (void)rain->choice<std::string>("precipitationType", words({"dry", "rain", "snow"}));
      read_numbers(*rain, {"precipitationIntensity", "intensity"});
      rain->finish();
    }
    if (auto wind = weather->optional_child("Wind")) {
      (void)wind->number("direction");
      (void)wind->number("speed");
      wind->finish();
    }
    weather->ignore_children({"DomeImage"});
    weather->finish();
  }
  if (auto road = environment.optional_child("RoadCondition")) {
    (void)road->number("frictionScaleFactor");
    (void)road->optional_choice<std::string>(
        "wetness", words({"dry", "moist", "wetWithPuddles", "lowFlooded", "highFlooded"}));
    road->ignore_children({"Properties"});
    road->finish();
  }
  environment.finish();
  return time_of_day;
}

}  // namespace

AppearanceAction read_light_state(Element& e) {
  (void)e.optional_number("transitionTime");
  Element type_holder = e.child("LightType");
  Element type = type_holder.one_of({"VehicleLight", "UserDefinedLight"});
  type_holder.finish();
  if (type.name() == "VehicleLight")
    (void)type.choice<std::string>(
        "vehicleLightType",
        words({"daytimeRunningLights", "lowBeam", "highBeam", "fogLights", "fogLightsFront", "fogLightsRear",
               "brakeLights", "warningLights", "indicatorLeft", "indicatorRight", "reversingLights",
               "licensePlateIllumination", "specialPurposeLights"}));
  else
    (void)type.text("userDefinedLightType");
  type.finish();
  Element state = e.child("LightState");
  (void)state.choice<std::string>("mode", words({"on", "off", "flashing"}));
  read_numbers(state, {"luminousIntensity", "flashingOnDuration", "flashingOffDuration"});
  if (auto color = state.optional_child("Color")) read_color(*color);
  state.finish();
  return AppearanceAction{"LightStateAction"};
}

// AnimationAction (1.2): a component's, a pedestrian's, a file's or a user-defined animation.
// Purely visual: read and checked, run with no effect on motion (no renderer), warned once.
AppearanceAction read_animation(Element& e, Context& context) {
  (void)e.optional_boolean("loop");
  const auto duration = e.optional_number("animationDuration");
  if (duration && *duration < 0) e.fail_attribute("animationDuration", "a duration cannot be negative");
  Element holder = e.child("AnimationType");
  Element type = holder.one_of({"ComponentAnimation", "PedestrianAnimation", "AnimationFile", "UserDefinedAnimation"});
  holder.finish();
  if (type.name() == "ComponentAnimation") {
    Element component = type.one_of({"VehicleComponent", "UserDefinedComponent"});
    (void)component.text(component.name() == "VehicleComponent" ? "vehicleComponentType" : "userDefinedComponentType");
    component.finish();
  } else if (type.name() == "PedestrianAnimation") {
    (void)type.optional_text("motion");
    (void)type.optional_text("userDefinedPedestrianMotion");
    for (Element gesture : type.children("PedestrianGesture")) {
      (void)gesture.text("gesture");
      gesture.finish();
    }
  } else if (type.name() == "AnimationFile") {
    Element file = type.child("File");
    (void)file.text("filepath");
    file.finish();
    (void)type.optional_number("timeOffset");
  } else {
    (void)type.text("userDefinedAnimationType");
  }
  type.finish();
  if (auto state = e.optional_child("AnimationState")) {
    (void)state->number("state");
    state->finish();
  }
  context.warnings.warning(e.source().where(e.node()),
                           "AnimationAction runs with no effect: an animation is visual, and SUMO runs render none; "
                           "its transitions are recorded");
  return AppearanceAction{"AnimationAction"};
}

EnvironmentAction read_environment_action(Element& e, Context& context) {
  Element source = e.one_of({"Environment", "CatalogReference"});
  if (source.name() == "CatalogReference") {
    Element entry = context.resolve(source, {"Environment"});
    const std::string name = entry.text("name");
    return EnvironmentAction{name, read_environment(entry)};
  }
  const std::string name = source.text("name");
  return EnvironmentAction{name, read_environment(source)};
}

}  // namespace orch::openscenario::reading

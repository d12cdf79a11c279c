// The ego of an OpenSCENARIO file (run/openscenario_ego_choice.hpp): one test per rule, in
// rank order, the ambiguity at a rank, and no ego at all.
#include <gtest/gtest.h>

#include "core/errors.hpp"
#include "run/openscenario_ego_choice.hpp"

namespace orch {
namespace {

openscenario::Entity entity(const std::string& name, const std::string& controller = "",
                            std::map<std::string, std::string> controller_properties = {}) {
  openscenario::Entity e;
  e.name = name;
  if (!controller.empty()) e.controller = openscenario::Controller{controller, std::move(controller_properties)};
  return e;
}

openscenario::Scenario scenario_of(std::vector<openscenario::Entity> entities) {
  openscenario::Scenario s;
  s.file = "s.xosc";
  s.entities = std::move(entities);
  return s;
}

std::string error_of(const openscenario::Scenario& s, const std::string& requested = "") {
  try {
    (void)choose_ego(s, requested);
  } catch (const ScenarioError& e) {
    return e.what();
  }
  return "";
}

TEST(OpenScenarioEgoChoice, EgoOptionWinsOverEveryOtherRule) {
  const auto s = scenario_of({entity("Ego"), entity("Subject", "ALKSController"), entity("Lead")});
  const EgoChoice c = choose_ego(s, "Lead");
  EXPECT_EQ(c.entity, "Lead");
  EXPECT_EQ(c.rule, "--ego Lead");
  EXPECT_NE(error_of(s, "Laed").find("did you mean \"Lead\""), std::string::npos);
  EXPECT_NE(error_of(s, "Laed").find("; the entities are Ego, Subject, Lead"), std::string::npos) << error_of(s, "Laed");
  EXPECT_TRUE(c.system_under_test);  // asked for: driven
}

TEST(OpenScenarioEgoChoice, SystemUnderTestControllersBeforeProperties) {
  for (const std::string name : {"ALKSController", "R157ReferenceDriver", "SystemUnderTest", "systemundertest", "SUT",
                                 "ExternalController"}) {
    auto carla = entity("Hero");
    carla.properties["type"] = "ego_vehicle";
    const auto s = scenario_of({carla, entity("Car", name), entity("Other", "DefaultDriver")});
    const EgoChoice c = choose_ego(s, "");
    EXPECT_EQ(c.entity, "Car") << name;
    EXPECT_EQ(c.rule, "its controller is named " + name);
    EXPECT_TRUE(c.system_under_test) << name;
    EXPECT_EQ(c.controller_note, "controller " + name + " is a system under test");
  }
}

TEST(OpenScenarioEgoChoice, EsminiExternalControllerProperty) {
  const auto s = scenario_of({entity("Ego"), entity("Car", "MyStack", {{"esminiController", "ExternalController"}}),
                              entity("Ghost", "G", {{"esminiController", "FollowGhostController"}})});
  const EgoChoice c = choose_ego(s, "");
  EXPECT_EQ(c.entity, "Car");
  EXPECT_NE(c.rule.find("esminiController=ExternalController"), std::string::npos) << c.rule;
}

TEST(OpenScenarioEgoChoice, CarlaEgoVehiclePropertyBeforeNames) {
  auto marked = entity("Vehicle1");
  marked.properties["type"] = "ego_vehicle";
  auto simulation = entity("Vehicle2");
  simulation.properties["type"] = "simulation";
  const auto s = scenario_of({entity("Ego"), simulation, marked});
  const EgoChoice c = choose_ego(s, "");
  EXPECT_EQ(c.entity, "Vehicle1");
  EXPECT_EQ(c.rule, "it has the Property type=ego_vehicle");
  EXPECT_FALSE(c.system_under_test);  // the ego of metrics and report, not driven
}

TEST(OpenScenarioEgoChoice, EgoNamesAnyCase) {
  for (const std::string name : {"Ego", "ego", "EGO", "hero", "ego_vehicle"}) {
    const EgoChoice c = choose_ego(scenario_of({entity("Lead"), entity(name), entity("Egon")}), "");
    EXPECT_EQ(c.entity, name);
    EXPECT_EQ(c.rule, "its name is " + name);
    EXPECT_FALSE(c.system_under_test);
    EXPECT_EQ(c.controller_note, "no controller");
  }
}

TEST(OpenScenarioEgoChoice, TwoCandidatesAtOneRankAskForTheEgoOption) {
  const std::string controllers =
      error_of(scenario_of({entity("A", "ALKSController"), entity("B", "SystemUnderTest"), entity("Ego")}));
  EXPECT_NE(controllers.find("2 entities could be the ego: A (its controller is named ALKSController), B (its "
                             "controller is named SystemUnderTest); name one with --ego NAME"),
            std::string::npos)
      << controllers;
  EXPECT_NE(controllers.find("s.xosc"), std::string::npos) << controllers;
  EXPECT_NE(error_of(scenario_of({entity("ego"), entity("hero")})).find("--ego NAME"), std::string::npos);
  // A candidate at a higher rank settles it, however many there are below.
  EXPECT_EQ(choose_ego(scenario_of({entity("ego"), entity("hero"), entity("X", "SUT")}), "").entity, "X");
}

TEST(OpenScenarioEgoChoice, NoCandidateNoEgo) {
  const EgoChoice c = choose_ego(scenario_of({entity("Lead", "DefaultDriver"), entity("Follower")}), "");
  EXPECT_EQ(c.entity, "");
  EXPECT_NE(c.rule.find("no --ego"), std::string::npos);
}

// The standard's meaning of a controller: an entity named Ego without a system-under-test
// controller follows the storyboard, unless the user asks for it to be driven.
TEST(OpenScenarioEgoDriving, OnlyASystemUnderTestControllerOrTheUserMakesTheEgoDriven) {
  const EgoRequests none{};
  const EgoChoice named = choose_ego(scenario_of({entity("Lead"), entity("Ego")}), "");
  EXPECT_EQ(named.entity, "Ego");
  EgoDriving d = ego_driving(named, none);
  EXPECT_FALSE(d.driven);
  EXPECT_EQ(d.why, "no controller");

  const EgoChoice other = choose_ego(scenario_of({entity("Lead"), entity("Ego", "DefaultDriver")}), "");
  d = ego_driving(other, none);
  EXPECT_FALSE(d.driven);
  EXPECT_EQ(d.why, "controller DefaultDriver is not a system under test");

  const EgoChoice sut = choose_ego(scenario_of({entity("Lead"), entity("Ego", "ALKSController")}), "");
  d = ego_driving(sut, none);
  EXPECT_TRUE(d.driven);
  EXPECT_EQ(d.why, "controller ALKSController is a system under test");

  const EgoChoice esmini =
      choose_ego(scenario_of({entity("Car", "MyStack", {{"esminiController", "ExternalController"}})}), "");
  EXPECT_EQ(ego_driving(esmini, none).why, "controller MyStack (esminiController=ExternalController) is a system under test");

  // The user asks: --ego, --ego-model, the reference run, --ego-port.
  d = ego_driving(choose_ego(scenario_of({entity("Lead"), entity("Ego")}), "Lead"), none);
  EXPECT_TRUE(d.driven);
  EXPECT_EQ(d.why, "--ego Lead");
  EXPECT_EQ(ego_driving(named, {"sumo", false, false}).why, "--ego-model sumo");
  EXPECT_TRUE(ego_driving(named, {"sumo", false, false}).driven);
  EXPECT_TRUE(ego_driving(named, {"", true, false}).driven);
  EXPECT_TRUE(ego_driving(named, {"", false, true}).driven);

  // No ego: nothing to drive.
  EXPECT_FALSE(ego_driving(choose_ego(scenario_of({entity("Lead")}), ""), {"r157", true, false}).driven);
}

// --controllers off (esmini's --disable_controllers): even a system-under-test controller or
// --ego NAME leaves the ego to the storyboard; it stays the ego of metrics and the report.
TEST(OpenScenarioEgoDriving, ControllersOffLeaveEveryEgoToTheStoryboard) {
  const EgoRequests off{"", false, false, true};
  const EgoChoice sut = choose_ego(scenario_of({entity("Lead"), entity("Ego", "ALKSController")}), "");
  EXPECT_TRUE(sut.system_under_test);
  EgoDriving d = ego_driving(sut, off);
  EXPECT_FALSE(d.driven);
  EXPECT_EQ(d.why, "--controllers off; controller ALKSController is a system under test");
  d = ego_driving(choose_ego(scenario_of({entity("Lead"), entity("Ego")}), "Lead"), off);
  EXPECT_FALSE(d.driven);
  EXPECT_EQ(d.why, "--controllers off; no controller");
}

}  // namespace
}  // namespace orch

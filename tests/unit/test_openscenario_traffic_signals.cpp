// Traffic signals: a controller's phases cycling (delay, reference, a jump by
// TrafficSignalControllerAction), TrafficSignalStateAction and the two conditions through the
// reader and the storyboard runtime, the SUMO colours of the states, the traffic lights'
// links read from a net, and the commands that set them.
#include <gtest/gtest.h>

#include <string>

#include "core/errors.hpp"
#include "opendrive/sumo_signals.hpp"
#include "opendrive/xodr_reader.hpp"
#include "openscenario/storyboard_runtime.hpp"
#include "openscenario/traffic_signals.hpp"
#include "openscenario/xosc_reader.hpp"
#include "run/openscenario_signals.hpp"
#include "support/cli_runner.hpp"
#include "unit/openscenario_snippets.hpp"

namespace orch::openscenario {
namespace {

using test::kStraightTwoLaneRoad;
using test::place;
using test::run_until;
using test::transition_times;
using test::vehicle;

TrafficSignalController controller(const std::string& name, double delay, const std::string& reference) {
  TrafficSignalController c{name, delay, reference, {}};
  c.phases.push_back({"go", 10, {{"1", "off;off;on"}}, std::nullopt, {}});
  c.phases.push_back({"wait", 3, {{"1", "off;on;off"}}, std::nullopt, {}});
  c.phases.push_back({"stop", 7, {{"1", "on;off;off"}, {"2", "off;on"}}, std::nullopt, {}});
  return c;
}

TEST(TrafficSignals, AControllerCyclesThroughItsPhasesFromItsDelay) {
  const std::vector<TrafficSignalController> controllers{controller("C", 2, "")};
  TrafficSignals signals(controllers);
  signals.advance(0);
  EXPECT_EQ(signals.phase("C"), "stop");  // the cycle virtually started at 2: t = 0 is 18 s into it
  EXPECT_EQ(signals.state("1"), "on;off;off");
  signals.advance(2);
  EXPECT_EQ(signals.phase("C"), "go");
  EXPECT_EQ(signals.state("1"), "off;off;on");
  EXPECT_EQ(signals.state("2"), "off;on");  // a phase that does not name a signal leaves it as it is
  signals.advance(11.95);
  EXPECT_EQ(signals.phase("C"), "go");
  signals.advance(12);
  EXPECT_EQ(signals.phase("C"), "wait");
  signals.advance(22);  // one cycle of 20 s later
  EXPECT_EQ(signals.phase("C"), "go");
}

TEST(TrafficSignals, AReferencedControllerShiftsTheStartAndAStateActionHoldsUntilThePhaseChanges) {
  const std::vector<TrafficSignalController> controllers{controller("A", 1, ""), controller("B", 4, "A")};
  TrafficSignals signals(controllers);
  signals.advance(4.9);
  EXPECT_EQ(signals.phase("A"), "go");
  EXPECT_EQ(signals.phase("B"), "stop");  // starts at 1 + 4
  signals.advance(5);
  EXPECT_EQ(signals.phase("B"), "go");
  signals.set_state("1", "on;off;off");
  signals.advance(6);
  EXPECT_EQ(signals.state("1"), "on;off;off");  // no phase started since
  signals.set_phase("A", "stop", 6);
  EXPECT_EQ(signals.phase("A"), "stop");
  signals.advance(12.9);
  EXPECT_EQ(signals.phase("A"), "stop");
  signals.advance(13);  // 7 s of "stop" from 6
  EXPECT_EQ(signals.phase("A"), "go");
  EXPECT_EQ(normalized_signal_state(" On; OFF ;off"), "on;off;off");
}

// TrafficSignalGroupState (1.2): a phase's one state for every signal of the controller's
// signal group (the OpenDRIVE controller of the TrafficSignalController's name); the phase's
// own TrafficSignalStates override it for their signals.
TEST(TrafficSignals, AGroupStateSetsEverySignalOfTheControllersSignalGroup) {
  TrafficSignalController c{"J1", 0, "", {}};
  c.phases.push_back({"go", 5, {}, "off;off;on", {}});
  c.phases.push_back({"stop", 5, {{"12", "off;on;off"}}, "on;off;off", {}});
  const std::vector<TrafficSignalController> controllers{c};
  const std::vector<opendrive::SignalController> groups{{"J0", "", {"99"}}, {"J1", "north", {"11", "12", "13"}}};
  TrafficSignals signals(controllers, groups);
  signals.advance(0);
  EXPECT_EQ(signals.state("11"), "off;off;on");
  EXPECT_EQ(signals.state("13"), "off;off;on");
  EXPECT_FALSE(signals.state("99"));  // another group's signal
  signals.advance(5);
  EXPECT_EQ(signals.state("11"), "on;off;off");
  EXPECT_EQ(signals.state("12"), "off;on;off");  // the signal's own state wins over the group's
  // The group found by the OpenDRIVE controller's name when no id matches.
  TrafficSignalController by_name = c;
  by_name.name = "north";
  const std::vector<TrafficSignalController> named{by_name};
  TrafficSignals named_signals(named, groups);
  named_signals.advance(0);
  EXPECT_EQ(named_signals.state("12"), "off;off;on");
  // No such group: an error naming the phase, its place and the groups there are.
  TrafficSignalController lost = c;
  lost.name = "J9";
  lost.phases[0].group_place = {"/OpenSCENARIO/RoadNetwork/TrafficSignals/TrafficSignalController/Phase/TrafficSignalGroupState", 7};
  const std::vector<TrafficSignalController> lost_controllers{lost};
  try {
    TrafficSignals bad(lost_controllers, groups);
    ADD_FAILURE() << "no error";
  } catch (const MapError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("phase \"go\" of TrafficSignalController \"J9\""), std::string::npos) << what;
    EXPECT_NE(what.find("line 7"), std::string::npos) << what;
    EXPECT_NE(what.find("(it has: J0, J1)"), std::string::npos) << what;
  }
}

// The OpenDRIVE reader keeps the signal groups (<controller>, its <control signalId>), and a
// scenario's phases read the group state; the storyboard sets the group's signals by it.
TEST(TrafficSignals, TheRoadsSignalGroupsReachTheStoryboardsGroupStates) {
  test::TempDir dir;
  std::string road = kStraightTwoLaneRoad;
  road.replace(road.rfind("</OpenDRIVE>"), std::string("</OpenDRIVE>").size(),
               R"(<controller id="5" name="main"><control signalId="41" type="0"/><control signalId="42"/></controller></OpenDRIVE>)");
  dir.write("road.xodr", road);
  const std::string text = R"(<?xml version="1.0"?><OpenSCENARIO>
<FileHeader revMajor="1" revMinor="3" date="2024-01-01T00:00:00" author="t" description="groups"/>
<RoadNetwork><LogicFile filepath="road.xodr"/><TrafficSignals>
 <TrafficSignalController name="5">
  <Phase name="go" duration="4"><TrafficSignalGroupState state="off;off;on"/></Phase>
  <Phase name="stop" duration="6"><TrafficSignalState trafficSignalId="42" state="off;on;off"/><TrafficSignalGroupState state="on;off;off"/></Phase>
 </TrafficSignalController></TrafficSignals></RoadNetwork>
<Entities>)" + vehicle("A") + R"(</Entities>
<Storyboard><Init><Actions>)" + place("A", 10, -1, 10) + R"(</Actions></Init><StopTrigger/></Storyboard></OpenSCENARIO>)";
  const Scenario scenario = load_scenario(dir.write("s.xosc", text).string());
  ASSERT_EQ(scenario.signal_controllers.size(), 1u);
  EXPECT_EQ(scenario.signal_controllers[0].phases[1].group_state, "on;off;off");
  const opendrive::RoadNetwork roads = opendrive::read_xodr_file((dir / "road.xodr").string());
  ASSERT_EQ(roads.signal_controllers().size(), 1u);
  EXPECT_EQ(roads.signal_controllers()[0].signals, (std::vector<std::string>{"41", "42"}));
  StoryboardRuntime runtime(scenario, roads);
  EXPECT_EQ(runtime.signal_states().at("41"), "off;off;on");
  EXPECT_EQ(runtime.signal_states().at("42"), "off;off;on");
  run_until(runtime, 4);
  EXPECT_EQ(runtime.signal_states().at("41"), "on;off;off");
  EXPECT_EQ(runtime.signal_states().at("42"), "off;on;off");
  // A road without that group: the run cannot start, the error says why.
  const opendrive::RoadNetwork plain = opendrive::read_xodr_text(kStraightTwoLaneRoad, "plain.xodr");
  try {
    StoryboardRuntime bad(scenario, plain);
    ADD_FAILURE() << "no error";
  } catch (const MapError& e) {
    EXPECT_NE(std::string(e.what()).find("the road network defines none"), std::string::npos) << e.what();
  }
}

class SignalStoryboard : public ::testing::Test {
 protected:
  void load(const std::string& events, const std::string& init_signals = "") {
    const std::string text = R"(<?xml version="1.0"?><OpenSCENARIO>
<FileHeader revMajor="1" revMinor="3" date="2024-01-01T00:00:00" author="t" description="signals"/>
<RoadNetwork><LogicFile filepath="road.xodr"/><TrafficSignals>
 <TrafficSignalController name="Main" delay="0">
  <Phase name="green" duration="4"><TrafficSignalState trafficSignalId="1" state="off;off;on"/></Phase>
  <Phase name="yellow" duration="2"><TrafficSignalState trafficSignalId="1" state="off;on;off"/></Phase>
  <Phase name="red" duration="6"><TrafficSignalState trafficSignalId="1" state="on;off;off"/></Phase>
 </TrafficSignalController></TrafficSignals></RoadNetwork>
<Entities>)" + vehicle("A") + R"(</Entities>
<Storyboard><Init><Actions>)" + init_signals + place("A", 10, -1, 10) + R"(</Actions></Init>
<Story name="S"><Act name="Act"><ManeuverGroup name="G" maximumExecutionCount="1">
<Actors selectTriggeringEntities="false"><EntityRef entityRef="A"/></Actors><Maneuver name="M">)" + events +
                             R"(</Maneuver></ManeuverGroup><StartTrigger><ConditionGroup><Condition name="Go" delay="0" conditionEdge="none">
<ByValueCondition><SimulationTimeCondition value="0" rule="greaterOrEqual"/></ByValueCondition></Condition></ConditionGroup></StartTrigger></Act></Story>
<StopTrigger/></Storyboard></OpenSCENARIO>)";
    dir_.write("road.xodr", kStraightTwoLaneRoad);
    scenario_ = load_scenario(dir_.write("s.xosc", text).string());
    roads_ = opendrive::read_xodr_file((dir_ / "road.xodr").string());
    runtime_ = std::make_unique<StoryboardRuntime>(scenario_, roads_);
  }
  std::string error_of(const std::string& events) {
    try {
      load(events);
    } catch (const ScenarioError& e) {
      return e.what();
    }
    return "";
  }
  test::TempDir dir_;
  Scenario scenario_;
  opendrive::RoadNetwork roads_;
  std::unique_ptr<StoryboardRuntime> runtime_;
};

const std::string kStop = R"(<Action name="Brake"><PrivateAction><LongitudinalAction><SpeedAction>
  <SpeedActionDynamics dynamicsShape="step" dynamicsDimension="time" value="0"/>
  <SpeedActionTarget><AbsoluteTargetSpeed value="0"/></SpeedActionTarget></SpeedAction></LongitudinalAction></PrivateAction></Action>)";

TEST_F(SignalStoryboard, AControllerConditionWaitsForThePhase) {
  load(R"(<Event name="OnRed" priority="parallel">)" + kStop + R"(<StartTrigger><ConditionGroup>
    <Condition name="Red" delay="0" conditionEdge="none"><ByValueCondition>
    <TrafficSignalControllerCondition trafficSignalControllerRef="Main" phase="red"/></ByValueCondition></Condition>
    </ConditionGroup></StartTrigger></Event>)");
  ASSERT_EQ(scenario_.signal_controllers.size(), 1u);
  EXPECT_EQ(runtime_->signal_phase("Main"), "green");
  EXPECT_EQ(runtime_->signal_states().at("1"), "off;off;on");
  run_until(*runtime_, 7);
  const auto braked = transition_times(*runtime_, "Brake", "startTransition");
  ASSERT_EQ(braked.size(), 1u);
  EXPECT_NEAR(braked[0], 6.0, 1e-9);  // green 4 s, yellow 2 s
  EXPECT_EQ(runtime_->signal_states().at("1"), "on;off;off");
}

TEST_F(SignalStoryboard, AStateActionSetsWhatASignalConditionReads) {
  const std::string set_yellow = R"(<Event name="Switch" priority="parallel"><Action name="ToYellow"><GlobalAction><InfrastructureAction>
    <TrafficSignalAction><TrafficSignalStateAction name="7" state="off;on;off"/></TrafficSignalAction></InfrastructureAction></GlobalAction></Action>
    <StartTrigger><ConditionGroup><Condition name="T1" delay="0" conditionEdge="none"><ByValueCondition>
    <SimulationTimeCondition value="1" rule="greaterOrEqual"/></ByValueCondition></Condition></ConditionGroup></StartTrigger></Event>)";
  const std::string on_yellow = R"(<Event name="OnYellow" priority="parallel">)" + kStop + R"(<StartTrigger><ConditionGroup>
    <Condition name="Yellow" delay="0.5" conditionEdge="none"><ByValueCondition>
    <TrafficSignalCondition name="7" state="Off; On; Off"/></ByValueCondition></Condition></ConditionGroup></StartTrigger></Event>)";
  const std::string init = R"(<GlobalAction><InfrastructureAction><TrafficSignalAction>
    <TrafficSignalStateAction name="7" state="off;off;on"/></TrafficSignalAction></InfrastructureAction></GlobalAction>)";
  load(set_yellow + on_yellow, init);
  EXPECT_EQ(runtime_->signal_states().at("7"), "off;off;on");
  run_until(*runtime_, 2);
  EXPECT_EQ(runtime_->signal_states().at("7"), "off;on;off");
  const auto braked = transition_times(*runtime_, "Brake", "startTransition");
  ASSERT_EQ(braked.size(), 1u);
  EXPECT_NEAR(braked[0], 1.5, 1e-9);  // the state from t = 1, the condition's delay 0.5 s
}

TEST_F(SignalStoryboard, AControllerActionJumpsToAPhase) {
  load(R"(<Event name="Jump" priority="parallel"><Action name="ToRed"><GlobalAction><InfrastructureAction><TrafficSignalAction>
    <TrafficSignalControllerAction trafficSignalControllerRef="Main" phase="red"/></TrafficSignalAction></InfrastructureAction></GlobalAction></Action>
    <StartTrigger><ConditionGroup><Condition name="T1" delay="0" conditionEdge="none"><ByValueCondition>
    <SimulationTimeCondition value="1" rule="greaterOrEqual"/></ByValueCondition></Condition></ConditionGroup></StartTrigger></Event>)");
  run_until(*runtime_, 1);
  EXPECT_EQ(runtime_->signal_phase("Main"), "red");
  EXPECT_EQ(runtime_->signal_states().at("1"), "on;off;off");
  run_until(*runtime_, 6.95);
  EXPECT_EQ(runtime_->signal_phase("Main"), "red");
  run_until(*runtime_, 7);  // 6 s of red from t = 1, then the cycle goes on
  EXPECT_EQ(runtime_->signal_phase("Main"), "green");
}

TEST_F(SignalStoryboard, AnUndeclaredControllerOrPhaseIsAnErrorWithASuggestion) {
  const std::string phase = error_of(R"(<Event name="E" priority="parallel">)" + kStop + R"(<StartTrigger><ConditionGroup>
    <Condition name="C" delay="0" conditionEdge="none"><ByValueCondition>
    <TrafficSignalControllerCondition trafficSignalControllerRef="Main" phase="redd"/></ByValueCondition></Condition>
    </ConditionGroup></StartTrigger></Event>)");
  EXPECT_NE(phase.find("s.xosc:"), std::string::npos) << phase;
  EXPECT_NE(phase.find("has no phase \"redd\""), std::string::npos) << phase;
  EXPECT_NE(phase.find("did you mean \"red\""), std::string::npos) << phase;
  const std::string controller = error_of(R"(<Event name="E" priority="parallel"><Action name="J"><GlobalAction><InfrastructureAction><TrafficSignalAction>
    <TrafficSignalControllerAction trafficSignalControllerRef="Mian" phase="red"/></TrafficSignalAction></InfrastructureAction></GlobalAction></Action>
    <StartTrigger><ConditionGroup><Condition name="T" delay="0" conditionEdge="none"><ByValueCondition>
    <SimulationTimeCondition value="1" rule="greaterOrEqual"/></ByValueCondition></Condition></ConditionGroup></StartTrigger></Event>)");
  EXPECT_NE(controller.find("no TrafficSignalController \"Mian\""), std::string::npos) << controller;
  EXPECT_NE(controller.find("did you mean \"Main\""), std::string::npos) << controller;
}

}  // namespace
}  // namespace orch::openscenario

namespace orch {
namespace {

TEST(SumoSignalColour, LampsAndWordsGiveSumoColours) {
  EXPECT_EQ(sumo_signal_colour("on;off;off")->colour, 'r');
  EXPECT_TRUE(sumo_signal_colour("on;off;off")->vehicle);
  EXPECT_EQ(sumo_signal_colour("on;on;off")->colour, 'u');
  EXPECT_EQ(sumo_signal_colour("off;on;off")->colour, 'y');
  EXPECT_EQ(sumo_signal_colour("off;off;on")->colour, 'G');
  EXPECT_EQ(sumo_signal_colour("off;off;off")->colour, 'O');
  EXPECT_EQ(sumo_signal_colour("off;flashing;off")->colour, 'o');
  EXPECT_EQ(sumo_signal_colour("on;off")->colour, 'r');
  EXPECT_FALSE(sumo_signal_colour("on;off")->vehicle);
  EXPECT_EQ(sumo_signal_colour("off;on")->colour, 'G');
  EXPECT_EQ(sumo_signal_colour("Green")->colour, 'G');
  EXPECT_EQ(sumo_signal_colour("amber")->colour, 'y');
  EXPECT_FALSE(sumo_signal_colour("on"));
  EXPECT_FALSE(sumo_signal_colour("blue;off;off"));
  EXPECT_FALSE(sumo_signal_colour("on;off;off;off"));
}

TEST(SumoSignalLinks, TheNetsLinkSignalIdsNameTheLinksOfEachSignal) {
  test::TempDir dir;
  const auto net = dir.write("n.net.xml", R"(<net>
<tlLogic id="4" type="static" programID="0" offset="0">
  <phase duration="42" state="rrrrGGGgrrrrGGGg"/>
  <param key="linkSignalID:10" value="1 2 3"/><param key="linkSignalID:8" value="1"/><param key="other" value="9"/>
</tlLogic></net>)");
  const opendrive::SumoSignalLinks links = opendrive::read_sumo_signal_links(net.string());
  EXPECT_EQ(links.link_counts.at("4"), 16);
  ASSERT_EQ(links.by_signal.at("1").size(), 2u);
  EXPECT_EQ(links.by_signal.at("3").at(0).link, 10);
  EXPECT_EQ(links.by_signal.at("3").at(0).order, 2);
  EXPECT_EQ(links.by_signal.count("9"), 0u);
}

TEST(OpenScenarioSignals, ALinkTakesItsVehicleSignalsColourAndLightsAreSentWhenTheyChange) {
  opendrive::SumoSignalLinks links;
  links.link_counts = {{"J", 4}};
  links.by_signal["1"] = {{"J", 1, 0}, {"J", 2, 0}};  // vehicle signal
  links.by_signal["2"] = {{"J", 2, 1}, {"J", 3, 0}};  // pedestrian signal, sharing link 2
  OpenScenarioSignals signals(links);
  auto out = signals.update({{"1", "off;off;on"}, {"2", "on;off"}, {"99", "on;off;off"}});
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(std::get<sim::SetTrafficLight>(out[0]).tls_id, "J");
  EXPECT_EQ(std::get<sim::SetTrafficLight>(out[0]).links, "-GGr");  // link 2: the vehicle signal's green
  EXPECT_EQ(signals.take_unlinked(), std::vector<std::string>{"99"});
  EXPECT_TRUE(signals.take_unlinked().empty());
  EXPECT_TRUE(signals.update({{"1", "off;off;on"}, {"2", "on;off"}}).empty());  // nothing changed
  out = signals.update({{"1", "on;off;off"}, {"2", "off;on"}});
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(std::get<sim::SetTrafficLight>(out[0]).links, "-rrG");
}

}  // namespace
}  // namespace orch

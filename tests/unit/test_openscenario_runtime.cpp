// The storyboard runtime's semantics on small scenarios (no simulator): edges, delays,
// priorities, execution counts, stop triggers and the motion of speed and lateral actions.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/errors.hpp"
#include "opendrive/xodr_reader.hpp"
#include "openscenario/storyboard_runtime.hpp"
#include "openscenario/xosc_reader.hpp"
#include "support/cli_runner.hpp"
#include "unit/openscenario_snippets.hpp"

namespace orch::openscenario {
namespace {

using test::kStraightTwoLaneRoad;
using test::place;
using test::vehicle;

std::string time_condition(const std::string& name, double at, const std::string& edge = "rising", double delay = 0) {
  return R"(<Condition name=")" + name + R"(" delay=")" + std::to_string(delay) + R"(" conditionEdge=")" + edge +
         R"("><ByValueCondition><SimulationTimeCondition value=")" + std::to_string(at) +
         R"(" rule="greaterOrEqual"/></ByValueCondition></Condition>)";
}

std::string speed_action(const std::string& name, double target, const std::string& shape, const std::string& dim,
                         double value) {
  return R"(<Action name=")" + name + R"("><PrivateAction><LongitudinalAction><SpeedAction><SpeedActionDynamics dynamicsShape=")" +
         shape + R"(" dynamicsDimension=")" + dim + R"(" value=")" + std::to_string(value) +
         R"("/><SpeedActionTarget><AbsoluteTargetSpeed value=")" + std::to_string(target) +
         R"("/></SpeedActionTarget></SpeedAction></LongitudinalAction></PrivateAction></Action>)";
}

std::string event(const std::string& name, const std::string& priority, const std::string& action,
                  const std::string& condition, int max_count = 1) {
  return R"(<Event name=")" + name + R"(" priority=")" + priority + R"(" maximumExecutionCount=")" +
         std::to_string(max_count) + R"(">)" + action + "<StartTrigger><ConditionGroup>" + condition +
         "</ConditionGroup></StartTrigger></Event>";
}

// A scenario with vehicles A (lane -1, s 10, 10 m/s) and B (lane -2, s 50, 10 m/s), one story
// whose maneuver (actor A) holds `events`, and a stop trigger at `stop` s.
class Runtime : public ::testing::Test {
 protected:
  // `act_trigger`: the Act's StartTrigger element (default: true from 0 s on).
  void load(const std::string& events, double stop = 100.0, int group_count = 1,
            const std::string& act_trigger = "<StartTrigger><ConditionGroup>" + time_condition("ActStart", 0, "none") +
                                             "</ConditionGroup></StartTrigger>") {
    const std::string text = R"(<?xml version="1.0"?><OpenSCENARIO>
<FileHeader revMajor="1" revMinor="2" date="2024-01-01T00:00:00" author="t" description="runtime"/>
<RoadNetwork><LogicFile filepath="road.xodr"/></RoadNetwork>
<Entities>)" + vehicle("A") + vehicle("B") + R"(</Entities>
<Storyboard><Init><Actions>)" + place("A", 10, -1, 10) + place("B", 50, -2, 10) + R"(</Actions></Init>
<Story name="S"><Act name="Act"><ManeuverGroup name="G" maximumExecutionCount=")" + std::to_string(group_count) + R"(">
<Actors selectTriggeringEntities="false"><EntityRef entityRef="A"/></Actors><Maneuver name="M">)" + events +
                             R"(</Maneuver></ManeuverGroup>)" + act_trigger + R"(</Act></Story>
<StopTrigger><ConditionGroup>)" + time_condition("Stop", stop) + R"(</ConditionGroup></StopTrigger></Storyboard></OpenSCENARIO>)";
    dir_.write("road.xodr", kStraightTwoLaneRoad);
    scenario_ = load_scenario(dir_.write("s.xosc", text).string());
    roads_ = opendrive::read_xodr_file((dir_ / "road.xodr").string());
    runtime_ = std::make_unique<StoryboardRuntime>(scenario_, roads_);
  }
  void run_until(double t) { test::run_until(*runtime_, t); }
  [[nodiscard]] std::vector<double> times(const std::string& name, const std::string& transition) const {
    return test::transition_times(*runtime_, name, transition);
  }
  const EntityState& a() const { return runtime_->entities().at("A"); }

  orch::test::TempDir dir_;
  Scenario scenario_;
  opendrive::RoadNetwork roads_;
  std::unique_ptr<StoryboardRuntime> runtime_;
};

TEST_F(Runtime, InitPlacesEntitiesOnTheirLanes) {
  load(event("E", "overwrite", speed_action("Go", 20, "step", "time", 0), time_condition("T", 1)));
  EXPECT_NEAR(a().pose.x, 10.0, 1e-12);
  EXPECT_NEAR(a().pose.y, -1.75, 1e-12);
  EXPECT_NEAR(runtime_->entities().at("B").pose.y, -5.25, 1e-12);
  run_until(0.5);
  EXPECT_NEAR(a().pose.x, 15.0, 1e-9);  // 10 m/s for 0.5 s
}

// A simulator-driven entity (the ego on SUMO): its observed pose sets road, lane, offset
// and speed, and the storyboard's motion goes on from there.
TEST_F(Runtime, ObservedStateReplacesTheStoryboardsOwn) {
  load(event("E", "overwrite", speed_action("Go", 20, "step", "time", 0), time_condition("T", 100)));
  runtime_->step(0.05);
  runtime_->observe("B", {100.0, -5.0, 0.0}, 5.0, -1.0);  // lane -2 (centre -5.25), 0.25 m left
  const EntityState& b = runtime_->entities().at("B");
  EXPECT_EQ(b.lane, -2);
  EXPECT_NEAR(b.s, 100.0, 1e-6);
  EXPECT_NEAR(b.offset, 0.25, 1e-6);
  EXPECT_DOUBLE_EQ(b.speed, 5.0);
  runtime_->observe("B", {120.0, -1.75, 0.0}, 5.0, 0.0);  // moved into lane -1
  EXPECT_EQ(b.lane, -1);
  EXPECT_NEAR(b.offset, 0.0, 1e-6);
  runtime_->step(0.05);  // from the observed place, not from where the storyboard had it
  EXPECT_GT(b.s, 120.0);
  EXPECT_LT(b.s, 120.0 + 10.0 * 0.05 + 1e-6);
}

TEST_F(Runtime, RisingEdgeAndDelay) {
  load(event("E", "overwrite", speed_action("Go", 20, "step", "time", 0), time_condition("T", 1.0, "rising", 0.5)));
  run_until(3);
  EXPECT_EQ(times("E", "startTransition"), std::vector<double>{1.5});
  EXPECT_NEAR(a().speed, 20.0, 1e-12);
}

TEST_F(Runtime, RisingEdgeNeedsAFalseBefore) {
  // True from the first evaluation on: a rising edge never happens.
  load(event("E", "overwrite", speed_action("Go", 20, "step", "time", 0), time_condition("T", 0.0, "rising")));
  run_until(2);
  EXPECT_TRUE(times("E", "startTransition").empty());
  EXPECT_EQ(runtime_->state("event", "E"), ElementState::Standby);
}

TEST_F(Runtime, LinearSpeedByRateAndSinusoidalByTime) {
  load(event("E", "overwrite", speed_action("Go", 20, "linear", "rate", 2.0), time_condition("T", 1.0)));
  run_until(3.5);  // 2.5 s into a 5 s ramp from 10 to 20 m/s
  EXPECT_NEAR(a().speed, 15.0, 1e-9);
  run_until(7.0);
  EXPECT_NEAR(a().speed, 20.0, 1e-12);
  EXPECT_EQ(times("Go", "endTransition"), std::vector<double>{6.0});
}

TEST_F(Runtime, OverwriteStopsTheRunningEventSkipWaits) {
  load(event("Slow", "overwrite", speed_action("SlowDown", 0, "linear", "time", 10), time_condition("T1", 1.0)) +
       event("Fast", "overwrite", speed_action("SpeedUp", 30, "linear", "time", 1), time_condition("T2", 2.0)) +
       event("Skipped", "skip", speed_action("Never", 5, "step", "time", 0), time_condition("T3", 2.5)));
  // 9 to 30 m/s "linear in 1 s" takes 2.1 s at the car's maxAcceleration of 10 m/s^2.
  run_until(4.1);
  EXPECT_EQ(times("SlowDown", "stopTransition"), std::vector<double>{2.0});
  EXPECT_EQ(times("Slow", "stopTransition"), std::vector<double>{2.0});
  EXPECT_EQ(times("Skipped", "skipTransition"), std::vector<double>{2.5});  // Fast was running
  EXPECT_TRUE(times("Never", "startTransition").empty());
  EXPECT_NEAR(a().speed, 30.0, 1e-12);
}

TEST_F(Runtime, MaximumExecutionCountRepeatsAnEvent) {
  load(event("E", "parallel", speed_action("Go", 12, "linear", "time", 1.0), time_condition("T", 1.0, "none"), 3));
  run_until(10);
  EXPECT_EQ(times("E", "startTransition").size(), 3u);
  EXPECT_EQ(runtime_->state("event", "E"), ElementState::Complete);
  EXPECT_EQ(runtime_->state("maneuver", "M"), ElementState::Complete);
  EXPECT_EQ(runtime_->state("act", "Act"), ElementState::Complete);
}

TEST_F(Runtime, StoryboardStopTriggerEndsTheRun) {
  load(event("E", "overwrite", speed_action("Go", 20, "step", "time", 0), time_condition("T", 1)), 2.0);
  run_until(10);
  EXPECT_TRUE(runtime_->finished());
  EXPECT_NEAR(runtime_->time(), 2.0, 1e-9);
}

TEST_F(Runtime, SinusoidalLaneChangeByRate) {
  const std::string change = R"(<Action name="Change"><PrivateAction><LateralAction><LaneChangeAction>
    <LaneChangeActionDynamics dynamicsShape="sinusoidal" dynamicsDimension="rate" value="1.0"/>
    <LaneChangeTarget><RelativeTargetLane entityRef="A" value="-1"/></LaneChangeTarget>
    </LaneChangeAction></LateralAction></PrivateAction></Action>)";
  load(event("E", "overwrite", change, time_condition("T", 1.0)));
  // 3.5 m to the right with a peak lateral speed of 1 m/s: T = 3.5 pi / 2.
  const double duration = 3.5 * std::numbers::pi / 2;
  run_until(1.0 + duration / 2 + 0.025);
  const double tau = runtime_->time() - 1.0;
  const double expected = -1.75 - 3.5 * 0.5 * (1 - std::cos(std::numbers::pi * tau / duration));
  EXPECT_NEAR(a().pose.y, expected, 1e-9);
  EXPECT_LT(a().pose.heading, 2 * std::numbers::pi);
  EXPECT_GT(a().pose.heading, 2 * std::numbers::pi - 0.2);  // turning right
  run_until(10);
  EXPECT_EQ(a().lane, -2);
  EXPECT_NEAR(a().pose.y, -5.25, 1e-12);
  ASSERT_EQ(times("Change", "endTransition").size(), 1u);
  EXPECT_NEAR(times("Change", "endTransition")[0], 1.0 + std::ceil(duration / 0.05 - 1e-9) * 0.05, 1e-9);
}

TEST_F(Runtime, RelativeDistanceFreespaceTriggers) {
  // B is 40 m ahead (s 50 vs 10) on the next lane: the gap between the boxes along the road
  // is 40 - 1 - 4 = 35 m. From t = 1 A runs 10 m/s faster, so the gap is 30 m at 1.5 s and
  // 29.5 m at 1.55 s, the first step below 29.99 m.
  const std::string near = R"(<Condition name="Near" delay="0" conditionEdge="rising"><ByEntityCondition>
    <TriggeringEntities triggeringEntitiesRule="any"><EntityRef entityRef="A"/></TriggeringEntities>
    <EntityCondition><RelativeDistanceCondition entityRef="B" relativeDistanceType="longitudinal" coordinateSystem="road"
      freespace="true" rule="lessThan" value="29.99"/></EntityCondition></ByEntityCondition></Condition>)";
  load(event("Accelerate", "parallel", speed_action("Faster", 20, "step", "time", 0), time_condition("T", 1.0)) +
       event("Brake", "parallel", speed_action("Stop", 0, "step", "time", 0), near));
  run_until(3);
  EXPECT_EQ(times("Brake", "startTransition"), std::vector<double>{1.55});
  EXPECT_NEAR(a().speed, 0.0, 1e-12);
}

std::string state_condition(const std::string& type, const std::string& ref, const std::string& state) {
  return R"(<Condition name="After" delay="0" conditionEdge="none"><ByValueCondition><StoryboardElementStateCondition
    storyboardElementType=")" + type + R"(" storyboardElementRef=")" + ref + R"(" state=")" + state +
         R"("/></ByValueCondition></Condition>)";
}

// Two actions named Go in different events (the standard allows it): each is its own element,
// and a reference qualified by its event's name ("Second::Go") follows that one only.
TEST_F(Runtime, OneNameInTwoEventsIsTwoElements) {
  load(event("First", "parallel", speed_action("Go", 12, "linear", "time", 1.0), time_condition("T1", 1.0)) +
       event("Second", "parallel", speed_action("Go", 14, "linear", "time", 2.0), time_condition("T2", 2.0)) +
       event("Then", "parallel", speed_action("Last", 20, "step", "time", 0),
             state_condition("action", "Second::Go", "endTransition")));
  run_until(6);
  EXPECT_EQ(times("Go", "startTransition"), (std::vector<double>{1.0, 2.0}));
  EXPECT_EQ(times("Go", "endTransition"), (std::vector<double>{2.0, 4.0}));
  EXPECT_EQ(times("Then", "startTransition"), std::vector<double>{4.0});  // not at 2.0, the first Go's end
  EXPECT_NEAR(a().speed, 20.0, 1e-12);
}

TEST_F(Runtime, AnAmbiguousReferenceIsAnErrorNamingBoth) {
  try {
    load(event("First", "parallel", speed_action("Go", 12, "step", "time", 0), time_condition("T1", 1.0)) +
         event("Second", "parallel", speed_action("Go", 14, "step", "time", 0), time_condition("T2", 2.0)) +
         event("Then", "parallel", speed_action("Last", 20, "step", "time", 0),
               state_condition("action", "Go", "endTransition")));
    FAIL() << "an ambiguous reference was accepted";
  } catch (const ScenarioError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("\"Go\" names more than one action: \"S::Act::G::M::First::Go\" (line "), std::string::npos)
        << what;
    EXPECT_NE(what.find("and \"S::Act::G::M::Second::Go\" (line "), std::string::npos) << what;
  }
}

// An empty trigger is kept by the standard for 1.0's sake only (an Act had to have one): an
// empty StartTrigger starts the Act as an absent one does, with its Story (as esmini does).
TEST_F(Runtime, AnEmptyActStartTriggerStartsTheActAtOnce) {
  load(event("E", "overwrite", speed_action("Go", 20, "step", "time", 0), time_condition("T", 1.0)), 100.0, 1,
       "<StartTrigger/>");
  run_until(2);
  EXPECT_EQ(times("Act", "startTransition"), std::vector<double>{0.0});
  EXPECT_EQ(times("E", "startTransition"), std::vector<double>{1.0});
  EXPECT_NEAR(a().speed, 20.0, 1e-12);
}

std::string entity_condition(const std::string& name, const std::string& inner) {
  return R"(<Condition name=")" + name + R"(" delay="0" conditionEdge="rising"><ByEntityCondition>
    <TriggeringEntities triggeringEntitiesRule="any"><EntityRef entityRef="A"/></TriggeringEntities>
    <EntityCondition>)" + inner + "</EntityCondition></ByEntityCondition></Condition>";
}

TEST_F(Runtime, EntityConditionsOnMotion) {
  // A: s 10 at 10 m/s; B: s 50 at 10 m/s. Each event marks when its condition first held.
  // The marking actions do not move anything.
  const auto mark = [](const std::string& name, const std::string& inner) {
    const std::string action = R"(<Action name=")" + name + R"(Action"><PrivateAction><ControllerAction>
      <ActivateControllerAction lateral="false" longitudinal="false"/></ControllerAction></PrivateAction></Action>)";
    return event(name, "parallel", action, entity_condition(name + "C", inner));
  };
  const auto first = [&](const std::string& name) {
    const auto all = times(name, "startTransition");
    return all.empty() ? -1.0 : all.front();
  };
  load(mark("Traveled", R"(<TraveledDistanceCondition value="25"/>)") +
       mark("Reached", R"(<ReachPositionCondition tolerance="0.5"><Position><LanePosition roadId="0" laneId="-1" s="40" offset="0"/></Position></ReachPositionCondition>)") +
       mark("Headway", R"(<TimeHeadwayCondition entityRef="B" value="3.0" freespace="false" coordinateSystem="road" rule="lessThan"/>)") +
       mark("Near", R"(<DistanceCondition value="20" freespace="false" rule="lessThan"><Position><WorldPosition x="100" y="-1.75"/></Position></DistanceCondition>)") +
       event("Brake", "parallel", speed_action("BrakeAction", 0, "linear", "time", 2.0), time_condition("T", 10.0)) +
       mark("Decelerating", R"(<AccelerationCondition value="-4" rule="lessThan"/>)") +
       mark("Slower", R"(<RelativeSpeedCondition entityRef="B" value="-8.9" rule="lessThan"/>)") +
       mark("Stopped", R"(<StandStillCondition duration="1.0"/>)"));
  run_until(15);
  EXPECT_NEAR(first("Traveled"), 2.5, 1e-9);   // 25 m at 10 m/s
  EXPECT_NEAR(first("Reached"), 3.0, 1e-9);    // s 40 at t 3.0 (s 39.5 at 2.95 is on the rim, not within)
  // Headway in s: (50 + 10 t - 10 - 10 t) / 10 = 4 s never drops below 3 s.
  EXPECT_TRUE(times("Headway", "startTransition").empty());
  EXPECT_NEAR(first("Near"), 7.05, 1e-9);           // x 80.5: 19.5 m from x 100
  EXPECT_NEAR(first("Decelerating"), 10.05, 1e-9);  // -5 m/s^2
  // A at 10 - 5 (t - 10) m/s, B at 10: below -8.9 m/s once t > 11.78.
  EXPECT_NEAR(first("Slower"), 11.8, 1e-9);
  EXPECT_NEAR(first("Stopped"), 13.0, 1e-9);  // still from 12.0
}

TEST_F(Runtime, HeadwayFallsWhenTheLeaderSlows) {
  const std::string headway = entity_condition(
      "H", R"(<TimeHeadwayCondition entityRef="B" value="3.0" freespace="false" coordinateSystem="road" rule="lessThan"/>)");
  load(event("Faster", "parallel", speed_action("Up", 20, "step", "time", 0), time_condition("T", 1.0)) +
       event("Close", "parallel", speed_action("Mark", 20, "step", "time", 0), headway));
  run_until(5);
  // From t = 1: gap 40 - 10 (t - 1) m at 20 m/s; below 3 s (60 m) at once.
  ASSERT_EQ(times("Close", "startTransition").size(), 1u);
  EXPECT_NEAR(times("Close", "startTransition")[0], 1.0, 1e-9);
}


// A marking event: starts (and its action ends at once, moving nothing) when `condition` holds.
std::string mark_event(const std::string& name, const std::string& condition) {
  const std::string action = R"(<Action name=")" + name + R"(Action"><PrivateAction><ControllerAction>
    <ActivateControllerAction lateral="false" longitudinal="false"/></ControllerAction></PrivateAction></Action>)";
  return event(name, "parallel", action, condition);
}

// A headway condition of `triggering` towards `reference`, evaluated on every step (no edge).
std::string headway_condition(const std::string& name, const std::string& triggering, const std::string& reference,
                              const std::string& attributes) {
  return R"(<Condition name=")" + name + R"(" delay="0" conditionEdge="none"><ByEntityCondition>
    <TriggeringEntities triggeringEntitiesRule="any"><EntityRef entityRef=")" + triggering + R"("/></TriggeringEntities>
    <EntityCondition><TimeHeadwayCondition entityRef=")" + reference + R"(" )" + attributes +
         "/></EntityCondition></ByEntityCondition></Condition>";
}

// The standard (1.3, TimeHeadwayCondition): "The reference entity is assumed to be
// leading/ahead" and the headway is "the time it takes the triggering entity to reach the
// current position of the reference entity": towards an entity behind there is none, so no
// rule holds (a headway measured as an unsigned distance made B's 40 m to A behind it a 4 s
// headway, and cut-ins of esmini's examples started at once).
TEST_F(Runtime, AnEntityBehindHasNoTimeHeadway) {
  // B is 40 m ahead of A (s 50 and 10), both at 10 m/s.
  const std::string road = R"(coordinateSystem="road" relativeDistanceType="longitudinal" freespace="false")";
  load(mark_event("Behind", headway_condition("BehindC", "B", "A", road + R"( value="100" rule="lessThan")")) +
       mark_event("Ahead", headway_condition("AheadC", "A", "B", road + R"( value="100" rule="lessThan")")) +
       mark_event("BehindFar", headway_condition("BehindFarC", "B", "A", road + R"( value="1" rule="greaterThan")")));
  run_until(2);
  EXPECT_TRUE(times("Behind", "startTransition").empty());
  EXPECT_TRUE(times("BehindFar", "startTransition").empty());
  EXPECT_EQ(times("Ahead", "startTransition"), std::vector<double>{0.0});  // 40 m / 10 m/s = 4 s
}

// Without relativeDistanceType the headway is over the euclidean distance (the standard,
// TimeHeadwayCondition: "If not provided, value is interpreted as euclideanDistance"); A and B
// are 40 m apart along the road and 3.5 m across it: 4.015 s euclidean, 4.0 s longitudinal.
TEST_F(Runtime, TimeHeadwayIsEuclideanUnlessTheFileSaysOtherwise) {
  load(mark_event("Euclidean", headway_condition("EC", "A", "B", R"(freespace="false" value="4.01" rule="greaterThan")")) +
       mark_event("Longitudinal",
                  headway_condition("LC", "A", "B",
                                    R"(freespace="false" relativeDistanceType="longitudinal" value="4.01" rule="greaterThan")")) +
       mark_event("OldAlongRoute",  // 1.0: alongRoute="true" is the distance along the road
                  headway_condition("OC", "A", "B", R"(freespace="false" alongRoute="true" value="4.01" rule="greaterThan")")));
  run_until(1);
  EXPECT_EQ(times("Euclidean", "startTransition"), std::vector<double>{0.0});
  EXPECT_TRUE(times("Longitudinal", "startTransition").empty());
  EXPECT_TRUE(times("OldAlongRoute", "startTransition").empty());
}

// The Storyboard's StopTrigger stops what still executes (the standard 1.3, 8.2 and 8.4.2):
// the running action and its event, the event still waiting for its trigger; the maneuver,
// group, act and story then have no executing child left and end; the Storyboard stops last.
TEST_F(Runtime, TheStoryboardStopStopsRunningAndWaitingElements) {
  load(event("Slow", "parallel", speed_action("SlowAction", 0, "linear", "time", 50), time_condition("T", 1.0)) +
           event("Never", "parallel", speed_action("NeverAction", 5, "step", "time", 0), time_condition("N", 1000.0)),
       5.0);
  run_until(10);
  ASSERT_TRUE(runtime_->finished());
  std::vector<std::string> at_stop;
  for (const TransitionLog& l : runtime_->log())
    if (std::abs(l.time - 5.0) < 1e-9) at_stop.push_back(l.name + " " + l.transition);
  EXPECT_EQ(at_stop, (std::vector<std::string>{"SlowAction stopTransition", "Slow stopTransition",
                                               "Never stopTransition", "M endTransition", "G endTransition",
                                               "Act endTransition", "S endTransition", " stopTransition"}));
  EXPECT_EQ(runtime_->state("event", "Never"), ElementState::Complete);
  EXPECT_TRUE(times("NeverAction", "stopTransition").empty());  // never started: nothing to stop
}

// An Act still waiting for its start trigger when the Storyboard stops leaves standbyState
// with a stopTransition (8.2); its Story then ends.
TEST_F(Runtime, TheStoryboardStopStopsAnActStillInStandby) {
  load(event("E", "parallel", speed_action("Go", 5, "step", "time", 0), time_condition("T", 1.0)), 5.0, 1,
       "<StartTrigger><ConditionGroup>" + time_condition("Late", 1000.0) + "</ConditionGroup></StartTrigger>");
  run_until(10);
  ASSERT_EQ(times("Act", "stopTransition").size(), 1u);
  EXPECT_NEAR(times("Act", "stopTransition")[0], 5.0, 1e-9);
  ASSERT_EQ(times("S", "endTransition").size(), 1u);
  EXPECT_NEAR(times("S", "endTransition")[0], 5.0, 1e-9);
  EXPECT_TRUE(times("E", "stopTransition").empty());  // its maneuver never started
}

}  // namespace
}  // namespace orch::openscenario

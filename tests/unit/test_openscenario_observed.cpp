// An OpenSCENARIO run as metrics and criteria see it (run/openscenario_observed.hpp) and the
// storyboard's transitions as result.json events (run/storyboard_events.hpp): no simulator,
// the snapshot built by hand.
#include <gtest/gtest.h>

#include "opendrive/xodr_reader.hpp"
#include "run/openscenario_observed.hpp"
#include "run/storyboard_events.hpp"
#include "support/cli_runner.hpp"

namespace orch {
namespace {

const char* kRoad = R"(<OpenDRIVE><header revMajor="1" revMinor="6"/>
<road id="3" length="500" junction="-1"><planView><geometry s="0" x="100" y="50" hdg="0" length="500"><line/></geometry></planView>
<lanes><laneSection s="0"><center><lane id="0" type="none"/></center><right>
 <lane id="-1" type="driving"><width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane>
 <lane id="-2" type="driving"><width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane>
</right></laneSection></lanes></road></OpenDRIVE>)";
const char* kNet = R"(<net><edge id="-3" from="a" to="b"><lane id="-3_0" index="0" length="500" shape="0,0 1,1"/>
<lane id="-3_1" index="1" length="500" shape="0,0 1,1"/></edge></net>)";

openscenario::Entity entity(const std::string& name, openscenario::EntityKind kind) {
  openscenario::Entity e;
  e.name = name;
  e.kind = kind;
  e.box.length = kind == openscenario::EntityKind::Vehicle ? 4.5 : 0.6;
  e.box.width = kind == openscenario::EntityKind::Vehicle ? 1.8 : 0.6;
  return e;
}

openscenario::Scenario three_entities() {
  openscenario::Scenario s;
  s.file = "s.xosc";
  s.entities = {entity("Lead", openscenario::EntityKind::Vehicle), entity("Ego", openscenario::EntityKind::Vehicle),
                entity("Walker", openscenario::EntityKind::Pedestrian)};
  return s;
}

class OpenScenarioRunOnRoad3 : public ::testing::Test {
 protected:
  OpenScenarioRunOnRoad3() {
    for (const auto& [name, lane, s] : {std::tuple{"Lead", -1, 80.0}, {"Ego", -1, 40.0}, {"Walker", -2, 60.0}}) {
      openscenario::EntityState& e = entities[name];
      e.placed = true;
      e.road_id = "3";
      e.lane = lane;
      e.s = s;
      e.pose = roads.lane_pose("3", lane, s, 0);
    }
  }
  // The snapshot of the actors SUMO has, at their poses.
  sim::WorldSnapshot snapshot(double time) const {
    sim::WorldSnapshot snap;
    snap.time = time;
    for (const auto& t : actors.tracked()) {
      sim::ActorState a;
      a.id = t.id;
      a.present = true;
      const auto& pose = entities.at(actors.name_of(t.id)).pose;
      a.position = {pose.x, pose.y};
      snap.actors.push_back(a);
    }
    return snap;
  }

  test::TempDir dir;
  const opendrive::RoadNetwork roads = opendrive::read_xodr_file(dir.write("r.xodr", kRoad).string());
  const opendrive::SumoLaneIndex lanes{roads, dir.write("n.net.xml", kNet).string()};
  const openscenario::Scenario scenario = three_entities();
  std::map<std::string, openscenario::EntityState> entities;
  OpenScenarioActors actors{scenario, lanes, "Ego"};
};

TEST_F(OpenScenarioRunOnRoad3, EntitiesByNameWithTheirKindAndTheLaneTheyStartedInAsPath) {
  OpenScenarioRun run(scenario, roads, actors);
  EXPECT_EQ(run.ego(), std::optional<sim::ActorId>(1));
  EXPECT_FALSE(run.body(0)) << "not spawned yet: SUMO does not know it";
  (void)actors.place(entities);
  run.update(snapshot(1.05), 1.0, entities, false);
  EXPECT_DOUBLE_EQ(run.judged().time, 1.0) << "rows carry the storyboard's time, like trace.csv";
  const auto lead = run.body(0), walker = run.body(2);
  ASSERT_TRUE(lead && walker);
  EXPECT_EQ(lead->label, "Lead");
  EXPECT_EQ(lead->kind, ActorKind::Vehicle);
  EXPECT_DOUBLE_EQ(lead->length, 4.5);
  EXPECT_EQ(walker->kind, ActorKind::Pedestrian) << "SUMO has it as a vehicle; the metrics measure it as a pedestrian";
  // The path: lane -1's centre along s (right lanes drive along s), y = 50 - 1.75.
  const Polyline* path = run.path_of(1);
  ASSERT_NE(path, nullptr);
  EXPECT_NEAR(path->point(0).x(), 100, 1e-9);
  EXPECT_NEAR(path->point(0).y(), 48.25, 1e-9);
  EXPECT_NEAR(path->length(), 500, 1e-6);
  EXPECT_EQ(run.id_of("Walker"), std::optional<sim::ActorId>(2));
  EXPECT_FALSE(run.id_of("Nobody"));
  EXPECT_FALSE(run.ending_reached());
  EXPECT_EQ(run.scene(), 0);
  EXPECT_TRUE(run.visits().empty());
  run.update(snapshot(2.05), 2.0, entities, true);
  EXPECT_TRUE(run.ending_reached()) << "the StopTrigger is the run's ending";
}

TEST_F(OpenScenarioRunOnRoad3, SumosCollisionReportsBecomeContactsOncePerPair) {
  OpenScenarioRun run(scenario, roads, actors);
  (void)actors.place(entities);
  sim::WorldSnapshot snap = snapshot(3.05);
  snap.collisions = {{"Ego", "Lead", "collision", "-3_0", 10}, {"bg.1", "bg.2", "collision", "-3_1", 5}};
  run.update(snap, 3.0, entities, false);
  snap.collisions = {{"Lead", "Ego", "collision", "-3_0", 11}, {"bg.7", "Ego", "collision", "-3_0", 12}};
  run.update(snap, 3.05, entities, false);
  ASSERT_EQ(run.contacts().size(), 2u);
  EXPECT_EQ(run.contacts()[0].a, "1");  // entities by run index, as criteria's With names them
  EXPECT_EQ(run.contacts()[0].b, "0");
  EXPECT_DOUBLE_EQ(run.contacts()[0].time, 3.0);
  EXPECT_EQ(run.contacts()[0].source, "sumo");
  EXPECT_EQ(run.contacts()[1].a, "bg.7");
  EXPECT_EQ(run.contacts()[1].b, "1");
  EXPECT_DOUBLE_EQ(run.contacts()[1].time, 3.05);
}

TEST(StoryboardEvents, ElementsAreStoryboardEventsActionsAreActionsWithTheRunLogText) {
  const engine::Event act = storyboard_event({2.5, "act", "CutInAct", "startTransition"});
  EXPECT_EQ(act.kind, engine::EventKind::Storyboard);
  EXPECT_DOUBLE_EQ(act.time, 2.5);
  EXPECT_EQ(act.text, "act CutInAct startTransition");
  EXPECT_EQ(storyboard_event({3, "event", "E", "endTransition"}).kind, engine::EventKind::Storyboard);
  const engine::Event action = storyboard_event({4, "action", "CutInLaneChange", "endTransition"});
  EXPECT_EQ(action.kind, engine::EventKind::Action);
  EXPECT_EQ(action.text, "action CutInLaneChange endTransition");
  EXPECT_EQ(storyboard_event({9, "storyboard", "", "stopTransition"}).text, "storyboard  stopTransition");
}

}  // namespace
}  // namespace orch

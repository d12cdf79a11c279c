// OpenSCENARIO entities as SUMO actors (no simulator): the ego choice, spawns on the SUMO
// lane of the entity's OpenDRIVE lane, poses at the bounding box centre and the way back
// to the reference point.
#include <gtest/gtest.h>

#include <cmath>

#include "core/errors.hpp"
#include "opendrive/xodr_reader.hpp"
#include "run/openscenario_world.hpp"
#include "support/cli_runner.hpp"

namespace orch {
namespace {

const char* kRoad = R"(<OpenDRIVE><header revMajor="1" revMinor="6"/>
<road id="3" length="500" junction="-1"><planView><geometry s="0" x="100" y="50" hdg="0.5" length="500"><line/></geometry></planView>
<lanes><laneSection s="0"><center><lane id="0" type="none"/></center><right>
 <lane id="-1" type="border"><width sOffset="0" a="0.5" b="0" c="0" d="0"/></lane>
 <lane id="-2" type="driving"><width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane>
 <lane id="-3" type="driving"><width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane>
</right></laneSection></lanes></road></OpenDRIVE>)";

// The edge netconvert makes of road 3's right side (two kept lanes; shapes do not matter here).
const char* kNet = R"(<net><edge id="-3" from="a" to="b"><lane id="-3_0" index="0" length="500" shape="0,0 1,1"/>
<lane id="-3_1" index="1" length="500" shape="0,0 1,1"/></edge></net>)";

openscenario::Entity car(const std::string& name, const std::string& controller) {
  openscenario::Entity e;
  e.name = name;
  e.category = "car";
  e.box.center_x = 1.4;
  e.box.length = 5;
  e.box.width = 2;
  if (!controller.empty()) e.controller = openscenario::Controller{controller, {}};
  return e;
}

// An entity placed on road 3's `lane` at `s`, as the storyboard has it.
openscenario::EntityState placed_on(const opendrive::RoadNetwork& roads, int lane, double s, double speed) {
  openscenario::EntityState state;
  state.placed = true;
  state.road_id = "3";
  state.lane = lane;
  state.s = s;
  state.speed = speed;
  state.pose = roads.lane_pose("3", lane, s, 0);
  return state;
}

// Road 3 and the SUMO lanes of its right side, in a temporary folder.
class OpenScenarioActorsOnRoad3 : public ::testing::Test {
 protected:
  test::TempDir dir;
  const opendrive::RoadNetwork roads = opendrive::read_xodr_file(dir.write("r.xodr", kRoad).string());
  const opendrive::SumoLaneIndex lanes{roads, dir.write("n.net.xml", kNet).string()};
};

TEST(OpenScenarioActors, TheEgoIsTheSystemUnderTestsEntityUnlessNamed) {
  openscenario::Scenario s;
  s.file = "s.xosc";
  s.entities = {car("Lead", ""), car("Subject", "ALKSController")};
  EXPECT_EQ(choose_ego_entity(s, ""), "Subject");
  EXPECT_EQ(choose_ego_entity(s, "Lead"), "Lead");
  try {
    (void)choose_ego_entity(s, "Laed");
    FAIL() << "an unknown --ego is an error";
  } catch (const ScenarioError& e) {
    EXPECT_NE(std::string(e.what()).find("did you mean \"Lead\""), std::string::npos) << e.what();
  }
  s.entities = {car("Lead", "")};
  EXPECT_EQ(choose_ego_entity(s, ""), "");
}

TEST_F(OpenScenarioActorsOnRoad3, SpawnsOnceOnTheSumoLaneAndPosesTheBoxCentre) {
  openscenario::Scenario s;
  s.entities = {car("Lead", "")};
  OpenScenarioActors actors(s, lanes, "");
  openscenario::EntityState state = placed_on(roads, -2, 40, 20);  // the inner kept lane: SUMO's leftmost of two
  std::map<std::string, openscenario::EntityState> entities{{"Lead", state}};

  const auto first = actors.place(entities);
  ASSERT_EQ(first.size(), 2u);
  const auto& spawn = std::get<sim::SpawnVehicle>(first[0]);
  EXPECT_EQ(spawn.edge, "-3");
  EXPECT_EQ(spawn.lane, 1);
  EXPECT_NEAR(spawn.lane_pos, 40 + 1.4, 1e-9);  // the centre
  EXPECT_TRUE(spawn.scripted);
  EXPECT_EQ(spawn.model.vclass, "authority");  // hard shoulders admit scripted entities
  const auto& pose = std::get<sim::SetPose>(first[1]);
  EXPECT_NEAR(pose.position.x(), state.pose.x + 1.4 * std::cos(0.5), 1e-9);
  EXPECT_NEAR(pose.position.y(), state.pose.y + 1.4 * std::sin(0.5), 1e-9);
  ASSERT_EQ(actors.tracked().size(), 1u);
  EXPECT_EQ(actors.tracked()[0].sumo_id, "Lead");

  // Later steps only pose; SUMO's centre maps back to the reference point.
  const auto second = actors.place(entities);
  ASSERT_EQ(second.size(), 1u);
  sim::ActorState seen;
  seen.id = actors.tracked()[0].id;
  seen.position = pose.position;
  seen.heading = pose.heading;
  const Vec2 ref = actors.reference_point(seen);
  EXPECT_NEAR(ref.x(), state.pose.x, 1e-9);
  EXPECT_NEAR(ref.y(), state.pose.y, 1e-9);

  // An entity that first appears where SUMO has no lane (lane -1, discarded by the net) enters
  // on the SUMO lane nearest it and is posed there off the lanes (no edge); one that SUMO
  // drives (the ego) cannot drive off the lanes: an error naming it.
  state.lane = -1;
  OpenScenarioActors other(s, lanes, "");
  entities["Lead"] = state;
  const auto off = other.place(entities);
  ASSERT_EQ(off.size(), 2u);
  EXPECT_EQ(std::get<sim::SpawnVehicle>(off[0]).edge, "-3");
  EXPECT_EQ(std::get<sim::SpawnVehicle>(off[0]).lane, 1);
  EXPECT_EQ(std::get<sim::SetPose>(off[1]).edge, "");
  OpenScenarioActors driven(s, lanes, "Lead", EgoDrive::Sumo);
  EXPECT_THROW((void)driven.place(entities), MapError);
}

TEST_F(OpenScenarioActorsOnRoad3, TheEgoIsPlacedOnceThenOnlyItsDesiredSpeedFollowsTheStoryboard) {
  openscenario::Scenario s;
  s.entities = {car("Ego", "ALKSController")};
  OpenScenarioActors actors(s, lanes, "Ego");
  openscenario::EntityState state = placed_on(roads, -3, 10, 15);
  std::map<std::string, openscenario::EntityState> entities{{"Ego", state}};
  const auto first = actors.place(entities);
  ASSERT_EQ(first.size(), 2u);
  const auto& spawn = std::get<sim::SpawnVehicle>(first[0]);
  EXPECT_FALSE(spawn.scripted);
  EXPECT_EQ(spawn.lane, 0);
  EXPECT_DOUBLE_EQ(spawn.max_speed, 15);
  EXPECT_FALSE(std::get<sim::SetPose>(first[1]).scripted);  // one placement, speed left to SUMO
  EXPECT_TRUE(actors.place(entities).empty());  // SUMO drives it
  entities["Ego"].speed_profile = openscenario::SpeedProfile{1, 2, 15, 25, openscenario::DynamicsShape::Linear};
  const auto changed = actors.place(entities);
  ASSERT_EQ(changed.size(), 1u);
  EXPECT_DOUBLE_EQ(std::get<sim::SetMaxSpeed>(changed[0]).speed, 25);
  EXPECT_TRUE(actors.place(entities).empty());  // sent once
}

// An ego nothing drives (no system-under-test controller, nothing asked on the command
// line) follows the storyboard: posed every step, scripted, like every other entity.
TEST_F(OpenScenarioActorsOnRoad3, AStoryboardEgoIsPosedEveryStepLikeAnyEntity) {
  openscenario::Scenario s;
  s.entities = {car("Ego", "")};
  OpenScenarioActors actors(s, lanes, "Ego", EgoDrive::Storyboard);
  EXPECT_EQ(actors.ego(), "Ego");
  EXPECT_FALSE(actors.ego_driven());
  std::map<std::string, openscenario::EntityState> entities{{"Ego", placed_on(roads, -3, 10, 15)}};
  const auto first = actors.place(entities);
  ASSERT_EQ(first.size(), 2u);
  EXPECT_TRUE(std::get<sim::SpawnVehicle>(first[0]).scripted);
  EXPECT_TRUE(std::get<sim::SetPose>(first[1]).scripted);
  entities["Ego"] = placed_on(roads, -3, 11, 15);
  const auto next = actors.place(entities);
  ASSERT_EQ(next.size(), 1u);  // posed again: the storyboard moves it
  EXPECT_TRUE(std::get<sim::SetPose>(next[0]).scripted);
  EXPECT_FALSE(actors.is_sumo_driven("Ego"));
  EXPECT_TRUE(actors.sumo_driven().empty());
}

// DeleteEntityAction / VisibilityAction(traffic=false) take the entity out of SUMO; it comes
// back under a new SUMO id. An activated controller of a non-ego entity hands it to SUMO.
TEST_F(OpenScenarioActorsOnRoad3, DeletedOrInvisibleEntitiesLeaveSumoActivatedControllersHandOver) {
  openscenario::Scenario s;
  s.entities = {car("Lead", "")};
  OpenScenarioActors actors(s, lanes, "");
  openscenario::EntityState state = placed_on(roads, -2, 40, 20);
  std::map<std::string, openscenario::EntityState> entities{{"Lead", state}};
  ASSERT_EQ(actors.place(entities).size(), 2u);  // spawn, pose

  entities["Lead"].visibility.traffic = false;
  auto out = actors.place(entities);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(std::get<sim::RemoveActor>(out[0]).sumo_id, "Lead");
  EXPECT_TRUE(actors.place(entities).empty());  // removed once

  entities["Lead"].visibility.traffic = true;
  out = actors.place(entities);
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(std::get<sim::SpawnVehicle>(out[0]).actor.sumo_id, "Lead~2");
  ASSERT_EQ(actors.tracked().size(), 1u);  // the same actor, a new SUMO id
  EXPECT_EQ(actors.tracked()[0].sumo_id, "Lead~2");
  EXPECT_EQ(actors.name_of(actors.tracked()[0].id), "Lead");

  entities["Lead"].controller = "Driver";
  entities["Lead"].controller_active = true;
  const std::string spawn_edge = std::get<sim::SpawnVehicle>(out[0]).edge;
  out = actors.place(entities);
  ASSERT_EQ(out.size(), 2u);  // handed over, with the route on from its lane (this road's edge: no links)
  EXPECT_EQ(std::get<sim::ReleaseActor>(out[0]).sumo_id, "Lead~2");
  EXPECT_DOUBLE_EQ(std::get<sim::ReleaseActor>(out[0]).max_speed, 20);
  EXPECT_EQ(std::get<sim::SetRoute>(out[1]).edges, std::vector<std::string>{spawn_edge});
  EXPECT_TRUE(actors.is_sumo_driven("Lead"));
  EXPECT_EQ(actors.sumo_driven(), std::vector<std::string>{"Lead"});
  EXPECT_TRUE(actors.place(entities).empty());  // SUMO drives it now

  entities["Lead"].placed = false;  // DeleteEntityAction
  out = actors.place(entities);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(std::get<sim::RemoveActor>(out[0]).sumo_id, "Lead~2");
  EXPECT_TRUE(actors.sumo_driven().empty());
}

}  // namespace
}  // namespace orch

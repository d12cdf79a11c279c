// The engine's actions on a fake world (no SUMO): each one does what the format says.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "scenario_executor_engine/engine.hpp"
#include "map/lane_map.hpp"
#include "map/map_registry.hpp"
#include "support/fake_world.hpp"
#include "support/scenario_text.hpp"

using namespace orch;
using namespace orch::engine;

namespace {

// A shipped map, loaded once for the whole suite (pure data: no SUMO runs).
struct LoadedMap {
  WaypointFile waypoints;
  LaneMap lanes;
};
const LoadedMap& shipped(const std::string& id) {
  static std::map<std::string, std::unique_ptr<LoadedMap>> cache;
  auto& slot = cache[id];
  if (!slot) {
    const MapManifest m = load_map_manifest(std::string(ORCH_SOURCE_DIR) + "/sumo_nets/" + id);
    WaypointFile wps = load_waypoint_file(m.waypoint_path().string());
    LaneMap lanes = LaneMap::build(m.net_path().string(), wps);
    slot = std::make_unique<LoadedMap>(LoadedMap{std::move(wps), std::move(lanes)});
  }
  return *slot;
}

// Ego on ALKS Waypoint02 at idx 5; actor 1 as given; scenes as given.
std::string alks(const std::string& actor1_opening, const std::string& scenes, const std::string& model = "vehicle.audi.tt") {
  return R"({"map_id": "ALKS_Road",
  "actors": {"ego": {"actor_id": 0, "model_id": "vehicle.toyota.prius"},
             "others": [{"actor_id": 1, "model_id": ")" + model + R"("},
                        {"actor_id": 2, "model_id": "vehicle.nissan.micra"}]},
  "scenario": {"opening_scene": {
      "ego": {"start_position": {"wp_id": "Waypoint02", "wp_idx": 5}},
      "others": [)" + actor1_opening + R"(,
                 {"actor_id": 2, "start_position": {"type": "waypoint", "wp_id": "Waypoint01", "wp_idx": 300}}],
      "next_scenes": [1]},
    "scenes": )" + scenes + R"(,
    "ending_scenes": [{"scene_id": 99, "conditions": {"and": [{"simulation_time": {"comparison": ">=", "value": 1000}}]}}]}})";
}

struct Rig {
  explicit Rig(const std::string& text, const std::string& map = "ALKS_Road", bool external_ego = false)
      : scenario(test::scenario_from(text)), m(shipped(map)),
        engine(scenario, MapContext{m.waypoints, m.lanes, 20.0}, Catalog::embedded(), EngineOptions{0.05, external_ego}),
        world(engine, *m.waypoints.find(scenario.opening.ego.start.waypoint->wp_id), 0.05) {}
  scenario::Scenario scenario;
  const LoadedMap& m;
  Engine engine;
  test::FakeWorld world;
};

const char* kActor1OnLane3 = R"({"actor_id": 1, "start_position": {"type": "waypoint", "wp_id": "Waypoint03", "wp_idx": 100}})";

}  // namespace

TEST(EngineActions, RelativeSpeedIsReevaluatedEveryStep) {
  Rig r(alks(R"({"actor_id": 1, "start_position": {"type": "waypoint", "wp_id": "Waypoint03", "wp_idx": 100},
                 "start_speed": {"type": "relative", "target_actor_id": 0, "value": 10}})",
             "[]"));
  r.world.start(5);
  r.world.ego_speed = 10;
  r.world.run_until(1);
  EXPECT_NEAR(r.world.pose("actor1").speed, 10 + 10 / 3.6, 1e-9);
  r.world.ego_speed = 20;  // the target speeds up: the actor follows at once (instant accel)
  r.world.run_until(2);
  EXPECT_NEAR(r.world.pose("actor1").speed, 20 + 10 / 3.6, 1e-9);
}

TEST(EngineActions, SpecifiedAccelerationBothWays) {
  Rig r(alks(R"({"actor_id": 1, "start_position": {"type": "waypoint", "wp_id": "Waypoint03", "wp_idx": 100},
                 "start_speed": {"type": "absolute", "value": 36}})",
             R"([{"scene_id": 1, "next_scenes": [2],
                 "actions": [{"speed": {"actor_id": 1, "type": "absolute", "value": 72, "accel": {"type": "specify", "value": 2}}}]},
                {"scene_id": 2, "conditions": {"and": [{"simulation_time": {"comparison": ">=", "value": 10}}]}, "next_scenes": [99],
                 "actions": [{"speed": {"actor_id": 1, "type": "absolute", "value": 0, "accel": {"type": "specify", "value": 4}}}]}])"));
  r.world.start(5);
  r.world.run_until(3.05);  // scene 1 at t = 0.05: 2 s of 2 m/s^2 from 10 m/s
  EXPECT_NEAR(r.world.pose("actor1").speed, 16.0, 1e-6);
  r.world.run_until(9.0);
  EXPECT_NEAR(r.world.pose("actor1").speed, 20.0, 1e-9);  // holds the target
  r.world.run_until(12.0);
  EXPECT_NEAR(r.world.pose("actor1").speed, 20.0 - 4 * 2.0, 1e-6);
}

TEST(EngineActions, GodsHandSpellingsAreBothInstant) {
  for (const char* spelling : {"gods_hand", "god_hands"}) {
    Rig r(alks(kActor1OnLane3, std::string(R"([{"scene_id": 1, "next_scenes": [99], "actions": [{"speed": {"actor_id": 1,
               "type": "absolute", "value": 90, "accel": {"type": ")") + spelling + R"("}}}]}])"));
    r.world.start(5);
    r.world.run_until(0.1);
    EXPECT_NEAR(r.world.pose("actor1").speed, 25.0, 1e-9) << spelling;
  }
}

TEST(EngineActions, SecondSpeedActionReplacesTheFirst) {
  Rig r(alks(kActor1OnLane3,
             R"([{"scene_id": 1, "next_scenes": [2],
                 "actions": [{"speed": {"actor_id": 1, "type": "absolute", "value": 100, "accel": {"type": "specify", "value": 1}}}]},
                {"scene_id": 2, "conditions": {"and": [{"simulation_time": {"comparison": ">=", "value": 2}}]}, "next_scenes": [99],
                 "actions": [{"speed": {"actor_id": 1, "type": "relative", "target_actor_id": 0, "value": 0}}]}])"));
  r.world.start(5);
  r.world.ego_speed = 5;
  r.world.run_until(3);
  EXPECT_NEAR(r.world.pose("actor1").speed, 5.0, 1e-9);  // now follows the ego, not 100 km/h
}

TEST(EngineActions, TraveledDistanceHoldsTheGapWhileTheTargetChangesSpeed) {
  // Actor 1 keeps 20 m ahead (centre) of the ego, which speeds up and slows down.
  Rig r(alks(kActor1OnLane3, R"([{"scene_id": 1, "next_scenes": [99],
      "actions": [{"traveled_distance": {"actor_id": 1, "target_actor_id": 0, "value": 20}}]}])"));
  r.world.start(5);
  r.world.ego_speed = 15;
  r.world.run_until(30);
  auto gap = [&] { return r.world.pose("actor1").position.x() - r.world.last().actors[0].position.x(); };
  EXPECT_NEAR(gap(), 20.0, 0.2);
  double worst = 0, hardest = 0;
  for (int i = 0; i < 200; ++i) {  // target changes speed: 15 -> 25 m/s at 1 m/s^2
    r.world.ego_speed = std::min(25.0, r.world.ego_speed + 0.05);
    r.world.step();
    worst = std::max(worst, std::abs(gap() - 20.0));
    hardest = std::max(hardest, std::abs(r.world.pose("actor1").speed - r.world.ego_speed) / 0.05);
  }
  EXPECT_LT(worst, 0.6);
  EXPECT_NEAR(gap(), 20.0, 0.6);
}

TEST(EngineActions, NegativeGapKeepsTheActorBehind) {
  Rig r(alks(kActor1OnLane3, R"([{"scene_id": 1, "next_scenes": [99],
      "actions": [{"traveled_distance": {"actor_id": 1, "target_actor_id": 0, "value": -10, "measure_type": "surface"}}]}])"));
  r.world.start(5);
  r.world.ego_speed = 20;
  r.world.run_until(40);
  // Surface gap: 10 m between the tt's front and the prius' rear.
  const double centre_gap = r.world.last().actors[0].position.x() - r.world.pose("actor1").position.x();
  EXPECT_NEAR(centre_gap, 10 + (4.18 + 4.51) / 2, 0.2);
}

TEST(EngineActions, LaneOffsetMovesLaterallyAndHolds) {
  Rig r(alks(kActor1OnLane3, R"([{"scene_id": 1, "next_scenes": [99],
      "actions": [{"lane_offset": {"actor_id": 1, "value": 1.2, "time": 2}}]}])"));
  r.world.start(5);
  r.world.run_until(1.05);
  const double y_mid = r.world.pose("actor1").position.y();
  EXPECT_NEAR(y_mid, -11.5 + 0.6, 1e-6);  // half way at half time (symmetric profile)
  r.world.run_until(2.05);
  EXPECT_NEAR(r.world.pose("actor1").position.y(), -11.5 + 1.2, 1e-9);
  r.world.run_until(10);
  EXPECT_NEAR(r.world.pose("actor1").position.y(), -11.5 + 1.2, 1e-9);
  EXPECT_EQ(r.world.pose("actor1").lane, 0);  // still in its lane (1.2 m < half a lane)
}

TEST(EngineActions, LaneChangeReplacesALaneOffset) {
  Rig r(alks(kActor1OnLane3,
             R"([{"scene_id": 1, "next_scenes": [2], "actions": [{"lane_offset": {"actor_id": 1, "value": -1, "time": 4}}]},
                {"scene_id": 2, "conditions": {"and": [{"simulation_time": {"comparison": ">=", "value": 1}}]}, "next_scenes": [99],
                 "actions": [{"lane_change": {"actor_id": 1, "type": "lane", "wp_id": "Waypoint02", "time": 3}}]}])"));
  r.world.start(5);
  r.world.run_until(4.0);  // lane change from t = 1 to 4
  EXPECT_NEAR(r.world.pose("actor1").position.y(), -8.0, 1e-9);
  EXPECT_EQ(r.world.pose("actor1").lane, 1);
  r.world.run_until(8.0);  // the interrupted lane_offset does not come back
  EXPECT_NEAR(r.world.pose("actor1").position.y(), -8.0, 1e-9);
}

TEST(EngineActions, VehicleRouteMoveArrivesOnTime) {
  Rig r(alks(kActor1OnLane3, R"([{"scene_id": 1, "next_scenes": [99], "actions": [{"route_move": {"actor_id": 1,
      "type": "waypoint", "route": [{"wp_id": "Waypoint02", "wp_idx": 300, "time": 10},
                                    {"wp_id": "Waypoint02", "wp_idx": 400, "wp_offset": 0.5, "time": 5}]}}]}])"));
  r.world.start(5);
  r.world.run_until(0.05);  // scene 1 entered at the first step
  r.world.run_until(10.05);
  EXPECT_NEAR(r.world.pose("actor1").position.x(), 300.0, 1e-6);
  EXPECT_NEAR(r.world.pose("actor1").position.y(), -8.0, 1e-6);
  EXPECT_NEAR(r.world.pose("actor1").speed, 20.0, 1e-6);  // 200 m in 10 s
  r.world.run_until(15.05);
  EXPECT_NEAR(r.world.pose("actor1").position.x(), 400.0, 1e-6);
  EXPECT_NEAR(r.world.pose("actor1").position.y(), -7.5, 1e-6);
  r.world.run_until(20.05);  // goes on at the speed it arrived with
  EXPECT_NEAR(r.world.pose("actor1").speed, 20.0, 1e-6);
  EXPECT_NEAR(r.world.pose("actor1").position.x(), 500.0, 1e-6);
}

TEST(EngineActions, PedestrianWalksStraightLegs) {
  Rig r(alks(R"({"actor_id": 1, "start_position": {"type": "waypoint", "wp_id": "Waypoint03", "wp_idx": 100, "wp_offset": -2}})",
             R"([{"scene_id": 1, "next_scenes": [99], "actions": [{"route_move": {"actor_id": 1, "type": "waypoint",
                 "route": [{"wp_id": "Waypoint01", "wp_idx": 100, "time": 6}]}}]}])",
             "walker.pedestrian.0001"));
  r.world.start(5);
  r.world.run_until(3.05);
  EXPECT_NEAR(r.world.pose("actor1").position.y(), -13.5 + 4.5, 1e-6);  // 9 m in 6 s: half way
  EXPECT_NEAR(r.world.pose("actor1").speed, 1.5, 1e-6);
  r.world.run_until(8.0);
  EXPECT_NEAR(r.world.pose("actor1").position.y(), -4.5, 1e-6);
  EXPECT_NEAR(r.world.pose("actor1").speed, 0.0, 1e-9);  // stands at the end
}

TEST(EngineActions, LightsStayUntilSwitchedOffAndSpecial1IsTheBlueLight) {
  Rig r(alks(kActor1OnLane3,
             R"([{"scene_id": 1, "next_scenes": [2], "actions": [{"light_state": {"actor_id": 1, "blinker_left": true, "special1": true}}]},
                {"scene_id": 2, "conditions": {"and": [{"simulation_time": {"comparison": ">=", "value": 5}}]}, "next_scenes": [99],
                 "actions": [{"light_state": {"actor_id": 1, "blinker_left": false}}]}])",
             "vehicle.garden.gambulancejp"));
  r.world.start(5);
  r.world.run_until(4.9);
  EXPECT_EQ(r.world.signals("actor1"), kSignalBlinkerLeft | kSignalEmergencyBlue);  // re-sent with every pose
  r.world.run_until(6);
  EXPECT_EQ(r.world.signals("actor1"), kSignalEmergencyBlue);  // special1 untouched by the second action
}

TEST(EngineActions, SoundStateAndHandOverAreRecorded) {
  Rig r(alks(kActor1OnLane3,
             R"([{"scene_id": 1, "next_scenes": [99], "actions": [
                  {"sound_state": {"actor_id": 1, "sound": true}},
                  {"hand_over": {"hand_over": true, "throttle": 0.3}}]}])",
             "vehicle.garden.gpolicecarjp"));
  r.world.start(5);
  r.world.run_until(1);
  EXPECT_TRUE(r.engine.siren(1));
  ASSERT_EQ(r.engine.hand_overs().size(), 1u);
  EXPECT_TRUE(r.engine.hand_overs()[0].action.hand_over);
  EXPECT_DOUBLE_EQ(*r.engine.hand_overs()[0].action.throttle, 0.3);
  bool siren_param = false, hand_over_param = false;
  for (const auto& c : r.world.history()) {
    if (const auto* p = std::get_if<SetParameter>(&c)) {
      siren_param |= p->sumo_id == "actor1" && p->key == "orch.siren" && p->value == "on";
      hand_over_param |= p->sumo_id == "ego" && p->key == "orch.hand_over" && p->value == "1";
    }
  }
  EXPECT_TRUE(siren_param);
  EXPECT_TRUE(hand_over_param);
}

TEST(EngineActions, ActionOnAnActorThatLeftIsARunError) {
  Rig r(alks(kActor1OnLane3,
             R"([{"scene_id": 1, "conditions": {"and": [{"simulation_time": {"comparison": ">=", "value": 2}}]}, "next_scenes": [99],
                 "actions": [{"speed": {"actor_id": 2, "type": "absolute", "value": 30}}]}])"));
  r.world.start(5);
  r.world.run_until(1);
  r.world.gone.insert(2);
  r.world.run_until(3);
  EXPECT_EQ(r.engine.state(), RunState::Error);
  EXPECT_NE(r.engine.end_reason().find("actor 2"), std::string::npos) << r.engine.end_reason();
}

TEST(EngineActions, LaneChangeIntoTheOppositeSideKeepsTheDirectionOfTravel) {
  // Highway: Waypoint01 runs north (+y), Waypoint01R south; a change onto 01R is a move
  // into a lane of the other carriageway, still driving north.
  const std::string text = R"({"map_id": "highway",
    "actors": {"ego": {"actor_id": 0, "model_id": "vehicle.toyota.prius"}, "others": [{"actor_id": 1, "model_id": "vehicle.audi.tt"}]},
    "scenario": {"opening_scene": {"ego": {"start_position": {"wp_id": "Waypoint03", "wp_idx": 5}},
        "others": [{"actor_id": 1, "start_position": {"type": "waypoint", "wp_id": "Waypoint01", "wp_idx": 100},
                    "start_speed": {"type": "absolute", "value": 36}}], "next_scenes": [1]},
      "scenes": [{"scene_id": 1, "next_scenes": [99], "actions": [{"lane_change": {"actor_id": 1, "type": "lane", "wp_id": "Waypoint01R", "time": 4}}]}],
      "ending_scenes": [{"scene_id": 99, "conditions": {"and": [{"simulation_time": {"comparison": ">=", "value": 1000}}]}}]}})";
  Rig r(text, "highway");
  r.world.start(5);
  r.world.step();
  const double y_before = r.world.pose("actor1").position.y();
  r.world.run_until(6);
  const SetPose& p = r.world.pose("actor1");
  EXPECT_GT(p.position.y(), y_before + 50);  // still northbound (+y), 10 m/s
  EXPECT_NEAR(std::cos(p.heading - 3.14159265 / 2), 1.0, 0.01);
  const auto place = r.m.lanes.locate(p.position, p.heading + 3.14159265, 1.0);  // lanes run south here
  ASSERT_TRUE(place.has_value());
  EXPECT_NE(std::find(r.m.lanes.lane(place->lane).routes.begin(), r.m.lanes.lane(place->lane).routes.end(),
                      "Waypoint01R"),
            r.m.lanes.lane(place->lane).routes.end());
  EXPECT_EQ(p.edge, r.m.lanes.lane(place->lane).edge);  // SUMO is told the opposite edge
}

TEST(EngineActions, BackgroundCarInTheWayOfALaneChangeIsRecordedAndTheChangeGoesOn) {
  Rig r(alks(R"({"actor_id": 1, "start_position": {"type": "waypoint", "wp_id": "Waypoint03", "wp_idx": 100},
                 "start_speed": {"type": "absolute", "value": 36}})",
             R"([{"scene_id": 1, "next_scenes": [99],
                 "actions": [{"lane_change": {"actor_id": 1, "type": "lane", "wp_id": "Waypoint02", "time": 3}}]}])"));
  r.world.start(5);
  r.world.run_until(0.1);
  // A background car right beside the actor in the target lane (y = -8), at its speed.
  const double x = r.world.pose("actor1").position.x();
  r.world.nearby = {NearbyVehicle{"bg.0", {x, -8.0}, 0.0, 10.0, 4.6, 1.8}};
  bool logged = false;
  while (r.world.time() < 3.2)
    for (const auto& e : r.world.step())
      logged |= e.kind == EventKind::Warning && e.text.find("lane change conflict: actor 1 changing to Waypoint02 has "
                                                             "vehicle bg.0") != std::string::npos;
  EXPECT_TRUE(logged);
  ASSERT_EQ(r.engine.lane_change_conflicts().size(), 1u);
  EXPECT_EQ(r.engine.lane_change_conflicts()[0].vehicle, "bg.0");
  EXPECT_DOUBLE_EQ(r.engine.lane_change_conflicts()[0].gap, 0.0);
  // The scenario's lane change is not altered by the traffic.
  EXPECT_NEAR(r.world.pose("actor1").position.y(), -8.0, 1e-9);
}

// With an external plug-in driving the ego, the engine sends nothing that drives it (no
// route speed, no end stop, no speed action's top speed; the type's own top speed at
// insertion) and everything else as usual: the same scenario without the option does.
TEST(EngineActions, AnExternalEgoGetsNoDrivingCommandsAndTheRestIsUnchanged) {
  const std::string text = R"({"map_id": "ALKS_Road",
    "actors": {"ego": {"actor_id": 0, "model_id": "vehicle.toyota.prius"},
               "others": [{"actor_id": 1, "model_id": "vehicle.audi.tt"}]},
    "scenario": {"opening_scene": {
        "ego": {"start_position": {"wp_id": "Waypoint02", "wp_idx": 5},
                "end_position": {"wp_id": "Waypoint02", "wp_idx": 900}},
        "others": [{"actor_id": 1, "start_position": {"type": "waypoint", "wp_id": "Waypoint03", "wp_idx": 100},
                    "start_speed": {"type": "absolute", "value": 36}}],
        "next_scenes": [1]},
      "scenes": [{"scene_id": 1, "next_scenes": [99], "actions": [
          {"speed": {"actor_id": 0, "type": "absolute", "value": 50}},
          {"speed": {"actor_id": 1, "type": "absolute", "value": 72}},
          {"hand_over": {"hand_over": true}}]}],
      "ending_scenes": [{"scene_id": 99, "conditions": {"and": [{"simulation_time": {"comparison": ">=", "value": 1000}}]}}]}})";
  struct Seen {
    int ego_max_speed = 0, ego_stop = 0, other_max_speed = 0, hand_over = 0, other_poses = 0;
    double ego_spawn_max_speed = -1;
  };
  const auto run = [&](bool external) {
    Rig r(text, "ALKS_Road", external);
    r.world.start(5);
    r.world.ego_speed = 10;
    r.world.run_until(2);
    Seen seen;
    for (const auto& c : r.world.history()) {
      if (const auto* m = std::get_if<SetMaxSpeed>(&c)) (m->sumo_id == "ego" ? seen.ego_max_speed : seen.other_max_speed)++;
      if (const auto* st = std::get_if<SetStop>(&c); st && st->sumo_id == "ego") ++seen.ego_stop;
      if (const auto* p = std::get_if<SetParameter>(&c); p && p->sumo_id == "ego") ++seen.hand_over;
      if (const auto* p = std::get_if<SetPose>(&c); p && p->sumo_id == "actor1") ++seen.other_poses;
      if (const auto* sp = std::get_if<SpawnVehicle>(&c); sp && sp->actor.sumo_id == "ego")
        seen.ego_spawn_max_speed = sp->max_speed;
    }
    EXPECT_NEAR(r.world.pose("actor1").speed, 20.0, 1e-9) << external;  // scripted actors as ever
    return seen;
  };
  const Seen builtin = run(false);
  const Seen external = run(true);
  EXPECT_GE(builtin.ego_max_speed, 1);  // the speed action (and the route speed) for the built-in driver
  EXPECT_EQ(builtin.ego_stop, 1);
  EXPECT_GT(builtin.ego_spawn_max_speed, 0);
  EXPECT_EQ(external.ego_max_speed, 0);
  EXPECT_EQ(external.ego_stop, 0);
  EXPECT_EQ(external.ego_spawn_max_speed, 0);  // the vehicle type's own top speed
  EXPECT_EQ(external.hand_over, builtin.hand_over);
  EXPECT_GE(external.hand_over, 1);
  EXPECT_EQ(external.other_max_speed, builtin.other_max_speed);
  EXPECT_EQ(external.other_poses, builtin.other_poses);
}

TEST(EngineEvents, TheStartsEventsBelongToTheOpeningScene) {
  Rig r(alks(R"({"actor_id": 1, "start_position": {"type": "waypoint", "wp_id": "Waypoint03", "wp_idx": 100},
                 "start_speed": {"type": "absolute", "value": 36}})",
             "[]"));
  const StepOutput out = r.engine.start();
  ASSERT_FALSE(out.events.empty());
  for (const Event& e : out.events) {
    ASSERT_TRUE(e.scene.has_value()) << e.text;
    EXPECT_EQ(*e.scene, scenario::kOpeningSceneId) << e.text;
  }
}

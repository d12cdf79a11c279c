// check_scenario: references, the catalog, waypoints, the scene graph, actor kinds, ranges.
#include <gtest/gtest.h>

#include "test_loader_support.hpp"

using namespace orch;
using namespace orch::scenario;
using namespace orch::loader_test;

namespace {

// Replaces the first occurrence of `from` in the text (which must hold it).
std::string edit(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

ValidationOptions strict() {
  ValidationOptions o;
  o.strict = true;
  return o;
}

}  // namespace

TEST(Validator, TheBaseScenarioIsClean) {
  const auto d = check_text(with_actions("[]"));
  EXPECT_EQ(d.items().size(), 0u) << d.format();
}

// ---------------------------------------------------------------- actors and models
TEST(Validator, DuplicateActorIds) {
  const auto d = check_text(edit(with_actions("[]"), R"("actor_id": 3, "model_id")", R"("actor_id": 0, "model_id")"));
  EXPECT_TRUE(has_error(d, "/actors/others/2", 3, "actor_id 0 is used twice: the ego at line 3"));
}

TEST(Validator, UnknownModelsWithSuggestionsAndAPedestrianEgo) {
  auto text = edit(with_actions("[]"), "vehicle.audi.tt", "vehicle.audi.ttt");
  text = edit(text, "vehicle.toyota.prius", "walker.pedestrian.0002");
  const auto d = check_text(text);
  EXPECT_TRUE(has_error(d, "/actors/others/0", 3, "model_id \"vehicle.audi.ttt\" is not in the model catalog "
                                                  "(did you mean \"vehicle.audi.tt\"?)"));
  EXPECT_TRUE(has_error(d, "/actors/ego", 3, "the ego must be a vehicle"));
  EXPECT_EQ(d.error_count(), 2) << d.format();
}

TEST(Validator, EveryOtherActorHasExactlyOneOpeningEntry) {
  auto text = edit(with_actions("[]"), R"({"actor_id": 3, "start_position")", R"({"actor_id": 1, "start_position")");
  const auto d = check_text(text);
  EXPECT_TRUE(has_error(d, "/scenario/opening_scene/others/2", 7, "actor 1 has a second opening entry; the first is at "
                                                                  "line 6"));
  EXPECT_TRUE(has_error(d, "/actors/others/2", 3, "actor 3 has no entry in"));
  EXPECT_EQ(d.error_count(), 2) << d.format();
}

TEST(Validator, OpeningEntriesForUnknownActorsOrTheEgo) {
  auto text = edit(with_actions("[]"), R"({"actor_id": 3, "start_position")", R"({"actor_id": 0, "start_position")");
  text = edit(text, R"({"actor_id": 2, "start_position")", R"({"actor_id": 12, "start_position")");
  const auto d = check_text(text);
  EXPECT_TRUE(has_error(d, "/scenario/opening_scene/others/2", 7, "actor_id 0 is the ego"));
  EXPECT_TRUE(has_error(d, "/scenario/opening_scene/others/1", 6,
                        "actor_id 12 is not defined under \"actors\" (defined: 0, 1, 2 and 3)"));
}

TEST(Validator, ActorReferencesInConditionsActionsAndStarts) {
  auto text = with_scene(R"({"scene_id": 1,
"conditions": {"and": [{"collision": {"actor_id": 7}}, {"distance": {"actor_id": 1, "target_actor_id": 8, "comparison": "<", "value": 3}}]},
"actions": [{"speed": {"actor_id": 1, "type": "relative", "target_actor_id": 9, "value": 0}},
            {"lane_offset": {"actor_id": 6, "value": 1, "time": 1}}],
"next_scenes": [9]})");
  text = edit(text, R"("type": "waypoint", "wp_id": "Waypoint01", "wp_idx": 20})",
              R"("type": "distance", "target_actor_id": 5, "distance": 10}, "start_speed": {"type": "relative", "target_actor_id": 4, "value": 0})");
  const auto d = check_text(text);
  EXPECT_TRUE(has_error(d, "/scenario/scenes/0/conditions/and/0/collision", 11, "actor_id 7 is not defined"));
  EXPECT_TRUE(has_error(d, "/scenario/scenes/0/conditions/and/1/distance", 11, "target_actor_id 8 is not defined"));
  EXPECT_TRUE(has_error(d, "/scenario/scenes/0/actions/0/speed", 12, "target_actor_id 9 is not defined"));
  EXPECT_TRUE(has_error(d, "/scenario/scenes/0/actions/1/lane_offset", 13, "actor_id 6 is not defined"));
  EXPECT_TRUE(has_error(d, "/scenario/opening_scene/others/0/start_position", 6, "target_actor_id 5 is not defined"));
  EXPECT_TRUE(has_error(d, "/scenario/opening_scene/others/0", 6, "target_actor_id 4 is not defined"));
  EXPECT_EQ(d.error_count(), 6) << d.format();
}

TEST(Validator, ConditionsOnAnyActorAreFine) {
  const auto d = check_text(with_conditions(R"({"or": [{"collision": {"actor_id": 2}}, {"collision": {"actor_id": 3}},
{"speed": {"actor_id": 2, "type": "absolute", "comparison": "<", "value": 1}}, {"speed": {"actor_id": 3, "type": "relative", "target_actor_id": 1, "comparison": "<", "value": 1}}]})"));
  EXPECT_EQ(d.items().size(), 0u) << d.format();
}

TEST(Validator, DistancesAndRelativeSpeedsToTheActorItself) {
  const auto d = check_text(with_scene(R"({"scene_id": 1,
"conditions": {"and": [{"distance": {"actor_id": 0, "comparison": "<", "value": 3}}, {"speed": {"actor_id": 1, "type": "relative", "target_actor_id": 1, "comparison": "<", "value": 1}}]},
"actions": [{"traveled_distance": {"actor_id": 0, "value": 10}}, {"speed": {"actor_id": 1, "type": "relative", "target_actor_id": 1, "value": 1}}],
"next_scenes": [9]})"));
  EXPECT_TRUE(has_error(d, "/scenario/scenes/0/conditions/and/0/distance", 11, "from actor 0 to itself"));
  EXPECT_TRUE(has_error(d, "/scenario/scenes/0/conditions/and/1/speed", 11, "of actor 1 to itself"));
  EXPECT_TRUE(has_error(d, "/scenario/scenes/0/actions/0/traveled_distance", 12, "from itself"));
  EXPECT_TRUE(has_error(d, "/scenario/scenes/0/actions/1/speed", 12, "relative to the actor itself"));
  EXPECT_EQ(d.error_count(), 4) << d.format();
}

// ---------------------------------------------------------------- waypoints
TEST(Validator, UnknownRoutesGetSuggestions) {
  auto text = with_actions(R"([{"lane_change": {"actor_id": 1, "wp_id": "Waypoint5", "time": 2}}])");
  text = edit(text, R"("wp_id": "Waypoint01", "wp_idx": 20)", R"("wp_id": "Waypoint1", "wp_idx": 20)");
  const auto d = check_text(text);
  EXPECT_TRUE(has_error(d, "/scenario/opening_scene/others/0/start_position", 6,
                        "wp_id \"Waypoint1\" is not a route of the map's waypoint file tiny.waypoint.json (did you "
                        "mean \"Waypoint01\"?)"));
  EXPECT_TRUE(has_error(d, "/scenario/scenes/0/actions/0/lane_change", 10, "wp_id \"Waypoint5\" is not a route"));
  EXPECT_EQ(d.error_count(), 2) << d.format();
}

TEST(Validator, PlacementsMustLieOnTheRoute) {
  auto text = with_actions(R"([{"route_move": {"actor_id": 2, "type": "waypoint", "route": [{"time": 1, "wp_id": "Waypoint03", "wp_idx": 100.5}]}}])");
  text = edit(text, R"("wp_id": "Waypoint02", "wp_idx": 5)", R"("wp_id": "Waypoint02", "wp_idx": -1)");
  text = edit(text, R"("wp_id": "Waypoint01", "wp_idx": 20)", R"("wp_id": "Waypoint01", "wp_idx": 101)");
  const auto d = check_text(text);
  EXPECT_TRUE(has_error(d, "/scenario/opening_scene/ego/start_position", 5, "wp_idx -1 is negative"));
  EXPECT_TRUE(has_error(d, "/scenario/opening_scene/others/0/start_position", 6,
                        "wp_idx 101 is past the end of route \"Waypoint01\" (last index 100): an actor cannot be "
                        "placed there"));
  EXPECT_TRUE(has_error(d, "/scenario/scenes/0/actions/0/route_move/route/0", 10, "wp_idx 100.5 is past the end"));
  EXPECT_EQ(d.error_count(), 3) << d.format();
}

TEST(Validator, TargetsPastTheRouteAreWarningsUnlessStrict) {
  auto text = with_conditions(R"({"or": [{"position": {"actor_id": 0, "type": "reach", "wp_id": "Waypoint02", "wp_idx": 10000, "tolerance": 1}},
{"time_headway": {"actor_id": 0, "wp_id": "Waypoint02", "wp_idx": 100, "comparison": "<", "value": 1}}]})");
  text = edit(text, R"("wp_idx": 5}})", R"("wp_idx": 5}, "end_position": {"wp_id": "Waypoint02", "wp_idx": 150}})");
  auto d = check_text(text);
  EXPECT_TRUE(has_warning(d, "/scenario/opening_scene/ego/end_position", 5,
                          "wp_idx 150 is past the end of route \"Waypoint02\" (last index 100); it will mean the "
                          "route's last point"));
  EXPECT_TRUE(has_warning(d, "/scenario/scenes/0/conditions/or/0/position", 10, "wp_idx 10000 is past the end"));
  EXPECT_EQ(d.error_count(), 0) << d.format();
  EXPECT_EQ(d.warning_count(), 2) << d.format();  // wp_idx 100 is the last point: fine

  d = check_text(text, strict());
  EXPECT_TRUE(has_error(d, "/scenario/opening_scene/ego/end_position", 5, "strict"));
  EXPECT_TRUE(has_error(d, "/scenario/scenes/0/conditions/or/0/position", 10, "strict"));
  EXPECT_EQ(d.warning_count(), 0) << d.format();
}

TEST(Validator, WithoutWaypointsTheRestIsStillChecked) {
  const auto loaded = load_text(edit(with_actions("[]"), "vehicle.audi.tt", "vehicle.audi.ttt"));
  ASSERT_TRUE(loaded.scenario.has_value());
  const auto d = check_scenario(*loaded.scenario, WaypointFile{}, Catalog::embedded());
  EXPECT_EQ(d.error_count(), 1) << d.format();
  EXPECT_TRUE(has_error(d, "/actors/others/0", 3, "not in the model catalog"));
}

// ---------------------------------------------------------------- scene graph
TEST(Validator, SceneIdsUniqueAndNotZero) {
  auto text = with_scene(R"({"scene_id": 1, "next_scenes": [9]},
{"scene_id": 9, "next_scenes": [1]},
{"scene_id": 0, "next_scenes": [9]})");
  const auto d = check_text(text);
  EXPECT_TRUE(has_error(d, "/scenario/ending_scenes/0", 14, "scene_id 9 is used twice"));
  EXPECT_TRUE(has_error(d, "/scenario/scenes/2", 12, "scene_id 0 is the opening scene's id"));
}

TEST(Validator, NextScenesMustExistAndLeadSomewhere) {
  const auto d = check_text(with_scene(R"({"scene_id": 1, "next_scenes": [4, 9, 9]},
{"scene_id": 2, "next_scenes": []})"));
  EXPECT_TRUE(has_error(d, "/scenario/scenes/0", 10, "next_scenes of scene 1 names scene 4, which is not defined "
                                                     "(scene ids: 1, 2, 9)"));
  EXPECT_TRUE(has_warning(d, "/scenario/scenes/0", 10, "names scene 9 twice"));
  EXPECT_TRUE(has_error(d, "/scenario/scenes/1", 11, "scene 2 has no next_scenes"));
  EXPECT_TRUE(has_error(d, "/scenario/scenes/1", 11, "scene 2 can never be reached"));
  EXPECT_EQ(d.error_count(), 3) << d.format();
}

TEST(Validator, UnreachableEndingAndNoReachableEnding) {
  auto text = with_scene(R"({"scene_id": 1, "next_scenes": [2]},
{"scene_id": 2, "next_scenes": [1]})");
  auto d = check_text(text);
  EXPECT_TRUE(has_error(d, "/scenario/ending_scenes/0", 13, "ending scene 9 can never be reached"));
  EXPECT_TRUE(has_error(d, "/scenario/opening_scene", 5, "no ending scene can be reached"));
  EXPECT_EQ(d.error_count(), 2) << d.format();

  d = check_text(edit(with_actions("[]"), R"("ending_scenes": [{"scene_id": 9}])", R"("ending_scenes": [])"));
  EXPECT_TRUE(has_error(d, "/scenario/opening_scene", 5, "the scenario has no ending scene"));
  EXPECT_TRUE(has_error(d, "/scenario/scenes/0", 10, "names scene 9, which is not defined"));
}

TEST(Validator, OpeningWithoutNextScenes) {
  const auto d = check_text(edit(with_actions("[]"), "}}],\n\"next_scenes\": [1]},", "}}]},"));
  EXPECT_TRUE(has_error(d, "/scenario/opening_scene", 5, "the opening scene has no next_scenes"));
  EXPECT_TRUE(has_error(d, "/scenario/scenes/0", 9, "scene 1 can never be reached"));  // one line less
}

TEST(Validator, ALoopThatCannotEndIsAWarning) {
  const auto d = check_text(with_scene(R"({"scene_id": 1, "next_scenes": [2, 9]},
{"scene_id": 2, "next_scenes": [3]},
{"scene_id": 3, "next_scenes": [2]})"));
  EXPECT_EQ(d.error_count(), 0) << d.format();
  EXPECT_TRUE(has_warning(d, "/scenario/scenes/1", 11, "no ending scene can be reached from scene 2"));
  EXPECT_TRUE(has_warning(d, "/scenario/scenes/2", 12, "no ending scene can be reached from scene 3"));
}

// ---------------------------------------------------------------- start positions by distance
TEST(Validator, StartPositionsRelativeToThemselvesOrInACycle) {
  auto text = edit(with_actions("[]"), R"({"actor_id": 1, "start_position": {"type": "waypoint", "wp_id": "Waypoint01", "wp_idx": 20}})",
                   R"({"actor_id": 1, "start_position": {"type": "distance", "target_actor_id": 3, "distance": 5}})");
  text = edit(text, R"({"actor_id": 3, "start_position": {"type": "waypoint", "wp_id": "Waypoint02", "wp_idx": 80}})",
              R"({"actor_id": 3, "start_position": {"type": "distance", "target_actor_id": 1, "distance": 5}})");
  text = edit(text, R"({"actor_id": 2, "start_position": {"type": "waypoint", "wp_id": "Waypoint03", "wp_idx": 50}})",
              R"({"actor_id": 2, "start_position": {"type": "distance", "target_actor_id": 2, "distance": 5}})");
  const auto d = check_text(text);
  EXPECT_TRUE(has_error(d, "/scenario/opening_scene/others/0/start_position", 6, "form a cycle (1 -> 3 -> 1)"));
  EXPECT_TRUE(has_error(d, "/scenario/opening_scene/others/1/start_position", 6, "measured from the actor itself"));
  EXPECT_EQ(d.error_count(), 2) << d.format();
}

TEST(Validator, AChainOfDistancesEndingAtAWaypointIsFine) {
  auto text = edit(with_actions("[]"), R"({"actor_id": 1, "start_position": {"type": "waypoint", "wp_id": "Waypoint01", "wp_idx": 20}})",
                   R"({"actor_id": 1, "start_position": {"type": "distance", "target_actor_id": 3, "distance": 5}})");
  text = edit(text, R"({"actor_id": 3, "start_position": {"type": "waypoint", "wp_id": "Waypoint02", "wp_idx": 80}})",
              R"({"actor_id": 3, "start_position": {"type": "distance", "distance": 5}})");
  const auto d = check_text(text);
  EXPECT_EQ(d.items().size(), 0u) << d.format();
}

// ---------------------------------------------------------------- what actors can do
TEST(Validator, ActionsThatMakeNoSenseForPedestriansAndObstacles) {
  const auto d = check_text(with_actions(R"([
{"lane_change": {"actor_id": 2, "wp_id": "Waypoint02", "time": 3}},
{"light_state": {"actor_id": 2, "blinker_left": true}},
{"lane_offset": {"actor_id": 2, "value": 1, "time": 1}},
{"speed": {"actor_id": 3, "type": "absolute", "value": 10}},
{"sound_state": {"actor_id": 3, "sound": true}},
{"route_move": {"actor_id": 2, "type": "waypoint", "route": [{"time": 4, "wp_id": "Waypoint02", "wp_idx": 50}]}},
{"speed": {"actor_id": 2, "type": "absolute", "value": 5}}])"));
  EXPECT_TRUE(has_error(d, "/scenario/scenes/0/actions/0/lane_change", 11,
                        "lane_change on actor 2, which is a pedestrian (model \"walker.pedestrian.0001\")"));
  EXPECT_TRUE(has_error(d, "/scenario/scenes/0/actions/1/light_state", 12, "which is a pedestrian"));
  EXPECT_TRUE(has_error(d, "/scenario/scenes/0/actions/2/lane_offset", 13, "which is a pedestrian"));
  EXPECT_TRUE(has_error(d, "/scenario/scenes/0/actions/3/speed", 14, "which is an obstacle"));
  EXPECT_TRUE(has_error(d, "/scenario/scenes/0/actions/4/sound_state", 15, "does not move or signal"));
  EXPECT_EQ(d.error_count(), 5) << d.format();  // route_move and speed on a pedestrian are fine
}

TEST(Validator, SirenAndSpecialLightsOnOrdinaryCarsWarn) {
  auto text = with_actions(R"([{"light_state": {"actor_id": 1, "special1": true}}, {"sound_state": {"actor_id": 1, "sound": true}},
{"light_state": {"actor_id": 1, "blinker_right": true}}])");
  auto d = check_text(text);
  EXPECT_TRUE(has_warning(d, "/scenario/scenes/0/actions/0/light_state", 10, "not an emergency vehicle"));
  EXPECT_TRUE(has_warning(d, "/scenario/scenes/0/actions/1/sound_state", 10, "not an emergency vehicle"));
  EXPECT_EQ(d.warning_count(), 2) << d.format();
  d = check_text(edit(text, "vehicle.audi.tt", "vehicle.garden.gpolicecarjp"));
  EXPECT_EQ(d.items().size(), 0u) << d.format();
}

// ---------------------------------------------------------------- value ranges
TEST(Validator, NegativeTimesDurationsAndTolerances) {
  const auto d = check_text(with_scene(R"({"scene_id": 1, "duration": -1,
"conditions": {"or": [{"position": {"actor_id": 1, "wp_id": "Waypoint01", "wp_idx": 30, "tolerance": -2}}]},
"actions": [{"lane_change": {"actor_id": 1, "wp_id": "Waypoint02", "time": -3}}, {"lane_change": {"actor_id": 1, "wp_id": "Waypoint02", "time": 0}},
{"lane_offset": {"actor_id": 1, "value": 1, "time": -1}},
{"route_move": {"actor_id": 1, "type": "wp_offset", "route": [{"time": -2, "wp_offset": 1}]}}],
"next_scenes": [9]})"));
  EXPECT_TRUE(has_error(d, "/scenario/scenes/0", 10, "\"duration\" is -1 s; it must be >= 0"));
  EXPECT_TRUE(has_error(d, "/scenario/scenes/0/conditions/or/0/position", 11, "\"tolerance\" is -2 m"));
  EXPECT_TRUE(has_error(d, "/scenario/scenes/0/actions/0/lane_change", 12, "\"time\" is -3 s"));
  EXPECT_TRUE(has_error(d, "/scenario/scenes/0/actions/2/lane_offset", 13, "\"time\" is -1 s"));
  EXPECT_TRUE(has_error(d, "/scenario/scenes/0/actions/3/route_move/route/0", 14, "\"time\" is -2 s"));
  EXPECT_EQ(d.error_count(), 5) << d.format();  // lane_change time 0 (instant) is fine
}

TEST(Validator, SpeedsAccelerationsAndHandOverRanges) {
  const auto d = check_text(with_actions(R"([
{"speed": {"actor_id": 1, "type": "absolute", "value": -10}},
{"speed": {"actor_id": 1, "type": "absolute", "value": 10, "accel": {"type": "specify", "value": 0}}},
{"speed": {"actor_id": 1, "type": "relative", "value": -10}},
{"hand_over": {"actor_id": 1, "hand_over": true, "throttle": 1.5, "brake": -0.1, "steer": -1}}])"));
  EXPECT_TRUE(has_error(d, "/scenario/scenes/0/actions/0/speed", 11, "an absolute speed must be >= 0, found -10 km/h"));
  EXPECT_TRUE(has_error(d, "/scenario/scenes/0/actions/1/speed", 12, "must be > 0"));
  EXPECT_TRUE(has_error(d, "/scenario/scenes/0/actions/3/hand_over", 14, "hand_over applies to the ego"));
  EXPECT_TRUE(has_error(d, "/scenario/scenes/0/actions/3/hand_over", 14, "\"throttle\" is 1.5"));
  EXPECT_TRUE(has_error(d, "/scenario/scenes/0/actions/3/hand_over", 14, "\"brake\" is -0.1"));
  EXPECT_EQ(d.error_count(), 5) << d.format();  // relative -10 and steer -1 are fine
}

TEST(Validator, StopConditionsThatAlwaysHoldWarn) {
  const auto d = check_text(edit(with_actions("[]"), R"("stop_conditions": {"or": [{"simulation_time": {"comparison": ">=", "value": 60}}]})",
                                 R"("stop_conditions": {})"));
  EXPECT_TRUE(has_warning(d, "/stop_conditions", 14, "always holds"));
  EXPECT_EQ(d.items().size(), 1u) << d.format();
}

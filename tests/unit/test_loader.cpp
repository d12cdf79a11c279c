// The loader on whole files: top level, actors, scenes, and what it does with bad input.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "scenario_executor/loader_internal.hpp"
#include "test_loader_support.hpp"

using namespace orch;
using namespace orch::scenario;
using namespace orch::loader_test;

TEST(Loader, TheBaseTextLoadsCleanly) {
  const auto loaded = load_text(with_actions("[]"));
  ASSERT_TRUE(loaded.scenario.has_value()) << loaded.diagnostics.format();
  EXPECT_EQ(loaded.diagnostics.items().size(), 0u) << loaded.diagnostics.format();
  const Scenario& s = *loaded.scenario;
  EXPECT_EQ(s.file, "s.json");
  EXPECT_EQ(s.map_id, "tiny");
  EXPECT_TRUE(s.ego.is_ego);
  EXPECT_EQ(s.others.size(), 3u);
  ASSERT_EQ(s.scenes.size(), 2u);
  EXPECT_FALSE(s.scenes[0].ending);
  EXPECT_TRUE(s.scenes[1].ending);
  EXPECT_EQ(s.scenes[1].id, 9);
  EXPECT_EQ(s.scenes[0].where.pointer, "/scenario/scenes/0");
  EXPECT_EQ(s.scenes[0].where.line, 10);
  EXPECT_EQ(s.scenes[1].where.pointer, "/scenario/ending_scenes/0");
  EXPECT_EQ(s.scenes[1].where.line, 12);
  // A scene without "conditions" is always true: an empty And group, located at the scene.
  EXPECT_TRUE(s.scenes[0].conditions.items.empty());
  EXPECT_EQ(s.scenes[0].conditions.logic, Logic::And);
  EXPECT_EQ(s.scenes[0].conditions.where.pointer, "/scenario/scenes/0");
}

TEST(Loader, TitleDescriptionsAndActorsAreKept) {
  const auto loaded = load_text(R"({
  "title": "T",
  "description": "D",
  "map_id": "m",
  "actors": {
    "ego": {"description": "Ego", "actor_id": 7, "model_id": "vehicle.toyota.prius", "color": "000000"},
    "others": [
      {"description": "Lead", "actor_id": 1, "model_id": "vehicle.audi.tt", "color": "FF00aa"}
    ]
  },
  "scenario": {"opening_scene": {"ego": {"start_position": {"wp_id": "A", "wp_idx": 0}}, "others": [], "next_scenes": [2]},
               "ending_scenes": [{"description": "end", "scene_id": 2}]}
})");
  ASSERT_TRUE(loaded.scenario) << loaded.diagnostics.format();
  const Scenario& s = *loaded.scenario;
  EXPECT_EQ(s.title, "T");
  EXPECT_EQ(s.description, "D");
  EXPECT_EQ(s.ego.id, 7);
  EXPECT_EQ(s.ego.description, "Ego");
  EXPECT_EQ(s.ego.color, "000000");
  EXPECT_EQ(s.ego.where.pointer, "/actors/ego");
  EXPECT_EQ(s.ego.where.line, 6);
  ASSERT_EQ(s.others.size(), 1u);
  EXPECT_FALSE(s.others[0].is_ego);
  EXPECT_EQ(s.others[0].color, "FF00aa");
  EXPECT_EQ(s.others[0].description, "Lead");
  EXPECT_EQ(s.others[0].where.line, 8);
  EXPECT_EQ(s.scenes.at(0).description, "end");
  EXPECT_FALSE(s.stop_conditions.has_value());
}

TEST(Loader, MissingTopLevelBlocksAreReportedAtTheRoot) {
  const auto loaded = load_text("{\n  \"title\": \"x\"\n}\n");
  EXPECT_FALSE(loaded.scenario.has_value());
  EXPECT_TRUE(has_error(loaded.diagnostics, "", 1, "needs \"map_id\""));
  EXPECT_TRUE(has_error(loaded.diagnostics, "", 1, "needs \"actors\""));
  EXPECT_TRUE(has_error(loaded.diagnostics, "", 1, "needs \"scenario\""));
  EXPECT_EQ(loaded.diagnostics.error_count(), 3);
}

TEST(Loader, UnknownTopLevelKeySuggestsTheRightOne) {
  auto text = with_actions("[]");
  text.replace(text.find("\"stop_conditions\""), 17, "\"stop_conditons\"");
  const auto loaded = load_text(text);
  EXPECT_TRUE(has_error(loaded.diagnostics, "/stop_conditons", 14, "did you mean \"stop_conditions\"?"));
  EXPECT_FALSE(loaded.scenario.has_value());
}

TEST(Loader, StopConditionsInsideTheScenarioBlockSaysWhereItBelongs) {
  auto text = with_actions("[]");
  text.replace(text.find("\"ending_scenes\""), 0, "\"stop_conditions\": {},\n");
  const auto loaded = load_text(text);
  EXPECT_TRUE(has_error(loaded.diagnostics, "/scenario/stop_conditions", 12, "belongs at the top level"));
}

TEST(Loader, ScalarRootIsOneErrorAndNoCrash) {
  for (const char* text : {"[1, 2]", "42", "\"x\"", "null"}) {
    const auto loaded = load_text(text);
    EXPECT_FALSE(loaded.scenario.has_value());
    EXPECT_EQ(loaded.diagnostics.error_count(), 1) << loaded.diagnostics.format();
    EXPECT_TRUE(has_error(loaded.diagnostics, "", 1, "expected the scenario file as an object"));
  }
}

TEST(Loader, WrongTypesEverywhereAreReportedWithoutCrashing) {
  const auto loaded = load_text(R"({
  "map_id": 3,
  "actors": {"ego": [], "others": {}},
  "scenario": {
    "opening_scene": {"ego": 1, "others": [7, {"actor_id": "1"}], "next_scenes": "1"},
    "scenes": [null, {"scene_id": 1.5, "duration": "long", "actions": {}, "next_scenes": [true]}],
    "ending_scenes": {}
  },
  "stop_conditions": []
})");
  const auto& d = loaded.diagnostics;
  EXPECT_FALSE(loaded.scenario.has_value());
  EXPECT_TRUE(has_error(d, "/map_id", 2, "\"map_id\" must be a string, found a number"));
  EXPECT_TRUE(has_error(d, "/actors/ego", 3, "\"ego\" must be an object, found an array"));
  EXPECT_TRUE(has_error(d, "/actors/others", 3, "\"others\" must be an array, found an object"));
  EXPECT_TRUE(has_error(d, "/scenario/opening_scene/ego", 5, "must be an object, found a number"));
  EXPECT_TRUE(has_error(d, "/scenario/opening_scene/others/0", 5, "found a number"));
  EXPECT_TRUE(has_error(d, "/scenario/opening_scene/others/1/actor_id", 5, "must be a whole number, found a string"));
  EXPECT_TRUE(has_error(d, "/scenario/opening_scene/next_scenes", 5, "must be an array, found a string"));
  EXPECT_TRUE(has_error(d, "/scenario/scenes/0", 6, "expected the scene as an object, found null"));
  EXPECT_TRUE(has_error(d, "/scenario/scenes/1/scene_id", 6, "must be a whole number, found 1.5"));
  EXPECT_TRUE(has_error(d, "/scenario/scenes/1/duration", 6, "must be a number, found a string"));
  EXPECT_TRUE(has_error(d, "/scenario/scenes/1/actions", 6, "must be an array, found an object"));
  EXPECT_TRUE(has_error(d, "/scenario/scenes/1/next_scenes/0", 6, "whole number (a scene_id), found a boolean"));
  EXPECT_TRUE(has_error(d, "/scenario/ending_scenes", 7, "must be an array, found an object"));
  EXPECT_TRUE(has_error(d, "/stop_conditions", 9, "conditions must be an object"));
}

TEST(Loader, BadColourAndEmptyModelId) {
  const auto loaded = load_text(R"({"map_id": "m",
"actors": {"ego": {"actor_id": 0, "model_id": "", "color": "#ff0000"}},
"scenario": {"opening_scene": {"ego": {"start_position": {"wp_id": "A", "wp_idx": 0}}, "next_scenes": [1]},
             "ending_scenes": [{"scene_id": 1}]}})");
  EXPECT_TRUE(has_error(loaded.diagnostics, "/actors/ego/color", 2, "six hex digits \"rrggbb\""));
  EXPECT_TRUE(has_error(loaded.diagnostics, "/actors/ego/model_id", 2, "must not be empty"));
}

TEST(Loader, EndingSceneWithActionsOrNextScenesIsAnError) {
  auto text = with_actions("[]");
  text.replace(text.find("{\"scene_id\": 9}"), 15,
               R"({"scene_id": 9, "actions": [{"speed": {"actor_id": 1, "type": "absolute", "value": 1}}],
"next_scenes": [1], "duration": 2})");
  const auto loaded = load_text(text);
  EXPECT_TRUE(has_error(loaded.diagnostics, "/scenario/ending_scenes/0/actions", 12, "an ending scene has no actions"));
  EXPECT_TRUE(has_error(loaded.diagnostics, "/scenario/ending_scenes/0/next_scenes", 13,
                        "an ending scene has no \"next_scenes\""));
  EXPECT_TRUE(has_warning(loaded.diagnostics, "/scenario/ending_scenes/0/duration", 13, "no effect"));
  EXPECT_EQ(loaded.diagnostics.error_count(), 2) << loaded.diagnostics.format();
}

TEST(Loader, EndingSceneWithAnEmptyActionListIsAccepted) {
  auto text = with_actions("[]");
  text.replace(text.find("{\"scene_id\": 9}"), 15, R"({"scene_id": 9, "actions": []})");
  const auto loaded = load_text(text);
  EXPECT_TRUE(loaded.scenario.has_value()) << loaded.diagnostics.format();
}

TEST(Loader, UnreadableFileIsADiagnosticNotAnException) {
  const auto loaded = load_scenario("/nonexistent/dir/s.json");
  EXPECT_FALSE(loaded.scenario.has_value());
  ASSERT_EQ(loaded.diagnostics.error_count(), 1);
  EXPECT_EQ(loaded.diagnostics.items()[0].where.file, "/nonexistent/dir/s.json");
  EXPECT_NE(loaded.diagnostics.items()[0].message.find("cannot open"), std::string::npos);
}

TEST(Loader, InvalidJsonAndDuplicateKeysFromAFile) {
  const auto dir = std::filesystem::temp_directory_path() / "orch_loader_test";
  std::filesystem::create_directories(dir);
  const auto bad = (dir / "bad.json").string();
  std::ofstream(bad) << "{\n  \"map_id\": \"a\",\n  \"map_id\": \"b\"\n}\n";
  auto loaded = load_scenario(bad);
  ASSERT_EQ(loaded.diagnostics.error_count(), 1);
  EXPECT_EQ(loaded.diagnostics.items()[0].where.pointer, "/map_id");
  EXPECT_EQ(loaded.diagnostics.items()[0].where.line, 3);
  EXPECT_NE(loaded.diagnostics.items()[0].message.find("duplicate key"), std::string::npos);

  std::ofstream(bad) << "{\n  \"map_id\": \"a\",\n  \"actors\": {,\n}\n";
  loaded = load_scenario(bad);
  ASSERT_EQ(loaded.diagnostics.error_count(), 1);
  EXPECT_EQ(loaded.diagnostics.items()[0].where.line, 3);
  EXPECT_NE(loaded.diagnostics.items()[0].message.find("invalid JSON"), std::string::npos);
  std::filesystem::remove_all(dir);
}

TEST(Loader, ErrorsInOnePartDoNotHideErrorsInAnother) {
  auto text = with_actions(R"([{"lane_chnage": {}}])");
  text.replace(text.find("\"vehicle.audi.tt\""), 17, "5");
  const auto loaded = load_text(text);
  EXPECT_TRUE(has_error(loaded.diagnostics, "/actors/others/0/model_id", 3, "must be a string"));
  EXPECT_TRUE(has_error(loaded.diagnostics, "/scenario/scenes/0/actions/0/lane_chnage", 10,
                        "did you mean \"lane_change\"?"));
}

// The best-effort model `validate` checks references on: kept even with errors, and it
// says whether everything with an id could be read.
TEST(Loader, BestEffortModelSaysWhetherItsSkeletonIsComplete) {
  Diagnostics d1;
  auto text = with_actions(R"([{"lane_chnage": {}}])");
  auto read = scenario_loading::read_scenario(JsonDocument::parse(text, "s.json"), d1);
  EXPECT_TRUE(d1.has_errors());
  EXPECT_TRUE(read.skeleton_complete);
  EXPECT_EQ(read.scenario.others.size(), 3u);
  EXPECT_TRUE(read.scenario.scenes.at(0).actions.empty());  // the bad action is left out

  Diagnostics d2;
  text = with_actions("[]");
  text.replace(text.find("\"scene_id\": 9"), 13, "\"scene_id\": \"9\"");
  read = scenario_loading::read_scenario(JsonDocument::parse(text, "s.json"), d2);
  EXPECT_FALSE(read.skeleton_complete);
  EXPECT_EQ(read.scenario.scenes.size(), 1u);
}

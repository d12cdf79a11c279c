// `orchestrator validate` as users run it: one small bad file per kind of mistake, each
// answered with file:line, the JSON pointer and the right suggestion, and the exit status.
#include <gtest/gtest.h>

#include <string>

#include "support/cli_runner.hpp"

using orch::test::CliResult;
using orch::test::run_cli;
using orch::test::TempDir;

namespace {

// A valid scenario; line numbers matter to the tests below.
const char* const kGood = R"({
  "title": "good",
  "map_id": "tiny",
  "actors": {
    "ego": {"actor_id": 0, "model_id": "vehicle.toyota.prius"},
    "others": [{"actor_id": 1, "model_id": "vehicle.audi.tt"}]
  },
  "scenario": {
    "opening_scene": {
      "ego": {"start_position": {"wp_id": "Waypoint02", "wp_idx": 5}},
      "others": [
        {
          "actor_id": 1,
          "start_position": {"type": "waypoint", "wp_id": "Waypoint01", "wp_idx": 20},
          "start_speed": {"type": "relative", "target_actor_id": 0, "value": 0}
        }
      ],
      "next_scenes": [1]
    },
    "scenes": [
      {
        "scene_id": 1,
        "conditions": {"or": [{"simulation_time": {"comparison": ">=", "value": 2}}]},
        "actions": [{"lane_change": {"actor_id": 1, "type": "lane", "wp_id": "Waypoint02", "time": 3}}],
        "next_scenes": [2]
      }
    ],
    "ending_scenes": [{"scene_id": 2, "conditions": {"or": [{"collision": {"actor_id": 0}}]}}]
  },
  "stop_conditions": {"or": [{"simulation_time": {"comparison": ">=", "value": 60}}]}
}
)";

std::string replaced(const std::string& from, const std::string& to) {
  std::string text = kGood;
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

class ValidateCli : public testing::Test {
 protected:
  void SetUp() override {
    // A synthetic map: three straight 101-point routes; the net file need not exist.
    std::string routes;
    for (int lane = 1; lane <= 3; ++lane) {
      std::string points;
      for (int i = 0; i <= 100; ++i)
        points += (i ? "," : "") + std::string("{\"x\":") + std::to_string(i) + ",\"y\":0,\"z\":" +
                  std::to_string(-4 * lane) + ",\"v\":60}";
      routes += (lane > 1 ? "," : "") + std::string("{\"id\":\"Waypoint0") + std::to_string(lane) +
                "\",\"points\":[" + points + "]}";
    }
    std::filesystem::create_directories(dir_ / "maps" / "tiny");
    dir_.write("maps/tiny/tiny.waypoint.json", R"({"id": "WayPoint_tiny", "mapId": "tiny.map", "waypoints": [)" +
                                                   routes + "]}");
    dir_.write("maps/tiny/map.json", R"({"id": "tiny", "aliases": ["tiny.map"], "waypoint_file": "tiny.waypoint.json",
                                        "net_file": "tiny.net.xml"})");
  }

  // validate FILE... --maps DIR (--maps last: it takes every value that follows it)
  CliResult validate(const std::vector<std::string>& files, const std::vector<std::string>& extra = {}) {
    std::vector<std::string> args{"validate"};
    for (const auto& f : files) args.push_back((dir_ / f).string());
    args.insert(args.end(), extra.begin(), extra.end());
    args.push_back("--maps");
    args.push_back((dir_ / "maps").string());
    return run_cli(args);
  }

  CliResult validate_text(const std::string& name, const std::string& text,
                          const std::vector<std::string>& extra = {}) {
    dir_.write(name, text);
    return validate({name}, extra);
  }

  // "PATH:LINE: error: POINTER: " of a file in the temp dir.
  std::string at(const std::string& name, int line, const std::string& pointer, const char* kind = "error") {
    return (dir_ / name).string() + ":" + std::to_string(line) + ": " + kind + ": " + pointer + ": ";
  }

  TempDir dir_;
};

#define EXPECT_OUTPUT_HAS(result, text) \
  EXPECT_NE((result).output.find(text), std::string::npos) << "missing: " << (text) << "\nin:\n" << (result).output

}  // namespace

TEST_F(ValidateCli, GoodFileExitsZero) {
  const auto r = validate_text("good.json", kGood);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(r.output, (dir_ / "good.json").string() + ": valid, 0 errors, 0 warnings\n");
}

TEST_F(ValidateCli, MapFoundByAlias) {
  const auto r = validate_text("alias.json", replaced("\"map_id\": \"tiny\"", "\"map_id\": \"tiny.map\""));
  EXPECT_EQ(r.exit_code, 0) << r.output;
}

TEST_F(ValidateCli, MisspeltKeySuggestsTheRightOne) {
  const auto r = validate_text("vlaue.json", replaced("\"target_actor_id\": 0, \"value\": 0", "\"target_actor_id\": 0, \"vlaue\": 0"));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_OUTPUT_HAS(r, at("vlaue.json", 15, "/scenario/opening_scene/others/0/start_speed/vlaue") +
                           "unknown key \"vlaue\" in the start speed (did you mean \"value\"?)");
  EXPECT_OUTPUT_HAS(r, at("vlaue.json", 15, "/scenario/opening_scene/others/0/start_speed") +
                           "the start speed needs \"value\" (a number)");
  EXPECT_OUTPUT_HAS(r, (dir_ / "vlaue.json").string() + ": INVALID, 2 errors, 0 warnings");
}

TEST_F(ValidateCli, NextScenesInsideAnOthersEntry) {
  const auto r = validate_text(
      "next.json", replaced("\"target_actor_id\": 0, \"value\": 0}", "\"target_actor_id\": 0, \"value\": 0},\n\"next_scenes\": [1]"));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_OUTPUT_HAS(r, at("next.json", 16, "/scenario/opening_scene/others/0/next_scenes") +
                           "\"next_scenes\" belongs directly under \"opening_scene\"");
}

TEST_F(ValidateCli, UnknownMapSuggestsAKnownOne) {
  const auto r = validate_text("map.json", replaced("\"map_id\": \"tiny\"", "\"map_id\": \"tyni\""));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_OUTPUT_HAS(r, at("map.json", 3, "/map_id") + "no map \"tyni\" (did you mean \"tiny\"?); known maps: \"tiny\" or \"tiny.map\"");
  // Everything else is still checked: the file has no other problem.
  EXPECT_OUTPUT_HAS(r, ": INVALID, 1 error, 0 warnings");
}

TEST_F(ValidateCli, UnknownRouteSuggestsTheNearest) {
  const auto r = validate_text("route.json", replaced("\"wp_id\": \"Waypoint01\"", "\"wp_id\": \"Waypoint1\""));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_OUTPUT_HAS(r, at("route.json", 14, "/scenario/opening_scene/others/0/start_position") +
                           "wp_id \"Waypoint1\" is not a route");
  EXPECT_OUTPUT_HAS(r, "(did you mean \"Waypoint01\"?)");
}

TEST_F(ValidateCli, UnknownActorAndModel) {
  auto text = replaced("\"lane_change\": {\"actor_id\": 1", "\"lane_change\": {\"actor_id\": 4");
  text.replace(text.find("vehicle.audi.tt"), 15, "vehicle.audi.t");
  const auto r = validate_text("actor.json", text);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_OUTPUT_HAS(r, at("actor.json", 24, "/scenario/scenes/0/actions/0/lane_change") +
                           "actor_id 4 is not defined under \"actors\" (defined: 0 and 1)");
  EXPECT_OUTPUT_HAS(r, at("actor.json", 6, "/actors/others/0") +
                           "model_id \"vehicle.audi.t\" is not in the model catalog (did you mean \"vehicle.audi.tt\"?)");
}

TEST_F(ValidateCli, InvalidJsonAndDuplicateKeys) {
  auto r = validate_text("syntax.json", replaced("\"title\": \"good\",", "\"title\": \"good\""));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_OUTPUT_HAS(r, at("syntax.json", 3, "/") + "invalid JSON");
  r = validate_text("dup.json", replaced("\"title\": \"good\",", "\"title\": \"good\",\n  \"title\": \"again\","));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_OUTPUT_HAS(r, at("dup.json", 3, "/title") + "duplicate key");
}

TEST_F(ValidateCli, EndingSceneWithActions) {
  const auto r = validate_text(
      "ending.json", replaced("{\"scene_id\": 2,", "{\"scene_id\": 2, \"actions\": [{\"lane_change\": {\"actor_id\": 1, \"wp_id\": \"Waypoint03\", \"time\": 3}}],"));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_OUTPUT_HAS(r, at("ending.json", 28, "/scenario/ending_scenes/0/actions") + "an ending scene has no actions");
}

TEST_F(ValidateCli, UnreachableSceneAndMissingTarget) {
  const auto r = validate_text("graph.json", replaced("\"next_scenes\": [1]", "\"next_scenes\": [3]"));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_OUTPUT_HAS(r, at("graph.json", 9, "/scenario/opening_scene") +
                           "next_scenes of the opening scene names scene 3, which is not defined (scene ids: 1, 2)");
  EXPECT_OUTPUT_HAS(r, at("graph.json", 21, "/scenario/scenes/0") + "scene 1 can never be reached");
}

TEST_F(ValidateCli, TwoActionsInOneObjectAndWrongShapes) {
  auto text = replaced("\"actions\": [{\"lane_change\"", "\"actions\": [{\"speed\": {\"actor_id\": 1, \"type\": \"absolute\", \"value\": 50}, \"lane_change\"");
  const std::string others_line = R"("others": [{"actor_id": 1, "model_id": "vehicle.audi.tt"}])";
  text.replace(text.find(others_line), others_line.size(), R"("others": {"actor_id": 1}, "x": [])");
  const auto r = validate_text("shape.json", text);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_OUTPUT_HAS(r, at("shape.json", 24, "/scenario/scenes/0/actions/0/lane_change") +
                           "one entry of \"actions\" holds exactly one action, found \"speed\" and \"lane_change\"");
  EXPECT_OUTPUT_HAS(r, at("shape.json", 6, "/actors/others") + "\"others\" must be an array, found an object");
  EXPECT_OUTPUT_HAS(r, at("shape.json", 6, "/actors/x") + "unknown key \"x\" in the actors");
}

TEST_F(ValidateCli, TargetPastTheRouteWarnsAndStrictFails) {
  const auto text = replaced("\"wp_idx\": 5}}", "\"wp_idx\": 5}, \"end_position\": {\"wp_id\": \"Waypoint02\", \"wp_idx\": 10000}}");
  auto r = validate_text("far.json", text);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_OUTPUT_HAS(r, at("far.json", 10, "/scenario/opening_scene/ego/end_position", "warning") +
                           "wp_idx 10000 is past the end of route \"Waypoint02\" (last index 100)");
  EXPECT_OUTPUT_HAS(r, ": valid, 0 errors, 1 warning");

  r = validate({"far.json"}, {"--quiet"});
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_EQ(r.output.find("warning:"), std::string::npos) << r.output;

  r = validate({"far.json"}, {"--strict"});
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_OUTPUT_HAS(r, at("far.json", 10, "/scenario/opening_scene/ego/end_position") + "wp_idx 10000");
}

TEST_F(ValidateCli, SeveralFilesOneSummaryEach) {
  dir_.write("a.json", kGood);
  dir_.write("b.json", replaced("\"comparison\": \">=\", \"value\": 2", "\"comparison\": \"=>\", \"value\": 2"));
  const auto r = validate({"a.json", "b.json"});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_OUTPUT_HAS(r, (dir_ / "a.json").string() + ": valid, 0 errors, 0 warnings");
  EXPECT_OUTPUT_HAS(r, at("b.json", 23, "/scenario/scenes/0/conditions/or/0/simulation_time/comparison") +
                           "\"comparison\" is \"=>\", expected \">\", \">=\", \"=\", \"<=\" or \"<\" (did you mean \">=\"?)");
  EXPECT_OUTPUT_HAS(r, "2 files checked: 1 valid, 1 invalid");
}

TEST_F(ValidateCli, MapWithoutItsWaypointFile) {
  std::filesystem::remove(dir_ / "maps" / "tiny" / "tiny.waypoint.json");
  const auto r = validate_text("nowp.json", kGood);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_OUTPUT_HAS(r, at("nowp.json", 3, "/map_id") + "the waypoint file of map \"tiny\"");
  EXPECT_OUTPUT_HAS(r, "cannot open file for reading");
}

TEST_F(ValidateCli, BrokenUserCatalogStopsWithStatusTwo) {
  dir_.write("good.json", kGood);
  dir_.write("models.json", "{\n\"models\": [{\"id\": \"x\", \"kind\": \"car\", \"length\": 1, \"width\": 1, \"height\": 1}]}");
  const auto r = validate({"good.json"}, {"--catalog", (dir_ / "models.json").string()});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_OUTPUT_HAS(r, (dir_ / "models.json").string() + ":2: error: /models/0/kind: \"kind\" is \"car\"");
}

TEST_F(ValidateCli, UserCatalogReplacesTheBuiltInOne) {
  dir_.write("good.json", kGood);
  dir_.write("models.json", R"({"models": [{"id": "vehicle.*", "kind": "vehicle", "length": 4, "width": 2, "height": 1.5}]})");
  auto r = validate({"good.json"}, {"--catalog", (dir_ / "models.json").string()});
  EXPECT_EQ(r.exit_code, 0) << r.output;
  dir_.write("models.json", R"({"models": [{"id": "car.*", "kind": "vehicle", "length": 4, "width": 2, "height": 1.5}]})");
  r = validate({"good.json"}, {"--catalog", (dir_ / "models.json").string()});
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_OUTPUT_HAS(r, "model_id \"vehicle.toyota.prius\" is not in the model catalog");
}

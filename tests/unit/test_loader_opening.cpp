// The loader on the opening scene: ego and others' start positions and speeds, and the
// format document's own mistakes (next_scenes inside an others entry, "vlaue").
#include <gtest/gtest.h>

#include "test_loader_support.hpp"

using namespace orch;
using namespace orch::scenario;
using namespace orch::loader_test;

namespace {

// A file whose opening scene is `opening` (starting on line 4); actors 0 (ego), 1 and 2.
std::string with_opening(const std::string& opening) {
  return R"({"map_id": "tiny",
"actors": {"ego": {"actor_id": 0, "model_id": "vehicle.toyota.prius"}, "others": [{"actor_id": 1, "model_id": "vehicle.audi.tt"}, {"actor_id": 2, "model_id": "vehicle.audi.a2"}]},
"scenario": {
"opening_scene": )" + opening + R"(,
"ending_scenes": [{"scene_id": 1}]}}
)";
}

}  // namespace

TEST(LoaderOpening, EgoStartWithOffsetHeadingAndEnd) {
  const auto loaded = load_text(with_opening(R"({
"ego": {"start_position": {"type": "waypoint", "wp_id": "Waypoint02", "wp_idx": 5, "wp_offset": 0.5, "orientation": {"heading": 0.1}},
        "end_position": {"wp_id": "Waypoint02", "wp_idx": 95}},
"others": [{"actor_id": 1, "start_position": {"type": "waypoint", "wp_id": "Waypoint01", "wp_idx": 1}},
           {"actor_id": 2, "start_position": {"type": "waypoint", "wp_id": "Waypoint01", "wp_idx": 2}}],
"next_scenes": [1]})"));
  ASSERT_TRUE(loaded.scenario.has_value()) << loaded.diagnostics.format();
  const auto& opening = loaded.scenario->opening;
  EXPECT_EQ(opening.where.pointer, "/scenario/opening_scene");
  EXPECT_EQ(opening.where.line, 4);
  const auto& start = opening.ego.start;
  EXPECT_EQ(start.type, StartPositionType::Waypoint);
  EXPECT_EQ(start.waypoint->wp_id, "Waypoint02");
  EXPECT_DOUBLE_EQ(start.waypoint->wp_idx, 5);
  EXPECT_DOUBLE_EQ(start.wp_offset, 0.5);
  EXPECT_DOUBLE_EQ(start.heading.value(), 0.1);
  EXPECT_EQ(start.where.pointer, "/scenario/opening_scene/ego/start_position");
  EXPECT_EQ(start.where.line, 5);
  ASSERT_TRUE(opening.ego.end.has_value());
  EXPECT_DOUBLE_EQ(opening.ego.end->wp_idx, 95);
  EXPECT_EQ(opening.ego.end->where.line, 6);
  EXPECT_EQ(opening.next_scenes, std::vector<SceneId>{1});
  EXPECT_EQ(opening.others.at(1).where.line, 8);
}

TEST(LoaderOpening, OthersByWaypointAndByDistanceWithStartSpeeds) {
  const auto loaded = load_text(with_opening(R"({
"ego": {"start_position": {"wp_id": "Waypoint02", "wp_idx": 5}},
"others": [{"actor_id": 1, "description": "lead", "start_position": {"wp_id": "Waypoint01", "wp_idx": 33.33333333},
            "start_speed": {"type": "relative", "value": 0}},
           {"actor_id": 2, "start_position": {"type": "distance", "target_actor_id": 1, "distance": -20, "measure_type": "surface"},
            "start_speed": {"type": "absolute", "value": 54, "accel": {"type": "specify", "value": 2}}}],
"next_scenes": [1]})"));
  ASSERT_TRUE(loaded.scenario.has_value()) << loaded.diagnostics.format();
  const auto& others = loaded.scenario->opening.others;
  ASSERT_EQ(others.size(), 2u);
  // No type: a waypoint, as in the format document's example.
  EXPECT_EQ(others[0].start.type, StartPositionType::Waypoint);
  EXPECT_DOUBLE_EQ(others[0].start.waypoint->wp_idx, 33.33333333);
  EXPECT_EQ(others[0].description, "lead");
  EXPECT_EQ(others[0].start_speed->actor, 1);
  EXPECT_EQ(others[0].start_speed->target, std::optional<ActorId>(0));  // relative, no target: the ego
  EXPECT_EQ(others[1].start.type, StartPositionType::Distance);
  EXPECT_EQ(others[1].start.target, std::optional<ActorId>(1));
  EXPECT_DOUBLE_EQ(others[1].start.distance, -20);
  EXPECT_EQ(others[1].start.measure, MeasureType::Surface);
  EXPECT_FALSE(others[1].start.waypoint.has_value());
  EXPECT_DOUBLE_EQ(others[1].start_speed->value, 15.0);
  EXPECT_EQ(others[1].start_speed->accel.type, AccelType::Specify);
  EXPECT_EQ(others[1].start_speed->actor, 2);
}

TEST(LoaderOpening, TheFormatDocumentsExampleGetsTwoHelpfulErrors) {
  // The opening_scene example of the format document, verbatim apart from its missing comma.
  const auto loaded = load_text(with_opening(R"({
   "ego": {
      "start_position": {
            "wp_id": "Waypoint01",
            "wp_idx": 0
      }
   },
   "others": [
      {
         "actor_id": 1,
         "start_position": {
            "wp_id": "Waypoint01",
            "wp_idx": 20
         },
         "start_speed": {
            "type": "relative",
            "target_actor_id": 0,
            "vlaue": 0
         },
         "next_scenes": [
            1, 2
         ]
      },
      {"actor_id": 2, "start_position": {"wp_id": "Waypoint01", "wp_idx": 40}}
   ]
})"));
  const auto& d = loaded.diagnostics;
  EXPECT_TRUE(has_error(d, "/scenario/opening_scene/others/0/start_speed/vlaue", 21, "did you mean \"value\"?"));
  EXPECT_TRUE(has_error(d, "/scenario/opening_scene/others/0/start_speed", 18, "needs \"value\""));
  EXPECT_TRUE(has_error(d, "/scenario/opening_scene/others/0/next_scenes", 23,
                        "belongs directly under \"opening_scene\""));
  EXPECT_EQ(d.error_count(), 3) << d.format();
}

TEST(LoaderOpening, KeysOfTheOtherStartType) {
  const auto d = load_text(with_opening(R"({
"ego": {"start_position": {"type": "distance", "wp_id": "Waypoint02", "wp_idx": 5, "distance": 3}},
"others": [{"actor_id": 1, "start_position": {"type": "waypoint", "wp_id": "Waypoint01", "wp_idx": 1, "target_actor_id": 0}},
           {"actor_id": 2, "start_position": {"type": "distance", "wp_id": "Waypoint01", "wp_idx": 7, "distance": 3}}],
"next_scenes": [1]})")).diagnostics;
  EXPECT_TRUE(has_error(d, "/scenario/opening_scene/ego/start_position/type", 5, "may only be \"waypoint\""));
  EXPECT_TRUE(has_error(d, "/scenario/opening_scene/ego/start_position/distance", 5, "only others may use"));
  EXPECT_TRUE(has_error(d, "/scenario/opening_scene/others/0/start_position/target_actor_id", 6,
                        "belongs to start positions of type \"distance\""));
  // A distance start may name the route the actor drives (wp_id), not a point on it.
  EXPECT_TRUE(has_error(d, "/scenario/opening_scene/others/1/start_position/wp_idx", 7,
                        "belongs to start positions of type \"waypoint\""));
  EXPECT_EQ(d.error_count(), 4) << d.format();
}

TEST(LoaderOpening, MissingPiecesAndBadTypes) {
  const auto d = load_text(with_opening(R"({
"ego": {"end_position": {"wp_id": "", "wp_idx": "5"}},
"others": [{"start_position": {"type": "distanse"}}, {"actor_id": 2, "start_position": {"wp_id": "Waypoint01", "wp_idx": 1, "orientation": {"yaw": 1}}}],
"next_scenes": [1, "2"]})")).diagnostics;
  EXPECT_TRUE(has_error(d, "/scenario/opening_scene/ego", 5, "needs \"start_position\""));
  EXPECT_TRUE(has_error(d, "/scenario/opening_scene/ego/end_position/wp_id", 5, "must not be empty"));
  EXPECT_TRUE(has_error(d, "/scenario/opening_scene/ego/end_position/wp_idx", 5, "must be a number"));
  EXPECT_TRUE(has_error(d, "/scenario/opening_scene/others/0", 6, "needs \"actor_id\""));
  EXPECT_TRUE(has_error(d, "/scenario/opening_scene/others/0/start_position/type", 6, "did you mean \"distance\"?"));
  EXPECT_TRUE(has_error(d, "/scenario/opening_scene/others/1/start_position/orientation", 6, "needs \"heading\""));
  EXPECT_TRUE(has_error(d, "/scenario/opening_scene/others/1/start_position/orientation/yaw", 6, "unknown key"));
  EXPECT_TRUE(has_error(d, "/scenario/opening_scene/next_scenes/1", 7, "found a string"));
  EXPECT_EQ(d.error_count(), 8) << d.format();
}

TEST(LoaderOpening, AMisspeltKeyListsOnlyTheKeysThatBelongThere) {
  const auto d = load_text(with_opening(R"({
"ego": {"start_position": {"wp_id": "Waypoint02", "wp_idx": 5}},
"others": [{"actor_id": 1, "start_postion": {"wp_id": "Waypoint01", "wp_idx": 1}},
           {"actor_id": 2, "start_position": {"wp_id": "Waypoint01", "wp_idx": 2}}],
"next_scenes": [1]})")).diagnostics;
  EXPECT_TRUE(has_error(d, "/scenario/opening_scene/others/0/start_postion", 6,
                        "unknown key \"start_postion\" in the opening entry of \"others\" (did you mean "
                        "\"start_position\"?); allowed here: \"actor_id\", \"description\", \"start_position\" or "
                        "\"start_speed\""));
  EXPECT_TRUE(has_error(d, "/scenario/opening_scene/others/0", 6, "needs \"start_position\""));
  EXPECT_EQ(d.error_count(), 2) << d.format();
}

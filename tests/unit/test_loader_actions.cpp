// The loader on actions: the eight kinds, their defaults, `{}`, and mistakes.
#include <gtest/gtest.h>

#include "test_loader_support.hpp"

using namespace orch;
using namespace orch::scenario;
using namespace orch::loader_test;

namespace {

std::vector<Action> actions_of(const std::string& actions) {
  const auto loaded = load_text(with_actions(actions));
  EXPECT_TRUE(loaded.scenario.has_value()) << loaded.diagnostics.format();
  return loaded.scenario ? loaded.scenario->scenes.at(0).actions : std::vector<Action>{};
}

template <typename T>
T only(const std::string& actions) {
  const auto list = actions_of(actions);
  EXPECT_EQ(list.size(), 1u);
  return list.empty() ? T{} : std::get<T>(list[0].kind);
}

Diagnostics diagnostics_of(const std::string& actions) { return load_text(with_actions(actions)).diagnostics; }

}  // namespace

TEST(LoaderActions, SpeedWithoutAccelIsInstantAndConvertedToMetresPerSecond) {
  const auto list = actions_of(R"([
{"speed": {"actor_id": 1, "type": "absolute", "value": 72, "description": "go"}}])");
  ASSERT_EQ(list.size(), 1u);
  EXPECT_EQ(list[0].description, "go");
  EXPECT_EQ(list[0].where.pointer, "/scenario/scenes/0/actions/0/speed");
  EXPECT_EQ(list[0].where.line, 11);
  const auto& s = std::get<SpeedAction>(list[0].kind);
  EXPECT_EQ(s.actor, 1);
  EXPECT_DOUBLE_EQ(s.value, 20.0);
  EXPECT_EQ(s.accel.type, AccelType::GodsHand);
  EXPECT_FALSE(s.target.has_value());
}

TEST(LoaderActions, AllThreeAccelSpellings) {
  const auto list = actions_of(R"([
{"speed": {"actor_id": 1, "type": "absolute", "value": 10, "accel": {"type": "specify", "value": 2.5}}},
{"speed": {"actor_id": 1, "type": "absolute", "value": 10, "accel": {"type": "gods_hand"}}},
{"speed": {"actor_id": 1, "type": "absolute", "value": 10, "accel": {"type": "god_hands", "value": 3}}}])");
  ASSERT_EQ(list.size(), 3u);
  EXPECT_EQ(std::get<SpeedAction>(list[0].kind).accel.type, AccelType::Specify);
  EXPECT_DOUBLE_EQ(std::get<SpeedAction>(list[0].kind).accel.value, 2.5);
  EXPECT_EQ(std::get<SpeedAction>(list[1].kind).accel.type, AccelType::GodsHand);
  EXPECT_EQ(std::get<SpeedAction>(list[2].kind).accel.type, AccelType::GodsHand);
}

TEST(LoaderActions, SpecifyNeedsAValueAndAMisspeltTypeGetsASuggestion) {
  const auto d = diagnostics_of(R"([
{"speed": {"actor_id": 1, "type": "absolute", "value": 10, "accel": {"type": "specify"}}},
{"speed": {"actor_id": 1, "type": "absolute", "value": 10, "accel": {"type": "gods_hands"}}}])");
  EXPECT_TRUE(has_error(d, "/scenario/scenes/0/actions/0/speed/accel", 11, "needs \"value\""));
  EXPECT_TRUE(has_error(d, "/scenario/scenes/0/actions/1/speed/accel/type", 12, "did you mean"));
}

TEST(LoaderActions, RelativeSpeedDefaultsToTheEgo) {
  const auto s = only<SpeedAction>(R"([{"speed": {"actor_id": 1, "type": "relative", "value": -3.6}}])");
  EXPECT_EQ(s.type, SpeedType::Relative);
  EXPECT_EQ(s.target, std::optional<ActorId>(0));
  EXPECT_DOUBLE_EQ(s.value, -1.0);
  const auto t = only<SpeedAction>(R"([{"speed": {"actor_id": 1, "type": "relative", "target_actor_id": 2, "value": 0}}])");
  EXPECT_EQ(t.target, std::optional<ActorId>(2));
}

TEST(LoaderActions, TraveledDistanceLaneChangeLaneOffset) {
  const auto list = actions_of(R"([
{"traveled_distance": {"actor_id": 1, "value": -12}},
{"traveled_distance": {"actor_id": 1, "target_actor_id": 2, "value": 5, "measure_type": "surface"}},
{"lane_change": {"actor_id": 1, "type": "lane", "wp_id": "Waypoint02", "time": 3}},
{"lane_change": {"actor_id": 1, "wp_id": "Waypoint03", "time": 0}},
{"lane_offset": {"actor_id": 1, "value": -0.5, "time": 2}}])");
  ASSERT_EQ(list.size(), 5u);
  const auto& d0 = std::get<TraveledDistanceAction>(list[0].kind);
  EXPECT_EQ(d0.target, 0);
  EXPECT_EQ(d0.measure, MeasureType::Center);
  EXPECT_DOUBLE_EQ(d0.value, -12);
  const auto& d1 = std::get<TraveledDistanceAction>(list[1].kind);
  EXPECT_EQ(d1.target, 2);
  EXPECT_EQ(d1.measure, MeasureType::Surface);
  EXPECT_EQ(std::get<LaneChangeAction>(list[2].kind).wp_id, "Waypoint02");
  EXPECT_DOUBLE_EQ(std::get<LaneChangeAction>(list[2].kind).time, 3);
  EXPECT_DOUBLE_EQ(std::get<LaneChangeAction>(list[3].kind).time, 0);
  EXPECT_DOUBLE_EQ(std::get<LaneOffsetAction>(list[4].kind).value, -0.5);
  EXPECT_DOUBLE_EQ(std::get<LaneOffsetAction>(list[4].kind).time, 2);
}

TEST(LoaderActions, RouteMoveOfBothTypes) {
  const auto list = actions_of(R"([
{"route_move": {"actor_id": 2, "type": "waypoint", "route": [{"time": 7.2, "wp_id": "Waypoint02", "wp_idx": 50, "wp_offset": 5},
                                                             {"time": 3, "wp_id": "Waypoint01", "wp_idx": 60.5}]}},
{"route_move": {"actor_id": 1, "type": "wp_offset", "route": [{"time": 2, "wp_offset": 1.0}, {"time": 2, "wp_offset": 0}]}}])");
  ASSERT_EQ(list.size(), 2u);
  const auto& walk = std::get<RouteMoveAction>(list[0].kind);
  EXPECT_EQ(walk.type, RouteMoveType::Waypoint);
  ASSERT_EQ(walk.legs.size(), 2u);
  EXPECT_DOUBLE_EQ(walk.legs[0].time, 7.2);
  EXPECT_EQ(walk.legs[0].waypoint->wp_id, "Waypoint02");
  EXPECT_DOUBLE_EQ(walk.legs[0].wp_offset.value(), 5);
  EXPECT_FALSE(walk.legs[1].wp_offset.has_value());
  EXPECT_DOUBLE_EQ(walk.legs[1].waypoint->wp_idx, 60.5);
  EXPECT_EQ(walk.legs[1].where.pointer, "/scenario/scenes/0/actions/0/route_move/route/1");
  EXPECT_EQ(walk.legs[1].where.line, 12);
  const auto& swerve = std::get<RouteMoveAction>(list[1].kind);
  EXPECT_EQ(swerve.type, RouteMoveType::WpOffset);
  EXPECT_FALSE(swerve.legs[0].waypoint.has_value());
  EXPECT_DOUBLE_EQ(swerve.legs[0].wp_offset.value(), 1.0);
}

TEST(LoaderActions, RouteMoveMistakes) {
  const auto d = diagnostics_of(R"([
{"route_move": {"actor_id": 1, "type": "wp_offset", "route": [{"time": 2, "wp_offset": 1, "wp_id": "Waypoint01"}]}},
{"route_move": {"actor_id": 1, "type": "waypoint", "route": [{"time": 2, "wp_offset": 1}]}},
{"route_move": {"actor_id": 1, "type": "waypoint", "route": []}},
{"route_move": {"actor_id": 1, "type": "offset", "route": [{"time": 1}]}}])");
  EXPECT_TRUE(has_error(d, "/scenario/scenes/0/actions/0/route_move/route/0/wp_id", 11,
                        "belongs to route_move of type \"waypoint\""));
  EXPECT_TRUE(has_error(d, "/scenario/scenes/0/actions/1/route_move/route/0", 12, "needs \"wp_id\""));
  EXPECT_TRUE(has_error(d, "/scenario/scenes/0/actions/1/route_move/route/0", 12, "needs \"wp_idx\""));
  EXPECT_TRUE(has_error(d, "/scenario/scenes/0/actions/2/route_move/route", 13, "\"route\" is empty"));
  EXPECT_TRUE(has_error(d, "/scenario/scenes/0/actions/3/route_move/type", 14, "did you mean \"wp_offset\"?"));
  EXPECT_EQ(d.error_count(), 5) << d.format();
}

TEST(LoaderActions, LightsSoundAndHandOver) {
  const auto list = actions_of(R"([
{"light_state": {"actor_id": 1, "blinker_left": true, "special1": false}},
{"sound_state": {"actor_id": 1, "sound": true}},
{"hand_over": {"hand_over": true, "throttle": 0.3, "steer": -0.1}},
{"hand_over": {"actor_id": 0, "hand_over": false}}])");
  ASSERT_EQ(list.size(), 4u);
  const auto& light = std::get<LightStateAction>(list[0].kind);
  EXPECT_EQ(light.blinker_left, std::optional<bool>(true));
  EXPECT_FALSE(light.blinker_right.has_value());
  EXPECT_EQ(light.special1, std::optional<bool>(false));
  EXPECT_EQ(std::get<SoundStateAction>(list[1].kind).sound, std::optional<bool>(true));
  const auto& take = std::get<HandOverAction>(list[2].kind);
  EXPECT_TRUE(take.hand_over);
  EXPECT_FALSE(take.actor.has_value());
  EXPECT_DOUBLE_EQ(take.throttle.value(), 0.3);
  EXPECT_FALSE(take.brake.has_value());
  EXPECT_DOUBLE_EQ(take.steer.value(), -0.1);
  const auto& give = std::get<HandOverAction>(list[3].kind);
  EXPECT_FALSE(give.hand_over);
  EXPECT_EQ(give.actor, std::optional<ActorId>(0));
}

TEST(LoaderActions, HandOverNeedsItsFlagAndLightsWithoutLightsWarn) {
  const auto d = diagnostics_of(R"([
{"hand_over": {"actor_id": 0}},
{"light_state": {"actor_id": 1}},
{"sound_state": {"actor_id": 1, "sound": "on"}}])");
  EXPECT_TRUE(has_error(d, "/scenario/scenes/0/actions/0/hand_over", 11, "needs \"hand_over\" (true or false)"));
  EXPECT_TRUE(has_warning(d, "/scenario/scenes/0/actions/1/light_state", 12, "changes nothing"));
  EXPECT_TRUE(has_error(d, "/scenario/scenes/0/actions/2/sound_state/sound", 13, "must be true or false"));
}

TEST(LoaderActions, EmptyActionIsAcceptedWithAWarning) {
  const auto loaded = load_text(with_actions(R"([
{},
{"description": "placeholder"}])"));
  ASSERT_TRUE(loaded.scenario.has_value()) << loaded.diagnostics.format();
  const auto& actions = loaded.scenario->scenes.at(0).actions;
  ASSERT_EQ(actions.size(), 2u);
  EXPECT_TRUE(std::holds_alternative<EmptyAction>(actions[0].kind));
  EXPECT_EQ(actions[1].description, "placeholder");
  EXPECT_TRUE(has_warning(loaded.diagnostics, "/scenario/scenes/0/actions/0", 11, "empty action"));
  EXPECT_TRUE(has_warning(loaded.diagnostics, "/scenario/scenes/0/actions/1", 12, "empty action"));
}

TEST(LoaderActions, TwoActionKeysInOneObjectIsAnError) {
  const auto d = diagnostics_of(R"([
{"lane_change": {"actor_id": 1, "wp_id": "Waypoint02", "time": 3}, "speed": {"actor_id": 1, "type": "absolute", "value": 1}}])");
  EXPECT_TRUE(has_error(d, "/scenario/scenes/0/actions/0/lane_change", 11,
                        "holds exactly one action, found \"speed\" and \"lane_change\""));
  EXPECT_EQ(d.error_count(), 1) << d.format();
}

TEST(LoaderActions, UnknownKeysInsideAndOutsideTheAction) {
  const auto d = diagnostics_of(R"([
{"lane_chnge": {}},
{"lane_offset": {"actor_id": 1, "value": 1, "time": 1, "tiem": 2}},
{"speed": {"actor_id": 1, "type": "absolute", "vlaue": 1}},
"speed",
{"speed": []}])");
  EXPECT_TRUE(has_error(d, "/scenario/scenes/0/actions/0/lane_chnge", 11, "did you mean \"lane_change\"?"));
  EXPECT_TRUE(has_error(d, "/scenario/scenes/0/actions/1/lane_offset/tiem", 12, "did you mean \"time\"?"));
  EXPECT_TRUE(has_error(d, "/scenario/scenes/0/actions/2/speed/vlaue", 13, "did you mean \"value\"?"));
  EXPECT_TRUE(has_error(d, "/scenario/scenes/0/actions/2/speed", 13, "needs \"value\""));
  EXPECT_TRUE(has_error(d, "/scenario/scenes/0/actions/3", 14, "expected an action such as"));
  EXPECT_TRUE(has_error(d, "/scenario/scenes/0/actions/4/speed", 15, "as an object, found an array"));
  EXPECT_EQ(d.error_count(), 6) << d.format();
}

TEST(LoaderActions, LaneChangeTypeIsOnlyLane) {
  const auto d = diagnostics_of(R"([{"lane_change": {"actor_id": 1, "type": "lanes", "wp_id": "Waypoint02", "time": 3}}])");
  EXPECT_TRUE(has_error(d, "/scenario/scenes/0/actions/0/lane_change/type", 10, "did you mean \"lane\"?"));
}

// The loader on conditions: groups, nesting, the six kinds, defaults and mistakes.
#include <gtest/gtest.h>

#include "test_loader_support.hpp"

using namespace orch;
using namespace orch::scenario;
using namespace orch::loader_test;

namespace {

ConditionGroup conditions_of(const std::string& conditions) {
  const auto loaded = load_text(with_conditions(conditions));
  EXPECT_TRUE(loaded.scenario.has_value()) << loaded.diagnostics.format();
  return loaded.scenario ? loaded.scenario->scenes.at(0).conditions : ConditionGroup{};
}

const Condition& only_condition(const ConditionGroup& g) {
  EXPECT_EQ(g.items.size(), 1u);
  return std::get<Condition>(g.items.at(0).node);
}

Diagnostics errors_of(const std::string& conditions) { return load_text(with_conditions(conditions)).diagnostics; }

}  // namespace

TEST(LoaderConditions, EmptyObjectAndEmptyListsAreAlwaysTrue) {
  for (const char* text : {"{}", R"({"and": []})", R"({"or": []})"}) {
    const auto g = conditions_of(text);
    EXPECT_TRUE(g.items.empty()) << text;
  }
  EXPECT_EQ(conditions_of(R"({"or": []})").logic, Logic::Or);
}

TEST(LoaderConditions, OrGroupWithPositionAndSimulationTime) {
  const auto g = conditions_of(R"({
"or": [
  {"position": {"actor_id": 1, "type": "reach", "wp_id": "Waypoint01", "wp_idx": 12.5, "tolerance": 2, "description": "near"}},
  {"simulation_time": {"comparison": ">", "value": 30}}
]})");
  EXPECT_EQ(g.logic, Logic::Or);
  EXPECT_EQ(g.where.pointer, "/scenario/scenes/0/conditions");
  EXPECT_EQ(g.where.line, 10);
  ASSERT_EQ(g.items.size(), 2u);
  const auto& first = std::get<Condition>(g.items[0].node);
  EXPECT_EQ(first.description, "near");
  EXPECT_EQ(first.where.pointer, "/scenario/scenes/0/conditions/or/0/position");
  EXPECT_EQ(first.where.line, 12);
  const auto& reach = std::get<PositionCondition>(first.kind);
  EXPECT_EQ(reach.actor, 1);
  EXPECT_EQ(reach.waypoint.wp_id, "Waypoint01");
  EXPECT_DOUBLE_EQ(reach.waypoint.wp_idx, 12.5);
  EXPECT_EQ(reach.waypoint.where.pointer, "/scenario/scenes/0/conditions/or/0/position");
  EXPECT_DOUBLE_EQ(reach.tolerance, 2);
  const auto& time = std::get<SimulationTimeCondition>(std::get<Condition>(g.items[1].node).kind);
  EXPECT_EQ(time.comparison, Comparison::Greater);
  EXPECT_DOUBLE_EQ(time.value, 30);
  EXPECT_EQ(std::get<Condition>(g.items[1].node).where.line, 13);
}

TEST(LoaderConditions, BothKeysMeanBothMustHold) {
  const auto g = conditions_of(R"({"and": [{"collision": {"actor_id": 0}}],
"or": [{"collision": {"actor_id": 1}}, {"collision": {"actor_id": 2}}]})");
  EXPECT_EQ(g.logic, Logic::And);
  ASSERT_EQ(g.items.size(), 2u);
  const auto& all = std::get<ConditionGroup>(g.items[0].node);
  const auto& any = std::get<ConditionGroup>(g.items[1].node);
  EXPECT_EQ(all.logic, Logic::And);
  EXPECT_EQ(all.items.size(), 1u);
  EXPECT_EQ(all.where.pointer, "/scenario/scenes/0/conditions/and");
  EXPECT_EQ(any.logic, Logic::Or);
  EXPECT_EQ(any.items.size(), 2u);
  EXPECT_EQ(any.where.pointer, "/scenario/scenes/0/conditions/or");
  EXPECT_EQ(any.where.line, 11);
}

TEST(LoaderConditions, GroupsNest) {
  const auto g = conditions_of(R"({"or": [{"and": [{"collision": {"actor_id": 0}}, {"or": [{"collision": {"actor_id": 1}}]}]},
{"simulation_time": {"comparison": ">=", "value": 5}}]})");
  ASSERT_EQ(g.items.size(), 2u);
  const auto& nested = std::get<ConditionGroup>(g.items[0].node);
  EXPECT_EQ(nested.logic, Logic::And);
  EXPECT_EQ(nested.where.pointer, "/scenario/scenes/0/conditions/or/0");
  ASSERT_EQ(nested.items.size(), 2u);
  const auto& deeper = std::get<ConditionGroup>(nested.items[1].node);
  EXPECT_EQ(deeper.logic, Logic::Or);
  EXPECT_EQ(std::get<CollisionCondition>(std::get<Condition>(deeper.items.at(0).node).kind).actor, 1);
  EXPECT_TRUE(std::holds_alternative<Condition>(g.items[1].node));
}

TEST(LoaderConditions, DistanceDefaultsToTraveledCentreAndTheEgo) {
  const auto d = std::get<DistanceCondition>(
      only_condition(conditions_of(R"({"and": [{"distance": {"actor_id": 1, "comparison": "<", "value": 30}}]})")).kind);
  EXPECT_EQ(d.actor, 1);
  EXPECT_EQ(d.target, 0);
  EXPECT_EQ(d.type, DistanceType::Traveled);
  EXPECT_EQ(d.measure, MeasureType::Center);
  EXPECT_EQ(d.comparison, Comparison::Less);
  const auto s = std::get<DistanceCondition>(only_condition(conditions_of(
      R"({"and": [{"distance": {"actor_id": 1, "type": "straight", "target_actor_id": 2, "comparison": "=", "value": -4, "measure_type": "surface"}}]})"))
                                                  .kind);
  EXPECT_EQ(s.type, DistanceType::Straight);
  EXPECT_EQ(s.target, 2);
  EXPECT_EQ(s.measure, MeasureType::Surface);
  EXPECT_EQ(s.comparison, Comparison::Equal);
  EXPECT_DOUBLE_EQ(s.value, -4);
}

TEST(LoaderConditions, SpeedIsConvertedAndRelativeDefaultsToTheEgo) {
  const auto abs = std::get<SpeedCondition>(only_condition(conditions_of(
      R"({"and": [{"speed": {"actor_id": 1, "type": "absolute", "comparison": ">=", "value": 36}}]})")).kind);
  EXPECT_DOUBLE_EQ(abs.value, 10.0);
  EXPECT_EQ(abs.type, SpeedType::Absolute);
  EXPECT_FALSE(abs.target.has_value());
  EXPECT_EQ(abs.comparison, Comparison::GreaterEqual);
  const auto rel = std::get<SpeedCondition>(only_condition(conditions_of(
      R"({"and": [{"speed": {"actor_id": 1, "type": "relative", "comparison": "<=", "value": -18}}]})")).kind);
  EXPECT_EQ(rel.target, std::optional<ActorId>(0));
  EXPECT_DOUBLE_EQ(rel.value, -5.0);
  EXPECT_EQ(rel.comparison, Comparison::LessEqual);
}

TEST(LoaderConditions, TimeHeadwayAndCollision) {
  const auto g = conditions_of(R"({"and": [{"time_headway": {"actor_id": 0, "wp_id": "Waypoint02", "wp_idx": 90, "comparison": "<", "value": 2.5}},
{"collision": {"actor_id": 0, "description": "crash"}}]})");
  const auto& th = std::get<TimeHeadwayCondition>(std::get<Condition>(g.items.at(0).node).kind);
  EXPECT_EQ(th.waypoint.wp_id, "Waypoint02");
  EXPECT_DOUBLE_EQ(th.waypoint.wp_idx, 90);
  EXPECT_DOUBLE_EQ(th.value, 2.5);
  EXPECT_EQ(std::get<Condition>(g.items.at(1).node).description, "crash");
}

TEST(LoaderConditions, DescriptionMayAlsoStandBesideTheConditionKey) {
  const auto group = conditions_of(R"({"and": [{"description": "outer", "collision": {"actor_id": 0}}]})");
  EXPECT_EQ(only_condition(group).description, "outer");
}

TEST(LoaderConditions, MisspeltKindSuggestsTheRightOne) {
  const auto d = errors_of(R"({"or": [{"postion": {"actor_id": 1}}]})");
  EXPECT_TRUE(has_error(d, "/scenario/scenes/0/conditions/or/0/postion", 10, "did you mean \"position\"?"));
  EXPECT_EQ(d.error_count(), 1) << d.format();
}

TEST(LoaderConditions, MisspeltComparisonsAndOperators) {
  auto d = errors_of(R"({"and": [{"simulation_time": {"comparison": "=>", "value": 1}}]})");
  EXPECT_TRUE(has_error(d, "/scenario/scenes/0/conditions/and/0/simulation_time/comparison", 10,
                        "(did you mean \">=\"?)"));
  d = errors_of(R"({"and": [{"simulation_time": {"comparison": "==", "value": 1}}]})");
  EXPECT_TRUE(has_error(d, "/scenario/scenes/0/conditions/and/0/simulation_time/comparison", 10,
                        "(did you mean \"=\"?)"));
  d = errors_of(R"({"AND": []})");
  EXPECT_TRUE(has_error(d, "/scenario/scenes/0/conditions/AND", 10, "did you mean \"and\"?"));
}

TEST(LoaderConditions, BadEnumValuesAndMissingKeys) {
  const auto d = errors_of(R"({"and": [
{"distance": {"actor_id": 1, "type": "travelled", "comparison": "<", "value": 3, "measure_type": "centre"}},
{"speed": {"actor_id": 1, "comparison": "<"}},
{"position": {"actor_id": 1, "type": "arrive", "wp_id": "Waypoint01", "wp_idx": 3, "tolerance": 1}}
]})");
  EXPECT_TRUE(has_error(d, "/scenario/scenes/0/conditions/and/0/distance/type", 11, "did you mean \"traveled\"?"));
  EXPECT_TRUE(has_error(d, "/scenario/scenes/0/conditions/and/0/distance/measure_type", 11,
                        "did you mean \"center\"?"));
  EXPECT_TRUE(has_error(d, "/scenario/scenes/0/conditions/and/1/speed", 12, "needs \"type\""));
  EXPECT_TRUE(has_error(d, "/scenario/scenes/0/conditions/and/1/speed", 12, "needs \"value\""));
  EXPECT_TRUE(has_error(d, "/scenario/scenes/0/conditions/and/2/position/type", 13, "expected \"reach\""));
  EXPECT_EQ(d.error_count(), 5) << d.format();
}

TEST(LoaderConditions, ShapeMistakes) {
  auto d = errors_of(R"([{"collision": {"actor_id": 0}}])");
  EXPECT_TRUE(has_error(d, "/scenario/scenes/0/conditions", 10, "must be an object {\"and\": [...]}"));
  d = errors_of(R"({"collision": {"actor_id": 0}})");
  EXPECT_TRUE(has_error(d, "/scenario/scenes/0/conditions/collision", 10, "a condition goes inside a list"));
  d = errors_of(R"({"and": [{}, 3, {"collision": {"actor_id": 0}, "speed": {}}, {"or": [], "collision": {"actor_id": 0}}]})");
  EXPECT_TRUE(has_error(d, "/scenario/scenes/0/conditions/and/0", 10, "empty condition"));
  EXPECT_TRUE(has_error(d, "/scenario/scenes/0/conditions/and/1", 10, "found a number"));
  EXPECT_TRUE(has_error(d, "/scenario/scenes/0/conditions/and/2/collision", 10, "found \"speed\" and \"collision\""));
  EXPECT_TRUE(has_error(d, "/scenario/scenes/0/conditions/and/3/or", 10, "either one condition or a group"));
  d = errors_of(R"({"and": [{"collision": []}]})");
  EXPECT_TRUE(has_error(d, "/scenario/scenes/0/conditions/and/0/collision", 10,
                        "expected the collision condition as an object, found an array"));
  EXPECT_EQ(d.error_count(), 1) << d.format();
}

TEST(LoaderConditions, AbsoluteSpeedWithATargetWarns) {
  const auto loaded = load_text(with_conditions(
      R"({"and": [{"speed": {"actor_id": 1, "type": "absolute", "target_actor_id": 0, "comparison": ">", "value": 1}}]})"));
  EXPECT_TRUE(loaded.scenario.has_value());
  EXPECT_TRUE(has_warning(loaded.diagnostics, "/scenario/scenes/0/conditions/and/0/speed/target_actor_id", 10,
                          "no effect"));
}

TEST(LoaderConditions, StopConditionsAreReadLikeSceneConditions) {
  const auto loaded = load_text(with_actions("[]"));
  ASSERT_TRUE(loaded.scenario && loaded.scenario->stop_conditions);
  const auto& stop = *loaded.scenario->stop_conditions;
  EXPECT_EQ(stop.logic, Logic::Or);
  EXPECT_EQ(stop.where.pointer, "/stop_conditions");
  EXPECT_EQ(stop.where.line, 14);
  EXPECT_DOUBLE_EQ(std::get<SimulationTimeCondition>(std::get<Condition>(stop.items.at(0).node).kind).value, 60);
}

TEST(LoaderConditions, CollisionKeepsTheTargetActorRealFilesWrite) {
  const auto g = conditions_of(R"({"and": [{"collision": {"actor_id": 0, "target_actor_id": 1}},
{"collision": {"actor_id": 1}}]})");
  ASSERT_EQ(g.items.size(), 2u);
  const auto& with_target = std::get<CollisionCondition>(std::get<Condition>(g.items[0].node).kind);
  EXPECT_EQ(with_target.actor, 0);
  ASSERT_TRUE(with_target.target.has_value());
  EXPECT_EQ(*with_target.target, 1);
  EXPECT_FALSE(std::get<CollisionCondition>(std::get<Condition>(g.items[1].node).kind).target.has_value());
  const auto d = errors_of(R"({"and": [{"collision": {"actor_id": 0, "target_actor_id": "one"}}]})");
  EXPECT_TRUE(d.has_errors());
}

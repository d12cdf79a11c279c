#include <gtest/gtest.h>

#include "scenario_executor_engine/scene_machine.hpp"
#include "support/scenario_text.hpp"

using namespace orch;
using namespace orch::engine;

namespace {
// Scenes 1..3 in a chain, 2 held for 1.5 s; which scenes "hold" is decided by the test.
const char* kChain = R"({
  "map_id": "m",
  "actors": {"ego": {"actor_id": 0, "model_id": "vehicle.toyota.prius"}},
  "scenario": {
    "opening_scene": {"ego": {"start_position": {"wp_id": "Waypoint02", "wp_idx": 0}}, "next_scenes": [1]},
    "scenes": [
      {"scene_id": 1, "next_scenes": [3, 2]},
      {"scene_id": 2, "duration": 1.5, "next_scenes": [4]},
      {"scene_id": 3, "next_scenes": [4]}
    ],
    "ending_scenes": [{"scene_id": 4}]
  }})";
}  // namespace

TEST(SceneMachine, TriesNextScenesInOrderOneTransitionPerStep) {
  auto s = test::scenario_from(kChain);
  SceneMachine m(s);
  std::set<int> ready{1, 2, 3, 4};
  auto holds = [&](const scenario::Scene& sc) { return ready.count(sc.id) > 0; };
  ASSERT_TRUE(m.step(0.05, holds));
  EXPECT_EQ(m.current(), 1);
  ASSERT_TRUE(m.step(0.10, holds));
  EXPECT_EQ(m.current(), 3);  // 3 is written before 2
  ASSERT_TRUE(m.step(0.15, holds));
  EXPECT_EQ(m.current(), 4);
  EXPECT_TRUE(m.ended());
  EXPECT_FALSE(m.step(0.20, holds));
  ASSERT_EQ(m.visits().size(), 4u);
  EXPECT_DOUBLE_EQ(m.visits()[2].enter_time, 0.10);
}

TEST(SceneMachine, DurationHoldsTheSceneEvenWhenTheNextIsReady) {
  auto s = test::scenario_from(kChain);
  SceneMachine m(s);
  std::set<int> ready{1, 2, 4};
  auto holds = [&](const scenario::Scene& sc) { return ready.count(sc.id) > 0; };
  m.step(1.0, holds);
  m.step(2.0, holds);
  ASSERT_EQ(m.current(), 2);
  EXPECT_FALSE(m.step(3.0, holds));  // 1.0 s in scene 2
  EXPECT_FALSE(m.step(3.45, holds));
  EXPECT_TRUE(m.step(3.5, holds));  // 1.5 s: the hold is over
  EXPECT_EQ(m.current(), 4);
}

TEST(SceneMachine, StaysWhileNoNextSceneHolds) {
  auto s = test::scenario_from(kChain);
  SceneMachine m(s);
  std::set<int> ready{};
  auto holds = [&](const scenario::Scene& sc) { return ready.count(sc.id) > 0; };
  EXPECT_FALSE(m.step(1.0, holds));
  EXPECT_EQ(m.current(), 0);
  ready.insert(1);
  EXPECT_TRUE(m.step(1.05, holds));
}

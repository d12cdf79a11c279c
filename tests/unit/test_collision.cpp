#include <gtest/gtest.h>

#include <numbers>

#include "scenario_executor_engine/collision.hpp"
#include "support/scenario_text.hpp"

using namespace orch;
using namespace orch::engine;

TEST(BoxesTouch, OverlapTouchAndMiss) {
  const Box a{{0, 0}, 0, 4, 2};
  EXPECT_TRUE(boxes_touch(a, Box{{3.9, 0}, 0, 4, 2}));   // 0.1 m overlap nose to tail
  EXPECT_TRUE(boxes_touch(a, Box{{4.0, 0}, 0, 4, 2}));   // edges touching count
  EXPECT_FALSE(boxes_touch(a, Box{{4.01, 0}, 0, 4, 2}));
  EXPECT_FALSE(boxes_touch(a, Box{{0, 2.05}, 0, 4, 2}));  // side by side, 5 cm apart
  EXPECT_TRUE(boxes_touch(a, Box{{0, 1.95}, 0, 4, 2}));
}

TEST(BoxesTouch, RotationMatters) {
  // A box turned 45 degrees whose corner would reach into an axis-aligned box's bounding
  // region but not into the box itself.
  const Box a{{0, 0}, 0, 4, 2};
  const Box turned{{3.3, 1.9}, std::numbers::pi / 4, 2, 2};
  EXPECT_FALSE(boxes_touch(a, turned));
  const Box closer{{2.8, 1.6}, std::numbers::pi / 4, 2, 2};
  EXPECT_TRUE(boxes_touch(a, closer));
}

namespace {
const char* kThree = R"({"map_id": "m",
  "actors": {"ego": {"actor_id": 0, "model_id": "vehicle.toyota.prius"},
             "others": [{"actor_id": 1, "model_id": "vehicle.audi.a2"}, {"actor_id": 2, "model_id": "walker.pedestrian.0001"}]},
  "scenario": {"opening_scene": {"ego": {"start_position": {"wp_id": "Waypoint02", "wp_idx": 0}},
      "others": [{"actor_id": 1, "start_position": {"type": "waypoint", "wp_id": "Waypoint02", "wp_idx": 50}},
                 {"actor_id": 2, "start_position": {"type": "waypoint", "wp_id": "Waypoint02", "wp_idx": 80}}],
      "next_scenes": [1]}, "scenes": [], "ending_scenes": [{"scene_id": 1}]}})";

ActorState at(ActorId id, double x, double y) {
  ActorState a;
  a.id = id;
  a.present = true;
  a.position = Vec2(x, y);
  return a;
}
}  // namespace

TEST(CollisionMonitor, OneRecordPerContactEpisode) {
  auto s = test::scenario_from(kThree);
  ActorTable actors(s, Catalog::embedded());
  CollisionMonitor m(actors);
  WorldSnapshot snap;
  auto step = [&](double t, double x1) {
    snap.time = t;
    snap.actors = {at(0, 0, 0), at(1, x1, 0), at(2, 100, 0)};
    return m.step(snap);
  };
  EXPECT_TRUE(step(0.05, 5.0).empty());  // prius 4.51 and a2 3.71: touch below 4.11 m
  EXPECT_FALSE(m.touching(0));
  const auto first = step(0.10, 4.1);
  ASSERT_EQ(first.size(), 1u);
  EXPECT_DOUBLE_EQ(first[0].time, 0.10);
  EXPECT_EQ(first[0].a, "0");
  EXPECT_EQ(first[0].b, "1");
  EXPECT_EQ(first[0].source, "geometry");
  EXPECT_TRUE(first[0].position_b.isApprox(Vec2(4.1, 0)));
  EXPECT_TRUE(m.touching(0));
  EXPECT_TRUE(m.touching(1));
  EXPECT_FALSE(m.touching(2));
  EXPECT_TRUE(step(0.15, 3.0).empty());  // still touching: the same episode
  EXPECT_TRUE(step(0.20, 6.0).empty());  // apart
  EXPECT_EQ(step(0.25, 4.0).size(), 1u);  // a second contact is a second record
  EXPECT_EQ(m.all().size(), 2u);
}

TEST(CollisionMonitor, BackgroundVehiclesAndSumoReports) {
  auto s = test::scenario_from(kThree);
  ActorTable actors(s, Catalog::embedded());
  CollisionMonitor m(actors);
  WorldSnapshot snap;
  snap.time = 1.0;
  snap.actors = {at(0, 0, 0), at(1, 50, 0), at(2, 100, 0)};
  snap.nearby = {NearbyVehicle{"bg.7", Vec2(0, 1.9), 0, 20, 4.5, 1.8}};  // scraping the ego's left side
  // SUMO reports two contacts: one between actors (the geometry test decides those), one
  // with a vehicle the orchestrator does not see (SUMO is the only witness).
  snap.collisions = {SimCollision{"actor1", "ego", "collision", "e_0", 1.0},
                     SimCollision{"bg.99", "actor1", "collision", "e_0", 50.0}};
  const auto started = m.step(snap);
  ASSERT_EQ(started.size(), 3u);
  EXPECT_EQ(started[0].b, "bg.7");
  EXPECT_TRUE(started[0].counted);
  EXPECT_EQ(started[1].source, "sumo");
  EXPECT_FALSE(started[1].counted);  // actors 0 and 1 are 50 m apart: SUMO's report is noted, not counted
  EXPECT_TRUE(started[2].counted);
  EXPECT_TRUE(m.touching(0));
  EXPECT_TRUE(m.touching(1));  // through the unseen vehicle's report
}

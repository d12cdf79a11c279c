// Runs share SUMO while their commands are the same (run/fork_group.hpp): a field that
// same_commands did not compare would make two runs share a world they should not.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "run/same_commands.hpp"

using namespace orch;

namespace {

sim::SpawnVehicle spawn() {
  sim::SpawnVehicle s;
  s.actor = {1, "actor1", ActorKind::Vehicle, 4.5, 1.8};
  s.model.id = "vehicle.tesla.model3";
  s.model.length = 4.5;
  s.route = {"a", "b"};
  s.edge = "a";
  s.lane_pos = 10;
  s.speed = 20;
  return s;
}

sim::SetPose pose() {
  sim::SetPose p;
  p.sumo_id = "actor1";
  p.position = Vec2(1.0, 2.0);
  p.heading = 0.5;
  p.speed = 20;
  p.edge = "a";
  return p;
}

// Each change of one field makes the step's commands differ.
template <typename T>
void expect_each_change_differs(const T& base, const std::vector<std::function<void(T&)>>& changes) {
  const std::vector<sim::Command> a{base};
  EXPECT_TRUE(same_commands(a, std::vector<sim::Command>{base}));
  for (std::size_t i = 0; i < changes.size(); ++i) {
    T changed = base;
    changes[i](changed);
    EXPECT_FALSE(same_commands(a, std::vector<sim::Command>{changed})) << "change " << i;
  }
}

}  // namespace

TEST(SameCommands, EveryFieldOfASpawnCounts) {
  expect_each_change_differs<sim::SpawnVehicle>(
      spawn(), {[](auto& s) { s.actor.id = 2; }, [](auto& s) { s.actor.width = 2.0; },
                [](auto& s) { s.model.id = "x"; }, [](auto& s) { s.model.height = 1.0; },
                [](auto& s) { s.model.emergency = true; }, [](auto& s) { s.color = "ff0000"; },
                [](auto& s) { s.scripted = false; }, [](auto& s) { s.route.push_back("c"); },
                [](auto& s) { s.edge = "b"; }, [](auto& s) { s.lane = 1; }, [](auto& s) { s.lane_pos = 10.000001; },
                [](auto& s) { s.speed = 21; }, [](auto& s) { s.max_speed = 30; },
                [](auto& s) { s.keep_lateral = true; }});
}

TEST(SameCommands, EveryFieldOfAPoseCounts) {
  expect_each_change_differs<sim::SetPose>(
      pose(), {[](auto& p) { p.sumo_id = "actor2"; }, [](auto& p) { p.kind = ActorKind::Pedestrian; },
               [](auto& p) { p.length = 5; }, [](auto& p) { p.position = Vec2(1.0, 2.0000000001); },
               [](auto& p) { p.position = Vec2(1.1, 2.0); }, [](auto& p) { p.heading = std::nextafter(0.5, 1.0); },
               [](auto& p) { p.speed = 19; }, [](auto& p) { p.edge = "b"; }, [](auto& p) { p.lane = 2; },
               [](auto& p) { p.signals = 1; }, [](auto& p) { p.scripted = false; }, [](auto& p) { p.centred = true; }});
}

TEST(SameCommands, DoublesCountBitForBit) {
  sim::DriveSpeed zero{"ego", 0.0}, negative_zero{"ego", -0.0};
  EXPECT_FALSE(same_commands({zero}, {negative_zero}));
  sim::DriveSpeed nan{"ego", std::nan("")};
  EXPECT_TRUE(same_commands({nan}, {nan}));
}

TEST(SameCommands, KindOrderAndCountCount) {
  const sim::Command a = sim::SetSignals{"actor1", 2};
  const sim::Command b = sim::SetMaxSpeed{"actor1", 2};
  EXPECT_FALSE(same_commands({a}, {b}));
  EXPECT_FALSE(same_commands({a, b}, {b, a}));
  EXPECT_FALSE(same_commands({a}, {a, a}));
  EXPECT_TRUE(same_commands({a, b}, {a, b}));
  EXPECT_FALSE(same_commands({sim::SetRoute{"v", {"a"}}}, {sim::SetRoute{"v", {"a", "b"}}}));
  EXPECT_FALSE(same_commands({sim::SetStop{"v", "e", 0, 1, 4}}, {sim::SetStop{"v", "e", 0, 1, 5}}));
  EXPECT_FALSE(same_commands({sim::SetParameter{"v", "k", "1"}}, {sim::SetParameter{"v", "k", "2"}}));
  EXPECT_FALSE(same_commands({sim::RemoveActor{"v", ActorKind::Vehicle}}, {sim::RemoveActor{"v", ActorKind::Pedestrian}}));
  EXPECT_FALSE(same_commands({sim::ReleaseActor{"v", 10}}, {sim::ReleaseActor{"v", 11}}));
  EXPECT_FALSE(same_commands({sim::SetTrafficLight{"4", "-rG"}}, {sim::SetTrafficLight{"4", "-GG"}}));
  EXPECT_TRUE(same_commands({sim::SetTrafficLight{"4", "-rG"}}, {sim::SetTrafficLight{"4", "-rG"}}));
}

TEST(SameCommands, TrackedActorsCompareEveryField) {
  const std::vector<sim::TrackedActor> a{{0, "ego", ActorKind::Vehicle, 4.5, 1.8}};
  auto b = a;
  EXPECT_TRUE(same_tracked(a, b));
  b[0].length = 4.6;
  EXPECT_FALSE(same_tracked(a, b));
  b = a;
  b.push_back({1, "actor1", ActorKind::Vehicle, 4.5, 1.8});
  EXPECT_FALSE(same_tracked(a, b));
}

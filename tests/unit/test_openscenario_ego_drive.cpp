// Who moves the ego of an OpenSCENARIO run, and what SUMO is told (run/openscenario_ego.hpp):
// SUMO's car-following with the storyboard's speed target, the storyboard during lateral
// actions, the external ego once its controller is active, with the hand-over parameter.
#include <gtest/gtest.h>

#include "run/openscenario_ego.hpp"

namespace orch {
namespace {

using openscenario::EntityState;
using Driver = OpenScenarioEgo::Driver;

template <class T>
std::vector<T> of_type(const std::vector<sim::Command>& commands) {
  std::vector<T> out;
  for (const auto& c : commands)
    if (const auto* x = std::get_if<T>(&c)) out.push_back(*x);
  return out;
}

EntityState cruising(double speed) {
  EntityState s;
  s.placed = true;
  s.speed = speed;
  s.speed_profile = openscenario::SpeedProfile{0, 0, speed, speed, openscenario::DynamicsShape::Step};
  return s;
}

sim::SetPose pose_at(double x) {
  sim::SetPose p;
  p.position = {x, 0};
  p.edge = "-1";
  p.lane = 2;
  return p;
}

TEST(OpenScenarioEgoDrive, SumoDrivesWithTheStoryboardsSpeedTargetSentOnlyWhenItChanges) {
  OpenScenarioEgo ego("Ego", false);
  EXPECT_EQ(ego.sumo_id(), "Ego");
  EntityState s = cruising(20);
  EXPECT_EQ(ego.spawn_speed(s), 20);
  EXPECT_EQ(ego.driver(s), Driver::Sumo);
  EXPECT_TRUE(ego.commands(s, pose_at(0)).empty());
  s.speed_profile->to = 25;  // a new SpeedAction
  const auto c = ego.commands(s, pose_at(0));
  ASSERT_EQ(of_type<sim::SetMaxSpeed>(c).size(), 1u);
  EXPECT_EQ(of_type<sim::SetMaxSpeed>(c)[0].speed, 25);
  EXPECT_EQ(of_type<sim::SetMaxSpeed>(c)[0].sumo_id, "Ego");
  EXPECT_TRUE(ego.commands(s, pose_at(0)).empty());
  // Without an external ego an active controller changes nothing: SUMO keeps driving.
  s.controller_active = true;
  EXPECT_EQ(ego.driver(s), Driver::Sumo);
  EXPECT_TRUE(of_type<sim::SetParameter>(ego.commands(s, pose_at(0))).empty());
}

TEST(OpenScenarioEgoDrive, TheStoryboardPlacesItDuringALateralAction) {
  OpenScenarioEgo ego("Ego", false);
  EntityState s = cruising(20);
  ego.spawn_speed(s);
  s.lateral_profile = openscenario::LateralProfile{2, 3, -3.5, 0, openscenario::DynamicsShape::Sinusoidal};
  EXPECT_EQ(ego.driver(s), Driver::Storyboard);
  EXPECT_STREQ(OpenScenarioEgo::label(ego.driver(s)), "script");
  const auto poses = of_type<sim::SetPose>(ego.commands(s, pose_at(42)));
  ASSERT_EQ(poses.size(), 1u);
  EXPECT_FALSE(poses[0].scripted);  // placed, SUMO's speed handling stays
  EXPECT_EQ(poses[0].sumo_id, "Ego");
  EXPECT_DOUBLE_EQ(poses[0].position.x(), 42);
  s.lateral_profile.reset();  // the action ended
  EXPECT_EQ(ego.driver(s), Driver::Sumo);
  EXPECT_TRUE(of_type<sim::SetPose>(ego.commands(s, pose_at(43))).empty());
}

TEST(OpenScenarioEgoDrive, AnActivatedControllerHandsTheEgoToTheExternalEgo) {
  OpenScenarioEgo ego("Ego", true);
  EXPECT_EQ(ego.sumo_id(), "ego");
  EntityState s = cruising(20);
  ego.spawn_speed(s);
  EXPECT_TRUE(ego.commands(s, pose_at(0)).empty());  // SUMO drives, the plug-in watches
  s.controller_active = true;
  s.speed_profile->to = 30;
  s.lateral_profile = openscenario::LateralProfile{2, 3, -3.5, 0, openscenario::DynamicsShape::Sinusoidal};
  EXPECT_EQ(ego.driver(s), Driver::Plugin);
  EXPECT_STREQ(OpenScenarioEgo::label(Driver::Plugin), "plugin");
  const auto c = ego.commands(s, pose_at(0));
  // Only the hand-over: no speed target, no lateral placement for the plug-in's ego.
  ASSERT_EQ(c.size(), 1u);
  const auto& p = std::get<sim::SetParameter>(c[0]);
  EXPECT_EQ(p.sumo_id, "ego");
  EXPECT_EQ(p.key, "orch.hand_over");
  EXPECT_EQ(p.value, "1");
  EXPECT_TRUE(ego.commands(s, pose_at(0)).empty());  // said once
  s.controller_active = false;  // a later ActivateControllerAction with false
  s.lateral_profile.reset();
  const auto back = ego.commands(s, pose_at(0));
  ASSERT_EQ(of_type<sim::SetParameter>(back).size(), 1u);
  EXPECT_EQ(of_type<sim::SetParameter>(back)[0].value, "0");
  ASSERT_EQ(of_type<sim::SetMaxSpeed>(back).size(), 1u);  // SUMO drives again, at the target
  EXPECT_EQ(of_type<sim::SetMaxSpeed>(back)[0].speed, 30);
}

}  // namespace
}  // namespace orch

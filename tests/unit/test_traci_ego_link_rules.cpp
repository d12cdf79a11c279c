// What changes in a run when an external plug-in drives the ego (run/ego_link.hpp): the
// built-in driver's commands for the ego are dropped, everything else passes.
#include <gtest/gtest.h>

#include "run/ego_link.hpp"

using namespace orch;
using namespace orch::engine;

namespace {

class ConnectedLink : public EgoLink {
 public:
  bool connected = true;
  std::string listen() override { return {}; }
  void exchange(double) override {}
  void finish(const std::string&, const std::string&) noexcept override {}
  [[nodiscard]] bool driving() const override { return connected; }
  [[nodiscard]] EgoLinkReport report() const override { return {}; }
};

}  // namespace

TEST(TraciEgoLinkRules, TheBuiltInDriverLetsGoOfTheEgoOnly) {
  SpawnVehicle ego;
  ego.actor.sumo_id = "ego";
  ego.max_speed = 16.7;
  SpawnVehicle other;
  other.actor.sumo_id = "actor1";
  other.max_speed = 10;
  std::vector<Command> commands{ego,
                                other,
                                SetStop{"ego", "E0", 1, 500, 4.5},
                                SetMaxSpeed{"ego", 20},
                                SetMaxSpeed{"actor1", 20},
                                SetParameter{"ego", "orch.hand_over", "1"},
                                SetSignals{"ego", 2}};
  hand_ego_to_plugin(commands);
  ASSERT_EQ(commands.size(), 5u);
  EXPECT_EQ(std::get<SpawnVehicle>(commands[0]).max_speed, 0);     // the type's top speed
  EXPECT_EQ(std::get<SpawnVehicle>(commands[1]).max_speed, 10);    // others untouched
  EXPECT_EQ(std::get<SetMaxSpeed>(commands[2]).sumo_id, "actor1");
  EXPECT_EQ(std::get<SetParameter>(commands[3]).key, "orch.hand_over");  // hand_over reaches the plug-in
  EXPECT_TRUE(std::holds_alternative<SetSignals>(commands[4]));
}

TEST(TraciEgoLinkRules, TheTraceMarksTheEgoOnlyWhileAPluginIsConnected) {
  const std::vector<TrackedActor> tracked{{3, "actor3", ActorKind::Vehicle, 4, 2}, {7, "ego", ActorKind::Vehicle, 4, 2}};
  ConnectedLink link;
  EXPECT_EQ(plugin_driven_actor(&link, tracked), 7);
  link.connected = false;
  EXPECT_EQ(plugin_driven_actor(&link, tracked), std::nullopt);
  EXPECT_EQ(plugin_driven_actor(nullptr, tracked), std::nullopt);
}

TEST(TraciEgoLinkRules, TheRunLogLineNamesPeerClientAndEnd) {
  EgoLinkReport r;
  r.listen = "127.0.0.1:8813";
  EXPECT_EQ(describe(r), "ego plug-in: none connected to 127.0.0.1:8813");
  r.peer = "127.0.0.1:5000";
  r.client = "stack 1";
  r.steps_driven = 10;
  r.commands = {{"simulationStep", 10}, {"vehicle.setSpeed", 10}};
  r.end = "timeout";
  EXPECT_EQ(describe(r), "ego plug-in 127.0.0.1:5000 (stack 1): 10 step(s) driven, 20 command(s), 2 distinct; timeout");
}

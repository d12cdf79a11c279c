// The run's side of an external plug-in (run/ego_link.hpp): who the trace says drives, and
// the run log line. What the engine stops doing for the ego: test_engine_actions.cpp.
#include <gtest/gtest.h>

#include "run/ego_link.hpp"

using namespace orch;
using namespace orch::sim;

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

// The shipped example ego plug-in (adapters/ego_plugin_example, a C++ program on SUMO's
// libtraci) drives the ego of the sample scenarios; the same scenarios run with the
// built-in SUMO driver end with a verdict too.
#include <gtest/gtest.h>

#include <fstream>

#include "support/ego_plugin_run.hpp"
#include "support/trace_csv.hpp"

using namespace orch::test;

namespace {

std::vector<std::string> example_plugin(const TempDir& out, const std::string& speed_kmh) {
  return {ORCH_EGO_PLUGIN_EXAMPLE, "--port", "{port}", "--speed", speed_kmh, "--log", (out / "plugin.csv").string()};
}

}  // namespace

TEST(EgoPluginLibtraci, ExamplePluginFollowsABrakingLeadAndStopsBehindIt) {
  TempDir out;
  const auto r = run_with_plugin(source_path("scenarios/alks_lead_brake.json"), out, example_plugin(out, "70"));
  ASSERT_EQ(r.orchestrator_exit, 0) << r.orchestrator_output << r.plugin_output;
  EXPECT_EQ(r.plugin_exit, 0) << r.plugin_output;
  EXPECT_EQ(r.result["verdict"], "success") << r.result["reason"];
  EXPECT_EQ(r.result["ego_plugin"]["client"], "ego_plugin_example 1.0 (libtraci)");
  EXPECT_TRUE(r.result["collisions"].empty());

  Trace trace(out / "trace.csv");
  const auto ego = trace.actor(0);
  const auto lead = trace.actor(1);
  EXPECT_EQ(ego.back().str("driver"), "plugin");
  EXPECT_LT(ego.back().num("x") + 4.51 / 2, lead.back().num("x") - 4.61 / 2);
  // It perceived the lead through its context subscription (its own log) and kept a gap.
  Trace plugin(out / "plugin.csv");
  std::size_t following = 0;
  for (const auto& row : plugin.rows())
    if (row.str("leader") == "actor1") {
      ++following;
      EXPECT_GT(row.num("gap"), 1.0) << "t=" << row.num("time");
    }
  EXPECT_GT(following, plugin.rows().size() / 2);
}

TEST(EgoPluginLibtraci, ExamplePluginAndBuiltInDriverBothEndTheObstacleScenarioWithAVerdict) {
  TempDir with_plugin, builtin;
  const auto r = run_with_plugin(source_path("scenarios/alks_obstacle_stop.json"), with_plugin,
                                 example_plugin(with_plugin, "70"));  // the scenario waits for 60 km/h
  ASSERT_EQ(r.orchestrator_exit, 0) << r.orchestrator_output << r.plugin_output;
  EXPECT_EQ(r.result["verdict"], "success");
  const auto b = run_cli({"run", source_path("scenarios/alks_obstacle_stop.json"), "--out", builtin.path().string(), "-q"});
  ASSERT_EQ(b.exit_code, 0) << b.output;
  const auto builtin_result = read_json(builtin / "result.json");
  EXPECT_EQ(builtin_result["verdict"], "success");
  EXPECT_TRUE(builtin_result["ego_plugin"].is_null());
  // Different drivers, same judge: both reached the ending scene.
  EXPECT_EQ(r.result["ending_scene"], builtin_result["ending_scene"]);
  Trace plugin_trace(with_plugin / "trace.csv");
  Trace builtin_trace(builtin / "trace.csv");
  EXPECT_EQ(plugin_trace.actor(0).back().str("driver"), "plugin");
  EXPECT_EQ(builtin_trace.actor(0).back().str("driver"), "sumo");
}

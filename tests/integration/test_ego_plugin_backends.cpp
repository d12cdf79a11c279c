// The ego plug-in works the same whichever SUMO client library the orchestrator uses: the
// example plug-in gives byte-identical traces on libsumo and traci, and a plug-in that
// vanishes on the traci backend leaves no SUMO process behind.
#include <gtest/gtest.h>

#include <fstream>

#include "support/ego_plugin_run.hpp"

using namespace orch::test;

namespace {

// Processes whose command line mentions `needle` (SUMO is started with --log OUT/sumo.log).
int processes_mentioning(const std::string& needle) {
  int n = 0;
  for (const auto& entry : std::filesystem::directory_iterator("/proc")) {
    const std::string name = entry.path().filename();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    std::ifstream in(entry.path() / "cmdline", std::ios::binary);
    std::string cmdline((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (cmdline.find(needle) != std::string::npos && cmdline.rfind("sumo", 0) == 0) ++n;
  }
  return n;
}

}  // namespace

TEST(EgoPluginBackends, TheExamplePluginGivesTheSameTraceOnLibsumoAndTraci) {
  TempDir on_libsumo, on_traci;
  const auto plugin = [](const TempDir& out) {
    return std::vector<std::string>{ORCH_EGO_PLUGIN_EXAMPLE, "--port", "{port}", "--speed", "70", "--log",
                                    (out / "plugin.csv").string()};
  };
  const auto a = run_with_plugin(source_path("scenarios/alks_lead_brake.json"), on_libsumo, plugin(on_libsumo));
  const auto b = run_with_plugin(source_path("scenarios/alks_lead_brake.json"), on_traci, plugin(on_traci),
                                 {"--backend", "traci"});
  ASSERT_EQ(a.orchestrator_exit, 0) << a.orchestrator_output;
  ASSERT_EQ(b.orchestrator_exit, 0) << b.orchestrator_output;
  EXPECT_EQ(a.result["backend"], "libsumo");
  EXPECT_EQ(b.result["backend"], "traci");
  EXPECT_EQ(a.result["verdict"], "success");
  EXPECT_EQ(b.result["verdict"], "success");
  const std::string trace = slurp(on_libsumo / "trace.csv");
  EXPECT_GT(trace.size(), 10000u);
  EXPECT_EQ(trace, slurp(on_traci / "trace.csv"));
  // The plug-in saw the same world on both.
  EXPECT_EQ(slurp(on_libsumo / "plugin.csv"), slurp(on_traci / "plugin.csv"));
}

TEST(EgoPluginBackends, APluginThatVanishesOnTheTraciBackendLeavesNoSumoBehind) {
  TempDir out;
  const auto r = run_with_plugin(source_path("scenarios/alks_obstacle_stop.json"), out,
                                 python_client("drive.py", {"--port", "{port}", "--mode", "disconnect", "--after", "30"}),
                                 {"--backend", "traci"});
  EXPECT_EQ(r.orchestrator_exit, 2) << r.orchestrator_output;
  EXPECT_EQ(r.result["reason"].get<std::string>().rfind("ego disconnected at t=1.550 s", 0), 0u) << r.result["reason"];
  EXPECT_EQ(processes_mentioning(out.path().string()), 0);
}

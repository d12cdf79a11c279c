// `run FILE.xosc --controllers off` (esmini's --disable_controllers, docs/command-line.md):
// no controller runs, every entity follows the storyboard, on real SUMO. ego_hand_over.xosc's
// Ego has a system-under-test controller (ALKSController) and its storyboard speed is 20 m/s;
// from 2 s it changes into the lane of a car at 14 m/s ahead, and at 8 s an
// ActivateControllerAction activates its controller. SUMO's driver brakes behind that car;
// the storyboard's ego keeps 20 m/s.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <set>

#include "support/cli_runner.hpp"
#include "support/trace_csv.hpp"

using namespace orch::test;
namespace fs = std::filesystem;

namespace {

struct EgoTrace {
  std::set<std::string> drivers;
  double min_speed = 1e9, max_speed = -1e9;
};

EgoTrace ego_trace(const fs::path& trace_file) {
  const Trace trace(trace_file);
  EgoTrace out;
  for (const auto& row : trace.rows()) {
    if (row.str("actor_id") != "Ego") continue;
    out.drivers.insert(row.str("driver"));
    out.min_speed = std::min(out.min_speed, row.num("speed"));
    out.max_speed = std::max(out.max_speed, row.num("speed"));
  }
  return out;
}

std::vector<std::string> run_args(const std::string& scenario, const fs::path& out) {
  return {"run", scenario, "--out", out.string(), "-q", "--no-report", "--max-time", "12"};
}

}  // namespace

TEST(ControllersOffCli, ASystemUnderTestEgoFollowsItsStoryboardSpeedOnlyWithControllersOff) {
  const std::string scenario = source_path("scenarios/openscenario/ego_hand_over.xosc");
  TempDir on, off;

  auto r = run_cli(run_args(scenario, on.path()));
  ASSERT_NE(r.exit_code, 2) << r.output;
  const EgoTrace driven = ego_trace(on / "trace.csv");
  EXPECT_TRUE(driven.drivers.count("sumo")) << "SUMO drives the ego with its controller";
  EXPECT_LT(driven.min_speed, 18.0) << "SUMO's driver brakes behind the slower car";
  auto result = read_json(on / "result.json");
  EXPECT_EQ(result["ego_model"], "sumo");
  EXPECT_EQ(result["controllers"], "on");

  auto args = run_args(scenario, off.path());
  args.insert(args.end(), {"--controllers", "off"});
  r = run_cli(args);
  ASSERT_NE(r.exit_code, 2) << r.output;
  const EgoTrace scripted = ego_trace(off / "trace.csv");
  EXPECT_EQ(scripted.drivers, std::set<std::string>{"script"});
  EXPECT_NEAR(scripted.min_speed, 20.0, 1e-3) << "the storyboard's speed, every step";
  EXPECT_NEAR(scripted.max_speed, 20.0, 1e-3);
  result = read_json(off / "result.json");
  EXPECT_EQ(result["ego_model"], "storyboard");
  EXPECT_EQ(result["controllers"], "off");
  const std::string log = slurp(off / "run.log");
  EXPECT_NE(log.find("--controllers off: no controller runs"), std::string::npos) << log;
  EXPECT_NE(log.find("Ego: follows the storyboard (--controllers off; controller ALKSController is a system under "
                     "test); the ego of metrics and the report because its controller is named ALKSController"),
            std::string::npos)
      << log;
  // The ActivateControllerAction at 8 s runs and is logged; it hands the ego to nobody.
  EXPECT_NE(log.find("Ego: its controller ALKSController was activated; --controllers off: it goes on following the "
                     "storyboard"),
            std::string::npos)
      << log;
  bool activated = false;
  for (const auto& e : result["events"])
    if (e["text"] == "action HandOver startTransition") activated = true;
  EXPECT_TRUE(activated) << result["events"].dump();
}

// Options that ask for something to drive the ego contradict it: a clear error, no run.
TEST(ControllersOffCli, OptionsThatAskForADriverAreErrors) {
  const std::string scenario = source_path("scenarios/openscenario/ego_hand_over.xosc");
  for (const std::vector<std::string>& extra :
       {std::vector<std::string>{"--ego-model", "r157"}, {"--reference-run"}, {"--ego-port", "0"}}) {
    TempDir dir;
    auto args = run_args(scenario, dir.path());
    args.insert(args.end(), {"--controllers", "off"});
    args.insert(args.end(), extra.begin(), extra.end());
    const auto r = run_cli(args);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("--controllers off: every entity follows the storyboard; " + extra.front()),
              std::string::npos)
        << r.output;
  }
  // --ego NAME only names the ego then: it runs.
  TempDir named;
  auto args = run_args(scenario, named.path());
  args.insert(args.end(), {"--controllers", "off", "--ego", "SlowCar"});
  const auto r = run_cli(args);
  EXPECT_NE(r.exit_code, 2) << r.output;
  EXPECT_EQ(read_json(named / "result.json")["ego_model"], "storyboard");
  // ScenarioExecutor scenarios have no controllers to switch off.
  TempDir se;
  const auto s = run_cli({"run", source_path("scenarios/highway_cut_in.json"), "--out", se.path().string(), "-q", "--no-report",
                          "--controllers", "off"});
  EXPECT_EQ(s.exit_code, 2) << s.output;
  EXPECT_NE(s.output.find("--controllers off: OpenSCENARIO runs only"), std::string::npos) << s.output;
}
